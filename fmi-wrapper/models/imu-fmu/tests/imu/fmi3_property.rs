//! Property test of the FMI 3.0 binary (issue 16), on the functions a co-simulation master
//! uses: instantiate, fmi3SetFloat64 (random variables, sizes and values incl. NaN/±inf/huge),
//! enter/exit initialisation, doStep with random sizes, fmi3GetFloat64 of every Float64 output,
//! get/set/serialise/deserialise/free state, terminate, reset, free. Checked against the FMI 3
//! co-simulation state machine: forbidden calls are refused, no call crashes, every non-OK
//! status comes with a logged message (never fatal), outputs stay finite, a saved state replays
//! the next steps bit for bit, and corrupted serialised states are refused with a reason.
//!
//! There is no FMI 3 importer in Rust: the functions are loaded into a local table.
//! Needs the cdylibs: `cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3`.
//! Fixed seeds (ChaCha8): a failure prints the seed, sequence and call number to replay.

#![allow(unsafe_code)] // calling the FMI 3 binary through C function pointers

use std::ffi::{CStr, CString, c_char, c_void};
use std::sync::Mutex;

use rand::{Rng, RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rins_fmi::fmu;
use rins_fmi::standard::FmiVersion;
use rins_imu_fmu::RinsImu;

use crate::common::{Fmi3, Inst};

const SEED: u64 = 0x5eed_0016;
const SEQUENCES: usize = 600;
const CALLS: usize = 200;

unsafe extern "C" fn logger(
    env: *mut c_void,
    status: i32,
    _cat: *const c_char,
    msg: *const c_char,
) {
    if env.is_null() || msg.is_null() {
        return;
    }
    // SAFETY: `env` is the Mutex given at instantiation; the message is NUL-terminated.
    let sink = unsafe { &*(env as *const Mutex<Vec<String>>) };
    let m = unsafe { CStr::from_ptr(msg) }
        .to_string_lossy()
        .into_owned();
    if let Ok(mut v) = sink.lock() {
        v.push(format!("[{status}] {m}"));
    }
}

/// A Float64 variable of the modelDescription: name, value reference, causality, elements.
struct Var {
    vr: u32,
    causality: String,
    size: usize,
}

fn attr(tag: &str, key: &str) -> Option<String> {
    let i = tag.find(&format!(" {key}=\""))? + key.len() + 3;
    Some(tag[i..].split('"').next()?.to_string())
}

fn float64_vars(xml: &str) -> Vec<Var> {
    let lines: Vec<&str> = xml.lines().collect();
    lines
        .iter()
        .enumerate()
        .filter(|(_, l)| l.trim_start().starts_with("<Float64 "))
        .map(|(i, l)| Var {
            vr: attr(l, "valueReference").unwrap().parse().unwrap(),
            causality: attr(l, "causality").unwrap_or_default(),
            size: if l.trim_end().ends_with("/>") {
                1
            } else {
                attr(lines[i + 1], "start").map_or(1, |s| s.parse().unwrap())
            },
        })
        .collect()
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    Instantiated,
    Initialization,
    Step,
    Terminated,
    /// After a call that returned fmi3Error: only reset (or a state restore) leaves it.
    Error,
}

struct Run<'a> {
    f: &'a Fmi3,
    c: Inst,
    log: &'a Mutex<Vec<String>>,
    outputs: Vec<u32>,
    n_out: usize,
    /// A call returned fmi3Error since the last look (the instance is then in error mode).
    failed: std::cell::Cell<bool>,
}

