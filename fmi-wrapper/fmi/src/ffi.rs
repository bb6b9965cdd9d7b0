//! C-ABI helpers the FMI 2 and FMI 3 layers share, written once: arrays from the caller's
//! pointers, the component behind an FMI instance handle with its logging rule (a handle is
//! only used while [`crate::live`] has it), the panic-catching call wrapper, log-category and
//! token checks, and the FMU state functions.

#![allow(unsafe_code)] // turning the caller's pointers into references and slices

use std::ffi::{CStr, c_char, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};

use crate::fmu;
use crate::instance::{FmiError, Instance, Status};
use crate::live;
use crate::model::Model;
use crate::standard::{FmiVersion, LOG_CATEGORIES};

/// The caller's array of `n` elements at `p` (NULL only when `n` is 0).
///
/// # Safety
/// `p` must point at `n` initialised elements that stay valid for the returned lifetime.
pub unsafe fn slice<'a, T>(p: *const T, n: usize) -> Result<&'a [T], FmiError> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(FmiError::error("NULL array with a non-zero length"));
    }
    // SAFETY: the caller guarantees `n` elements at `p`.
    Ok(unsafe { std::slice::from_raw_parts(p, n) })
}

/// The caller's writable array of `n` elements at `p` (NULL only when `n` is 0).
///
/// # Safety
/// `p` must point at `n` writable elements, not aliased, valid for the returned lifetime.
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize) -> Result<&'a mut [T], FmiError> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(FmiError::error("NULL array with a non-zero length"));
    }
    // SAFETY: the caller guarantees `n` writable elements at `p`.
    Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
}

/// The text of a C string, `""` for NULL or invalid UTF-8.
///
/// # Safety
/// `p` is NULL or a NUL-terminated string valid for the returned lifetime.
pub unsafe fn text<'a>(p: *const c_char) -> &'a str {
    if p.is_null() {
        ""
    } else {
        // SAFETY: NUL-terminated per the caller.
        unsafe { CStr::from_ptr(p) }.to_str().unwrap_or("")
    }
}

/// The text of a panic payload (for the "internal error" log line).
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}

/// How an FMI version hands a message to the importer's callback (`'static`: the component
/// type is the key of its handles in [`crate::live`]).
pub trait Logger: 'static {
    /// Passes one message on (NULL callbacks are skipped by the implementation).
    fn emit(&self, status: Status, category: &str, message: &str);
}

/// What an FMI instance handle points at: the generic instance and the importer's logger.
pub struct Component<M: Model, L: Logger> {
    /// The state machine and model.
    pub inst: Instance<M>,
    /// The importer's callback.
    pub logger: L,
    /// `loggingOn`: event messages are only sent when set.
    pub logging_on: bool,
}

impl<M: Model, L: Logger> Component<M, L> {
    /// Logs: errors and warnings always, event messages (status OK) only with loggingOn.
    pub fn log(&self, status: Status, category: &str, message: &str) {
        if status == Status::Ok && !self.logging_on {
            return;
        }
        self.logger.emit(status, category, message);
    }

    /// The logEvents message of an accepted doStep (callers test `logging_on` first, so the
    /// message is only formatted when it is sent).
    #[cold]
    pub fn log_step(&self, t_s: f64, h_s: f64) {
        self.log(
            Status::Ok,
            "logEvents",
            &format!(
                "doStep from t = {t_s} s by {h_s} s; now at t = {} s",
                self.inst.time_s()
            ),
        );
    }

    /// A new component on the heap, as the opaque handle instantiate returns, registered as
    /// live.
    pub fn into_handle(self) -> *mut c_void {
        let handle = Box::into_raw(Box::new(self)) as *mut c_void;
        live::register::<Self>(handle);
        handle
    }

    /// Frees a handle from [`Component::into_handle`], catching panics. NULL, a handle freed
    /// before and any pointer that is not a live component of this type are ignored: there is
    /// nothing to free, and no logger to tell (the instance's logger went with it).
    ///
    /// # Safety
    /// None beyond the FMI call: the pointer is only dereferenced if [`crate::live`] has it.
    pub unsafe fn free_handle(c: *mut c_void) {
        if !live::unregister::<Self>(c) {
            return;
        }
        let _ = catch_unwind(AssertUnwindSafe(|| {
            // SAFETY: a live Box from `into_handle`, now unregistered, so freed only here.
            drop(unsafe { Box::from_raw(c as *mut Self) })
        }));
    }
}

