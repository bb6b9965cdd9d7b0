//! A small FMI 2.0 co-simulation importer (libloading): unpacks an `.fmu`, reads the variables
//! from its modelDescription.xml, loads the binary and drives it. Tests use it to check the
//! exported C API from the outside, and `rins fmu run` uses it to run a packaged FMU exactly as
//! the in-process plant runs. Every refused call returns the messages the FMU logged for it.

#![allow(unsafe_code)] // calling into a shared library is unsafe by nature; see each SAFETY note

use std::collections::HashMap;
use std::ffi::{CStr, CString, c_char, c_int, c_uint, c_void};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use libloading::{Library, Symbol};

/// A variable as the modelDescription declares it.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    /// Name.
    pub name: String,
    /// Value reference.
    pub vr: u32,
    /// `Real`, `Integer`, `Boolean`, `Enumeration` or `String`.
    pub type_name: String,
    /// `parameter`, `input`, `output`, `local`, …
    pub causality: String,
}

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

/// Attributes of every `<tag ...>` in `xml`, in order (enough for modelDescription files).
fn tags(xml: &str) -> Vec<(String, HashMap<String, String>)> {
    let mut out = Vec::new();
    let mut rest = xml;
    while let Some(i) = rest.find('<') {
        rest = &rest[i + 1..];
        let Some(end) = rest.find('>') else { break };
        let body = rest[..end].trim_end_matches('/');
        rest = &rest[end + 1..];
        if body.starts_with(['?', '!', '/']) {
            continue;
        }
        let (name, mut attrs_text) = body.split_once(char::is_whitespace).unwrap_or((body, ""));
        let mut attrs = HashMap::new();
        while let Some(eq) = attrs_text.find("=\"") {
            let key = attrs_text[..eq].trim().to_string();
            let after = &attrs_text[eq + 2..];
            let Some(close) = after.find('"') else { break };
            let v = after[..close]
                .replace("&quot;", "\"")
                .replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&amp;", "&");
            attrs.insert(key, v);
            attrs_text = &after[close + 1..];
        }
        out.push((name.to_string(), attrs));
    }
    out
}

/// The GUID and variables of an FMI 2.0 modelDescription.
pub fn parse_model_description(xml: &str) -> Result<(String, String, Vec<Variable>), String> {
    let t = tags(xml);
    let root = t
        .iter()
        .find(|(n, _)| n == "fmiModelDescription")
        .ok_or("no fmiModelDescription element")?;
    if root.1.get("fmiVersion").map(String::as_str) != Some("2.0") {
        return Err(format!(
            "this importer reads FMI 2.0; the FMU says fmiVersion {:?}",
            root.1.get("fmiVersion")
        ));
    }
    let guid = root.1.get("guid").cloned().ok_or("no guid")?;
    let id = t
        .iter()
        .find(|(n, _)| n == "CoSimulation")
        .and_then(|(_, a)| a.get("modelIdentifier").cloned())
        .ok_or("not a co-simulation FMU")?;
    let mut vars = Vec::new();
    for (i, (name, attrs)) in t.iter().enumerate() {
        if name != "ScalarVariable" {
            continue;
        }
        let type_name = t.get(i + 1).map(|(n, _)| n.clone()).unwrap_or_default();
        vars.push(Variable {
            name: attrs.get("name").cloned().unwrap_or_default(),
            vr: attrs
                .get("valueReference")
                .and_then(|v| v.parse().ok())
                .ok_or("ScalarVariable without a valueReference")?,
            type_name,
            causality: attrs
                .get("causality")
                .cloned()
                .unwrap_or_else(|| "local".into()),
        });
    }
    Ok((guid, id, vars))
}

type Component = *mut c_void;
type LoggerFn =
    unsafe extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char);

