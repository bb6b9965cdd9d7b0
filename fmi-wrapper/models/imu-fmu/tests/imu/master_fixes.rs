//! What connecting the FMUs in libcosim and ecos exposed (issues 17 and 29), tested on the
//! built binaries: initial outputs in initialization mode (the temperature readings included),
//! chamber inputs reaching the initial state and later steps, Integer codes of the enumerations, FMI 3 `nValues` validated before
//! anything is written and no step after an error, the logEvents messages, and a table of
//! fault sequences run through both FMI versions (a refused set blocks the end of
//! initialisation, a refused step leaves NaN increments, and what each refusal says).
//!
//! Needs the cdylibs: `cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3`.

#![allow(unsafe_code)] // the FMI 3 binary through C function pointers

use std::ffi::{CStr, CString, c_char, c_void};
use std::sync::Mutex;

use rins_fmi::fmu;
use rins_fmi::standard::FmiVersion;
use rins_fmi_import::{Fmu2, Instance2, parse_model_description};
use rins_imu_fmu::RinsImu;
use rins_plant::Plant;
use rins_plant::thermal::node;

use crate::common;
use crate::common::{Fmi3, Inst};

fn library() -> Fmu2 {
    let (guid, _, vars) =
        parse_model_description(&fmu::description::<RinsImu>(FmiVersion::V2).0).unwrap();
    Fmu2::load(&common::library_path(FmiVersion::V2), guid, vars).unwrap()
}

/// The thermal outputs: every node, then the chamber.
fn thermal_names() -> Vec<String> {
    node::NAMES
        .iter()
        .map(|n| format!("thermal.{n}_c"))
        .chain(["thermal.chamber_c".to_string()])
        .collect()
}

fn thermal(fmu: &Fmu2, inst: &Instance2<'_>) -> Vec<f64> {
    let vrs: Vec<u32> = thermal_names().iter().map(|n| fmu.vr(n).unwrap()).collect();
    let mut v = vec![0.0; vrs.len()];
    inst.get_real(&vrs, &mut v).unwrap();
    v
}

/// The in-process plant's initial node and chamber temperatures at chamber `chamber_c`.
fn plant_initial(chamber_c: f64) -> Vec<f64> {
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.thermal.chamber.temp_c = chamber_c;
    let p = Plant::new(&cfg).unwrap();
    let t = p.truth().temps;
    t.nodes_c.iter().copied().chain([t.chamber_c]).collect()
}

fn set_chamber(fmu: &Fmu2, inst: &Instance2<'_>, temp_c: f64) {
    inst.set_boolean(&[fmu.vr("input.chamber_override").unwrap()], &[true])
        .unwrap();
    inst.set_real(&[fmu.vr("input.chamber_temp_c").unwrap()], &[temp_c])
        .unwrap();
}

#[test]
fn thermal_outputs_read_in_initialization_mode_are_the_initial_state() {
    let fmu = library();
    let at25 = plant_initial(25.0);
    // The steady state is well above the chamber (self-heating): not the start value 0.
    assert!(at25[node::BOARD] > 26.0, "{at25:?}");
    let inst = fmu.instantiate("init", false).unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    inst.enter_initialization_mode().unwrap();
    assert_eq!(thermal(&fmu, &inst), at25, "initialization mode, defaults");
    // A chamber input set during initialization mode is the initial chamber temperature.
    set_chamber(&fmu, &inst, 35.0);
    let at35 = plant_initial(35.0);
    assert_eq!(
        thermal(&fmu, &inst),
        at35,
        "initialization mode, chamber 35"
    );
    inst.exit_initialization_mode().unwrap();
    assert_eq!(thermal(&fmu, &inst), at35, "after initialization");
    // The first thermal update is after 1 s: the first step keeps the initial state.
    inst.do_step(0.0, 0.01).unwrap();
    assert_eq!(thermal(&fmu, &inst), at35, "after the first step");
}

