//! The FMI 2.0 binary tested from the outside through its C API (the importer loads the built
//! `librins_imu_fmi2.so`): independence of instances, state save/restore and serialisation (also
//! across processes), every kind of refused call with its logged reason, and a caller's misuse
//! of the instance handle (freed twice, used after free) through the raw C functions.
//!
//! Needs the cdylibs: `cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3`
//! (tests/run-all.sh builds the workspace first).

#![allow(unsafe_code)] // the misuse tests call fmi2FreeInstance on a handle the importer hides

use std::ffi::{CStr, c_char, c_int, c_void};
use std::path::PathBuf;
use std::sync::Mutex;

use rins_fmi::fmu;
use rins_fmi::standard::FmiVersion;
use rins_fmi_import::{CallError, Fmu2, Instance2, parse_model_description};
use rins_imu_fmu::{RinsImu, library_file};

use crate::common;

fn library() -> Fmu2 {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().and_then(|d| d.parent()).unwrap();
    let so: PathBuf = dir.join(library_file(FmiVersion::V2));
    assert!(
        so.exists(),
        "{} missing: run `cargo build --release -p rins-imu-fmi2` before the tests",
        so.display()
    );
    let (guid, _, vars) =
        parse_model_description(&fmu::description::<RinsImu>(FmiVersion::V2).0).unwrap();
    Fmu2::load(&so, guid, vars).unwrap()
}

const DTHETA: [&str; 3] = [
    "imu.dtheta_rad[0]",
    "imu.dtheta_rad[1]",
    "imu.dtheta_rad[2]",
];

fn start<'a>(fmu: &'a Fmu2, seed: i32) -> Instance2<'a> {
    let inst = fmu.instantiate("t", false).unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    inst.set_integer(&[fmu.vr("run.seed").unwrap()], &[seed])
        .unwrap();
    // Turn on every stochastic term so that any cross-talk between instances shows.
    inst.set_boolean(
        &[fmu.vr("sensor.gyro.bias_instability.enabled").unwrap()],
        &[true],
    )
    .unwrap();
    inst.set_real(
        &[fmu.vr("sensor.gyro.bias_instability.sigma_dph[0]").unwrap()],
        &[0.01],
    )
    .unwrap();
    inst.enter_initialization_mode().unwrap();
    inst.exit_initialization_mode().unwrap();
    inst
}

fn step_n(fmu: &Fmu2, inst: &Instance2<'_>, t0: f64, n: usize) -> Vec<[f64; 3]> {
    let vrs: Vec<u32> = DTHETA.iter().map(|n| fmu.vr(n).unwrap()).collect();
    let mut out = Vec::with_capacity(n);
    let mut t = t0;
    for _ in 0..n {
        inst.do_step(t, 0.01).unwrap();
        let mut v = [0.0; 3];
        inst.get_real(&vrs, &mut v).unwrap();
        out.push(v);
        let mut ts = [0.0];
        inst.get_real(&[fmu.vr("imu.time_s").unwrap()], &mut ts)
            .unwrap();
        t = ts[0];
    }
    out
}

#[test]
fn two_instances_stepping_interleaved_equal_two_separate_runs() {
    let fmu = library();
    let separate_a = step_n(&fmu, &start(&fmu, 1), 0.0, 500);
    let separate_b = step_n(&fmu, &start(&fmu, 2), 0.0, 500);
    assert_ne!(separate_a, separate_b);
    let (a, b) = (start(&fmu, 1), start(&fmu, 2));
    let (mut ia, mut ib) = (Vec::new(), Vec::new());
    for k in 0..500 {
        let t = k as f64 * 0.01;
        ia.extend(step_n(&fmu, &a, t, 1));
        ib.extend(step_n(&fmu, &b, t, 1));
    }
    assert_eq!(ia, separate_a);
    assert_eq!(ib, separate_b);
}

#[test]
fn state_save_and_restore_replays_bit_identically() {
    let fmu = library();
    let inst = start(&fmu, 5);
    let _ = step_n(&fmu, &inst, 0.0, 1234);
    let saved = inst.get_state().unwrap();
    let first = step_n(&fmu, &inst, 12.34, 800);
    inst.set_state(&saved).unwrap();
    let again = step_n(&fmu, &inst, 12.34, 800);
    assert_eq!(first, again);
    // Serialised and deserialised in the same process: the same again.
    let bytes = inst.serialize_state(&saved).unwrap();
    let restored = inst.deserialize_state(&bytes).unwrap();
    inst.set_state(&restored).unwrap();
    assert_eq!(step_n(&fmu, &inst, 12.34, 800), first);
    inst.free_state(saved).unwrap();
    inst.free_state(restored).unwrap();
}