/// Runs `f` on the component behind handle `c`, catching panics: a refusal is logged as
/// "`what`: reason" and its status returned, a panic is logged and returns Fatal.
///
/// A handle that is not a live component of this type (NULL, freed, never instantiated:
/// [`crate::live`]) returns Error untouched, with nothing logged, since there is no instance
/// whose logger could be called.
pub fn with<M: Model, L: Logger>(
    c: *mut c_void,
    what: &str,
    f: impl FnOnce(&mut Component<M, L>) -> Result<(), FmiError>,
) -> Status {
    with_errors(c, what, false, f)
}

/// [`with`], and when `sticky` a call that fails (Error or Fatal) leaves the instance in
/// [`crate::instance::Mode::Error`], so that only reset, free, state restore and reads are
/// accepted until reset, as the standard says after an error (FMI 3: ecos carries on
/// after an error status, and must not step an instance whose last call was refused).
pub fn with_errors<M: Model, L: Logger>(
    c: *mut c_void,
    what: &str,
    sticky: bool,
    f: impl FnOnce(&mut Component<M, L>) -> Result<(), FmiError>,
) -> Status {
    // One uncontended lock per call (tens of nanoseconds against the microseconds of a
    // doStep); the lock is not held during the call, so instances step in parallel. The
    // standard forbids calling one instance from two threads at once, so it cannot be freed
    // between this check and the end of the call.
    if !live::is_live::<Component<M, L>>(c) {
        return Status::Error;
    }
    // SAFETY: `c` is a live Box<Component<M, L>> (registered by `into_handle`, not freed).
    let comp = unsafe { &mut *(c as *mut Component<M, L>) };
    match catch_unwind(AssertUnwindSafe(|| f(comp))) {
        Ok(Ok(())) => Status::Ok,
        Ok(Err(e)) => {
            comp.log(e.status, e.category, &format!("{what}: {}", e.message));
            if sticky && e.status >= Status::Error {
                comp.inst.fail();
            }
            e.status
        }
        Err(panic) => {
            let msg = panic_message(panic.as_ref());
            comp.log(
                Status::Fatal,
                "logStatusError",
                &format!("{what}: internal error: {msg}"),
            );
            if sticky {
                comp.inst.fail();
            }
            Status::Fatal
        }
    }
}

/// An entry point this FMU does not provide: logs why and returns Error.
pub fn unsupported<M: Model, L: Logger>(c: *mut c_void, what: &str, why: &str) -> Status {
    with::<M, L>(c, what, |_| {
        Err(FmiError::error(format!("not supported: {why}")))
    })
}

/// Checks the categories of setDebugLogging against those the FMUs declare.
///
/// # Safety
/// `categories` holds `n` C strings (NULL only when `n` is 0).
pub unsafe fn check_log_categories(
    categories: *const *const c_char,
    n: usize,
) -> Result<(), FmiError> {
    // SAFETY: per the contract.
    for &cat in unsafe { slice(categories, n)? } {
        let name = unsafe { text(cat) };
        if !LOG_CATEGORIES.iter().any(|(n, _)| *n == name) {
            return Err(FmiError::error(format!("unknown log category {name:?}")));
        }
    }
    Ok(())
}

/// Checks the GUID / instantiation token the importer read from modelDescription.xml against
/// the one this binary computes for `M`.
pub fn check_token<M: Model>(version: FmiVersion, given: &str) -> Result<(), String> {
    let expected = &fmu::description::<M>(version).1;
    if given == expected {
        Ok(())
    } else {
        let what = match version {
            FmiVersion::V2 => "GUID",
            FmiVersion::V3 => "instantiation token",
        };
        Err(format!(
            "{what} {given:?} does not match this binary's {expected:?}: modelDescription.xml and binary are from different builds"
        ))
    }
}