/// The temperature sensors' readings (`imu.temp_*_c`, what a master initialising a
/// controller reads) in initialization mode, after a parameter set, are those of the initial
/// state, not 0, through both binaries.
#[test]
fn temperature_readings_in_initialization_mode_are_the_initial_states() {
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.thermal.chamber.temp_c = 35.0;
    let want = Plant::new(&cfg).unwrap().temp_readings_c().to_vec();
    assert!(want[node::HOUSING] > 35.0, "{want:?}");
    let names: Vec<String> = node::NAMES
        .iter()
        .map(|n| format!("imu.temp_{n}_c"))
        .collect();
    // FMI 2: between fmi2EnterInitializationMode and fmi2ExitInitializationMode.
    let fmu = library();
    let inst = fmu.instantiate("readings", false).unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    inst.set_real(&[fmu.vr("thermal.chamber.temp_c").unwrap()], &[35.0])
        .unwrap();
    inst.enter_initialization_mode().unwrap();
    let vrs: Vec<u32> = names.iter().map(|n| fmu.vr(n).unwrap()).collect();
    let mut got = vec![0.0; vrs.len()];
    inst.get_real(&vrs, &mut got).unwrap();
    assert_eq!(got, want, "FMI 2, initialization mode");
    inst.exit_initialization_mode().unwrap();
    inst.get_real(&vrs, &mut got).unwrap();
    assert_eq!(got, want, "FMI 2, after initialization");
    // FMI 3 likewise.
    let xml = &fmu::description::<RinsImu>(FmiVersion::V3).0;
    let vr = |n: &str| attr(xml, n, "valueReference").parse::<u32>().unwrap();
    let vrs: Vec<u32> = names.iter().map(|n| vr(n)).collect();
    let chamber = vr("thermal.chamber.temp_c");
    let f = Fmi3::load();
    let log = Mutex::new(Vec::new());
    let c = fmi3_instance(&f, &log, false);
    let mut got = vec![0.0; vrs.len()];
    // SAFETY: fmi3Functions.h signatures on a live instance, arrays of the lengths passed.
    unsafe {
        assert_eq!((f.set_f64)(c, &chamber, 1, &35.0, 1), 0);
        assert_eq!((f.enter_init)(c, false, 0.0, 0.0, false, 0.0), 0);
        let n = vrs.len();
        assert_eq!((f.get_f64)(c, vrs.as_ptr(), n, got.as_mut_ptr(), n), 0);
        assert_eq!(got, want, "FMI 3, initialization mode");
        assert_eq!((f.exit_init)(c), 0);
        assert_eq!((f.terminate)(c), 0);
        (f.free)(c);
    }
}

#[test]
fn a_chamber_input_set_before_initialization_reaches_the_initial_state() {
    let fmu = library();
    let inst = fmu.instantiate("before", false).unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    set_chamber(&fmu, &inst, 15.0);
    inst.enter_initialization_mode().unwrap();
    inst.exit_initialization_mode().unwrap();
    assert_eq!(thermal(&fmu, &inst), plant_initial(15.0));
    // A saved state carries the start temperature (it is part of the configuration).
    inst.do_step(0.0, 2.0).unwrap();
    let s = inst.get_state().unwrap();
    let bytes = inst.serialize_state(&s).unwrap();
    let other = fmu.instantiate("other", false).unwrap();
    let d = other.deserialize_state(&bytes).unwrap();
    other.set_state(&d).unwrap();
    inst.do_step(2.0, 1.0).unwrap();
    other.do_step(2.0, 1.0).unwrap();
    assert_eq!(thermal(&fmu, &inst), thermal(&fmu, &other));
}

/// Steps of 10 ms from `t0` to `t1` (tick counts, so the times are exact multiples).
fn run(inst: &Instance2<'_>, from: u64, to: u64) {
    for k in from..to {
        inst.do_step(k as f64 / 100.0, 0.01).unwrap();
    }
}