/// Child half of the cross-process test: restores the state given in a file and prints the
/// next outputs. Does nothing unless the parent set the variable.
#[test]
fn child_restores_serialized_state() {
    let Ok(path) = std::env::var("RINS_FMU_STATE_FILE") else {
        return;
    };
    let fmu = library();
    let inst = fmu.instantiate("child", false).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let s = inst.deserialize_state(&bytes).unwrap();
    inst.set_state(&s).unwrap();
    let out = step_n(&fmu, &inst, 12.34, 300);
    std::fs::write(format!("{path}.out"), format!("{out:?}")).unwrap();
}

#[test]
fn serialized_state_restores_in_a_new_process() {
    let fmu = library();
    let inst = start(&fmu, 9);
    let _ = step_n(&fmu, &inst, 0.0, 1234);
    let s = inst.get_state().unwrap();
    let bytes = inst.serialize_state(&s).unwrap();
    let expected = step_n(&fmu, &inst, 12.34, 300);
    let path = std::env::temp_dir().join(format!("rins-fmu-state-{}", std::process::id()));
    std::fs::write(&path, &bytes).unwrap();
    let status = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            // The test's name in the crate's one test binary (tests/imu/main.rs).
            "c_api::child_restores_serialized_state",
            "--test-threads=1",
        ])
        .env("RINS_FMU_STATE_FILE", &path)
        .status()
        .unwrap();
    assert!(status.success());
    let got = std::fs::read_to_string(format!("{}.out", path.display())).unwrap();
    assert_eq!(got, format!("{expected:?}"));
    let _ = std::fs::remove_file(&path);
    let _ = std::fs::remove_file(format!("{}.out", path.display()));
}

fn refused(r: Result<(), CallError>, reason: &str) {
    let e = r.expect_err("the call must be refused");
    assert_eq!(e.status, 3, "{e}");
    assert!(
        e.log.iter().any(|l| l.contains(reason)),
        "log {:?} lacks {reason:?}",
        e.log
    );
}

#[test]
fn bad_calls_return_errors_with_a_logged_reason_and_no_crash() {
    let fmu = library();
    // Wrong GUID: NULL instance, reason logged.
    let e = fmu
        .instantiate_with_guid("g", "{not-the-guid}", false)
        .err()
        .expect("refused");
    assert!(
        e.log.iter().any(|l| l.contains("does not match")),
        "{:?}",
        e.log
    );

    let inst = fmu.instantiate("bad", false).unwrap();
    // Wrong state: stepping before initialisation.
    refused(inst.do_step(0.0, 0.01), "not allowed in Instantiated mode");
    // Unknown value reference.
    refused(
        inst.set_real(&[999_999], &[1.0]),
        "unknown value reference 999999",
    );
    let bias = fmu.vr("sensor.gyro.bias.dph[0]").unwrap();
    // NaN and out-of-range parameters name the variable and range.
    refused(inst.set_real(&[bias], &[f64::NAN]), "NaN");
    refused(
        inst.set_real(&[bias], &[1e6]),
        "sensor.gyro.bias.dph[0] = 1000000 is outside its range [-100, 100]",
    );
    // Type mismatch.
    refused(
        inst.set_real(&[fmu.vr("run.seed").unwrap()], &[1.0]),
        "(run.seed) is an Integer variable, not a Real: set it with fmi2SetInteger",
    );
    // Enumeration out of its items.
    refused(
        inst.set_integer(&[fmu.vr("scheme.kind").unwrap()], &[99]),
        "not an item of SchemeKind",
    );
    inst.setup_experiment(0.0, None).unwrap();
    inst.enter_initialization_mode().unwrap();
    // A master carrying on after those refused sets cannot leave initialization mode: the
    // first refusal is named (issue 29). After a reset it can.
    refused(
        inst.exit_initialization_mode(),
        "cannot leave initialization mode: an earlier call setting a value was refused (fmi2SetReal: unknown value reference 999999",
    );
    inst.reset().unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    inst.enter_initialization_mode().unwrap();
    inst.exit_initialization_mode().unwrap();
    // Parameters are fixed after initialisation.
    refused(
        inst.set_real(&[bias], &[0.02]),
        "setting parameter sensor.gyro.bias.dph[0] is not allowed in Step mode",
    );
    // Outputs cannot be set.
    refused(
        inst.set_real(&[fmu.vr("imu.dtheta_rad[0]").unwrap()], &[0.0]),
        "is an output",
    );
    // A communication step that is not a whole number of 10 ms steps.
    refused(
        inst.do_step(0.0, 0.015),
        "not a whole positive number of internal steps",
    );
    // A step from the wrong time.
    refused(inst.do_step(5.0, 0.01), "but the FMU is at t = 0 s");
    // Still usable after all that.
    inst.do_step(0.0, 0.05).unwrap();
    let mut n = [0];
    inst.get_integer(&[fmu.vr("imu.sample_count").unwrap()], &mut n)
        .unwrap();
    assert_eq!(n[0], 5);
    // A configuration that fails whole-plant validation is refused at exit-initialisation.
    let inst2 = fmu.instantiate("bad2", false).unwrap();
    inst2
        .set_real(&[fmu.vr("thermal.step_s").unwrap()], &[0.015])
        .unwrap();
    inst2.enter_initialization_mode().unwrap();
    let e = inst2.exit_initialization_mode().expect_err("refused");
    assert!(
        e.log.iter().any(|l| l.contains("thermal.step_s")),
        "{:?}",
        e.log
    );
}

