//! The FMI 3.0 C API over [`rins_fmi::instance::Instance`]: all functions of `fmi3Functions.h`
//! exported, nothing else. Co-simulation is implemented; Model Exchange, Scheduled Execution,
//! clocks, intervals and derivatives log why they are unsupported and return `fmi3Error`.
//! Every entry point catches panics.

// The C ABI needs raw pointers from the caller; each dereference is guarded by a NULL check and
// the lengths the standard defines.
#![allow(unsafe_code)]
#![allow(non_snake_case, non_camel_case_types)]
// The exported functions are documented by the FMI 3.0 standard.
#![allow(missing_docs)]
// Signatures are the standard's; callers pass what the header says.
#![allow(clippy::not_unsafe_ptr_arg_deref, clippy::too_many_arguments)]

use std::ffi::{CStr, CString, c_char, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};

use rins_fmi::ffi::{panic_message, slice, slice_mut};
use rins_fmi::fmu;
use rins_fmi::instance::{FmiError, Instance, Mode, Status};
use rins_fmi::rins::RinsModel;
use rins_fmi::vars::{Kind, Value};
use rins_fmi::xml::FmiVersion;

type fmi3Instance = *mut c_void;
type fmi3InstanceEnvironment = *mut c_void;
type fmi3FMUState = *mut c_void;
type fmi3ValueReference = u32;
type fmi3Status = i32;
type fmi3String = *const c_char;
type fmi3Boolean = bool;
type LogMessage =
    Option<unsafe extern "C" fn(fmi3InstanceEnvironment, fmi3Status, fmi3String, fmi3String)>;
type Callback = *const c_void;

struct Fmi3 {
    inst: Instance<RinsModel>,
    logger: LogMessage,
    env: fmi3InstanceEnvironment,
    logging_on: bool,
}

fn log_to(
    logger: LogMessage,
    env: fmi3InstanceEnvironment,
    status: Status,
    category: &str,
    message: &str,
) {
    let Some(f) = logger else { return };
    let msg = CString::new(message.replace('\0', " ")).unwrap_or_default();
    let cat = CString::new(category).unwrap_or_default();
    // SAFETY: the importer gave us this callback with exactly this signature.
    unsafe { f(env, status as fmi3Status, cat.as_ptr(), msg.as_ptr()) };
}

impl Fmi3 {
    fn log(&self, status: Status, category: &str, message: &str) {
        if status == Status::Ok && !self.logging_on {
            return;
        }
        log_to(self.logger, self.env, status, category, message);
    }
}

fn with(
    c: fmi3Instance,
    what: &str,
    f: impl FnOnce(&mut Fmi3) -> Result<(), FmiError>,
) -> fmi3Status {
    if c.is_null() {
        return Status::Error as fmi3Status;
    }
    // SAFETY: `c` came from fmi3InstantiateCoSimulation and has not been freed.
    let comp = unsafe { &mut *(c as *mut Fmi3) };
    match catch_unwind(AssertUnwindSafe(|| f(comp))) {
        Ok(Ok(())) => Status::Ok as fmi3Status,
        Ok(Err(e)) => {
            comp.log(e.status, e.category, &format!("{what}: {}", e.message));
            e.status as fmi3Status
        }
        Err(panic) => {
            let msg = panic_message(panic.as_ref());
            comp.log(
                Status::Fatal,
                "logStatusError",
                &format!("{what}: internal error: {msg}"),
            );
            Status::Fatal as fmi3Status
        }
    }
}

fn unsupported(c: fmi3Instance, what: &str, why: &str) -> fmi3Status {
    with(c, what, |_| {
        Err(FmiError::error(format!("not supported: {why}")))
    })
}

/// Slots of FMI 3 value reference `vr` (0 is `time`, which has none).
fn slots(comp: &Fmi3, vr: u32) -> Result<std::ops::Range<usize>, FmiError> {
    let arrays = &comp.inst.table().arrays;
    match vr {
        0 => Err(FmiError::error(
            "value reference 0 is the independent variable time (read it with fmi3GetFloat64 only)",
        )),
        _ => arrays
            .get(vr as usize - 1)
            .map(|a| a.slots.clone())
            .ok_or_else(|| {
                FmiError::error(format!(
                    "unknown value reference {vr} (valid: 0…{})",
                    arrays.len()
                ))
            }),
    }
}

