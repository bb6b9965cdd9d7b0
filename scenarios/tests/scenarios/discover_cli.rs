//! `rins diagnose --discover` and `--apply custom:NAME` on the command line, on the
//! walkthrough's plant-written dataset (docs/model-vs-measurements.md, "Discovery").

use rins_scenario::file::Scenario;

/// The command line of the walkthrough: `rins diagnose --discover --json` proposes the block,
/// `--apply custom:NAME` writes a model file that declares it with the fitted coefficients, and
/// `rins compare` on that file brings the gyro residual to the noise floor.
#[test]
fn command_line_discover_and_apply() {
    let rins = env!("CARGO_BIN_EXE_rins");
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let truth = root.join("docs/examples/discovery-truth.toml");
    let model = root.join("docs/examples/diagnosis-model.toml");
    let dir = std::env::temp_dir().join(format!("rins-discover-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let data = dir.join("unit.csv");
    let fitted = dir.join("fitted.toml");
    let run = |args: &[&std::ffi::OsStr]| {
        let o = std::process::Command::new(rins)
            .args(args)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        o
    };
    let s = |x: &'static str| std::ffi::OsStr::new(x);
    run(&[
        s("measure"),
        truth.as_os_str(),
        s("--out"),
        data.as_os_str(),
    ]);
    let o = run(&[
        s("diagnose"),
        s("--model"),
        model.as_os_str(),
        s("--data"),
        data.as_os_str(),
        s("--discover"),
        s("--json"),
    ]);
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        j["discovery"]["proposals"][0]["name"], "b_dtdt_block",
        "{j:#}"
    );
    let block = j["discovery"]["proposals"][0]["toml"].as_str().unwrap();
    assert!(block.contains("regressor = \"dtemp_dt:block\""), "{block}");
    // Without --discover the report has no discovery section (the JSON is unchanged).
    let o = run(&[
        s("diagnose"),
        s("--model"),
        model.as_os_str(),
        s("--data"),
        data.as_os_str(),
        s("--json"),
    ]);
    let plain: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(plain.get("discovery").is_none());
    run(&[
        s("diagnose"),
        s("--model"),
        model.as_os_str(),
        s("--data"),
        data.as_os_str(),
        s("--apply"),
        s("custom:b_dtdt_block"),
        s("--out"),
        fitted.as_os_str(),
    ]);
    let text = std::fs::read_to_string(&fitted).unwrap();
    let back = Scenario::from_toml(&text, "fitted").unwrap().plant;
    let c = &back.sensor.gyro.custom[0];
    assert_eq!(
        (c.name.as_str(), c.regressor.as_str()),
        ("b_dtdt_block", "dtemp_dt:block")
    );
    assert!(
        (c.coef[0] - 8.0).abs() < 0.5 && (c.coef[2] + 6.0).abs() < 0.5,
        "{c:?}"
    );
    let o = run(&[
        s("compare"),
        s("--model"),
        fitted.as_os_str(),
        s("--data"),
        data.as_os_str(),
        s("--json"),
    ]);
    let after: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for ch in after["channels"].as_array().unwrap() {
        let name = ch["channel"].as_str().unwrap();
        if name == "gyro_x" || name == "gyro_z" {
            let (r, f) = (
                ch["residual_rms"].as_f64().unwrap(),
                ch["noise_floor_rms"].as_f64().unwrap(),
            );
            assert!(r <= 1.1 * f, "{name}: {r} vs {f}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