#[test]
fn gimbal_command_inputs_drive_the_table() {
    let fmu = library();
    let inst = fmu.instantiate("cmd", false).unwrap();
    inst.set_integer(&[fmu.vr("scheme.kind").unwrap()], &[4])
        .unwrap(); // static
    inst.enter_initialization_mode().unwrap();
    inst.exit_initialization_mode().unwrap();
    inst.set_boolean(&[fmu.vr("input.gimbal_command").unwrap()], &[true])
        .unwrap();
    inst.set_real(
        &[
            fmu.vr("input.gimbal_inner_deg").unwrap(),
            fmu.vr("input.gimbal_rate_dps").unwrap(),
        ],
        &[180.0, 10.0],
    )
    .unwrap();
    // 18 s cruise plus 0.5 s for the 20 °/s² ramps.
    inst.do_step(0.0, 20.0).unwrap();
    let mut g = [0.0; 2];
    inst.get_real(
        &[
            fmu.vr("gimbal.inner_rad").unwrap(),
            fmu.vr("effect.position_weight").unwrap(),
        ],
        &mut g,
    )
    .unwrap();
    assert_eq!(g[0], std::f64::consts::PI);
    // Z-down after the flip: full position-dependent bias weight (Eq. 9).
    assert!((g[1] - 1.0).abs() < 1e-12, "{}", g[1]);
}

/// The 34 functions of fmi2Functions.h a co-simulation FMU exports (FMI 2.0.4).
const FMI2_FUNCTIONS: [&str; 34] = [
    "fmi2GetTypesPlatform",
    "fmi2GetVersion",
    "fmi2SetDebugLogging",
    "fmi2Instantiate",
    "fmi2FreeInstance",
    "fmi2SetupExperiment",
    "fmi2EnterInitializationMode",
    "fmi2ExitInitializationMode",
    "fmi2Terminate",
    "fmi2Reset",
    "fmi2GetReal",
    "fmi2GetInteger",
    "fmi2GetBoolean",
    "fmi2GetString",
    "fmi2SetReal",
    "fmi2SetInteger",
    "fmi2SetBoolean",
    "fmi2SetString",
    "fmi2GetFMUstate",
    "fmi2SetFMUstate",
    "fmi2FreeFMUstate",
    "fmi2SerializedFMUstateSize",
    "fmi2SerializeFMUstate",
    "fmi2DeSerializeFMUstate",
    "fmi2GetDirectionalDerivative",
    "fmi2SetRealInputDerivatives",
    "fmi2GetRealOutputDerivatives",
    "fmi2DoStep",
    "fmi2CancelStep",
    "fmi2GetStatus",
    "fmi2GetRealStatus",
    "fmi2GetIntegerStatus",
    "fmi2GetBooleanStatus",
    "fmi2GetStringStatus",
];

fn exported(lib: &str) -> Vec<String> {
    let exe = std::env::current_exe().unwrap();
    let so = exe.parent().and_then(|d| d.parent()).unwrap().join(lib);
    let out = std::process::Command::new("nm")
        .args(["-D", "--defined-only"])
        .arg(&so)
        .output()
        .expect("nm (binutils) is installed");
    assert!(
        out.status.success(),
        "nm {}: {}",
        so.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| l.split_whitespace().nth(2).map(str::to_string))
        .collect()
}