#[test]
fn a_chamber_input_acts_at_the_step_it_is_set_for() {
    let fmu = library();
    let chamber = fmu.vr("thermal.chamber_c").unwrap();
    let housing = fmu
        .vr(&format!("thermal.{}_c", node::NAMES[node::HOUSING]))
        .unwrap();
    let read = |inst: &Instance2<'_>, vr| {
        let mut v = [0.0];
        inst.get_real(&[vr], &mut v).unwrap();
        v[0]
    };
    let start = |name| {
        let inst = fmu.instantiate(name, false).unwrap();
        inst.setup_experiment(0.0, None).unwrap();
        inst.enter_initialization_mode().unwrap();
        inst.exit_initialization_mode().unwrap();
        inst
    };
    // Set at t = 100.00 s, a thermal update time: in effect in the step from 100.00 s.
    let a = start("a");
    run(&a, 0, 10_000);
    assert_eq!(read(&a, chamber), 25.0);
    let h0 = read(&a, housing);
    set_chamber(&fmu, &a, 40.0);
    run(&a, 10_000, 10_001);
    assert_eq!(read(&a, chamber), 40.0, "first step after 100.00 s");
    assert!(read(&a, housing) > h0, "the housing warms in that step");
    // Set at t = 100.37 s, between the 1 s updates: in effect in the step from 100.37 s too
    // (the thermal step ends early there), and the housing warms in that step.
    let b = start("b");
    run(&b, 0, 10_037);
    let h0 = read(&b, housing);
    set_chamber(&fmu, &b, 40.0);
    run(&b, 10_037, 10_038);
    assert_eq!(read(&b, chamber), 40.0, "in the step from 100.37 s");
    assert!(read(&b, housing) > h0, "the housing warms in that step");
    // The same value set again is no change: no extra update, the grid (from 100.37 s) holds.
    let h1 = read(&b, housing);
    set_chamber(&fmu, &b, 40.0);
    run(&b, 10_038, 10_137);
    assert_eq!(read(&b, housing), h1, "held until 101.37 s");
    run(&b, 10_137, 10_138);
    assert!(read(&b, housing) > h1, "the update at 101.37 s");
}

/// A chamber input set mid-second (t = 100.005 s, at 200 Hz) against the closed form of one
/// backward-Euler step of a single RC node (the housing, every internal link cut and no
/// power): C·(T⁺ − T)/h = G·(T_ch − T⁺), so T⁺ = (C/h·T + G·T_ch) / (C/h + G), over the
/// h = 5 ms since the 100.000 s update, then over the full 1 s step at 101.005 s.
#[test]
fn a_chamber_input_set_mid_second_follows_the_closed_form_of_one_thermal_step() {
    let fmu = library();
    let vr = |n: &str| fmu.vr(n).unwrap();
    let read = |inst: &Instance2<'_>, name: &str| {
        let mut v = [0.0];
        inst.get_real(&[vr(name)], &mut v).unwrap();
        v[0]
    };
    let inst = fmu.instantiate("mid", false).unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    inst.set_real(&[vr("run.rate_hz")], &[200.0]).unwrap();
    let mut cut: Vec<String> = (0..6).map(|i| format!("thermal.power_w[{i}]")).collect();
    for a in [
        "g_gyro_housing_w_per_k",
        "g_board_gyro_w_per_k",
        "g_board_gyro_convection_w_per_k",
    ] {
        cut.extend((0..3).map(|i| format!("thermal.{a}[{i}]")));
    }
    cut.extend(
        [
            "g_board_housing_w_per_k",
            "g_accel_housing_w_per_k",
            "g_gyro_gyro_w_per_k",
        ]
        .map(|a| format!("thermal.{a}")),
    );
    for n in &cut {
        inst.set_real(&[vr(n)], &[0.0]).unwrap();
    }
    inst.enter_initialization_mode().unwrap();
    inst.exit_initialization_mode().unwrap();
    let c = read(
        &inst,
        &format!("thermal.capacitance_j_per_k[{}]", node::HOUSING),
    );
    let g = read(&inst, "thermal.g_housing_chamber_w_per_k");
    let hname = format!("thermal.{}_c", node::NAMES[node::HOUSING]);
    let step = |from: u64, to: u64| {
        for k in from..to {
            inst.do_step(k as f64 / 200.0, 0.005).unwrap();
        }
    };
    step(0, 20_001); // to 100.005 s
    let t0 = read(&inst, &hname);
    assert_eq!(
        t0, 25.0,
        "no power: the housing sits at the chamber temperature"
    );
    set_chamber(&fmu, &inst, 40.0);
    step(20_001, 20_002);
    let (h, t_ch) = (0.005, 40.0);
    let t1 = (c / h * t0 + g * t_ch) / (c / h + g);
    assert_eq!(read(&inst, "thermal.chamber_c"), 40.0);
    let got = read(&inst, &hname);
    assert!(
        (got - t1).abs() <= 1e-12 * t1,
        "first step after 100.005 s: {got} vs closed form {t1}"
    );
    // 15 K × G·h/C = 4.5e-5 K in 5 ms.
    assert!(got > t0 + 4e-5, "the housing warmed: {got}");
    // The other nodes are cut off: they stay at 25 °C.
    assert_eq!(read(&inst, "thermal.board_c"), 25.0);
    // The grid restarts at 100.005 s: held until 101.005 s, then one full 1 s step.
    step(20_002, 20_201);
    assert_eq!(read(&inst, &hname), got, "held until 101.005 s");
    step(20_201, 20_202);
    let t2 = (c * got + g * t_ch) / (c + g);
    let got2 = read(&inst, &hname);
    assert!((got2 - t2).abs() <= 1e-12 * t2, "{got2} vs {t2}");
}

