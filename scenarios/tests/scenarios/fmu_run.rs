//! `rins fmu run` against `rins run`: the packaged FMI 2 FMU, driven through its C API one
//! communication step per sample, writes the same imu.csv bytes as the in-process plant, with
//! every effect, the truth columns and a chamber profile (fed through the chamber input).
//! Needs the cdylibs (`cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3`).

use rins_scenario::file::Scenario;
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

/// The FMUs packaged from the cdylibs next to this test's binary, in a folder of the test's
/// own (`tag`), removed by the caller.
fn built_fmus(tag: &str) -> (Vec<std::path::PathBuf>, std::path::PathBuf) {
    let exe = std::env::current_exe().unwrap();
    let lib_dir = exe.parent().and_then(|d| d.parent()).unwrap().to_path_buf();
    let out = std::env::temp_dir().join(format!("rins-fmu-test-{tag}-{}", std::process::id()));
    let fmus = rins_scenarios::fmu::build(&out, &lib_dir)
        .expect("FMI libraries built (cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3)");
    (fmus, out)
}

#[test]
fn the_fmu_writes_the_same_csv_bytes_as_the_in_process_plant() {
    let (fmus, out) = built_fmus("csv");
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
    let (fmus, out) = built_fmus("steps");
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

/// `rins fmu run` puts the scenario's declared effects into the FMU's slots: a gyro bias on
/// the block temperature rate and a degree-2 accelerometer term give the same CSV bytes as the
/// in-process plant, and the declared effect is really acting (the run differs from the same
/// scenario without it).
#[test]
fn declared_effects_reach_the_fmu_through_its_slots() {
    let (fmus, out) = built_fmus("slots");
    let declared = r#"
[[sensor.gyro.custom]]
name = "trate"
kind = "bias"
regressor = "dtemp_dt:block"
unit = "K/s"
axes = ["x", "z"]
coef = [400.0, 0.0, -250.0]
[[sensor.accel.custom]]
name = "tilt"
kind = "bias"
regressor = "u_x*u_z"
unit = "1"
axes = ["y"]
coef = [0.0, 300.0, 0.0]
"#;
    let with = format!("{SCENARIO}{declared}").replace("duration_s = 700.0", "duration_s = 120.0");
    let without = SCENARIO.replace("duration_s = 700.0", "duration_s = 120.0");
    let csv = |text: &str, fmu: bool| {
        let sc = Scenario::from_toml(text, "test").unwrap();
        let mut sink = CsvSink::new(Vec::new(), sc.outputs, &sc.plant).unwrap();
        if fmu {
            rins_scenarios::fmu::run(&fmus[0], &sc, sc.samples(), &mut [&mut sink]).unwrap();
        } else {
            rins_scenarios::run(&sc, sc.samples(), &mut [&mut sink]).unwrap();
        }
        sink.into_inner()
    };
    let direct = csv(&with, false);
    assert!(
        direct == csv(&with, true),
        "the FMU's CSV differs with declared effects"
    );
    assert!(
        direct != csv(&without, false),
        "the declared effects changed nothing"
    );
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_moving_carrier_is_refused_with_what_to_use_instead() {
    let (fmus, out) = built_fmus("ship");
    let text = r#"
[scenario]
name = "ship"
duration_s = 1.0
[carrier]
kind = "ship"
"#;
    let sc = Scenario::from_toml(text, "test").unwrap();
    let e = rins_scenarios::fmu::run(&fmus[0], &sc, 10, &mut [])
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "test: carrier.kind: `rins fmu run` drives the static carrier only (the FMU outputs no carrier truth); connect the RinsCarrier FMU to the IMU FMU's carrier inputs instead (docs/cosimulation.md)"
    );
    let _ = std::fs::remove_dir_all(&out);
}