#[test]
fn the_libraries_export_exactly_the_fmi_functions() {
    let mut fmi2 = exported(library_file(FmiVersion::V2));
    fmi2.sort();
    let mut want: Vec<String> = FMI2_FUNCTIONS.iter().map(|s| s.to_string()).collect();
    want.sort();
    assert_eq!(
        fmi2, want,
        "the FMI 2 library exports the 34 functions and nothing else"
    );
    let fmi3 = exported(library_file(FmiVersion::V3));
    assert_eq!(fmi3.len(), 75, "{fmi3:?}");
    assert!(fmi3.iter().all(|s| s.starts_with("fmi3")), "{fmi3:?}");
    for f in [
        "fmi3InstantiateCoSimulation",
        "fmi3DoStep",
        "fmi3GetFloat64",
        "fmi3SerializeFMUState",
        "fmi3InstantiateModelExchange",
        "fmi3ActivateModelPartition",
    ] {
        assert!(fmi3.iter().any(|s| s == f), "{f} missing");
    }
}

/// B1: `scheme.accel_dps2 = inf` is valid (as in scenario files) and must initialise; the FMU
/// then equals the in-process plant with the same configuration through a move.
#[test]
fn infinite_gimbal_acceleration_initialises_and_matches_the_plant() {
    let fmu = library();
    let inst = fmu.instantiate("inf", false).unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    inst.set_real(&[fmu.vr("scheme.accel_dps2").unwrap()], &[f64::INFINITY])
        .unwrap();
    inst.enter_initialization_mode().unwrap();
    inst.exit_initialization_mode().unwrap();
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.scheme.accel_dps2 = f64::INFINITY;
    let mut plant = rins_plant::Plant::new(&cfg).unwrap();
    let vrs: Vec<u32> = DTHETA.iter().map(|n| fmu.vr(n).unwrap()).collect();
    let rate = [fmu.vr("gimbal.outer_rate_rps").unwrap()];
    let (mut v, mut r, mut peak_rate) = ([0.0; 3], [0.0], 0.0f64);
    // The first dwell is 180 s; the move after it starts at full rate (no ramp).
    for k in 0..19_000u64 {
        let s = plant.step();
        inst.do_step(k as f64 * 0.01, 0.01).unwrap();
        inst.get_real(&vrs, &mut v).unwrap();
        assert_eq!(
            v,
            [s.dtheta_rad.x, s.dtheta_rad.y, s.dtheta_rad.z],
            "sample {k}"
        );
        inst.get_real(&rate, &mut r).unwrap();
        peak_rate = peak_rate.max(r[0].abs());
    }
    assert!(peak_rate > 0.0, "the run covers a move");
}

/// B2: fmi2SetupExperiment is allowed only right after instantiation: in initialization mode
/// it is refused with a logged reason and the start time stays.
#[test]
fn setup_experiment_in_initialization_mode_is_refused_and_keeps_the_start_time() {
    let fmu = library();
    let inst = fmu.instantiate("setup", false).unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    inst.enter_initialization_mode().unwrap();
    refused(
        inst.setup_experiment(5.0, None),
        "setting the start time is not allowed in Initialization mode",
    );
    inst.exit_initialization_mode().unwrap();
    assert_eq!(inst.last_successful_time().unwrap(), 0.0);
    inst.do_step(0.0, 0.01).unwrap();
    assert_eq!(inst.last_successful_time().unwrap(), 0.01);
}

/// B3: fmi2GetString with valid arrays names the real problem (the variable is not a String),
/// not a NULL array; zero references are fine.
#[test]
fn get_string_with_valid_arrays_reports_the_type() {
    let fmu = library();
    let inst = fmu.instantiate("str", false).unwrap();
    inst.enter_initialization_mode().unwrap();
    let mut out = [std::ptr::null(); 1];
    let e = inst
        .get_string(&[fmu.vr("imu.time_s").unwrap()], &mut out)
        .expect_err("no String variables");
    assert_eq!(e.status, 3, "{e}");
    assert!(
        e.log
            .iter()
            .any(|l| l.contains("(imu.time_s) is a Real variable, not a String (this FMU has none): read it with fmi2GetReal")),
        "{:?}",
        e.log
    );
    assert!(
        !e.log.iter().any(|l| l.contains("NULL array")),
        "{:?}",
        e.log
    );
    inst.get_string(&[], &mut []).unwrap();
}