#[test]
fn an_enumeration_is_set_through_its_integer_code() {
    let fmu = library();
    let outputs: Vec<u32> = ["gimbal.outer_rad", "gimbal.inner_rad", "imu.dtheta_rad[2]"]
        .iter()
        .map(|n| fmu.vr(n).unwrap())
        .collect();
    let run_with = |set: &dyn Fn(&Instance2<'_>)| {
        let inst = fmu.instantiate("enum", false).unwrap();
        inst.setup_experiment(0.0, None).unwrap();
        set(&inst);
        inst.enter_initialization_mode().unwrap();
        inst.exit_initialization_mode().unwrap();
        inst.do_step(0.0, 400.0).unwrap();
        let mut v = vec![0.0; outputs.len()];
        inst.get_real(&outputs, &mut v).unwrap();
        let mut kind = [0];
        inst.get_integer(&[fmu.vr("scheme.kind").unwrap()], &mut kind)
            .unwrap();
        (v, kind[0])
    };
    // 4 = static: the table stays at its start angles.
    let by_code = run_with(&|i| {
        i.set_integer(&[fmu.vr("scheme.kind_code").unwrap()], &[4])
            .unwrap()
    });
    let by_enum = run_with(&|i| {
        i.set_integer(&[fmu.vr("scheme.kind").unwrap()], &[4])
            .unwrap()
    });
    let default = run_with(&|_| {});
    assert_eq!(by_code, by_enum);
    assert_eq!(by_code.1, 4);
    assert_eq!(default.1, 1);
    assert_ne!(
        by_code.0, default.0,
        "the 16-position table has moved by 400 s"
    );
    // Codes outside the items are refused with the valid values.
    let inst = fmu.instantiate("bad", true).unwrap();
    let e = inst
        .set_integer(&[fmu.vr("scheme.axis_code").unwrap()], &[3])
        .unwrap_err();
    assert!(format!("{e}").contains("outside its range [1, 2]"), "{e}");
}

unsafe extern "C" fn logger(env: *mut c_void, _s: i32, _c: *const c_char, msg: *const c_char) {
    if env.is_null() || msg.is_null() {
        return;
    }
    // SAFETY: `env` is the Mutex given at instantiation; the message is NUL-terminated.
    let sink = unsafe { &*(env as *const Mutex<Vec<String>>) };
    let m = unsafe { CStr::from_ptr(msg) }
        .to_string_lossy()
        .into_owned();
    sink.lock().unwrap().push(m);
}

fn attr(xml: &str, name: &str, key: &str) -> String {
    let tag = &xml[xml.find(&format!("name=\"{name}\"")).unwrap()..];
    let i = tag.find(&format!(" {key}=\"")).unwrap() + key.len() + 3;
    tag[i..].split('"').next().unwrap().to_string()
}

/// A new FMI 3 instance logging into `log`.
fn fmi3_instance(f: &Fmi3, log: &Mutex<Vec<String>>, logging_on: bool) -> Inst {
    let xml = &fmu::description::<RinsImu>(FmiVersion::V3).0;
    let i = xml.find("instantiationToken=\"").unwrap() + 20;
    let token = CString::new(xml[i..].split('"').next().unwrap()).unwrap();
    let name = CString::new("fixes").unwrap();
    // SAFETY: fmi3Functions.h signature; the strings are copied, the log outlives the
    // instance.
    let c = unsafe {
        (f.instantiate)(
            name.as_ptr(),
            token.as_ptr(),
            std::ptr::null(),
            false,
            logging_on,
            false,
            false,
            std::ptr::null(),
            0,
            log as *const Mutex<Vec<String>> as *mut c_void,
            Some(logger),
            std::ptr::null(),
        )
    };
    assert!(!c.is_null());
    c
}

