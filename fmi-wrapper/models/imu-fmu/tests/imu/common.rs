//! What the FMI tests share: the built libraries' path and a table of the FMI 3 functions the
//! tests call through C function pointers (there is no Rust FMI 3 importer).

// Each test binary uses a different subset of this module.
#![allow(dead_code, unsafe_code)]

use std::ffi::{c_char, c_void};
use std::path::PathBuf;

use rins_fmi::standard::FmiVersion;
use rins_imu_fmu::library_file;

/// The built FMI library of `version` beside the test binaries' folder.
pub fn library_path(version: FmiVersion) -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let p = exe
        .parent()
        .and_then(|d| d.parent())
        .unwrap()
        .join(library_file(version));
    assert!(
        p.exists(),
        "{} missing: run `cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3` first",
        p.display()
    );
    p
}

pub type Inst = *mut c_void;
pub type LogFn = unsafe extern "C" fn(*mut c_void, i32, *const c_char, *const c_char);

/// The FMI 3 functions used (fmi3Functions.h signatures).
pub struct Fmi3 {
    _lib: libloading::Library,
    pub instantiate: unsafe extern "C" fn(
        *const c_char,
        *const c_char,
        *const c_char,
        bool,
        bool,
        bool,
        bool,
        *const u32,
        usize,
        *mut c_void,
        Option<LogFn>,
        *const c_void,
    ) -> Inst,
    pub free: unsafe extern "C" fn(Inst),
    pub enter_init: unsafe extern "C" fn(Inst, bool, f64, f64, bool, f64) -> i32,
    pub exit_init: unsafe extern "C" fn(Inst) -> i32,
    pub terminate: unsafe extern "C" fn(Inst) -> i32,
    pub reset: unsafe extern "C" fn(Inst) -> i32,
    pub do_step: unsafe extern "C" fn(
        Inst,
        f64,
        f64,
        bool,
        *mut bool,
        *mut bool,
        *mut bool,
        *mut f64,
    ) -> i32,
    pub get_f64: unsafe extern "C" fn(Inst, *const u32, usize, *mut f64, usize) -> i32,
    pub set_f64: unsafe extern "C" fn(Inst, *const u32, usize, *const f64, usize) -> i32,
    pub get_i32: unsafe extern "C" fn(Inst, *const u32, usize, *mut i32, usize) -> i32,
    pub get_state: unsafe extern "C" fn(Inst, *mut *mut c_void) -> i32,
    pub state_size: unsafe extern "C" fn(Inst, *mut c_void, *mut usize) -> i32,
    pub serialize: unsafe extern "C" fn(Inst, *mut c_void, *mut u8, usize) -> i32,
    pub deserialize: unsafe extern "C" fn(Inst, *const u8, usize, *mut *mut c_void) -> i32,
    pub set_state: unsafe extern "C" fn(Inst, *mut c_void) -> i32,
    pub free_state: unsafe extern "C" fn(Inst, *mut *mut c_void) -> i32,
}

impl Fmi3 {
    pub fn load() -> Self {
        let so = library_path(FmiVersion::V3);
        // SAFETY: each symbol is read with the type fmi3Functions.h declares for it; the
        // pointers live as long as `_lib`.
        unsafe {
            let lib = libloading::Library::new(&so).unwrap();
            macro_rules! f {
                ($name:literal) => {
                    *lib.get($name.as_bytes()).unwrap()
                };
            }
            Self {
                instantiate: f!("fmi3InstantiateCoSimulation"),
                free: f!("fmi3FreeInstance"),
                enter_init: f!("fmi3EnterInitializationMode"),
                exit_init: f!("fmi3ExitInitializationMode"),
                terminate: f!("fmi3Terminate"),
                reset: f!("fmi3Reset"),
                do_step: f!("fmi3DoStep"),
                get_f64: f!("fmi3GetFloat64"),
                set_f64: f!("fmi3SetFloat64"),
                get_i32: f!("fmi3GetInt32"),
                get_state: f!("fmi3GetFMUState"),
                state_size: f!("fmi3SerializedFMUStateSize"),
                serialize: f!("fmi3SerializeFMUState"),
                deserialize: f!("fmi3DeserializeFMUState"),
                set_state: f!("fmi3SetFMUState"),
                free_state: f!("fmi3FreeFMUState"),
                _lib: lib,
            }
        }
    }
}