impl Run<'_> {
    /// A status: OK, or non-OK with a logged message and never fatal.
    fn status(&self, s: i32, ctx: &str) -> bool {
        let log = std::mem::take(&mut *self.log.lock().unwrap());
        if s == 0 {
            return true;
        }
        if s == 3 {
            self.failed.set(true);
        }
        assert!((1..=3).contains(&s), "{ctx}: status {s}, log {log:?}");
        assert!(
            !log.is_empty(),
            "{ctx}: status {s} without a logged message"
        );
        false
    }

    fn refused(&self, s: i32, ctx: &str) {
        assert!(
            !self.status(s, ctx),
            "{ctx}: accepted although the state machine forbids it"
        );
    }

    fn step(&self, t: f64, h: f64) -> i32 {
        let (mut a, mut b, mut e, mut last) = (false, false, false, 0.0);
        // SAFETY: live instance, valid out-pointers.
        unsafe { (self.f.do_step)(self.c, t, h, false, &mut a, &mut b, &mut e, &mut last) }
    }

    fn outputs(&self, ctx: &str) -> Vec<u64> {
        let mut v = vec![0.0; self.n_out];
        // SAFETY: value count is the sum of the outputs' sizes.
        let s = unsafe {
            (self.f.get_f64)(
                self.c,
                self.outputs.as_ptr(),
                self.outputs.len(),
                v.as_mut_ptr(),
                v.len(),
            )
        };
        assert!(self.status(s, ctx), "{ctx}: fmi3GetFloat64 of the outputs");
        assert!(
            v.iter().all(|x| x.is_finite()),
            "{ctx}: non-finite output {v:?}"
        );
        v.into_iter().map(f64::to_bits).collect()
    }

    /// `n` steps of 10 ms from `ticks`, with the outputs after each.
    fn run(&self, ticks: &mut u64, n: u64, ctx: &str) -> Vec<Vec<u64>> {
        (0..n)
            .map(|_| {
                assert!(
                    self.status(self.step(*ticks as f64 * 0.01, 0.01), ctx),
                    "{ctx}: step"
                );
                *ticks += 1;
                self.outputs(ctx)
            })
            .collect()
    }

    fn get_state(&self, ctx: &str) -> *mut c_void {
        let mut s = std::ptr::null_mut();
        // SAFETY: valid out-pointer.
        assert!(self.status(unsafe { (self.f.get_state)(self.c, &mut s) }, ctx));
        s
    }

    fn serialize(&self, s: *mut c_void, ctx: &str) -> Vec<u8> {
        let mut n = 0;
        // SAFETY: state from this instance; buffer of the size asked.
        unsafe {
            assert!(self.status((self.f.state_size)(self.c, s, &mut n), ctx));
            let mut b = vec![0u8; n];
            assert!(self.status((self.f.serialize)(self.c, s, b.as_mut_ptr(), n), ctx));
            b
        }
    }

    fn free_state(&self, mut s: *mut c_void, ctx: &str) {
        // SAFETY: state from this instance, freed once.
        assert!(self.status(unsafe { (self.f.free_state)(self.c, &mut s) }, ctx));
    }
}

fn real_value(rng: &mut ChaCha8Rng) -> f64 {
    match rng.random_range(0..9) {
        0 => f64::NAN,
        1 => f64::INFINITY,
        2 => f64::NEG_INFINITY,
        3 => f64::MAX,
        4 => 5e-324,
        5 => rng.random_range(-1e6..1e6),
        _ => rng.random_range(-10.0..10.0),
    }
}

