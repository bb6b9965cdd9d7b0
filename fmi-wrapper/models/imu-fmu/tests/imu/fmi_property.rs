//! Property test of the FMI 2.0 binary (issue 16): random call sequences (instantiate, setup,
//! sets of every type with random value references and values incl. NaN/±inf/huge, enter/exit
//! initialisation, doStep with random sizes, get/set/serialise/deserialise state, terminate,
//! reset, free) checked against the FMI 2 co-simulation state machine:
//! - a call the state machine forbids is refused;
//! - after a set refused before the end of initialisation, leaving initialization mode is
//!   refused and the instance is in the error state until reset (issue 29);
//! - no call crashes, and every non-OK status comes with a logged reason (never fatal);
//! - after every successful doStep all Real outputs are finite and the FMU's time is the time
//!   the test tracks;
//! - a saved state (handle, or serialised bytes restored) replays the following steps bit for
//!   bit, and serialise(deserialise(bytes)) == bytes;
//! - mutated and random serialised states are refused with a reason, or restore without a crash.
//!
//! Needs the cdylibs: `cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3`.
//! Fixed seeds (ChaCha8): a failure prints the seed, sequence and call number to replay.

use std::path::PathBuf;

use rand::{Rng, RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rins_fmi::fmu;
use rins_fmi::standard::FmiVersion;
use rins_fmi_import::{CallError, Fmu2, Instance2, StateHandle, Variable, parse_model_description};
use rins_imu_fmu::{RinsImu, library_file};

const SEED: u64 = 0x5eed_0016;
/// Random call sequences, each on a fresh instance (freed at its end).
const SEQUENCES: usize = 400;
/// Calls per sequence.
const CALLS: usize = 300;

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

/// The FMI 2 co-simulation states the test tracks.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    Instantiated,
    Initialization,
    Step,
    Terminated,
    /// After a refused exit from initialization mode: reset or free only.
    Error,
}

/// A refused call: never fatal, never without a logged reason.
fn check_refusal(e: &CallError, ctx: &str) {
    assert!((1..=3).contains(&e.status), "{ctx}: {e}");
    assert!(
        !e.log.is_empty(),
        "{ctx}: non-OK status without a logged reason: {e}"
    );
}

/// A call the state machine forbids must be refused (with a reason).
fn must_refuse<T>(r: Result<T, CallError>, ctx: &str) {
    match r {
        Ok(_) => panic!("{ctx}: accepted although the state machine forbids it"),
        Err(e) => check_refusal(&e, ctx),
    }
}

/// Extreme and ordinary Real values.
fn real_value(rng: &mut ChaCha8Rng) -> f64 {
    match rng.random_range(0..10) {
        0 => f64::NAN,
        1 => f64::INFINITY,
        2 => f64::NEG_INFINITY,
        3 => f64::MAX,
        4 => -1e300,
        5 => 5e-324,
        6 => -0.0,
        7 => rng.random_range(-1e6..1e6),
        _ => rng.random_range(-10.0..10.0),
    }
}

fn int_value(rng: &mut ChaCha8Rng) -> i32 {
    match rng.random_range(0..6) {
        0 => i32::MIN,
        1 => i32::MAX,
        2 => -1,
        3 => 0,
        _ => rng.random_range(0..8),
    }
}

struct Model<'a> {
    fmu: &'a Fmu2,
    vars: &'a [Variable],
    real_outputs: Vec<u32>,
    rate_hz: u32,
}

impl Model<'_> {
    /// A value reference: mostly declared ones of any type, sometimes an unknown one.
    fn vr(&self, rng: &mut ChaCha8Rng, type_name: &str) -> u32 {
        if rng.random_bool(0.1) {
            return rng.random_range(0..u32::MAX);
        }
        let same: Vec<&Variable> = self
            .vars
            .iter()
            .filter(|v| v.type_name == type_name || rng.random_bool(0.02))
            .collect();
        same[rng.random_range(0..same.len())].vr
    }

    fn outputs(&self, inst: &Instance2<'_>) -> Vec<u64> {
        let mut v = vec![0.0; self.real_outputs.len()];
        inst.get_real(&self.real_outputs, &mut v).unwrap();
        v.into_iter().map(f64::to_bits).collect()
    }

    /// Steps `n` times by one sample from `ticks`; the Real outputs after each step (finite).
    fn run(&self, inst: &Instance2<'_>, ticks: &mut u64, n: u64, ctx: &str) -> Vec<Vec<u64>> {
        let dt = 1.0 / self.rate_hz as f64;
        (0..n)
            .map(|_| {
                inst.do_step(*ticks as f64 * dt, dt)
                    .unwrap_or_else(|e| panic!("{ctx}: {e}"));
                *ticks += 1;
                let out = self.outputs(inst);
                assert!(
                    out.iter().all(|b| f64::from_bits(*b).is_finite()),
                    "{ctx}: non-finite output"
                );
                out
            })
            .collect()
    }
}

