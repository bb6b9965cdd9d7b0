//! `rins fmu run` against `rins run`: the packaged FMI 2 FMU, driven through its C API one
//! communication step per sample, writes the same imu.csv bytes as the in-process plant, with
//! every effect, the truth columns and a chamber profile (fed through the chamber input).
//! Needs the cdylibs (`cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3`).

use rins_scenarios::file::Scenario;
use rins_scenarios::sinks::CsvSink;

const SCENARIO: &str = r#"
[scenario]
name = "fmu-vs-in-process"
duration_s = 700.0
[run]
rate_hz = 100.0
seed = 17
[scheme]
kind = "sixteen-position"
[sensor]
preset = "nav-grade-full"
[thermal]
chamber = { profile = [[0.0, 15.0], [500.0, 35.0]] }
[outputs]
decimation = 3
truth = true
effects = true
"#;

#[test]
fn the_fmu_writes_the_same_csv_bytes_as_the_in_process_plant() {
    let exe = std::env::current_exe().unwrap();
    let lib_dir = exe.parent().and_then(|d| d.parent()).unwrap().to_path_buf();
    let out = std::env::temp_dir().join(format!("rins-fmu-test-{}", std::process::id()));
    let fmus = rins_scenarios::fmu::build(&out, &lib_dir)
        .expect("FMI libraries built (cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3)");
    let sc = Scenario::from_toml(SCENARIO, "test").unwrap();

    let mut direct = CsvSink::new(Vec::new(), sc.outputs, &sc.plant).unwrap();
    rins_scenarios::run(&sc, sc.samples(), &mut [&mut direct]).unwrap();
    let mut via_fmu = CsvSink::new(Vec::new(), sc.outputs, &sc.plant).unwrap();
    rins_scenarios::fmu::run(&fmus[0], &sc, sc.samples(), &mut [&mut via_fmu]).unwrap();
    let (a, b) = (direct.into_inner(), via_fmu.into_inner());
    assert!(a.len() > 100_000, "{} bytes", a.len());
    assert!(a == b, "the FMU's CSV differs from the in-process plant's");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn scheme_steps_are_refused_with_what_to_use_instead() {
    let exe = std::env::current_exe().unwrap();
    let lib_dir = exe.parent().and_then(|d| d.parent()).unwrap().to_path_buf();
    let out = std::env::temp_dir().join(format!("rins-fmu-test-steps-{}", std::process::id()));
    let fmus = rins_scenarios::fmu::build(&out, &lib_dir).unwrap();
    let text = r#"
[scenario]
name = "steps"
duration_s = 1.0
[scheme]
kind = "steps"
steps = [{ axis = "outer", angle_deg = 90.0, rate_dps = 10.0, dwell_s = 5.0 }]
"#;
    let sc = Scenario::from_toml(text, "test").unwrap();
    let e = rins_scenarios::fmu::run(&fmus[0], &sc, 10, &mut [])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("scheme.steps") && e.contains("gimbal command"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&out);
}