#[test]
fn random_fmi3_call_sequences_follow_the_state_machine_and_never_crash() {
    let xml = &fmu::description::<RinsImu>(FmiVersion::V3).0;
    let token = CString::new(attr(xml, "instantiationToken").unwrap()).unwrap();
    let vars = float64_vars(xml);
    let outs: Vec<&Var> = vars.iter().filter(|v| v.causality == "output").collect();
    let settable: Vec<&Var> = vars.iter().filter(|v| v.causality != "output").collect();
    assert!(outs.len() > 5 && settable.len() > 5, "variables parsed");
    let f = Fmi3::load();
    let log = Mutex::new(Vec::new());
    let name = CString::new("prop3").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let mut tally = [0usize; 3];
    for seq in 0..SEQUENCES {
        // SAFETY: fmi3Functions.h signature; strings and the log outlive the instance.
        let c = unsafe {
            (f.instantiate)(
                name.as_ptr(),
                token.as_ptr(),
                std::ptr::null(),
                false,
                rng.random(),
                false,
                false,
                std::ptr::null(),
                0,
                &log as *const Mutex<Vec<String>> as *mut c_void,
                Some(logger),
                std::ptr::null(),
            )
        };
        assert!(!c.is_null(), "seed {SEED:#x}, sequence {seq}: instantiate");
        let r = Run {
            f: &f,
            c,
            log: &log,
            outputs: outs.iter().map(|v| v.vr).collect(),
            n_out: outs.iter().map(|v| v.size).sum(),
            failed: std::cell::Cell::new(false),
        };
        let (mut mode, mut ticks) = (Mode::Instantiated, 0u64);
        let mut saved: Vec<(*mut c_void, u64)> = Vec::new();
        for call in 0..CALLS {
            let mut op = rng.random_range(0..12);
            if op >= 10 && rng.random_bool(0.7) {
                op = 3;
            }
            if rng.random_bool(0.3) && mode == Mode::Instantiated {
                op = 1;
            } else if rng.random_bool(0.3) && mode == Mode::Initialization {
                op = 2;
            } else if rng.random_bool(0.5) && mode == Mode::Error {
                op = 11;
            }
            let ctx = format!("seed {SEED:#x}, sequence {seq}, call {call} (op {op}, {mode:?})");
            // SAFETY (all calls below): fmi3Functions.h signatures on the live instance, arrays
            // of the lengths passed.
            match op {
                0 => {
                    // Mostly parameters and inputs (settable in some mode), some outputs.
                    let v = if rng.random_bool(0.8) {
                        settable[rng.random_range(0..settable.len())]
                    } else {
                        &vars[rng.random_range(0..vars.len())]
                    };
                    let n = if rng.random_bool(0.9) {
                        v.size
                    } else {
                        v.size + 1
                    };
                    let mut vals: Vec<f64> = (0..n).map(|_| real_value(&mut rng)).collect();
                    if rng.random_bool(0.4) {
                        // Its current value, which is in range: such sets are accepted where
                        // the mode allows them.
                        let g = unsafe { (f.get_f64)(c, &v.vr, 1, vals.as_mut_ptr(), v.size) };
                        r.status(g, &ctx);
                    }
                    let vr = if rng.random_bool(0.1) {
                        rng.random()
                    } else {
                        v.vr
                    };
                    let s = unsafe { (f.set_f64)(c, &vr, 1, vals.as_ptr(), n) };
                    tally[!r.status(s, &ctx) as usize] += 1;
                }
                1 => {
                    let s = unsafe { (f.enter_init)(c, false, 0.0, 0.0, false, 0.0) };
                    if mode != Mode::Instantiated {
                        r.refused(s, &ctx);
                    } else if r.status(s, &ctx) {
                        mode = Mode::Initialization;
                    }
                }
                2 => {
                    let s = unsafe { (f.exit_init)(c) };
                    if mode != Mode::Initialization {
                        r.refused(s, &ctx);
                    } else if r.status(s, &ctx) {
                        (mode, ticks) = (Mode::Step, 0);
                    }
                }
                3..=5 => {
                    let n = rng.random_range(1..=50u64);
                    let bad = rng.random_bool(0.2);
                    let h = if bad {
                        (n as f64 + 0.5) * 0.01
                    } else {
                        n as f64 * 0.01
                    };
                    let s = r.step(ticks as f64 * 0.01, h);
                    if mode != Mode::Step || bad {
                        r.refused(s, &ctx);
                    } else {
                        assert!(r.status(s, &ctx), "{ctx}: a valid step was refused");
                        ticks += n;
                        r.outputs(&ctx);
                    }
                }
                6 | 7 if mode == Mode::Step => {
                    // Save, run, restore (handle or deserialised bytes), run again: identical.
                    let s = r.get_state(&ctx);
                    let bytes = r.serialize(s, &ctx);
                    let (start, n) = (ticks, rng.random_range(1..20));
                    let first = r.run(&mut ticks, n, &ctx);
                    let mut d = std::ptr::null_mut();
                    assert!(r.status(
                        unsafe { (f.deserialize)(c, bytes.as_ptr(), bytes.len(), &mut d) },
                        &ctx
                    ));
                    assert_eq!(r.serialize(d, &ctx), bytes, "{ctx}");
                    let back = if op == 6 { s } else { d };
                    assert!(r.status(unsafe { (f.set_state)(c, back) }, &ctx));
                    ticks = start;
                    assert_eq!(r.run(&mut ticks, n, &ctx), first, "{ctx}: replay differs");
                    r.free_state(d, &ctx);
                    saved.push((s, start));
                    tally[2] += 1;
                }
                8 if mode == Mode::Step && !saved.is_empty() => {
                    // A corrupted serialised state: refused with a reason, or restored; then
                    // back to the good one.
                    let k = rng.random_range(0..saved.len());
                    let mut b = r.serialize(saved[k].0, &ctx);
                    if rng.random_bool(0.5) {
                        let i = rng.random_range(0..b.len());
                        b[i] ^= 1 << rng.random_range(0..8);
                    } else {
                        let n = rng.random_range(0..b.len());
                        b.truncate(n);
                        rng.fill_bytes(&mut b[n / 2..]);
                    }
                    let mut d = std::ptr::null_mut();
                    if r.status(
                        unsafe { (f.deserialize)(c, b.as_ptr(), b.len(), &mut d) },
                        &ctx,
                    ) {
                        if r.status(unsafe { (f.set_state)(c, d) }, &ctx) {
                            let s = r.step(ticks as f64 * 0.01, 0.01);
                            r.status(s, &ctx);
                            assert!(r.status(unsafe { (f.set_state)(c, saved[k].0) }, &ctx));
                            ticks = saved[k].1;
                            // The restored state is out of error mode.
                            r.failed.set(false);
                        }
                        r.free_state(d, &ctx);
                    }
                }
                9 | 10 if r.status(unsafe { (f.terminate)(c) }, &ctx) => mode = Mode::Terminated,
                11 if r.status(unsafe { (f.reset)(c) }, &ctx) => {
                    (mode, ticks) = (Mode::Instantiated, 0);
                }
                _ => {}
            }
            // The standard: after fmi3Error only reset, free or a state restore; steps and
            // mode changes are refused until then (checked by the next calls above).
            if r.failed.take() {
                mode = Mode::Error;
            }
            if mode == Mode::Terminated && rng.random_bool(0.5) {
                r.refused(r.step(ticks as f64 * 0.01, 0.01), &ctx);
                break;
            }
        }
        for (s, _) in saved {
            r.free_state(s, "free");
        }
        // SAFETY: freed once.
        unsafe { (f.free)(c) };
        log.lock().unwrap().clear();
    }
    println!("sets accepted/refused, state round trips: {tally:?}");
    assert!(tally.iter().all(|n| *n > 20), "{tally:?}");
}

