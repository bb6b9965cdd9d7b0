//! `rins schemes` as a user meets it: the JSON every figure comes from, the report page whose
//! verdict comes first and quotes the JSON, design files that read back as schemes, and bad
//! input named by file, field or flag with the expected range.

use std::path::PathBuf;
use std::process::{Command, Output};

use serde_json::Value;

const RINS: &str = env!("CARGO_BIN_EXE_rins");

fn tmp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rins-schemes-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn rins(args: &[&str]) -> Output {
    Command::new(RINS).args(args).output().unwrap()
}

fn json(args: &[&str]) -> Value {
    let out = rins(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn failure(args: &[&str]) -> String {
    let out = rins(args);
    assert!(!out.status.success(), "{args:?} must fail");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The invariant member is the same under every scheme, and the general worst case is never
/// below it; the page opens with the verdict, which quotes the JSON's invariant figure.
#[test]
fn analyse_json_and_report_agree_and_the_invariant_bounds_every_scheme() {
    let dir = tmp("analyse");
    let d = dir.to_str().unwrap();
    let v = json(&["schemes", "analyse", "--json", "--report", d]);
    let bounds = v["bounds"].as_array().unwrap();
    let general: Vec<&Value> = bounds
        .iter()
        .filter(|b| b["class"] == "general-b(u)")
        .collect();
    assert_eq!(general.len(), 5, "one per built-in scheme");
    let inv = general[0]["invariant_horizontal_m"].as_f64().unwrap();
    for b in &general {
        let i = b["invariant_horizontal_m"].as_f64().unwrap();
        assert!((i - inv).abs() <= 1e-6 * inv, "{b}");
        assert!(b["worst_horizontal_m"].as_f64().unwrap() >= inv * (1.0 - 1e-9));
    }
    let page = std::fs::read_to_string(dir.join("report.html")).unwrap();
    let first_h2 = page.find("<h2>").expect("a section");
    assert!(
        page[first_h2..].starts_with("<h2>Verdict</h2>"),
        "verdict first"
    );
    let verdict_end = page[first_h2..].find("</p>").unwrap() + first_h2;
    let shown = format!("{:.1}", inv);
    let shown_sig = rins_report::html::format_sig(inv, 4);
    assert!(
        page[first_h2..verdict_end].contains(&shown_sig),
        "the verdict quotes {shown} ({shown_sig}): {}",
        &page[first_h2..verdict_end]
    );
    assert!(dir.join("schemes_effects.svg").exists() && dir.join("schemes_classes.png").exists());
}

/// A design written by `rins schemes design --out` is a scheme file `analyse` reads back, and
/// its figures there are the design's.
#[test]
fn designs_read_back_as_scheme_files() {
    let dir = tmp("design");
    let d = dir.to_str().unwrap();
    let r = json(&[
        "schemes",
        "design",
        "--class",
        "plant-delta-beta",
        "--positions",
        "16",
        "--top",
        "1",
        "--json",
        "--out",
        d,
    ]);
    let name = r["best"][0]["file"]["name"].as_str().unwrap();
    let file = dir.join(format!("{name}.toml"));
    let a = json(&["schemes", "analyse", file.to_str().unwrap(), "--json"]);
    let b = a["bounds"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["class"] == "plant-delta-beta")
        .unwrap();
    let got = b["worst_horizontal_m"].as_f64().unwrap();
    let want = r["best"][0]["bounds"][2]["worst_horizontal_m"]
        .as_f64()
        .unwrap();
    assert!((got - want).abs() <= 1e-6 * want, "{got} vs {want}");
}

#[test]
fn bad_input_names_the_file_field_or_flag() {
    let dir = tmp("bad");
    let err = failure(&["schemes", "analyse", "no-such-scheme"]);
    assert!(
        err.contains("no-such-scheme") && err.contains("sixteen-position"),
        "{err}"
    );
    let f = dir.join("bad.toml");
    std::fs::write(
        &f,
        "name = \"bad\"\n[scheme]\nkind = \"steps\"\nrepeat = true\n[[scheme.steps]]\naxis = \"inner\"\nangle_deg = 180.0\nrate_dps = 500.0\ndwell_s = 10.0\n",
    )
    .unwrap();
    let err = failure(&["schemes", "analyse", f.to_str().unwrap()]);
    assert!(
        err.contains("bad.toml") && err.contains("scheme.steps[0].rate_dps"),
        "{err}"
    );
    let err = failure(&["schemes", "analyse", "--bound-dph", "0"]);
    assert!(err.contains("--bound-dph") && err.contains("> 0"), "{err}");
    let err = failure(&["schemes", "design", "--positions", "7"]);
    assert!(err.contains("--positions") && err.contains("even"), "{err}");
    // A scheme that does not come back to its start has no per-cycle residual.
    std::fs::write(
        &f,
        "name = \"open\"\n[scheme]\nkind = \"steps\"\nrepeat = true\n[[scheme.steps]]\naxis = \"inner\"\nangle_deg = 90.0\nrate_dps = 2.0\ndwell_s = 10.0\n",
    )
    .unwrap();
    let err = failure(&["schemes", "analyse", f.to_str().unwrap()]);
    assert!(
        err.contains("open") && err.contains("start attitude"),
        "{err}"
    );
}