fn type_error(comp: &Fmi3, vr: u32, wanted: &str) -> FmiError {
    let a = &comp.inst.table().arrays[vr as usize - 1];
    FmiError::error(format!(
        "value reference {vr} ({}) is {:?}, not {wanted}",
        a.name,
        comp.inst.table().scalars[a.slots.start].kind
    ))
}

/// Shared body of the fmi3Get* functions: walks the value references, checks `nValues`.
fn get_typed<T: Copy>(
    c: fmi3Instance,
    what: &str,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    out: *mut T,
    n_values: usize,
    time: Option<fn(f64) -> T>,
    conv: fn(Value) -> Option<T>,
    wanted: &'static str,
) -> fmi3Status {
    with(c, what, |comp| {
        if comp.inst.mode() == Mode::Instantiated {
            return Err(FmiError::error(
                "values can be read from initialization mode on",
            ));
        }
        // SAFETY: the standard gives `n_vr` references and room for `n_values` values.
        let (vrs, out) = unsafe { (slice(vr, n_vr)?, slice_mut(out, n_values)?) };
        let mut k = 0;
        for &r in vrs {
            if r == 0
                && let Some(t) = time
            {
                *out.get_mut(k).ok_or_else(|| {
                    FmiError::error(format!("nValues = {n_values} is too small"))
                })? = t(comp.inst.time_s());
                k += 1;
                continue;
            }
            for slot in slots(comp, r)? {
                let v =
                    conv(comp.inst.get_slot(slot)).ok_or_else(|| type_error(comp, r, wanted))?;
                *out.get_mut(k).ok_or_else(|| {
                    FmiError::error(format!(
                        "nValues = {n_values} is too small for these value references"
                    ))
                })? = v;
                k += 1;
            }
        }
        if k != n_values {
            return Err(FmiError::error(format!(
                "nValues = {n_values}, but the value references hold {k} values"
            )));
        }
        Ok(())
    })
}