/// One random sequence on a fresh instance.
fn sequence(m: &mut Model<'_>, rng: &mut ChaCha8Rng, seq: usize) -> [usize; 3] {
    let fmu = m.fmu;
    let inst = fmu.instantiate("prop", rng.random_bool(0.5)).unwrap();
    let mut mode = Mode::Instantiated;
    // A set refused since instantiation or the last reset, before step mode.
    let mut refused_set = false;
    let mut ticks = 0u64;
    let mut saved: Vec<(StateHandle, u64)> = Vec::new();
    // Calls accepted, refused, and state round trips checked.
    let mut tally = [0usize; 3];
    for call in 0..CALLS {
        // Weighted so that sequences reach Step mode and stay there a while: reset and
        // terminate are rarer, and the next lifecycle call is favoured before Step mode.
        let mut op = rng.random_range(0..16);
        if op >= 14 && rng.random_bool(0.7) {
            op = 7;
        }
        if rng.random_bool(0.3) {
            match mode {
                Mode::Instantiated => op = 5,
                Mode::Initialization => op = 6,
                _ => {}
            }
        }
        let ctx = format!("seed {SEED:#x}, sequence {seq}, call {call} (op {op}, {mode:?})");
        let before_step = matches!(mode, Mode::Instantiated | Mode::Initialization);
        let r: Result<(), CallError> = match op {
            0 => {
                let r = inst.setup_experiment(0.0, None);
                if mode != Mode::Instantiated {
                    must_refuse(r, &ctx);
                    continue;
                }
                r
            }
            1 | 2 => {
                let n = rng.random_range(0..4);
                let vrs: Vec<u32> = (0..n).map(|_| m.vr(rng, "Real")).collect();
                let vals: Vec<f64> = (0..n).map(|_| real_value(rng)).collect();
                let r = inst.set_real(&vrs, &vals);
                refused_set |= before_step && r.is_err();
                r
            }
            3 => {
                let kind = ["Integer", "Enumeration"][rng.random_range(0..2)];
                let n = rng.random_range(0..3);
                let vrs: Vec<u32> = (0..n).map(|_| m.vr(rng, kind)).collect();
                let vals: Vec<i32> = (0..n).map(|_| int_value(rng)).collect();
                let r = inst.set_integer(&vrs, &vals);
                refused_set |= before_step && r.is_err();
                r
            }
            4 => {
                let n = rng.random_range(0..3);
                let vrs: Vec<u32> = (0..n).map(|_| m.vr(rng, "Boolean")).collect();
                let vals: Vec<bool> = (0..n).map(|_| rng.random()).collect();
                let r = inst.set_boolean(&vrs, &vals);
                refused_set |= before_step && r.is_err();
                r
            }
            5 => {
                let r = inst.enter_initialization_mode();
                if mode != Mode::Instantiated {
                    must_refuse(r, &ctx);
                    continue;
                }
                r.map(|_| mode = Mode::Initialization)
            }
            6 => {
                let r = inst.exit_initialization_mode();
                if mode != Mode::Initialization {
                    must_refuse(r, &ctx);
                    continue;
                }
                if refused_set {
                    let e = r.expect_err(&format!("{ctx}: exit after a refused set"));
                    check_refusal(&e, &ctx);
                    assert!(
                        e.log
                            .iter()
                            .any(|l| l.contains("an earlier call setting a value was refused")),
                        "{ctx}: {e}"
                    );
                    mode = Mode::Error;
                    tally[1] += 1;
                    continue;
                }
                r.map(|_| {
                    mode = Mode::Step;
                    ticks = 0;
                    let mut hz = [0.0];
                    inst.get_real(&[fmu.vr("run.rate_hz").unwrap()], &mut hz)
                        .unwrap();
                    m.rate_hz = hz[0] as u32;
                    assert_eq!(m.rate_hz as f64, hz[0], "{ctx}: rate is whole Hz");
                })
                // A configuration the model refuses also leaves the error state.
                .inspect_err(|_| mode = Mode::Error)
            }
            7..=9 => {
                // Mostly whole numbers of samples; sometimes a fraction, a wrong start time,
                // zero, negative or non-finite sizes (all refused).
                let dt = 1.0 / m.rate_hz as f64;
                let n = rng.random_range(1..=50u64);
                let (t, h, good) = match rng.random_range(0..10) {
                    0 => (ticks as f64 * dt, (n as f64 + 0.5) * dt, false),
                    1 => ((ticks + 3) as f64 * dt, n as f64 * dt, false),
                    2 => (
                        ticks as f64 * dt,
                        [0.0, -dt, f64::NAN, f64::INFINITY][n as usize % 4],
                        false,
                    ),
                    _ => (ticks as f64 * dt, n as f64 * dt, true),
                };
                let r = inst.do_step(t, h);
                if mode != Mode::Step || !good {
                    must_refuse(r, &ctx);
                    continue;
                }
                r.map(|_| {
                    ticks += n;
                    let out = m.outputs(&inst);
                    assert!(
                        out.iter().all(|b| f64::from_bits(*b).is_finite()),
                        "{ctx}: non-finite output"
                    );
                    let now = inst.last_successful_time().unwrap();
                    assert!(
                        (now - ticks as f64 * dt).abs() <= 1e-9 * now.abs().max(1.0),
                        "{ctx}: the FMU is at {now} s, {ticks} samples were stepped"
                    );
                })
            }
            10 | 11 if mode == Mode::Step => {
                // Save, run, restore (from the handle or from serialised bytes), run again.
                let s = inst.get_state().unwrap_or_else(|e| panic!("{ctx}: {e}"));
                let bytes = inst
                    .serialize_state(&s)
                    .unwrap_or_else(|e| panic!("{ctx}: {e}"));
                let n = rng.random_range(1..30);
                let start = ticks;
                let first = m.run(&inst, &mut ticks, n, &ctx);
                let restored = inst.deserialize_state(&bytes).unwrap();
                assert_eq!(inst.serialize_state(&restored).unwrap(), bytes, "{ctx}");
                inst.set_state(if op == 10 { &s } else { &restored })
                    .unwrap();
                ticks = start;
                assert_eq!(
                    m.run(&inst, &mut ticks, n, &ctx),
                    first,
                    "{ctx}: replay differs"
                );
                inst.free_state(restored).unwrap();
                saved.push((s, start));
                tally[2] += 1;
                Ok(())
            }
            12 if mode == Mode::Step && !saved.is_empty() => {
                // Back to an older saved state; time goes back with it.
                let k = rng.random_range(0..saved.len());
                inst.set_state(&saved[k].0).unwrap();
                ticks = saved[k].1;
                Ok(())
            }
            13 if mode == Mode::Step && !saved.is_empty() => {
                // A mutated or random serialised state: refused with a reason, or restored.
                let k = rng.random_range(0..saved.len());
                let mut bytes = inst.serialize_state(&saved[k].0).unwrap();
                match rng.random_range(0..3) {
                    0 => bytes.truncate(rng.random_range(0..bytes.len())),
                    1 => {
                        let i = rng.random_range(0..bytes.len());
                        bytes[i] ^= 1 << rng.random_range(0..8);
                    }
                    _ => {
                        let n = rng.random_range(0..2 * bytes.len());
                        bytes = vec![0; n];
                        rng.fill_bytes(&mut bytes);
                    }
                }
                match inst.deserialize_state(&bytes) {
                    Err(e) => check_refusal(&e, &ctx),
                    Ok(h) => {
                        if inst.set_state(&h).is_ok() {
                            // It may hold any bits; only no crash is required. Then back.
                            let t = inst.last_successful_time().unwrap_or(0.0);
                            if let Err(e) = inst.do_step(t, 1.0 / m.rate_hz as f64) {
                                check_refusal(&e, &ctx);
                            }
                            inst.set_state(&saved[k].0).unwrap();
                            ticks = saved[k].1;
                        }
                        inst.free_state(h).unwrap();
                    }
                }
                Ok(())
            }
            14 => inst.terminate().map(|_| mode = Mode::Terminated),
            _ => {
                let r = inst.reset();
                r.map(|_| {
                    mode = Mode::Instantiated;
                    refused_set = false;
                    ticks = 0;
                })
            }
        };
        match r {
            Ok(()) => tally[0] += 1,
            Err(e) => {
                check_refusal(&e, &ctx);
                tally[1] += 1;
            }
        }
        // Terminated: only reset or free are allowed next; free ends the sequence early.
        if mode == Mode::Terminated && rng.random_bool(0.5) {
            must_refuse(inst.do_step(0.0, 0.01), &ctx);
            break;
        }
        let _ = inst.take_log();
    }
    for (s, _) in saved {
        inst.free_state(s).unwrap();
    }
    tally
}

#[test]
fn random_call_sequences_follow_the_state_machine_and_never_crash() {
    let fmu = library();
    let real_outputs: Vec<u32> = fmu
        .variables
        .iter()
        .filter(|v| v.type_name == "Real" && v.causality == "output")
        .map(|v| v.vr)
        .collect();
    let vars = fmu.variables.clone();
    let mut m = Model {
        fmu: &fmu,
        vars: &vars,
        real_outputs,
        rate_hz: 100,
    };
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let mut total = [0usize; 3];
    for seq in 0..SEQUENCES {
        m.rate_hz = 100;
        let t = sequence(&mut m, &mut rng, seq);
        total.iter_mut().zip(t).for_each(|(a, b)| *a += b);
    }
    println!("calls accepted, refused, state round trips: {total:?}");
    // Every branch was exercised.
    assert!(total.iter().all(|n| *n > 20), "{total:?}");
}