fn step3(f: &Fmi3, c: Inst, t: f64) -> i32 {
    let (mut a, mut b, mut e, mut last) = (false, false, false, 0.0);
    // SAFETY: live instance, valid out-pointers.
    unsafe { (f.do_step)(c, t, 0.01, false, &mut a, &mut b, &mut e, &mut last) }
}

#[test]
fn log_events_reports_mode_changes_and_every_step() {
    let f = Fmi3::load();
    for on in [true, false] {
        let log = Mutex::new(Vec::new());
        let c = fmi3_instance(&f, &log, on);
        // SAFETY: fmi3Functions.h signatures on a live instance.
        unsafe {
            assert_eq!((f.enter_init)(c, false, 0.0, 0.0, false, 0.0), 0);
            assert_eq!((f.exit_init)(c), 0);
            assert_eq!(step3(&f, c, 0.0), 0);
            assert_eq!(step3(&f, c, 0.01), 0);
            assert_eq!((f.terminate)(c), 0);
            (f.free)(c);
        }
        let log = log.lock().unwrap().join("\n");
        if !on {
            assert!(log.is_empty(), "without loggingOn: {log}");
            continue;
        }
        for m in [
            "instantiated",
            "initialization mode",
            "initialized; step mode",
            "doStep from t = 0 s by 0.01 s; now at t = 0.01 s",
            "doStep from t = 0.01 s by 0.01 s; now at t = 0.02 s",
            "terminated",
        ] {
            assert!(log.contains(m), "{m:?} not in\n{log}");
        }
    }
}

#[test]
fn fmi3_refuses_a_short_value_count_before_writing_and_steps_after_an_error() {
    let xml = &fmu::description::<RinsImu>(FmiVersion::V3).0;
    let vr = |n: &str| attr(xml, n, "valueReference").parse::<u32>().unwrap();
    let (dtheta, bias, lat) = (
        vr("imu.dtheta_rad"),
        vr("sensor.gyro.bias.dph"),
        vr("site.lat_deg"),
    );
    let f = Fmi3::load();
    let log = Mutex::new(Vec::new());
    let c = fmi3_instance(&f, &log, false);
    let step = |t: f64| step3(&f, c, t);
    // SAFETY (whole test): fmi3Functions.h signatures on a live instance, arrays of the
    // lengths passed.
    unsafe {
        // A set with a valid first value and a bad later one sets nothing.
        assert_eq!((f.enter_init)(c, false, 0.0, 0.0, false, 0.0), 0);
        let vrs = [lat, bias];
        let vals = [10.0, 0.01, f64::NAN, 0.02];
        assert_eq!((f.set_f64)(c, vrs.as_ptr(), 2, vals.as_ptr(), 4), 3);
        let mut back = [0.0];
        assert_eq!((f.get_f64)(c, &lat, 1, back.as_mut_ptr(), 1), 0);
        assert_eq!(back[0], 36.6, "the valid first value was not set");
        // Refused from then on until reset.
        assert_eq!((f.exit_init)(c), 3, "error mode after the refused set");
        assert_eq!((f.reset)(c), 0);
        assert_eq!((f.enter_init)(c, false, 0.0, 0.0, false, 0.0), 0);
        assert_eq!((f.exit_init)(c), 0);
        assert_eq!(step(0.0), 0);
        // nValues 1 for a 3-element array (as ecos asks): nothing written, then no step.
        let mut out = [-7.0; 3];
        assert_eq!((f.get_f64)(c, &dtheta, 1, out.as_mut_ptr(), 1), 3);
        assert_eq!(out, [-7.0; 3], "nothing written");
        assert_eq!(step(0.01), 3, "a step after the error is refused");
        let msgs = log.lock().unwrap().join("\n");
        assert!(
            msgs.contains("nValues = 1, but the value references hold 3 values"),
            "{msgs}"
        );
        assert!(
            msgs.contains("doStep is refused: the instance is in the error state"),
            "{msgs}"
        );
        // Reset: usable again.
        assert_eq!((f.reset)(c), 0);
        assert_eq!((f.enter_init)(c, false, 0.0, 0.0, false, 0.0), 0);
        assert_eq!((f.exit_init)(c), 0);
        assert_eq!(step(0.0), 0);
        assert_eq!((f.get_f64)(c, &dtheta, 1, out.as_mut_ptr(), 3), 0);
        assert!(out.iter().all(|x| x.abs() < 1e-3), "{out:?}");
        (f.free)(c);
    }
}