/// getFMUstate: a snapshot into a new handle, or into the caller's existing one.
///
/// # Safety
/// `state` is a valid pointer; a non-NULL `*state` is a handle from these functions for `M`.
pub unsafe fn get_state<M: Model>(
    inst: &Instance<M>,
    state: *mut *mut c_void,
) -> Result<(), FmiError> {
    if state.is_null() {
        return Err(FmiError::error("NULL FMU state pointer"));
    }
    // SAFETY: per the contract; an existing state is overwritten in place.
    unsafe {
        if (*state).is_null() {
            *state = Box::into_raw(Box::new(inst.snapshot())) as *mut c_void;
        } else {
            *(*state as *mut Instance<M>) = inst.snapshot();
        }
    }
    Ok(())
}

/// setFMUstate.
///
/// # Safety
/// `state` is NULL or a handle from these functions for `M`.
pub unsafe fn set_state<M: Model>(
    inst: &mut Instance<M>,
    state: *mut c_void,
) -> Result<(), FmiError> {
    if state.is_null() {
        return Err(FmiError::error("NULL FMU state"));
    }
    // SAFETY: per the contract.
    inst.restore_snapshot(unsafe { &*(state as *const Instance<M>) });
    Ok(())
}

/// freeFMUstate: frees `*state` and clears it (NULL pointers are fine).
///
/// # Safety
/// `state` is NULL or points at NULL or a handle from these functions for `M`.
pub unsafe fn free_state<M: Model>(state: *mut *mut c_void) -> Result<(), FmiError> {
    // SAFETY: per the contract; freed once and cleared.
    unsafe {
        if !state.is_null() && !(*state).is_null() {
            drop(Box::from_raw(*state as *mut Instance<M>));
            *state = std::ptr::null_mut();
        }
    }
    Ok(())
}

/// serializedFMUstateSize.
///
/// # Safety
/// `state` is NULL or a handle for `M`; `size` is NULL or writable.
pub unsafe fn state_size<M: Model>(state: *mut c_void, size: *mut usize) -> Result<(), FmiError> {
    if state.is_null() || size.is_null() {
        return Err(FmiError::error("NULL FMU state or size pointer"));
    }
    // SAFETY: per the contract.
    unsafe { *size = (*(state as *const Instance<M>)).serialize().len() };
    Ok(())
}

/// serializeFMUstate into the caller's buffer of `size` bytes.
///
/// # Safety
/// `state` is NULL or a handle for `M`; `bytes` has `size` writable bytes.
pub unsafe fn serialize_state<M: Model>(
    state: *mut c_void,
    bytes: *mut u8,
    size: usize,
) -> Result<(), FmiError> {
    if state.is_null() {
        return Err(FmiError::error("NULL FMU state"));
    }
    // SAFETY: per the contract.
    let data = unsafe { (*(state as *const Instance<M>)).serialize() };
    if data.len() != size {
        return Err(FmiError::error(format!(
            "buffer has {size} bytes, the state needs {}",
            data.len()
        )));
    }
    unsafe { slice_mut(bytes, size)? }.copy_from_slice(&data);
    Ok(())
}

/// deSerializeFMUstate into a new handle.
///
/// # Safety
/// `bytes` has `size` readable bytes; `state` is NULL or writable.
pub unsafe fn deserialize_state<M: Model>(
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> Result<(), FmiError> {
    if state.is_null() {
        return Err(FmiError::error("NULL FMU state pointer"));
    }
    // SAFETY: per the contract.
    let inst = Instance::<M>::deserialize(unsafe { slice(bytes, size)? })?;
    unsafe { *state = Box::into_raw(Box::new(inst)) as *mut c_void };
    Ok(())
}

/// Defines one exported C function per entry, each forwarding its arguments to a generic Rust
/// function instantiated for one model: how `export_fmi2!` / `export_fmi3!` name a model once.
/// Entries read `cName(arg: Type, …) -> Ret = path::to::generic_fn::<Model>;`.
#[macro_export]
macro_rules! forward_c_functions {
    ($( $name:ident ( $($arg:ident : $t:ty),* $(,)? ) -> $ret:ty = $imp:path ; )*) => {$(
        #[allow(unsafe_code, non_snake_case, missing_docs, clippy::missing_safety_doc)]
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name($($arg: $t),*) -> $ret {
            // SAFETY: the caller follows the FMI standard's contract for this function, which
            // is the generic function's contract.
            unsafe { $imp($($arg),*) }
        }
    )*};
}
