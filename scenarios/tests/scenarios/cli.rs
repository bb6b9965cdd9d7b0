//! The `rins` command line as a user meets it: negative numbers reach the range checks, which
//! name the flag and the range (and echo the value short: 1e300, not 301 digits); `rins fmu
//! build` on a fresh build finds or builds its libraries; `rins fmu run` names the scenario file
//! whose carrier it refuses.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use rins_scenarios::commands::fmu::{FMI_PACKAGES, library_files};

const RINS: &str = env!("CARGO_BIN_EXE_rins");

fn tmp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rins-cli-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn rins(args: &[&str]) -> Output {
    Command::new(RINS).args(args).output().unwrap()
}

/// stderr of a run that must fail.
fn failure(args: &[&str]) -> String {
    let out = rins(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "{args:?} must fail; stderr: {err}");
    assert!(
        !err.contains("-- -"),
        "{args:?}: clap's tip instead of the range check: {err}"
    );
    err
}

#[test]
fn negative_numbers_reach_the_range_check_which_names_flag_and_range() {
    let dir = tmp("negative");
    let out = dir.to_str().unwrap();
    let err = failure(&[
        "run",
        "builtin:calibration-z-up",
        "--out",
        out,
        "--duration-s",
        "-5",
    ]);
    assert!(
        err.contains("--duration-s: scenario.duration_s: expected a number in (0, 1e7], got -5"),
        "{err}"
    );
    let err = failure(&[
        "run",
        "builtin:calibration-z-up",
        "--out",
        out,
        "--rate-hz",
        "-100",
    ]);
    let (_, lo, hi) = rins_plant::params::RANGES
        .iter()
        .find(|(k, _, _)| *k == "run.rate_hz")
        .copied()
        .unwrap();
    assert!(
        err.contains("--rate-hz: run.rate_hz: expected")
            && err.contains(&format!("{lo}"))
            && err.contains(&format!("{hi}"))
            && err.contains("got -100"),
        "{err}"
    );
    let err = failure(&["run", "builtin:calibration-z-up", "--seed", "-1"]);
    assert!(
        err.contains("--seed") && err.contains(&u64::MAX.to_string()),
        "{err}"
    );
    let err = failure(&["paper", "table4", "--runs", "-2", "--out", out]);
    assert!(
        err.contains("--runs: expected at least 1 seed, got -2"),
        "{err}"
    );
    let err = failure(&["paper", "table5", "--days", "-1", "--out", out]);
    assert!(
        err.contains("--days: expected a number in (0, 60], got -1"),
        "{err}"
    );
    for (study, bad) in [
        ("table4", "0"),
        ("table4", "5"),
        ("table4", "two"),
        ("sea", "9"),
    ] {
        let err = failure(&["paper", study, "--subsamples", bad, "--out", out]);
        assert!(
            err.contains("--subsamples") && err.contains("1 to 4"),
            "{study} {bad}: {err}"
        );
    }
    let err = failure(&["verify", "ins", "--runs", "-8"]);
    assert!(
        err.contains("--runs: expected at least 8 Monte Carlo runs, got -8"),
        "{err}"
    );
    // A negative value that is valid is taken: the campaign fails on its missing file, not on
    // the reference temperature.
    let missing = dir.join("missing.toml");
    let err = failure(&[
        "campaign",
        missing.to_str().unwrap(),
        "--ref-temp-c",
        "-10",
        "--out",
        out,
    ]);
    assert!(err.contains("missing.toml"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 44: a positive flag given inf, 1e-300 or 1e300 names the flag, says the value must be
/// finite and above 0, and echoes the value short ("--time-window-s must be a positive number,
/// got inf" before; -1e300 as 302 characters). The flags are checked before the data file is
/// read.
#[test]
fn positive_flags_say_finite_and_echo_the_value_short() {
    let dir = tmp("positive");
    let data = dir.join("never-read.csv");
    for (flag, value, echo) in [
        ("--time-window-s", "inf", "inf"),
        ("--window-s", "-1e300", "-1e300"),
        // `=`: clap takes "-1e-300" (a negative exponent) for a flag, not a negative number.
        ("--temp-bin-k", "-1e-300", "-1e-300"),
        ("--time-window-s", "0", "0"),
    ] {
        let err = failure(&[
            "compare",
            "--model",
            "builtin:calibration-z-up",
            "--data",
            data.to_str().unwrap(),
            &format!("{flag}={value}"),
        ]);
        assert_eq!(
            err.trim_end(),
            format!("error: {flag}: expected a finite number > 0, got {echo}"),
            "{flag} {value}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The folder of the `rins` under test, where cargo puts the FMI libraries too.
fn built_libraries() -> PathBuf {
    let dir = Path::new(RINS).parent().unwrap().to_path_buf();
    for f in library_files() {
        let lib = dir.join(f);
        assert!(
            lib.exists(),
            "{} missing: build the FMI libraries first (cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3 -p rins-carrier-fmi2 -p rins-carrier-fmi3)",
            lib.display()
        );
    }
    dir
}

#[test]
fn fmu_build_builds_missing_libraries_with_cargo_in_the_workspace() {
    let real = built_libraries();
    let dir = tmp("fmu-build");
    // A fresh clone: `rins` in a target folder without the libraries. A stand-in for cargo
    // records its arguments and "builds" by copying the real libraries into the target folder
    // it was given (a real build here would rebuild every dependency in a new target folder).
    let target = dir.join("target");
    std::fs::create_dir_all(target.join("release")).unwrap();
    let exe = target.join("release/rins");
    std::fs::copy(RINS, &exe).unwrap();
    let stage = dir.join("stage");
    std::fs::create_dir_all(&stage).unwrap();
    for f in library_files() {
        std::fs::copy(real.join(f), stage.join(f)).unwrap();
    }
    let log = dir.join("cargo-args");
    let cargo = dir.join("cargo");
    std::fs::write(
        &cargo,
        format!(
            "#!/bin/sh\necho \"$@\" > '{log}'\nwhile [ $# -gt 0 ]; do [ \"$1\" = --target-dir ] && t=\"$2\"; shift; done\ncp '{stage}'/* \"$t/release/\"\n",
            log = log.display(),
            stage = stage.display()
        ),
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&cargo, std::fs::Permissions::from_mode(0o755)).unwrap();
    let out = Command::new(&exe)
        .args(["fmu", "build", "--out"])
        .arg(dir.join("fmu"))
        .env("CARGO", &cargo)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("building the FMI libraries"), "{err}");
    let args = std::fs::read_to_string(&log).unwrap();
    let mut expect = "build --release".to_string();
    for p in FMI_PACKAGES {
        expect += &format!(" -p {p}");
    }
    expect += &format!(" --target-dir {}", target.display());
    assert_eq!(args.trim(), expect);
    // The FMUs equal those packaged from the real libraries.
    let listed = String::from_utf8_lossy(&out.stdout).into_owned();
    let reference = rins(&[
        "fmu",
        "build",
        "--lib-dir",
        real.to_str().unwrap(),
        "--out",
        dir.join("reference").to_str().unwrap(),
    ]);
    assert!(reference.status.success());
    let paths: Vec<&str> = listed.lines().collect();
    // One FMU per library: the IMU and the carrier, FMI 2 and FMI 3.
    assert_eq!(paths.len(), library_files().len(), "{listed}");
    for p in paths {
        let p = Path::new(p);
        let a = std::fs::read(p).unwrap();
        let b = std::fs::read(dir.join("reference").join(p.file_name().unwrap())).unwrap();
        assert!(
            a.starts_with(b"PK\x03\x04") && a.len() > 100_000,
            "{}",
            p.display()
        );
        assert!(a == b, "{} differs from the reference", p.display());
    }
    // Run again: the libraries are there now, and cargo is not called.
    std::fs::remove_file(&log).unwrap();
    let again = Command::new(&exe)
        .args(["fmu", "build", "--out"])
        .arg(dir.join("fmu"))
        .env("CARGO", &cargo)
        .output()
        .unwrap();
    assert!(again.status.success());
    assert!(!log.exists(), "cargo called although the libraries exist");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fmu_build_outside_a_cargo_target_names_what_to_build() {
    let dir = tmp("fmu-installed");
    let exe = dir.join("bin/rins");
    std::fs::create_dir_all(exe.parent().unwrap()).unwrap();
    std::fs::copy(RINS, &exe).unwrap();
    let out = Command::new(&exe)
        .args(["fmu", "build", "--out"])
        .arg(dir.join("fmu"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        FMI_PACKAGES
            .iter()
            .all(|p| err.contains(&format!("-p {p}")))
            && err.contains("--lib-dir"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `rins fmu run` refuses a moving carrier before it opens the FMU (issue 44), naming the
/// scenario file as the scenario loader's own refusals do: with several scenarios in a script,
/// the message alone says which one to change.
#[test]
fn fmu_run_refuses_a_moving_carrier_naming_the_scenario_file() {
    let dir = tmp("fmu-run-ship");
    let scenario = dir.join("ship.toml");
    std::fs::write(
        &scenario,
        "[scenario]\nname = \"ship\"\nduration_s = 1.0\n[carrier]\nkind = \"ship\"\n",
    )
    .unwrap();
    let (fmu, out) = (dir.join("RinsImu.fmu"), dir.join("out"));
    let err = failure(&[
        "fmu",
        "run",
        fmu.to_str().unwrap(),
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        err,
        format!(
            "error: {}: carrier.kind: `rins fmu run` drives the static carrier only (the FMU outputs no carrier truth); connect the RinsCarrier FMU to the IMU FMU's carrier inputs instead (docs/cosimulation.md)\n",
            scenario.display()
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}