/// One call of a fault sequence and the status it must return (0 OK, 3 error).
#[derive(Clone, Copy, Debug)]
enum Op {
    /// Set a Real / Float64 variable.
    Set(&'static str, f64, i32),
    /// Enter initialization mode (FMI 2: setupExperiment at 0 s first).
    Enter(i32),
    /// Exit initialization mode.
    Exit(i32),
    /// doStep from `t` by 0.01 s.
    Step(f64, i32),
    /// Read Real / Float64 variables (one value each): all NaN (`true`) or all finite.
    Nan(&'static [&'static str], bool),
    /// Read a Real variable with an integer getter (fmi2GetInteger / fmi3GetInt32).
    IntOfReal(&'static str, i32),
    /// Read an Integer / UInt64 variable with the Real getter (fmi2GetReal / fmi3GetFloat64).
    RealOfInt(&'static str, i32),
}

/// A fault sequence: FMI version, calls, and what the log must say (`{vr:NAME}` stands for
/// NAME's value reference in that version).
struct Fault {
    name: &'static str,
    version: FmiVersion,
    ops: &'static [Op],
    log: &'static [&'static str],
}

const INCREMENTS: &[&str] = &[
    "imu.dtheta_rad[0]",
    "imu.dtheta_rad[2]",
    "imu.dv_mps[1]",
    "truth.dtheta_rad[0]",
    "truth.dv_mps[2]",
    "effect.gyro.angle_random_walk_rad[0]",
];
/// States at the FMU's time: still valid after a refused step.
const STATES: &[&str] = &["imu.time_s", "thermal.board_c", "truth.q_bn[0]"];
const BAD_BIAS: Op = Op::Set("sensor.gyro.bias.dph[0]", 1e6, 3);

const FAULTS: &[Fault] = &[
    Fault {
        name: "refused parameter set, master carries on: every step refused, increments NaN",
        version: FmiVersion::V2,
        ops: &[
            BAD_BIAS,
            Op::Enter(0),
            Op::Exit(3),
            Op::Step(0.0, 3),
            Op::Nan(INCREMENTS, true),
            Op::Nan(STATES, false),
        ],
        log: &[
            "fmi2SetReal: sensor.gyro.bias.dph[0] = 1000000 is outside its range",
            "fmi2ExitInitializationMode: cannot leave initialization mode: an earlier call setting a value was refused (fmi2SetReal: sensor.gyro.bias.dph[0] = 1000000 is outside its range",
            "reset the instance and set valid values",
            "fmi2DoStep: doStep is refused: the instance is in the error state",
        ],
    },
    Fault {
        name: "refused parameter set, master carries on: every step refused, increments NaN",
        version: FmiVersion::V3,
        ops: &[
            BAD_BIAS,
            Op::Enter(3),
            Op::Exit(3),
            Op::Step(0.0, 3),
            Op::Nan(INCREMENTS, true),
            Op::Nan(STATES, false),
        ],
        log: &[
            "fmi3SetFloat64: sensor.gyro.bias.dph[0] = 1000000 is outside its range",
            "fmi3EnterInitializationMode: entering initialization mode is refused: the instance is in the error state after an earlier call failed",
            "only reset, free, reading values and getting, setting or serializing the FMU state are allowed",
            "fmi3ExitInitializationMode: exiting initialization mode is refused: the instance is in the error state",
        ],
    },
    Fault {
        name: "refused step (wrong time): increments NaN, states kept; FMI 2 steps on",
        version: FmiVersion::V2,
        ops: &[
            Op::Enter(0),
            Op::Exit(0),
            Op::Step(0.0, 0),
            Op::Nan(INCREMENTS, false),
            Op::Step(0.5, 3),
            Op::Nan(INCREMENTS, true),
            Op::Nan(STATES, false),
            Op::Step(0.01, 0),
            Op::Nan(INCREMENTS, false),
        ],
        log: &["fmi2DoStep: doStep from t = 0.5 s, but the FMU is at t = 0.01 s"],
    },
    Fault {
        name: "refused step (wrong time): increments NaN, states kept; FMI 3 stays refused",
        version: FmiVersion::V3,
        ops: &[
            Op::Enter(0),
            Op::Exit(0),
            Op::Step(0.0, 0),
            Op::Nan(INCREMENTS, false),
            Op::Step(0.5, 3),
            Op::Nan(INCREMENTS, true),
            Op::Nan(STATES, false),
            Op::Step(0.01, 3),
            Op::Nan(INCREMENTS, true),
        ],
        log: &[
            "fmi3DoStep: doStep from t = 0.5 s, but the FMU is at t = 0.01 s",
            "fmi3DoStep: doStep is refused: the instance is in the error state",
        ],
    },
    Fault {
        name: "wrong getter types name the variable, its type and the right call",
        version: FmiVersion::V2,
        ops: &[
            Op::Enter(0),
            Op::IntOfReal("imu.time_s", 3),
            Op::RealOfInt("run.seed", 3),
        ],
        log: &[
            "fmi2GetInteger: value reference {vr:imu.time_s} (imu.time_s) is a Real variable, not an Integer or Enumeration: read it with fmi2GetReal",
            "fmi2GetReal: value reference {vr:run.seed} (run.seed) is an Integer variable, not a Real: read it with fmi2GetInteger",
        ],
    },
    Fault {
        name: "wrong getter types name the variable, its type and the right call",
        version: FmiVersion::V3,
        ops: &[Op::Enter(0), Op::IntOfReal("imu.time_s", 3), Op::Exit(3)],
        log: &[
            "fmi3GetInt32: value reference {vr:imu.time_s} (imu.time_s) is a Float64 variable, not an Int32 (this FMU has no Int32 variables): read it with fmi3GetFloat64",
        ],
    },
    Fault {
        name: "GetFloat64 of a UInt64",
        version: FmiVersion::V3,
        ops: &[Op::Enter(0), Op::RealOfInt("run.seed", 3)],
        log: &[
            "fmi3GetFloat64: value reference {vr:run.seed} (run.seed) is a UInt64 variable, not a Float64: read it with fmi3GetUInt64",
        ],
    },
];

/// The FMI 2 binary through the importer, or the FMI 3 binary through C pointers: each call
/// returns its status; the log collects every message.
trait Driver {
    fn vr(&self, name: &str) -> u32;
    fn run(&mut self, op: Op) -> Result<(), String>;
    fn log(&self) -> String;
}

fn expect_status(op: Op, want: i32, got: i32) -> Result<(), String> {
    if want == got {
        Ok(())
    } else {
        Err(format!("{op:?}: status {got}, expected {want}"))
    }
}

fn check_values(op: Op, names: &[&str], values: &[f64], nan: bool) -> Result<(), String> {
    for (n, v) in names.iter().zip(values) {
        if v.is_nan() != nan || (!nan && !v.is_finite()) {
            return Err(format!("{op:?}: {n} = {v}"));
        }
    }
    Ok(())
}

struct Drive2<'a> {
    fmu: &'a Fmu2,
    inst: Instance2<'a>,
    log: Vec<String>,
}

