//! A small FMI 2.0 co-simulation importer (libloading): unpacks an `.fmu`, reads the variables
//! from its modelDescription.xml, loads the binary and drives it. Tests use it to check the
//! exported C API from the outside, and `rins fmu run` uses it to run a packaged FMU exactly as
//! the in-process plant runs. Every refused call returns the messages the FMU logged for it.

#![allow(unsafe_code)] // calling into a shared library is unsafe by nature; see each SAFETY note

mod description;
mod instance;

pub use description::{Variable, parse_model_description};
pub use instance::{Instance2, StateHandle};

use std::ffi::{CStr, CString, c_char, c_int, c_uint, c_void};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use libloading::{Library, Symbol};

/// A failed FMI call: its status and what the FMU logged while handling it.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{function} returned status {status}: {}", if log.is_empty() { "(nothing logged)".to_string() } else { log.join(" | ") })]
pub struct CallError {
    /// The function.
    pub function: &'static str,
    /// Its status (0 OK … 4 fatal; -1 when instantiate returned NULL).
    pub status: i32,
    /// Messages logged during the call.
    pub log: Vec<String>,
}

type Component = *mut c_void;
type Vr = c_uint;
type LoggerFn =
    unsafe extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char);

#[repr(C)]
pub(crate) struct Callbacks {
    logger: Option<LoggerFn>,
    allocate: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: *const c_void,
    env: *mut c_void,
}

/// `calloc` for FMUs that use the master's allocator: a 16-byte header holds the size so that
/// [`free_cb`] can rebuild the layout.
unsafe extern "C" fn calloc_cb(n: usize, size: usize) -> *mut c_void {
    let Some(bytes) = n.checked_mul(size).and_then(|b| b.checked_add(16)) else {
        return std::ptr::null_mut();
    };
    let Ok(layout) = std::alloc::Layout::from_size_align(bytes, 16) else {
        return std::ptr::null_mut();
    };
    // SAFETY: non-zero size; the header is written before handing out the rest.
    unsafe {
        let p = std::alloc::alloc_zeroed(layout);
        if p.is_null() {
            return std::ptr::null_mut();
        }
        (p as *mut usize).write(bytes);
        p.add(16) as *mut c_void
    }
}

unsafe extern "C" fn free_cb(p: *mut c_void) {
    if p.is_null() {
        return;
    }
    // SAFETY: `p` came from calloc_cb, 16 bytes after the header.
    unsafe {
        let base = (p as *mut u8).sub(16);
        let bytes = (base as *const usize).read();
        std::alloc::dealloc(
            base,
            std::alloc::Layout::from_size_align_unchecked(bytes, 16),
        );
    }
}

/// Collects the messages an instance logs. The FMU calls the logger as a C variadic function;
/// we read only the fixed arguments (our FMUs pass messages with `%` escaped and no arguments).
unsafe extern "C" fn logger_cb(
    env: *mut c_void,
    _name: *const c_char,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    if env.is_null() || message.is_null() {
        return;
    }
    // SAFETY: `env` is the Mutex we passed at instantiation; strings are NUL-terminated.
    let sink = unsafe { &*(env as *const Mutex<Vec<String>>) };
    let cat = if category.is_null() {
        String::new()
    } else {
        unsafe { CStr::from_ptr(category) }
            .to_string_lossy()
            .into_owned()
    };
    let msg = unsafe { CStr::from_ptr(message) }
        .to_string_lossy()
        .replace("%%", "%");
    if let Ok(mut v) = sink.lock() {
        v.push(format!("[{status} {cat}] {msg}"));
    }
}

type DoStepFn = unsafe extern "C" fn(Component, f64, f64, c_int) -> c_int;
type GetRealFn = unsafe extern "C" fn(Component, *const Vr, usize, *mut f64) -> c_int;
type SetRealFn = unsafe extern "C" fn(Component, *const Vr, usize, *const f64) -> c_int;

/// Functions called once per communication step, resolved once at load (a symbol lookup per
/// call would cost more than the step itself).
#[derive(Clone, Copy)]
pub(crate) struct HotFns {
    pub(crate) do_step: DoStepFn,
    pub(crate) get_real: GetRealFn,
    pub(crate) set_real: SetRealFn,
}

/// An unpacked, loaded FMI 2.0 co-simulation FMU.
pub struct Fmu2 {
    pub(crate) hot: HotFns,
    lib: Library,
    /// GUID from the modelDescription.
    pub guid: String,
    /// Model identifier.
    pub model_identifier: String,
    /// Variables by name.
    pub variables: Vec<Variable>,
    dir: PathBuf,
}