/// Shared body of the fmi3Set* functions.
fn set_typed<T: Copy>(
    c: fmi3Instance,
    what: &str,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    vals: *const T,
    n_values: usize,
    conv: fn(Kind, T) -> Option<Value>,
    wanted: &'static str,
) -> fmi3Status {
    with(c, what, |comp| {
        // SAFETY: as in get_typed.
        let (vrs, vals) = unsafe { (slice(vr, n_vr)?, slice(vals, n_values)?) };
        let mut k = 0;
        for &r in vrs {
            for slot in slots(comp, r)? {
                let kind = comp.inst.table().scalars[slot].kind;
                let x = *vals.get(k).ok_or_else(|| {
                    FmiError::error(format!(
                        "nValues = {n_values} is too small for these value references"
                    ))
                })?;
                let v = conv(kind, x).ok_or_else(|| type_error(comp, r, wanted))?;
                comp.inst.set_slot(slot, v)?;
                k += 1;
            }
        }
        if k != n_values {
            return Err(FmiError::error(format!(
                "nValues = {n_values}, but the value references hold {k} values"
            )));
        }
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetDebugLogging(
    c: fmi3Instance,
    logging_on: fmi3Boolean,
    n: usize,
    categories: *const fmi3String,
) -> fmi3Status {
    with(c, "fmi3SetDebugLogging", |comp| {
        // SAFETY: `categories` holds `n` C strings.
        for &cat in unsafe { slice(categories, n)? } {
            let name = if cat.is_null() {
                ""
            } else {
                unsafe { CStr::from_ptr(cat) }.to_str().unwrap_or("")
            };
            if !rins_fmi::instance::LOG_CATEGORIES
                .iter()
                .any(|(n, _)| *n == name)
            {
                return Err(FmiError::error(format!("unknown log category {name:?}")));
            }
        }
        comp.logging_on = logging_on;
        Ok(())
    })
}

fn refuse_instantiate(
    logger: LogMessage,
    env: fmi3InstanceEnvironment,
    what: &str,
) -> fmi3Instance {
    log_to(
        logger,
        env,
        Status::Error,
        "logStatusError",
        &format!("{what}: this FMU supports co-simulation only"),
    );
    std::ptr::null_mut()
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3InstantiateModelExchange(
    _name: fmi3String,
    _token: fmi3String,
    _resources: fmi3String,
    _visible: fmi3Boolean,
    _logging_on: fmi3Boolean,
    env: fmi3InstanceEnvironment,
    logger: LogMessage,
) -> fmi3Instance {
    catch_unwind(|| refuse_instantiate(logger, env, "fmi3InstantiateModelExchange"))
        .unwrap_or(std::ptr::null_mut())
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3InstantiateScheduledExecution(
    _name: fmi3String,
    _token: fmi3String,
    _resources: fmi3String,
    _visible: fmi3Boolean,
    _logging_on: fmi3Boolean,
    env: fmi3InstanceEnvironment,
    logger: LogMessage,
    _clock_update: Callback,
    _lock: Callback,
    _unlock: Callback,
) -> fmi3Instance {
    catch_unwind(|| refuse_instantiate(logger, env, "fmi3InstantiateScheduledExecution"))
        .unwrap_or(std::ptr::null_mut())
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3InstantiateCoSimulation(
    _name: fmi3String,
    token: fmi3String,
    _resources: fmi3String,
    _visible: fmi3Boolean,
    logging_on: fmi3Boolean,
    event_mode_used: fmi3Boolean,
    _early_return_allowed: fmi3Boolean,
    _required_intermediate: *const fmi3ValueReference,
    _n_required_intermediate: usize,
    env: fmi3InstanceEnvironment,
    logger: LogMessage,
    _intermediate_update: Callback,
) -> fmi3Instance {
    catch_unwind(AssertUnwindSafe(|| {
        let fail = |msg: &str| {
            log_to(logger, env, Status::Error, "logStatusError", &format!("fmi3InstantiateCoSimulation: {msg}"));
            std::ptr::null_mut()
        };
        if event_mode_used {
            return fail("hasEventMode is false: instantiate with eventModeUsed = false");
        }
        let expected = &fmu::description(FmiVersion::V3).1;
        // SAFETY: NULL-checked C string.
        let given = if token.is_null() { "" } else { unsafe { CStr::from_ptr(token) }.to_str().unwrap_or("") };
        if given != expected {
            return fail(&format!("instantiation token {given:?} does not match this binary's {expected:?}: modelDescription.xml and binary are from different builds"));
        }
        let comp = Box::new(Fmi3 { inst: Instance::new(), logger, env, logging_on });
        comp.log(Status::Ok, "logEvents", "instantiated");
        Box::into_raw(comp) as fmi3Instance
    }))
    .unwrap_or(std::ptr::null_mut())
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3FreeInstance(c: fmi3Instance) {
    if c.is_null() {
        return;
    }
    // SAFETY: `c` is the Box from instantiate, freed once.
    let _ = catch_unwind(AssertUnwindSafe(|| {
        drop(unsafe { Box::from_raw(c as *mut Fmi3) })
    }));
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3EnterInitializationMode(
    c: fmi3Instance,
    _tol_defined: fmi3Boolean,
    _tol: f64,
    start: f64,
    stop_defined: fmi3Boolean,
    stop: f64,
) -> fmi3Status {
    with(c, "fmi3EnterInitializationMode", |comp| {
        if stop_defined && !(stop >= start) {
            return Err(FmiError::error(format!(
                "stop time {stop} is before start time {start}"
            )));
        }
        comp.inst.setup(start)?;
        comp.inst.enter_initialization()
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3ExitInitializationMode(c: fmi3Instance) -> fmi3Status {
    with(c, "fmi3ExitInitializationMode", |comp| {
        comp.inst.exit_initialization()?;
        comp.log(Status::Ok, "logEvents", "initialized; step mode");
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3EnterEventMode(c: fmi3Instance) -> fmi3Status {
    unsupported(c, "fmi3EnterEventMode", "hasEventMode is false")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3Terminate(c: fmi3Instance) -> fmi3Status {
    with(c, "fmi3Terminate", |comp| comp.inst.terminate())
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3Reset(c: fmi3Instance) -> fmi3Status {
    with(c, "fmi3Reset", |comp| {
        comp.inst.reset();
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetFloat64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *mut f64,
    n_values: usize,
) -> fmi3Status {
    get_typed(
        c,
        "fmi3GetFloat64",
        vr,
        n_vr,
        values,
        n_values,
        Some(|t| t),
        |v| {
            if let Value::Real(x) = v {
                Some(x)
            } else {
                None
            }
        },
        "Float64",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetFloat64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *const f64,
    n_values: usize,
) -> fmi3Status {
    set_typed(
        c,
        "fmi3SetFloat64",
        vr,
        n_vr,
        values,
        n_values,
        |k, x| (k == Kind::Real).then_some(Value::Real(x)),
        "Float64",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetUInt64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *mut u64,
    n_values: usize,
) -> fmi3Status {
    get_typed(
        c,
        "fmi3GetUInt64",
        vr,
        n_vr,
        values,
        n_values,
        None,
        |v| {
            if let Value::Integer(u) = v {
                Some(u)
            } else {
                None
            }
        },
        "UInt64",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetUInt64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *const u64,
    n_values: usize,
) -> fmi3Status {
    set_typed(
        c,
        "fmi3SetUInt64",
        vr,
        n_vr,
        values,
        n_values,
        |k, x| (k == Kind::Integer).then_some(Value::Integer(x)),
        "UInt64",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetInt64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *mut i64,
    n_values: usize,
) -> fmi3Status {
    get_typed(
        c,
        "fmi3GetInt64",
        vr,
        n_vr,
        values,
        n_values,
        None,
        |v| {
            if let Value::Enumeration(i) = v {
                Some(i as i64 + 1)
            } else {
                None
            }
        },
        "an Enumeration (Int64)",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetInt64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *const i64,
    n_values: usize,
) -> fmi3Status {
    set_typed(
        c,
        "fmi3SetInt64",
        vr,
        n_vr,
        values,
        n_values,
        |k, x| {
            matches!(k, Kind::Enumeration { .. }).then_some(Value::Enumeration(if x >= 1 {
                x as usize - 1
            } else {
                usize::MAX
            }))
        },
        "an Enumeration (Int64)",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetBoolean(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *mut fmi3Boolean,
    n_values: usize,
) -> fmi3Status {
    get_typed(
        c,
        "fmi3GetBoolean",
        vr,
        n_vr,
        values,
        n_values,
        None,
        |v| {
            if let Value::Boolean(b) = v {
                Some(b)
            } else {
                None
            }
        },
        "Boolean",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetBoolean(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *const fmi3Boolean,
    n_values: usize,
) -> fmi3Status {
    set_typed(
        c,
        "fmi3SetBoolean",
        vr,
        n_vr,
        values,
        n_values,
        |k, x| (k == Kind::Boolean).then_some(Value::Boolean(x)),
        "Boolean",
    )
}

/// Getters and setters of types this FMU has no variables of: fine for zero references,
/// an error naming the type otherwise.
macro_rules! absent_type {
    ($get:ident, $set:ident, $t:ty, $name:literal) => {
        #[unsafe(no_mangle)]
        pub extern "C" fn $get(
            c: fmi3Instance,
            vr: *const fmi3ValueReference,
            n_vr: usize,
            values: *mut $t,
            n_values: usize,
        ) -> fmi3Status {
            get_typed(
                c,
                stringify!($get),
                vr,
                n_vr,
                values,
                n_values,
                None,
                |_| None,
                concat!("a ", $name, " (this FMU has none)"),
            )
        }
        #[unsafe(no_mangle)]
        pub extern "C" fn $set(
            c: fmi3Instance,
            vr: *const fmi3ValueReference,
            n_vr: usize,
            values: *const $t,
            n_values: usize,
        ) -> fmi3Status {
            set_typed(
                c,
                stringify!($set),
                vr,
                n_vr,
                values,
                n_values,
                |_, _| None,
                concat!("a ", $name, " (this FMU has none)"),
            )
        }
    };
}

absent_type!(fmi3GetFloat32, fmi3SetFloat32, f32, "Float32");
absent_type!(fmi3GetInt8, fmi3SetInt8, i8, "Int8");
absent_type!(fmi3GetUInt8, fmi3SetUInt8, u8, "UInt8");
absent_type!(fmi3GetInt16, fmi3SetInt16, i16, "Int16");
absent_type!(fmi3GetUInt16, fmi3SetUInt16, u16, "UInt16");
absent_type!(fmi3GetInt32, fmi3SetInt32, i32, "Int32");
absent_type!(fmi3GetUInt32, fmi3SetUInt32, u32, "UInt32");
absent_type!(fmi3GetString, fmi3SetString, fmi3String, "String");

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetBinary(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    _sizes: *mut usize,
    values: *mut *const u8,
    n_values: usize,
) -> fmi3Status {
    get_typed(
        c,
        "fmi3GetBinary",
        vr,
        n_vr,
        values,
        n_values,
        None,
        |_| None,
        "a Binary (this FMU has none)",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetBinary(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    _sizes: *const usize,
    values: *const *const u8,
    n_values: usize,
) -> fmi3Status {
    set_typed(
        c,
        "fmi3SetBinary",
        vr,
        n_vr,
        values,
        n_values,
        |_, _| None,
        "a Binary (this FMU has none)",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetClock(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _values: *mut fmi3Boolean,
) -> fmi3Status {
    unsupported(c, "fmi3GetClock", "this FMU has no clocks")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetClock(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _values: *const fmi3Boolean,
) -> fmi3Status {
    unsupported(c, "fmi3SetClock", "this FMU has no clocks")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetNumberOfVariableDependencies(
    c: fmi3Instance,
    _vr: fmi3ValueReference,
    _n: *mut usize,
) -> fmi3Status {
    unsupported(
        c,
        "fmi3GetNumberOfVariableDependencies",
        "providesPerElementDependencies is false",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetVariableDependencies(
    c: fmi3Instance,
    _dependent: fmi3ValueReference,
    _elem_dep: *mut usize,
    _independents: *mut fmi3ValueReference,
    _elem_ind: *mut usize,
    _kinds: *mut i32,
    _n: usize,
) -> fmi3Status {
    unsupported(
        c,
        "fmi3GetVariableDependencies",
        "providesPerElementDependencies is false",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetFMUState(c: fmi3Instance, state: *mut fmi3FMUState) -> fmi3Status {
    with(c, "fmi3GetFMUState", |comp| {
        if state.is_null() {
            return Err(FmiError::error("NULL FMUState pointer"));
        }
        // SAFETY: valid out-pointer; a non-NULL *state is one of our boxes (overwritten in place).
        unsafe {
            if (*state).is_null() {
                *state = Box::into_raw(Box::new(comp.inst.snapshot())) as fmi3FMUState;
            } else {
                *(*state as *mut Instance<RinsModel>) = comp.inst.snapshot();
            }
        }
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetFMUState(c: fmi3Instance, state: fmi3FMUState) -> fmi3Status {
    with(c, "fmi3SetFMUState", |comp| {
        if state.is_null() {
            return Err(FmiError::error("NULL FMUState"));
        }
        // SAFETY: one of our boxes.
        comp.inst
            .restore_snapshot(unsafe { &*(state as *const Instance<RinsModel>) });
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3FreeFMUState(c: fmi3Instance, state: *mut fmi3FMUState) -> fmi3Status {
    with(c, "fmi3FreeFMUState", |_| {
        if state.is_null() {
            return Ok(());
        }
        // SAFETY: *state is NULL or one of our boxes, freed once and cleared.
        unsafe {
            if !(*state).is_null() {
                drop(Box::from_raw(*state as *mut Instance<RinsModel>));
                *state = std::ptr::null_mut();
            }
        }
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SerializedFMUStateSize(
    c: fmi3Instance,
    state: fmi3FMUState,
    size: *mut usize,
) -> fmi3Status {
    with(c, "fmi3SerializedFMUStateSize", |_| {
        if state.is_null() || size.is_null() {
            return Err(FmiError::error("NULL FMUState or size pointer"));
        }
        // SAFETY: one of our boxes; valid out-pointer.
        unsafe { *size = (*(state as *const Instance<RinsModel>)).serialize().len() };
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SerializeFMUState(
    c: fmi3Instance,
    state: fmi3FMUState,
    bytes: *mut u8,
    size: usize,
) -> fmi3Status {
    with(c, "fmi3SerializeFMUState", |_| {
        if state.is_null() {
            return Err(FmiError::error("NULL FMUState"));
        }
        // SAFETY: one of our boxes; `bytes` has `size` bytes.
        let data = unsafe { (*(state as *const Instance<RinsModel>)).serialize() };
        if data.len() != size {
            return Err(FmiError::error(format!(
                "buffer has {size} bytes, the state needs {}",
                data.len()
            )));
        }
        unsafe { slice_mut(bytes, size)? }.copy_from_slice(&data);
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3DeserializeFMUState(
    c: fmi3Instance,
    bytes: *const u8,
    size: usize,
    state: *mut fmi3FMUState,
) -> fmi3Status {
    with(c, "fmi3DeserializeFMUState", |_| {
        if state.is_null() {
            return Err(FmiError::error("NULL FMUState pointer"));
        }
        // SAFETY: `bytes` has `size` bytes; valid out-pointer.
        let inst = Instance::<RinsModel>::deserialize(unsafe { slice(bytes, size)? })?;
        unsafe { *state = Box::into_raw(Box::new(inst)) as fmi3FMUState };
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetDirectionalDerivative(
    c: fmi3Instance,
    _unknowns: *const fmi3ValueReference,
    _n_unknowns: usize,
    _knowns: *const fmi3ValueReference,
    _n_knowns: usize,
    _seed: *const f64,
    _n_seed: usize,
    _sensitivity: *mut f64,
    _n_sensitivity: usize,
) -> fmi3Status {
    unsupported(
        c,
        "fmi3GetDirectionalDerivative",
        "providesDirectionalDerivatives is false",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetAdjointDerivative(
    c: fmi3Instance,
    _unknowns: *const fmi3ValueReference,
    _n_unknowns: usize,
    _knowns: *const fmi3ValueReference,
    _n_knowns: usize,
    _seed: *const f64,
    _n_seed: usize,
    _sensitivity: *mut f64,
    _n_sensitivity: usize,
) -> fmi3Status {
    unsupported(
        c,
        "fmi3GetAdjointDerivative",
        "providesAdjointDerivatives is false",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3EnterConfigurationMode(c: fmi3Instance) -> fmi3Status {
    unsupported(
        c,
        "fmi3EnterConfigurationMode",
        "this FMU has no structural parameters",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3ExitConfigurationMode(c: fmi3Instance) -> fmi3Status {
    unsupported(
        c,
        "fmi3ExitConfigurationMode",
        "this FMU has no structural parameters",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetIntervalDecimal(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _intervals: *mut f64,
    _q: *mut i32,
) -> fmi3Status {
    unsupported(c, "fmi3GetIntervalDecimal", "this FMU has no clocks")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetIntervalFraction(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *mut u64,
    _res: *mut u64,
    _q: *mut i32,
) -> fmi3Status {
    unsupported(c, "fmi3GetIntervalFraction", "this FMU has no clocks")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetShiftDecimal(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _shifts: *mut f64,
) -> fmi3Status {
    unsupported(c, "fmi3GetShiftDecimal", "this FMU has no clocks")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetShiftFraction(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *mut u64,
    _res: *mut u64,
) -> fmi3Status {
    unsupported(c, "fmi3GetShiftFraction", "this FMU has no clocks")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetIntervalDecimal(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _intervals: *const f64,
) -> fmi3Status {
    unsupported(c, "fmi3SetIntervalDecimal", "this FMU has no clocks")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetIntervalFraction(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *const u64,
    _res: *const u64,
) -> fmi3Status {
    unsupported(c, "fmi3SetIntervalFraction", "this FMU has no clocks")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetShiftDecimal(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _shifts: *const f64,
) -> fmi3Status {
    unsupported(c, "fmi3SetShiftDecimal", "this FMU has no clocks")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3SetShiftFraction(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *const u64,
    _res: *const u64,
) -> fmi3Status {
    unsupported(c, "fmi3SetShiftFraction", "this FMU has no clocks")
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3EvaluateDiscreteStates(c: fmi3Instance) -> fmi3Status {
    unsupported(
        c,
        "fmi3EvaluateDiscreteStates",
        "providesEvaluateDiscreteStates is false",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3UpdateDiscreteStates(
    c: fmi3Instance,
    _need_update: *mut fmi3Boolean,
    _terminate: *mut fmi3Boolean,
    _nominals_changed: *mut fmi3Boolean,
    _values_changed: *mut fmi3Boolean,
    _next_defined: *mut fmi3Boolean,
    _next_time: *mut f64,
) -> fmi3Status {
    unsupported(c, "fmi3UpdateDiscreteStates", "hasEventMode is false")
}

macro_rules! model_exchange_only {
    ($($name:ident($($arg:ident: $t:ty),*);)*) => {$(
        #[unsafe(no_mangle)]
        pub extern "C" fn $name(c: fmi3Instance, $($arg: $t),*) -> fmi3Status {
            $(let _ = $arg;)*
            unsupported(c, stringify!($name), "Model Exchange is not provided (co-simulation only)")
        }
    )*};
}

model_exchange_only! {
    fmi3EnterContinuousTimeMode();
    fmi3CompletedIntegratorStep(no_set_prior: fmi3Boolean, enter_event: *mut fmi3Boolean, terminate: *mut fmi3Boolean);
    fmi3SetTime(time: f64);
    fmi3SetContinuousStates(x: *const f64, n: usize);
    fmi3GetContinuousStateDerivatives(dx: *mut f64, n: usize);
    fmi3GetEventIndicators(z: *mut f64, n: usize);
    fmi3GetContinuousStates(x: *mut f64, n: usize);
    fmi3GetNominalsOfContinuousStates(nominals: *mut f64, n: usize);
    fmi3GetNumberOfEventIndicators(n: *mut usize);
    fmi3GetNumberOfContinuousStates(n: *mut usize);
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3EnterStepMode(c: fmi3Instance) -> fmi3Status {
    unsupported(
        c,
        "fmi3EnterStepMode",
        "hasEventMode is false: exitInitializationMode enters step mode",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetOutputDerivatives(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _orders: *const i32,
    _values: *mut f64,
    _n_values: usize,
) -> fmi3Status {
    unsupported(
        c,
        "fmi3GetOutputDerivatives",
        "maxOutputDerivativeOrder is 0",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3DoStep(
    c: fmi3Instance,
    t: f64,
    h: f64,
    _no_set_prior: fmi3Boolean,
    event_handling_needed: *mut fmi3Boolean,
    terminate_simulation: *mut fmi3Boolean,
    early_return: *mut fmi3Boolean,
    last_successful_time: *mut f64,
) -> fmi3Status {
    with(c, "fmi3DoStep", |comp| {
        let r = comp.inst.do_step(t, h);
        // SAFETY: out-pointers may be NULL only if the importer does not want them.
        unsafe {
            for p in [event_handling_needed, terminate_simulation, early_return] {
                if !p.is_null() {
                    *p = false;
                }
            }
            if !last_successful_time.is_null() {
                *last_successful_time = comp.inst.time_s();
            }
        }
        r
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3ActivateModelPartition(
    c: fmi3Instance,
    _clock: fmi3ValueReference,
    _time: f64,
) -> fmi3Status {
    unsupported(
        c,
        "fmi3ActivateModelPartition",
        "Scheduled Execution is not provided",
    )
}