impl Driver for Drive2<'_> {
    fn vr(&self, name: &str) -> u32 {
        self.fmu.vr(name).unwrap()
    }

    fn run(&mut self, op: Op) -> Result<(), String> {
        let status = |r: Result<(), rins_fmi_import::CallError>, log: &mut Vec<String>| match r {
            Ok(()) => 0,
            Err(e) => {
                log.extend(e.log);
                e.status
            }
        };
        let inst = &self.inst;
        let (want, got) = match op {
            Op::Set(n, x, want) => (
                want,
                status(inst.set_real(&[self.vr(n)], &[x]), &mut self.log),
            ),
            Op::Enter(want) => {
                let r = inst
                    .setup_experiment(0.0, None)
                    .and_then(|_| inst.enter_initialization_mode());
                (want, status(r, &mut self.log))
            }
            Op::Exit(want) => (want, status(inst.exit_initialization_mode(), &mut self.log)),
            Op::Step(t, want) => (want, status(inst.do_step(t, 0.01), &mut self.log)),
            Op::Nan(names, nan) => {
                let vrs: Vec<u32> = names.iter().map(|n| self.vr(n)).collect();
                let mut v = vec![0.0; vrs.len()];
                inst.get_real(&vrs, &mut v)
                    .map_err(|e| format!("{op:?}: {e}"))?;
                return check_values(op, names, &v, nan);
            }
            Op::IntOfReal(n, want) => (
                want,
                status(inst.get_integer(&[self.vr(n)], &mut [0]), &mut self.log),
            ),
            Op::RealOfInt(n, want) => (
                want,
                status(inst.get_real(&[self.vr(n)], &mut [0.0]), &mut self.log),
            ),
        };
        expect_status(op, want, got)
    }

    fn log(&self) -> String {
        self.log.join("\n")
    }
}