#[repr(C)]
struct Callbacks {
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
struct HotFns {
    do_step: DoStepFn,
    get_real: GetRealFn,
    set_real: SetRealFn,
}

/// An unpacked, loaded FMI 2.0 co-simulation FMU.
pub struct Fmu2 {
    hot: HotFns,
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
    /// Unpacks `fmu` into a fresh folder under the system temp dir and loads its Linux binary.
    pub fn open(fmu: &Path) -> Result<Self, String> {
        let bytes = std::fs::read(fmu).map_err(|e| format!("{}: {e}", fmu.display()))?;
        let entries = crate::zip::read(&bytes).map_err(|e| format!("{}: {e}", fmu.display()))?;
        let stamp = crate::zip::crc32(&bytes);
        let dir = std::env::temp_dir().join(format!(
            "rins-fmu-{}-{stamp:08x}-{:p}",
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

    fn sym<T>(&self, name: &str) -> Result<Symbol<'_, T>, String> {
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

/// One instance of an [`Fmu2`].
pub struct Instance2<'a> {
    fmu: &'a Fmu2,
    c: Component,
    log: Box<Mutex<Vec<String>>>,
    _callbacks: Box<Callbacks>,
}

/// An FMU state handle (free it with [`Instance2::free_state`]).
#[derive(Debug)]
pub struct StateHandle(*mut c_void);

type Vr = c_uint;

impl Instance2<'_> {
    fn check(&self, function: &'static str, status: c_int) -> Result<(), CallError> {
        let log = std::mem::take(&mut *self.log.lock().expect("log lock"));
        if status == 0 {
            Ok(())
        } else {
            Err(CallError {
                function,
                status,
                log,
            })
        }
    }

    /// Messages logged since the last call that returned them.
    pub fn take_log(&self) -> Vec<String> {
        std::mem::take(&mut *self.log.lock().expect("log lock"))
    }

    fn call<F: Copy>(&self, name: &'static str) -> Result<Symbol<'_, F>, CallError> {
        self.fmu.sym(name).map_err(|e| CallError {
            function: name,
            status: -1,
            log: vec![e],
        })
    }

    /// fmi2SetupExperiment.
    pub fn setup_experiment(&self, start_s: f64, stop_s: Option<f64>) -> Result<(), CallError> {
        let f = self
            .call::<unsafe extern "C" fn(Component, c_int, f64, f64, c_int, f64) -> c_int>(
                "fmi2SetupExperiment",
            )?;
        // SAFETY: FMI 2.0 signature, live instance.
        self.check("fmi2SetupExperiment", unsafe {
            f(
                self.c,
                0,
                0.0,
                start_s,
                stop_s.is_some() as c_int,
                stop_s.unwrap_or(0.0),
            )
        })
    }

    fn unit_call(&self, name: &'static str) -> Result<(), CallError> {
        let f = self.call::<unsafe extern "C" fn(Component) -> c_int>(name)?;
        // SAFETY: FMI 2.0 signature, live instance.
        self.check(name, unsafe { f(self.c) })
    }

    /// fmi2EnterInitializationMode.
    pub fn enter_initialization_mode(&self) -> Result<(), CallError> {
        self.unit_call("fmi2EnterInitializationMode")
    }

    /// fmi2ExitInitializationMode.
    pub fn exit_initialization_mode(&self) -> Result<(), CallError> {
        self.unit_call("fmi2ExitInitializationMode")
    }

    /// fmi2Terminate.
    pub fn terminate(&self) -> Result<(), CallError> {
        self.unit_call("fmi2Terminate")
    }

    /// fmi2Reset.
    pub fn reset(&self) -> Result<(), CallError> {
        self.unit_call("fmi2Reset")
    }

    /// fmi2DoStep.
    pub fn do_step(&self, t_s: f64, h_s: f64) -> Result<(), CallError> {
        // SAFETY: FMI 2.0 signature, live instance.
        let status = unsafe { (self.fmu.hot.do_step)(self.c, t_s, h_s, 1) };
        if status == 0 {
            Ok(())
        } else {
            self.check("fmi2DoStep", status)
        }
    }

    /// fmi2GetReal.
    pub fn get_real(&self, vrs: &[Vr], out: &mut [f64]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), out.len());
        // SAFETY: arrays of equal length.
        let status =
            unsafe { (self.fmu.hot.get_real)(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr()) };
        if status == 0 {
            Ok(())
        } else {
            self.check("fmi2GetReal", status)
        }
    }

    /// fmi2GetInteger.
    pub fn get_integer(&self, vrs: &[Vr], out: &mut [i32]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), out.len());
        let f = self
            .call::<unsafe extern "C" fn(Component, *const Vr, usize, *mut c_int) -> c_int>(
                "fmi2GetInteger",
            )?;
        // SAFETY: arrays of equal length.
        self.check("fmi2GetInteger", unsafe {
            f(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr())
        })
    }