/// The FMI 2 logger, as the importer declares it: the FMU calls it as a C variadic function and
/// passes no arguments after the message, so the fixed ones are all there is to read.
unsafe extern "C" fn collect_log(
    env: *mut c_void,
    _name: *const c_char,
    status: c_int,
    _category: *const c_char,
    message: *const c_char,
) {
    if env.is_null() || message.is_null() {
        return;
    }
    // SAFETY: `env` is the Mutex the test passed at instantiation; the message is a C string.
    let sink = unsafe { &*(env as *const Mutex<Vec<String>>) };
    let m = unsafe { CStr::from_ptr(message) }.to_string_lossy();
    sink.lock().unwrap().push(format!("[{status}] {m}"));
}

/// `fmi2CallbackFunctions` with only the logger.
#[repr(C)]
struct Callbacks {
    logger: Option<
        unsafe extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char),
    >,
    allocate: *const c_void,
    free: *const c_void,
    step_finished: *const c_void,
    env: *mut c_void,
}

/// A caller's misuse (issue 44): fmi2FreeInstance twice, then fmi2DoStep and fmi2Reset on the
/// freed instance. The second free does nothing (a double free would abort this process with
/// "double free or corruption"), the calls return fmi2Error, and nothing is logged for them:
/// the instance's logger went with it, and the FMU cannot tell whose the pointer was.
#[test]
fn a_double_free_and_calls_on_a_freed_instance_are_refused_and_the_process_survives() {
    type Instantiate = unsafe extern "C" fn(
        *const c_char,
        c_int,
        *const c_char,
        *const c_char,
        *const Callbacks,
        c_int,
        c_int,
    ) -> *mut c_void;
    type Call = unsafe extern "C" fn(*mut c_void) -> c_int;
    type Free = unsafe extern "C" fn(*mut c_void);
    type Setup = unsafe extern "C" fn(*mut c_void, c_int, f64, f64, c_int, f64) -> c_int;
    type DoStep = unsafe extern "C" fn(*mut c_void, f64, f64, c_int) -> c_int;
    let guid =
        std::ffi::CString::new(fmu::description::<RinsImu>(FmiVersion::V2).1.clone()).unwrap();
    let log = Mutex::new(Vec::<String>::new());
    let callbacks = Callbacks {
        logger: Some(collect_log),
        allocate: std::ptr::null(),
        free: std::ptr::null(),
        step_finished: std::ptr::null(),
        env: &log as *const Mutex<Vec<String>> as *mut c_void,
    };
    // SAFETY: each symbol is read with its fmi2Functions.h type; `callbacks` and `log` outlive
    // the instance. The calls after the first free are the misuse under test, which the FMU
    // must refuse without touching memory.
    unsafe {
        let lib = libloading::Library::new(common::library_path(FmiVersion::V2)).unwrap();
        let instantiate: libloading::Symbol<Instantiate> = lib.get(b"fmi2Instantiate").unwrap();
        let free: libloading::Symbol<Free> = lib.get(b"fmi2FreeInstance").unwrap();
        let setup: libloading::Symbol<Setup> = lib.get(b"fmi2SetupExperiment").unwrap();
        let enter: libloading::Symbol<Call> = lib.get(b"fmi2EnterInitializationMode").unwrap();
        let exit: libloading::Symbol<Call> = lib.get(b"fmi2ExitInitializationMode").unwrap();
        let reset: libloading::Symbol<Call> = lib.get(b"fmi2Reset").unwrap();
        let do_step: libloading::Symbol<DoStep> = lib.get(b"fmi2DoStep").unwrap();
        let start = |name: &std::ffi::CStr| {
            let c = instantiate(
                name.as_ptr(),
                1,
                guid.as_ptr(),
                std::ptr::null(),
                &callbacks,
                0,
                1,
            );
            assert!(!c.is_null(), "{:?}", log.lock().unwrap());
            assert_eq!(setup(c, 0, 0.0, 0.0, 0, 0.0), 0);
            assert_eq!(enter(c), 0);
            assert_eq!(exit(c), 0);
            c
        };
        let c = start(c"freed");
        assert_eq!(do_step(c, 0.0, 0.01, 1), 0);
        free(c);
        log.lock().unwrap().clear();
        free(c);
        assert_eq!(
            do_step(c, 0.01, 0.01, 1),
            3,
            "fmi2DoStep on a freed instance"
        );
        assert_eq!(reset(c), 3, "fmi2Reset on a freed instance");
        free(c);
        assert_eq!(*log.lock().unwrap(), Vec::<String>::new());
        // The library still works: a new instance steps.
        let c = start(c"after");
        assert_eq!(do_step(c, 0.0, 0.01, 1), 0);
        free(c);
    }
}