struct Drive3<'a> {
    f: &'a Fmi3,
    c: Inst,
    log: &'a Mutex<Vec<String>>,
    xml: &'static str,
}

impl Driver for Drive3<'_> {
    fn vr(&self, name: &str) -> u32 {
        attr(self.xml, name, "valueReference").parse().unwrap()
    }

    fn run(&mut self, op: Op) -> Result<(), String> {
        let (f, c) = (self.f, self.c);
        // SAFETY: fmi3Functions.h signatures on a live instance, arrays of the lengths passed.
        let (want, got) = unsafe {
            match op {
                Op::Set(n, x, want) => (want, (f.set_f64)(c, &self.vr(n), 1, &x, 1)),
                Op::Enter(want) => (want, (f.enter_init)(c, false, 0.0, 0.0, false, 0.0)),
                Op::Exit(want) => (want, (f.exit_init)(c)),
                Op::Step(t, want) => (want, step3(f, c, t)),
                Op::Nan(names, nan) => {
                    let vrs: Vec<u32> = names.iter().map(|n| self.vr(n)).collect();
                    let mut v = vec![0.0; vrs.len()];
                    let s = (f.get_f64)(c, vrs.as_ptr(), vrs.len(), v.as_mut_ptr(), v.len());
                    expect_status(op, 0, s)?;
                    return check_values(op, names, &v, nan);
                }
                Op::IntOfReal(n, want) => (want, (f.get_i32)(c, &self.vr(n), 1, &mut 0, 1)),
                Op::RealOfInt(n, want) => (want, (f.get_f64)(c, &self.vr(n), 1, &mut 0.0, 1)),
            }
        };
        expect_status(op, want, got)
    }

    fn log(&self) -> String {
        self.log.lock().unwrap().join("\n")
    }
}

/// Runs `fault` on `d`: every call's status, then every expected log line.
fn run_fault(fault: &Fault, d: &mut dyn Driver) -> Result<(), String> {
    for op in fault.ops {
        d.run(*op)?;
    }
    let log = d.log();
    for want in fault.log {
        let mut want = want.to_string();
        while let Some(i) = want.find("{vr:") {
            let j = i + want[i..].find('}').unwrap();
            want = format!("{}{}{}", &want[..i], d.vr(&want[i + 4..j]), &want[j + 1..]);
        }
        if !log.contains(&want) {
            return Err(format!("log lacks {want:?}; it has:\n{log}"));
        }
    }
    Ok(())
}

/// Issue 29: each fault sequence of [`FAULTS`] on a fresh instance of the built FMI 2 or FMI 3
/// binary; every failure is reported, then the test fails if any.
#[test]
fn fault_sequences_are_refused_the_same_way_in_both_fmi_versions() {
    let fmu2 = library();
    let f3 = Fmi3::load();
    let xml3: &'static str = &fmu::description::<RinsImu>(FmiVersion::V3).0;
    let mut failures = Vec::new();
    for fault in FAULTS {
        let r = match fault.version {
            FmiVersion::V2 => {
                let inst = fmu2.instantiate("fault", false).unwrap();
                let mut d = Drive2 {
                    fmu: &fmu2,
                    inst,
                    log: Vec::new(),
                };
                run_fault(fault, &mut d)
            }
            FmiVersion::V3 => {
                let log = Mutex::new(Vec::new());
                let c = fmi3_instance(&f3, &log, false);
                let mut d = Drive3 {
                    f: &f3,
                    c,
                    log: &log,
                    xml: xml3,
                };
                let r = run_fault(fault, &mut d);
                // SAFETY: the live instance, freed once.
                unsafe { (f3.free)(c) };
                r
            }
        };
        if let Err(e) = r {
            failures.push(format!("{} ({:?}): {e}", fault.name, fault.version));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
