//! 1,000 instantiate/free cycles in one process keep the resident memory flat (the class of
//! FMPy issue #110: memory growing with every instance), for the FMI 2 and the FMI 3 binary.
//! Each cycle instantiates, initialises, steps, saves, serialises, deserialises and frees the
//! states, then frees the instance.
//!
//! The bound is measured, not guessed: the memory one live instance holds is taken from 50
//! instances kept alive at once, and the growth over 1,000 cycles must stay below what 5 % of
//! them (50 instances) would hold if leaked, and at least 256 kB (page and allocator slack: a
//! flat run moves by 0–16 kB here). A file of its own with a single test, so no other test
//! allocates in this process while it measures.
//!
//! Needs the cdylibs: `cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3`.

#![allow(unsafe_code)] // the FMI 3 binary is called through a local table of C function pointers

use std::ffi::{CString, c_char, c_void};

use rins_fmi::fmu;
use rins_fmi::standard::FmiVersion;
use rins_fmi_import::{Fmu2, parse_model_description};
use rins_imu_fmu::RinsImu;

use crate::common::{Fmi3, Inst, library_path};

const WARM_UP: usize = 50;
const CYCLES: usize = 1000;
const HELD: usize = 50;

unsafe extern "C" {
    /// glibc: gives the free pages of the heap back to the system.
    fn malloc_trim(pad: usize) -> i32;
}

/// VmRSS of this process in kB.
fn rss_kb() -> i64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap();
    s.lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .expect("VmRSS in /proc/self/status")
}

/// Runs `cycle` for the warm-up and the measured cycles, and holds `HELD` live instances made
/// by `hold` to size one; asserts the growth bound and returns (growth kB, per instance kB).
fn check_flat(what: &str, mut cycle: impl FnMut(usize), hold: impl FnOnce() -> i64) -> (i64, f64) {
    // One cycle first for the one-time tables, then the live instances are sized before any
    // freed memory exists that they could reuse: building the modelDescription (for the
    // token check of the first instantiate) frees more than 50 instances hold, so the heap's
    // free pages go back to the system first.
    cycle(0);
    // SAFETY: glibc's malloc_trim only returns free heap pages; any pad is valid.
    unsafe { malloc_trim(0) };
    let per_instance = hold() as f64 / HELD as f64;
    for k in 0..WARM_UP {
        cycle(k);
    }
    let before = rss_kb();
    for k in 0..CYCLES {
        cycle(k);
    }
    let growth = rss_kb() - before;
    let bound = (0.05 * CYCLES as f64 * per_instance).max(256.0);
    println!(
        "{what}: RSS growth over {CYCLES} cycles {growth} kB; one live instance {per_instance:.0} kB; bound {bound:.0} kB"
    );
    assert!(per_instance > 0.0, "{what}: live instances take no memory?");
    assert!(
        (growth as f64) < bound,
        "{what}: RSS grew {growth} kB over {CYCLES} cycles (bound {bound:.0} kB)"
    );
    (growth, per_instance)
}

#[test]
fn instantiate_free_cycles_keep_rss_flat() {
    // One after the other: a second test thread would move this process's RSS.
    fmi2_cycles();
    fmi3_cycles();
}

fn fmi2_cycles() {
    let (guid, _, vars) =
        parse_model_description(&fmu::description::<RinsImu>(FmiVersion::V2).0).unwrap();
    let lib = Fmu2::load(&library_path(FmiVersion::V2), guid, vars).unwrap();
    let start = |name: &str| {
        let inst = lib.instantiate(name, false).unwrap();
        inst.setup_experiment(0.0, None).unwrap();
        inst.enter_initialization_mode().unwrap();
        inst.exit_initialization_mode().unwrap();
        inst.do_step(0.0, 0.1).unwrap();
        inst
    };
    let cycle = |_k: usize| {
        let inst = start("cycle");
        let s = inst.get_state().unwrap();
        let bytes = inst.serialize_state(&s).unwrap();
        let r = inst.deserialize_state(&bytes).unwrap();
        inst.set_state(&r).unwrap();
        inst.free_state(s).unwrap();
        inst.free_state(r).unwrap();
    };
    let hold = || {
        let before = rss_kb();
        let live: Vec<_> = (0..HELD).map(|_| start("held")).collect();
        let d = rss_kb() - before;
        drop(live);
        d
    };
    check_flat("FMI 2", cycle, hold);
}

unsafe extern "C" fn ignore_log(_: *mut c_void, _: i32, _: *const c_char, _: *const c_char) {}

/// The cycle's instance set-up.
trait Start {
    fn start(&self, token: &CString) -> Inst;
}

impl Start for Fmi3 {
    /// An instance initialised and stepped by 0.1 s.
    fn start(&self, token: &CString) -> Inst {
        let name = CString::new("rss").unwrap();
        // SAFETY: fmi3Functions.h signatures; strings outlive the calls; out-pointers valid.
        unsafe {
            let c = (self.instantiate)(
                name.as_ptr(),
                token.as_ptr(),
                std::ptr::null(),
                false,
                false,
                false,
                false,
                std::ptr::null(),
                0,
                std::ptr::null_mut(),
                Some(ignore_log),
                std::ptr::null(),
            );
            assert!(!c.is_null(), "fmi3InstantiateCoSimulation returned NULL");
            assert_eq!((self.enter_init)(c, false, 0.0, 0.0, false, 0.0), 0);
            assert_eq!((self.exit_init)(c), 0);
            let (mut a, mut b, mut e, mut t) = (false, false, false, 0.0);
            assert_eq!(
                (self.do_step)(c, 0.0, 0.1, false, &mut a, &mut b, &mut e, &mut t),
                0
            );
            assert!((t - 0.1).abs() < 1e-12, "{t}");
            c
        }
    }
}

fn fmi3_cycles() {
    let xml = &fmu::description::<RinsImu>(FmiVersion::V3).0;
    let token = xml
        .split("instantiationToken=\"")
        .nth(1)
        .and_then(|s| s.split('"').next())
        .expect("instantiationToken in the FMI 3 modelDescription");
    let token = CString::new(token).unwrap();
    let f = Fmi3::load();
    let cycle = |_k: usize| {
        let c = f.start(&token);
        // SAFETY: fmi3Functions.h signatures on a live instance; buffers of the sizes asked.
        unsafe {
            let mut s = std::ptr::null_mut();
            assert_eq!((f.get_state)(c, &mut s), 0);
            let mut n = 0usize;
            assert_eq!((f.state_size)(c, s, &mut n), 0);
            let mut bytes = vec![0u8; n];
            assert_eq!((f.serialize)(c, s, bytes.as_mut_ptr(), n), 0);
            let mut r = std::ptr::null_mut();
            assert_eq!((f.deserialize)(c, bytes.as_ptr(), n, &mut r), 0);
            assert_eq!((f.set_state)(c, r), 0);
            assert_eq!((f.free_state)(c, &mut s), 0);
            assert_eq!((f.free_state)(c, &mut r), 0);
            (f.free)(c);
        }
    };
    let hold = || {
        let before = rss_kb();
        let live: Vec<Inst> = (0..HELD).map(|_| f.start(&token)).collect();
        let d = rss_kb() - before;
        // SAFETY: each instance is freed once.
        live.into_iter().for_each(|c| unsafe { (f.free)(c) });
        d
    };
    check_flat("FMI 3", cycle, hold);
}