    /// fmi2GetBoolean.
    pub fn get_boolean(&self, vrs: &[Vr], out: &mut [i32]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), out.len());
        let f = self
            .call::<unsafe extern "C" fn(Component, *const Vr, usize, *mut c_int) -> c_int>(
                "fmi2GetBoolean",
            )?;
        // SAFETY: arrays of equal length.
        self.check("fmi2GetBoolean", unsafe {
            f(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr())
        })
    }

    /// fmi2SetReal.
    pub fn set_real(&self, vrs: &[Vr], values: &[f64]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), values.len());
        // SAFETY: arrays of equal length.
        let status =
            unsafe { (self.fmu.hot.set_real)(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr()) };
        if status == 0 {
            Ok(())
        } else {
            self.check("fmi2SetReal", status)
        }
    }

    /// fmi2SetInteger.
    pub fn set_integer(&self, vrs: &[Vr], values: &[i32]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), values.len());
        let f = self
            .call::<unsafe extern "C" fn(Component, *const Vr, usize, *const c_int) -> c_int>(
                "fmi2SetInteger",
            )?;
        // SAFETY: arrays of equal length.
        self.check("fmi2SetInteger", unsafe {
            f(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr())
        })
    }

    /// fmi2SetBoolean.
    pub fn set_boolean(&self, vrs: &[Vr], values: &[bool]) -> Result<(), CallError> {
        let v: Vec<c_int> = values.iter().map(|b| *b as c_int).collect();
        let f = self
            .call::<unsafe extern "C" fn(Component, *const Vr, usize, *const c_int) -> c_int>(
                "fmi2SetBoolean",
            )?;
        // SAFETY: arrays of equal length.
        self.check("fmi2SetBoolean", unsafe {
            f(self.c, vrs.as_ptr(), vrs.len().min(v.len()), v.as_ptr())
        })
    }

    /// fmi2GetFMUstate (a new handle).
    pub fn get_state(&self) -> Result<StateHandle, CallError> {
        let f = self.call::<unsafe extern "C" fn(Component, *mut *mut c_void) -> c_int>(
            "fmi2GetFMUstate",
        )?;
        let mut s: *mut c_void = std::ptr::null_mut();
        // SAFETY: valid out-pointer.
        self.check("fmi2GetFMUstate", unsafe { f(self.c, &mut s) })?;
        Ok(StateHandle(s))
    }

    /// fmi2SetFMUstate.
    pub fn set_state(&self, s: &StateHandle) -> Result<(), CallError> {
        let f =
            self.call::<unsafe extern "C" fn(Component, *mut c_void) -> c_int>("fmi2SetFMUstate")?;
        // SAFETY: handle from this FMU.
        self.check("fmi2SetFMUstate", unsafe { f(self.c, s.0) })
    }

    /// fmi2FreeFMUstate.
    pub fn free_state(&self, mut s: StateHandle) -> Result<(), CallError> {
        let f = self.call::<unsafe extern "C" fn(Component, *mut *mut c_void) -> c_int>(
            "fmi2FreeFMUstate",
        )?;
        // SAFETY: handle from this FMU.
        self.check("fmi2FreeFMUstate", unsafe { f(self.c, &mut s.0) })
    }

    /// fmi2SerializedFMUstateSize + fmi2SerializeFMUstate.
    pub fn serialize_state(&self, s: &StateHandle) -> Result<Vec<u8>, CallError> {
        let size_f = self
            .call::<unsafe extern "C" fn(Component, *mut c_void, *mut usize) -> c_int>(
                "fmi2SerializedFMUstateSize",
            )?;
        let mut n = 0usize;
        // SAFETY: handle from this FMU, valid out-pointer.
        self.check("fmi2SerializedFMUstateSize", unsafe {
            size_f(self.c, s.0, &mut n)
        })?;
        let mut buf = vec![0u8; n];
        let f = self
            .call::<unsafe extern "C" fn(Component, *mut c_void, *mut c_char, usize) -> c_int>(
                "fmi2SerializeFMUstate",
            )?;
        // SAFETY: buffer of the size the FMU asked for.
        self.check("fmi2SerializeFMUstate", unsafe {
            f(self.c, s.0, buf.as_mut_ptr() as *mut c_char, n)
        })?;
        Ok(buf)
    }

    /// fmi2DeSerializeFMUstate.
    pub fn deserialize_state(&self, bytes: &[u8]) -> Result<StateHandle, CallError> {
        let f = self.call::<unsafe extern "C" fn(
            Component,
            *const c_char,
            usize,
            *mut *mut c_void,
        ) -> c_int>("fmi2DeSerializeFMUstate")?;
        let mut s: *mut c_void = std::ptr::null_mut();
        // SAFETY: byte buffer and out-pointer.
        self.check("fmi2DeSerializeFMUstate", unsafe {
            f(self.c, bytes.as_ptr() as *const c_char, bytes.len(), &mut s)
        })?;
        Ok(StateHandle(s))
    }
}

impl Drop for Instance2<'_> {
    fn drop(&mut self) {
        if let Ok(f) = self
            .fmu
            .sym::<unsafe extern "C" fn(Component)>("fmi2FreeInstance")
        {
            // SAFETY: the instance is freed exactly once, here.
            unsafe { f(self.c) };
        }
    }
}