/// A caller's misuse (issue 44): fmi3FreeInstance twice, then fmi3DoStep and fmi3Reset on the
/// freed instance. The second free does nothing (a double free would abort this process with
/// "double free or corruption"), the calls return fmi3Error, and nothing is logged for them:
/// the instance's logger went with it, and the FMU cannot tell whose the pointer was.
#[test]
fn a_double_free_and_calls_on_a_freed_instance_are_refused_and_the_process_survives() {
    let xml = &fmu::description::<RinsImu>(FmiVersion::V3).0;
    let token = CString::new(attr(xml, "instantiationToken").unwrap()).unwrap();
    let f = Fmi3::load();
    let log = Mutex::new(Vec::new());
    let name = CString::new("freed3").unwrap();
    // SAFETY: fmi3Functions.h signatures; the log outlives the instance. The calls after the
    // first free are the misuse under test, which the FMU must refuse without touching memory.
    unsafe {
        let c = (f.instantiate)(
            name.as_ptr(),
            token.as_ptr(),
            std::ptr::null(),
            false,
            true,
            false,
            false,
            std::ptr::null(),
            0,
            &log as *const Mutex<Vec<String>> as *mut c_void,
            Some(logger),
            std::ptr::null(),
        );
        assert!(!c.is_null());
        assert_eq!(
            (f.enter_init)(c, false, 0.0, 0.0, false, 0.0),
            0,
            "{:?}",
            log.lock().unwrap()
        );
        assert_eq!((f.exit_init)(c), 0, "{:?}", log.lock().unwrap());
        (f.free)(c);
        log.lock().unwrap().clear();
        (f.free)(c);
        let (mut a, mut b, mut e, mut last) = (false, false, false, -1.0);
        let s = (f.do_step)(c, 0.0, 0.01, false, &mut a, &mut b, &mut e, &mut last);
        assert_eq!(s, 3, "fmi3DoStep on a freed instance");
        assert_eq!(last, -1.0, "no out-pointer written for a freed instance");
        assert_eq!((f.reset)(c), 3, "fmi3Reset on a freed instance");
        (f.free)(c);
        assert_eq!(*log.lock().unwrap(), Vec::<String>::new());
    }
    // The library still works: a new instance steps.
    // SAFETY: as above, used correctly.
    unsafe {
        let c = (f.instantiate)(
            name.as_ptr(),
            token.as_ptr(),
            std::ptr::null(),
            false,
            false,
            false,
            false,
            std::ptr::null(),
            0,
            &log as *const Mutex<Vec<String>> as *mut c_void,
            Some(logger),
            std::ptr::null(),
        );
        assert!(!c.is_null());
        assert_eq!((f.enter_init)(c, false, 0.0, 0.0, false, 0.0), 0);
        assert_eq!((f.exit_init)(c), 0);
        let (mut a, mut b, mut e, mut last) = (false, false, false, 0.0);
        assert_eq!(
            (f.do_step)(c, 0.0, 0.01, false, &mut a, &mut b, &mut e, &mut last),
            0
        );
        (f.free)(c);
    }
}