impl Fmu2 {
    /// Unpacks `fmu` (stored or deflated entries) into a fresh folder under the system temp dir
    /// and loads its Linux binary.
    pub fn open(fmu: &Path) -> Result<Self, String> {
        let bytes = std::fs::read(fmu).map_err(|e| format!("{}: {e}", fmu.display()))?;
        let entries = rins_fmi::zip::read(&bytes).map_err(|e| format!("{}: {e}", fmu.display()))?;
        let stamp = {
            use std::hash::{Hash, Hasher};
            let mut h = std::collections::hash_map::DefaultHasher::new();
            bytes.hash(&mut h);
            h.finish()
        };
        let dir = std::env::temp_dir().join(format!(
            "rins-fmu-{}-{stamp:016x}-{:p}",
            std::process::id(),
            &bytes
        ));
        for (name, data) in &entries {
            if name.contains("..") {
                return Err(format!(
                    "{}: entry {name:?} escapes the FMU folder",
                    fmu.display()
                ));
            }
            let p = dir.join(name);
            std::fs::create_dir_all(p.parent().expect("entry has a parent"))
                .map_err(|e| format!("{}: {e}", p.display()))?;
            std::fs::write(&p, data).map_err(|e| format!("{}: {e}", p.display()))?;
        }
        let xml = std::fs::read_to_string(dir.join("modelDescription.xml"))
            .map_err(|e| format!("{}: modelDescription.xml: {e}", fmu.display()))?;
        let (guid, id, variables) =
            parse_model_description(&xml).map_err(|e| format!("{}: {e}", fmu.display()))?;
        let so = dir.join("binaries/linux64").join(format!("{id}.so"));
        let mut f = Self::load(&so, guid, variables)?;
        f.dir = dir;
        Ok(f)
    }

    /// Loads a bare shared library with the given GUID and variables (tests of the binary).
    pub fn load(so: &Path, guid: String, variables: Vec<Variable>) -> Result<Self, String> {
        // SAFETY: loading runs the library's initialisers; ours has none beyond Rust's.
        let lib = unsafe { Library::new(so) }.map_err(|e| format!("{}: {e}", so.display()))?;
        let model_identifier = so
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        // SAFETY: the types are the FMI 2.0 header's; the pointers live as long as `lib`, which
        // this struct owns and drops last.
        let hot = unsafe {
            let get = |name: &str| {
                lib.get::<*const c_void>(name.as_bytes())
                    .map(|s| *s)
                    .map_err(|e| format!("{name}: {e}"))
            };
            HotFns {
                do_step: std::mem::transmute::<*const c_void, DoStepFn>(get("fmi2DoStep")?),
                get_real: std::mem::transmute::<*const c_void, GetRealFn>(get("fmi2GetReal")?),
                set_real: std::mem::transmute::<*const c_void, SetRealFn>(get("fmi2SetReal")?),
            }
        };
        Ok(Self {
            hot,
            lib,
            guid,
            model_identifier,
            variables,
            dir: PathBuf::new(),
        })
    }

    /// Value reference of the variable `name`.
    pub fn vr(&self, name: &str) -> Result<u32, String> {
        self.variables
            .iter()
            .find(|v| v.name == name)
            .map(|v| v.vr)
            .ok_or_else(|| format!("the FMU has no variable {name:?}"))
    }

    /// The declared variable `name`.
    pub fn variable(&self, name: &str) -> Option<&Variable> {
        self.variables.iter().find(|v| v.name == name)
    }

    pub(crate) fn sym<T>(&self, name: &str) -> Result<Symbol<'_, T>, String> {
        // SAFETY: T is the function type the FMI 2.0 header declares for `name`.
        unsafe { self.lib.get(name.as_bytes()) }.map_err(|e| format!("{name}: {e}"))
    }

    /// Instantiates with this FMU's GUID.
    pub fn instantiate(&self, name: &str, logging_on: bool) -> Result<Instance2<'_>, CallError> {
        self.instantiate_with_guid(name, &self.guid.clone(), logging_on)
    }

    /// Instantiates with an explicit GUID (tests of the mismatch check).
    pub fn instantiate_with_guid(
        &self,
        name: &str,
        guid: &str,
        logging_on: bool,
    ) -> Result<Instance2<'_>, CallError> {
        let log = Box::new(Mutex::new(Vec::new()));
        let callbacks = Box::new(Callbacks {
            logger: Some(logger_cb),
            allocate: Some(calloc_cb),
            free: Some(free_cb),
            step_finished: std::ptr::null(),
            env: &*log as *const Mutex<Vec<String>> as *mut c_void,
        });
        let f: Symbol<
            unsafe extern "C" fn(
                *const c_char,
                c_int,
                *const c_char,
                *const c_char,
                *const Callbacks,
                c_int,
                c_int,
            ) -> Component,
        > = self.sym("fmi2Instantiate").map_err(|e| CallError {
            function: "fmi2Instantiate",
            status: -1,
            log: vec![e],
        })?;
        let (n, g) = (
            CString::new(name).unwrap_or_default(),
            CString::new(guid).unwrap_or_default(),
        );
        let uri =
            CString::new(format!("file://{}/resources", self.dir.display())).unwrap_or_default();
        // SAFETY: arguments follow the FMI 2.0 signature; callbacks and log outlive the instance.
        let c = unsafe {
            f(
                n.as_ptr(),
                1,
                g.as_ptr(),
                uri.as_ptr(),
                &*callbacks,
                0,
                logging_on as c_int,
            )
        };
        if c.is_null() {
            return Err(CallError {
                function: "fmi2Instantiate",
                status: -1,
                log: log.lock().map(|v| v.clone()).unwrap_or_default(),
            });
        }
        Ok(Instance2 {
            fmu: self,
            c,
            log,
            _callbacks: callbacks,
        })
    }
}

impl Drop for Fmu2 {
    fn drop(&mut self) {
        if !self.dir.as_os_str().is_empty() {
            let _ = std::fs::remove_dir_all(&self.dir);
        }
    }
}
