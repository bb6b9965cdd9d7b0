//! # rins-fmi2
//!
//! The FMI 2.0 co-simulation C API, generic over any [`rins_fmi::model::Model`]: the 34
//! functions of `fmi2Functions.h` as generic Rust functions ([`lifecycle`], [`values`],
//! [`state`]) and the [`export_fmi2!`] macro that exports them, under their C names and nothing
//! else, for one model. A model's FMI 2 library is a cdylib crate whose whole source is
//!
//! ```ignore
//! rins_fmi2::export_fmi2!(my_model_crate::MyModel);
//! ```
//!
//! Every entry point catches panics (a panic becomes `fmi2Fatal` with a logged reason),
//! tolerates NULL where the standard allows and logs why any call is refused.

// The C ABI needs raw pointers from the caller; each dereference is guarded by a NULL check and
// the lengths the standard defines.
#![allow(unsafe_code)]
#![allow(non_camel_case_types)]
// Each pointer's contract (valid for n elements, or NULL where allowed) is the standard's.
#![allow(clippy::missing_safety_doc)]

use std::ffi::{CStr, CString, c_char, c_int, c_uint, c_void};

use rins_fmi::ffi::{Component, Logger};
use rins_fmi::instance::Status;

pub mod lifecycle;
pub mod state;
pub mod values;

mod export;

/// `fmi2Component`.
pub type fmi2Component = *mut c_void;
/// `fmi2ComponentEnvironment`.
pub type fmi2ComponentEnvironment = *mut c_void;
/// `fmi2FMUstate`.
pub type fmi2FMUstate = *mut c_void;
/// `fmi2ValueReference`.
pub type fmi2ValueReference = c_uint;
/// `fmi2Real`.
pub type fmi2Real = f64;
/// `fmi2Integer`.
pub type fmi2Integer = c_int;
/// `fmi2Boolean`.
pub type fmi2Boolean = c_int;
/// `fmi2String`.
pub type fmi2String = *const c_char;
/// `fmi2Byte`.
pub type fmi2Byte = c_char;
/// `fmi2Status`.
pub type fmi2Status = c_int;
/// `fmi2Type`.
pub type fmi2Type = c_int;
/// `fmi2StatusKind`.
pub type fmi2StatusKind = c_int;

/// `fmi2CallbackLogger`: variadic in C; we always pass a format with no directives.
pub type fmi2CallbackLogger = Option<
    unsafe extern "C" fn(
        fmi2ComponentEnvironment,
        fmi2String,
        fmi2Status,
        fmi2String,
        fmi2String,
        ...
    ),
>;

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct fmi2CallbackFunctions {
    logger: fmi2CallbackLogger,
    allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2Status)>,
    component_environment: fmi2ComponentEnvironment,
}

/// The importer's FMI 2 logger, with the instance name it wants in every message.
pub struct Fmi2Logger {
    callback: fmi2CallbackLogger,
    env: fmi2ComponentEnvironment,
    name: CString,
}

impl Logger for Fmi2Logger {
    fn emit(&self, status: Status, category: &str, message: &str) {
        let Some(f) = self.callback else { return };
        // The message is used as a printf format by C masters: escape '%'.
        let msg = CString::new(message.replace('%', "%%").replace('\0', " ")).unwrap_or_default();
        let cat = CString::new(category).unwrap_or_default();
        // SAFETY: the master gave us this callback for exactly this call signature.
        unsafe {
            f(
                self.env,
                self.name.as_ptr(),
                status as fmi2Status,
                cat.as_ptr(),
                msg.as_ptr(),
            )
        };
    }
}

impl Fmi2Logger {
    /// The logger of `functions` (NULL: none) for the instance `name` (NULL: "(unnamed)").
    ///
    /// # Safety
    /// `functions` is NULL or a valid `fmi2CallbackFunctions`; `name` NULL or a C string.
    pub unsafe fn new(functions: *const fmi2CallbackFunctions, name: fmi2String) -> Self {
        // SAFETY: NULL-checked; the standard gives these as a struct / a C string.
        let (callback, env) = if functions.is_null() {
            (None, std::ptr::null_mut())
        } else {
            unsafe { ((*functions).logger, (*functions).component_environment) }
        };
        let name = if name.is_null() {
            CString::from(c"(unnamed)")
        } else {
            unsafe { CStr::from_ptr(name) }.to_owned()
        };
        Self {
            callback,
            env,
            name,
        }
    }
}

/// What an `fmi2Component` points at for model `M`.
pub type Fmi2<M> = Component<M, Fmi2Logger>;

/// Runs `f` on the component, catching panics and logging refusals (see [`rins_fmi::ffi::with`]).
pub fn with<M: rins_fmi::model::Model>(
    c: fmi2Component,
    what: &str,
    f: impl FnOnce(&mut Fmi2<M>) -> Result<(), rins_fmi::instance::FmiError>,
) -> fmi2Status {
    rins_fmi::ffi::with::<M, Fmi2Logger>(c, what, f) as fmi2Status
}

/// Logs why an entry point is not provided and returns `fmi2Error`.
pub fn unsupported<M: rins_fmi::model::Model>(
    c: fmi2Component,
    what: &str,
    why: &str,
) -> fmi2Status {
    rins_fmi::ffi::unsupported::<M, Fmi2Logger>(c, what, why) as fmi2Status
}

#[doc(hidden)]
pub use rins_fmi as __rins_fmi;

#[cfg(test)]
mod tests;
