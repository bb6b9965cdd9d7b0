//! # rins-fmi3
//!
//! The FMI 3.0 C API, generic over any [`rins_fmi::model::Model`]: every function of
//! `fmi3Functions.h` as a generic Rust function ([`lifecycle`], [`values`], [`state`],
//! [`unsupported`]) and the [`export_fmi3!`] macro that exports all 75, under their C names and
//! nothing else, for one model:
//!
//! ```ignore
//! rins_fmi3::export_fmi3!(my_model_crate::MyModel);
//! ```
//!
//! Co-simulation is implemented; Model Exchange, Scheduled Execution, clocks, intervals and
//! derivatives log why they are unsupported and return `fmi3Error`. Every entry point catches
//! panics.

// The C ABI needs raw pointers from the caller; each dereference is guarded by a NULL check and
// the lengths the standard defines.
#![allow(unsafe_code)]
#![allow(non_camel_case_types)]
// Each pointer's contract is the standard's.
#![allow(clippy::missing_safety_doc, clippy::too_many_arguments)]

use std::ffi::{CString, c_char, c_void};

use rins_fmi::ffi::{Component, Logger};
use rins_fmi::instance::{FmiError, Status};
use rins_fmi::model::Model;

pub mod lifecycle;
pub mod state;
pub mod unsupported;
pub mod values;

mod export;

#[doc(hidden)]
pub use rins_fmi as __rins_fmi;

/// `fmi3Instance`.
pub type fmi3Instance = *mut c_void;
/// `fmi3InstanceEnvironment`.
pub type fmi3InstanceEnvironment = *mut c_void;
/// `fmi3FMUState`.
pub type fmi3FMUState = *mut c_void;
/// `fmi3ValueReference`.
pub type fmi3ValueReference = u32;
/// `fmi3Status`.
pub type fmi3Status = i32;
/// `fmi3String`.
pub type fmi3String = *const c_char;
/// `fmi3Boolean`.
pub type fmi3Boolean = bool;
/// `fmi3Byte`.
pub type fmi3Byte = u8;
/// `fmi3Binary`.
pub type fmi3Binary = *const u8;
/// `fmi3LogMessageCallback`.
pub type fmi3LogMessageCallback =
    Option<unsafe extern "C" fn(fmi3InstanceEnvironment, fmi3Status, fmi3String, fmi3String)>;
/// Callbacks this FMU never calls (intermediate update, clock update, lock/unlock).
pub type fmi3Callback = *const c_void;

/// The importer's FMI 3 logger.
pub struct Fmi3Logger {
    callback: fmi3LogMessageCallback,
    env: fmi3InstanceEnvironment,
}

impl Logger for Fmi3Logger {
    fn emit(&self, status: Status, category: &str, message: &str) {
        let Some(f) = self.callback else { return };
        let msg = CString::new(message.replace('\0', " ")).unwrap_or_default();
        let cat = CString::new(category).unwrap_or_default();
        // SAFETY: the importer gave us this callback with exactly this signature.
        unsafe { f(self.env, status as fmi3Status, cat.as_ptr(), msg.as_ptr()) };
    }
}

/// What an `fmi3Instance` points at for model `M`.
pub type Fmi3<M> = Component<M, Fmi3Logger>;

/// Runs `f` on the instance, catching panics and logging refusals; a failed call leaves the
/// instance in error mode until reset or state restore (see [`rins_fmi::ffi::with_errors`]).
pub fn with<M: Model>(
    c: fmi3Instance,
    what: &str,
    f: impl FnOnce(&mut Fmi3<M>) -> Result<(), FmiError>,
) -> fmi3Status {
    rins_fmi::ffi::with_errors::<M, Fmi3Logger>(c, what, true, f) as fmi3Status
}

/// Logs why an entry point is not provided and returns `fmi3Error`.
pub fn refuse<M: Model>(c: fmi3Instance, what: &str, why: &str) -> fmi3Status {
    rins_fmi::ffi::unsupported::<M, Fmi3Logger>(c, what, why) as fmi3Status
}
