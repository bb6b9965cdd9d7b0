//! The FMI 2.0 co-simulation C API over [`rins_fmi::instance::Instance`]: all 34 functions of
//! `fmi2Functions.h` for a CS-only FMU, nothing else exported. Every entry point catches panics
//! (a panic becomes `fmi2Fatal` with a logged reason), tolerates NULL where the standard allows
//! and logs why any call is refused.

// The C ABI needs raw pointers from the caller; each dereference is guarded by a NULL check and
// the lengths the standard defines.
#![allow(unsafe_code)]
#![allow(non_snake_case, non_camel_case_types)]
// The exported functions are documented by the FMI 2.0 standard, section by section.
#![allow(missing_docs)]
// Each pointer's contract (valid for n elements, or NULL where allowed) is the standard's.
#![allow(clippy::missing_safety_doc)]

use std::ffi::{CStr, CString, c_char, c_int, c_uint, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};

use rins_fmi::ffi::{panic_message, slice, slice_mut};
use rins_fmi::fmu;
use rins_fmi::instance::{FmiError, Instance, Mode, Status};
use rins_fmi::rins::RinsModel;
use rins_fmi::vars::{Kind, Value};
use rins_fmi::xml::FmiVersion;

type fmi2Component = *mut c_void;
type fmi2ComponentEnvironment = *mut c_void;
type fmi2FMUstate = *mut c_void;
type fmi2ValueReference = c_uint;
type fmi2Real = f64;
type fmi2Integer = c_int;
type fmi2Boolean = c_int;
type fmi2String = *const c_char;
type fmi2Byte = c_char;
type fmi2Status = c_int;
type fmi2Type = c_int;
type fmi2StatusKind = c_int;

const FMI2_COSIMULATION: fmi2Type = 1;

/// `fmi2CallbackLogger`: variadic in C; we always pass a format with no directives.
type Logger = Option<
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
    logger: Logger,
    allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2Status)>,
    component_environment: fmi2ComponentEnvironment,
}

struct Fmi2 {
    inst: Instance<RinsModel>,
    name: CString,
    logger: Logger,
    env: fmi2ComponentEnvironment,
    logging_on: bool,
}

impl Fmi2 {
    fn log(&self, status: Status, category: &str, message: &str) {
        // Errors and warnings are always reported; event messages only with loggingOn.
        if status == Status::Ok && !self.logging_on {
            return;
        }
        log_to(self.logger, self.env, &self.name, status, category, message);
    }
}

fn log_to(
    logger: Logger,
    env: fmi2ComponentEnvironment,
    name: &CStr,
    status: Status,
    category: &str,
    message: &str,
) {
    let Some(f) = logger else { return };
    // The message is used as a printf format by C masters: escape '%'.
    let msg = CString::new(message.replace('%', "%%").replace('\0', " ")).unwrap_or_default();
    let cat = CString::new(category).unwrap_or_default();
    // SAFETY: the master gave us this callback for exactly this call signature.
    unsafe {
        f(
            env,
            name.as_ptr(),
            status as fmi2Status,
            cat.as_ptr(),
            msg.as_ptr(),
        )
    };
}

/// Runs `f` on the instance behind `c`, catching panics and logging refusals.
fn with(
    c: fmi2Component,
    what: &str,
    f: impl FnOnce(&mut Fmi2) -> Result<(), FmiError>,
) -> fmi2Status {
    if c.is_null() {
        return Status::Error as fmi2Status;
    }
    // SAFETY: `c` came from fmi2Instantiate (a Box<Fmi2>) and has not been freed.
    let comp = unsafe { &mut *(c as *mut Fmi2) };
    match catch_unwind(AssertUnwindSafe(|| f(comp))) {
        Ok(Ok(())) => Status::Ok as fmi2Status,
        Ok(Err(e)) => {
            comp.log(e.status, e.category, &format!("{what}: {}", e.message));
            e.status as fmi2Status
        }
        Err(panic) => {
            let msg = panic_message(panic.as_ref());
            comp.log(
                Status::Fatal,
                "logStatusError",
                &format!("{what}: internal error: {msg}"),
            );
            Status::Fatal as fmi2Status
        }
    }
}

fn unsupported(c: fmi2Component, what: &str, why: &str) -> fmi2Status {
    with(c, what, |_| {
        Err(FmiError::error(format!("not supported: {why}")))
    })
}

fn kind_of(comp: &Fmi2, vr: u32) -> Result<Kind, FmiError> {
    comp.inst
        .table()
        .scalars
        .get(vr as usize)
        .map(|s| s.kind)
        .ok_or_else(|| {
            FmiError::error(format!(
                "unknown value reference {vr} (valid: 0…{})",
                comp.inst.table().scalars.len() - 1
            ))
        })
}

fn type_error(comp: &Fmi2, vr: u32, wanted: &str) -> FmiError {
    let s = &comp.inst.table().scalars[vr as usize];
    FmiError::error(format!(
        "value reference {vr} ({}) is {:?}, not {wanted}",
        s.name, s.kind
    ))
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    logging_on: fmi2Boolean,
    n: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    with(c, "fmi2SetDebugLogging", |comp| {
        // SAFETY: `categories` holds `n` C strings per the standard.
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
        comp.logging_on = logging_on != 0;
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Instantiate(
    instance_name: fmi2String,
    fmu_type: fmi2Type,
    guid: fmi2String,
    _resource_location: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    logging_on: fmi2Boolean,
) -> fmi2Component {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: NULL-checked; the standard gives these as C strings / a struct.
        let (logger, env) = if functions.is_null() {
            (None, std::ptr::null_mut())
        } else {
            unsafe { ((*functions).logger, (*functions).component_environment) }
        };
        let name = if instance_name.is_null() {
            CString::from(c"(unnamed)")
        } else {
            unsafe { CStr::from_ptr(instance_name) }.to_owned()
        };
        let fail = |msg: &str| {
            log_to(
                logger,
                env,
                &name,
                Status::Error,
                "logStatusError",
                &format!("fmi2Instantiate: {msg}"),
            );
            std::ptr::null_mut()
        };
        if fmu_type != FMI2_COSIMULATION {
            return fail("this FMU supports co-simulation only (fmuType must be fmi2CoSimulation)");
        }
        let expected = &fmu::description(FmiVersion::V2).1;
        let given = if guid.is_null() {
            ""
        } else {
            unsafe { CStr::from_ptr(guid) }.to_str().unwrap_or("")
        };
        if given != expected {
            return fail(&format!(
                "GUID {given:?} does not match this binary's {expected:?}: modelDescription.xml and binary are from different builds"
            ));
        }
        let comp = Box::new(Fmi2 {
            inst: Instance::new(),
            name,
            logger,
            env,
            logging_on: logging_on != 0,
        });
        comp.log(Status::Ok, "logEvents", "instantiated");
        Box::into_raw(comp) as fmi2Component
    }));
    r.unwrap_or(std::ptr::null_mut())
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    if c.is_null() {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: `c` is the Box from fmi2Instantiate, freed once.
        drop(unsafe { Box::from_raw(c as *mut Fmi2) });
    }));
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2SetupExperiment(
    c: fmi2Component,
    _tol_defined: fmi2Boolean,
    _tol: fmi2Real,
    start: fmi2Real,
    stop_defined: fmi2Boolean,
    stop: fmi2Real,
) -> fmi2Status {
    with(c, "fmi2SetupExperiment", |comp| {
        if stop_defined != 0 && !(stop >= start) {
            return Err(FmiError::error(format!(
                "stop time {stop} is before start time {start}"
            )));
        }
        comp.inst.setup(start)
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
    with(c, "fmi2EnterInitializationMode", |comp| {
        comp.inst.enter_initialization()
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
    with(c, "fmi2ExitInitializationMode", |comp| {
        comp.inst.exit_initialization()?;
        comp.log(Status::Ok, "logEvents", "initialized; step mode");
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
    with(c, "fmi2Terminate", |comp| comp.inst.terminate())
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
    with(c, "fmi2Reset", |comp| {
        comp.inst.reset();
        Ok(())
    })
}

fn get_values<T: Copy>(
    c: fmi2Component,
    what: &str,
    vr: *const fmi2ValueReference,
    n: usize,
    out: *mut T,
    conv: impl Fn(&Fmi2, u32, Value) -> Result<T, FmiError>,
) -> fmi2Status {
    with(c, what, |comp| {
        if comp.inst.mode() == Mode::Instantiated {
            return Err(FmiError::error(
                "values can be read from initialization mode on",
            ));
        }
        // SAFETY: both arrays have `n` elements per the standard.
        let (vrs, out) = unsafe { (slice(vr, n)?, slice_mut(out, n)?) };
        for (v, o) in vrs.iter().zip(out.iter_mut()) {
            *o = conv(comp, *v, comp.inst.get(*v)?)?;
        }
        Ok(())
    })
}

fn set_values<T: Copy>(
    c: fmi2Component,
    what: &str,
    vr: *const fmi2ValueReference,
    n: usize,
    vals: *const T,
    conv: impl Fn(&Fmi2, u32, T) -> Result<Value, FmiError>,
) -> fmi2Status {
    with(c, what, |comp| {
        // SAFETY: both arrays have `n` elements per the standard.
        let (vrs, vals) = unsafe { (slice(vr, n)?, slice(vals, n)?) };
        for (v, x) in vrs.iter().zip(vals) {
            let value = conv(comp, *v, *x)?;
            comp.inst.set(*v, value)?;
        }
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    get_values(c, "fmi2GetReal", vr, n, value, |comp, r, v| match v {
        Value::Real(x) => Ok(x),
        _ => Err(type_error(comp, r, "a Real")),
    })
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    get_values(c, "fmi2GetInteger", vr, n, value, |comp, r, v| match v {
        Value::Integer(u) => i32::try_from(u).map_err(|_| {
            FmiError::error(format!(
                "value reference {r} = {u} does not fit an fmi2Integer"
            ))
        }),
        Value::Enumeration(i) => Ok(i as i32 + 1),
        _ => Err(type_error(comp, r, "an Integer or Enumeration")),
    })
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    get_values(c, "fmi2GetBoolean", vr, n, value, |comp, r, v| match v {
        Value::Boolean(b) => Ok(b as fmi2Boolean),
        _ => Err(type_error(comp, r, "a Boolean")),
    })
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    _value: *mut fmi2String,
) -> fmi2Status {
    get_values(
        c,
        "fmi2GetString",
        vr,
        n,
        std::ptr::null_mut::<u8>(),
        |comp, r, _| Err(type_error(comp, r, "a String (this FMU has none)")),
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    set_values(
        c,
        "fmi2SetReal",
        vr,
        n,
        value,
        |comp, r, x| match kind_of(comp, r)? {
            Kind::Real => Ok(Value::Real(x)),
            _ => Err(type_error(comp, r, "a Real")),
        },
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    set_values(
        c,
        "fmi2SetInteger",
        vr,
        n,
        value,
        |comp, r, x| match kind_of(comp, r)? {
            Kind::Integer if x >= 0 => Ok(Value::Integer(x as u64)),
            Kind::Integer => Err(FmiError::error(format!(
                "{} = {x} must be ≥ 0",
                comp.inst.table().scalars[r as usize].name
            ))),
            Kind::Enumeration { .. } if x >= 1 => Ok(Value::Enumeration(x as usize - 1)),
            Kind::Enumeration { .. } => Ok(Value::Enumeration(usize::MAX)),
            _ => Err(type_error(comp, r, "an Integer or Enumeration")),
        },
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    set_values(
        c,
        "fmi2SetBoolean",
        vr,
        n,
        value,
        |comp, r, x| match kind_of(comp, r)? {
            Kind::Boolean => Ok(Value::Boolean(x != 0)),
            _ => Err(type_error(comp, r, "a Boolean")),
        },
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2String,
) -> fmi2Status {
    set_values(c, "fmi2SetString", vr, n, value, |comp, r, _| {
        Err(type_error(comp, r, "a String (this FMU has none)"))
    })
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetFMUstate(c: fmi2Component, state: *mut fmi2FMUstate) -> fmi2Status {
    with(c, "fmi2GetFMUstate", |comp| {
        if state.is_null() {
            return Err(FmiError::error("NULL FMUstate pointer"));
        }
        // SAFETY: `state` is a valid out-pointer; a non-NULL *state is one of our boxes (reused).
        unsafe {
            if (*state).is_null() {
                *state = Box::into_raw(Box::new(comp.inst.snapshot())) as fmi2FMUstate;
            } else {
                *(*state as *mut Instance<RinsModel>) = comp.inst.snapshot();
            }
        }
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, state: fmi2FMUstate) -> fmi2Status {
    with(c, "fmi2SetFMUstate", |comp| {
        if state.is_null() {
            return Err(FmiError::error("NULL FMUstate"));
        }
        // SAFETY: `state` is a box from fmi2GetFMUstate / fmi2DeSerializeFMUstate.
        comp.inst
            .restore_snapshot(unsafe { &*(state as *const Instance<RinsModel>) });
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: fmi2Component,
    state: *mut fmi2FMUstate,
) -> fmi2Status {
    with(c, "fmi2FreeFMUstate", |_| {
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
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: fmi2Component,
    state: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    with(c, "fmi2SerializedFMUstateSize", |_| {
        if state.is_null() || size.is_null() {
            return Err(FmiError::error("NULL FMUstate or size pointer"));
        }
        // SAFETY: `state` is one of our boxes; `size` is a valid out-pointer.
        unsafe { *size = (*(state as *const Instance<RinsModel>)).serialize().len() };
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: fmi2Component,
    state: fmi2FMUstate,
    bytes: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    with(c, "fmi2SerializeFMUstate", |_| {
        if state.is_null() {
            return Err(FmiError::error("NULL FMUstate"));
        }
        // SAFETY: `state` is one of our boxes; `bytes` has `size` bytes.
        let data = unsafe { (*(state as *const Instance<RinsModel>)).serialize() };
        if data.len() != size {
            return Err(FmiError::error(format!(
                "buffer has {size} bytes, the state needs {}",
                data.len()
            )));
        }
        let out = unsafe { slice_mut(bytes as *mut u8, size)? };
        out.copy_from_slice(&data);
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: fmi2Component,
    bytes: *const fmi2Byte,
    size: usize,
    state: *mut fmi2FMUstate,
) -> fmi2Status {
    with(c, "fmi2DeSerializeFMUstate", |_| {
        if state.is_null() {
            return Err(FmiError::error("NULL FMUstate pointer"));
        }
        // SAFETY: `bytes` has `size` bytes; `state` is a valid out-pointer.
        let data = unsafe { slice(bytes as *const u8, size)? };
        let inst = Instance::<RinsModel>::deserialize(data)?;
        unsafe { *state = Box::into_raw(Box::new(inst)) as fmi2FMUstate };
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetDirectionalDerivative(
    c: fmi2Component,
    _unknowns: *const fmi2ValueReference,
    _n_unknown: usize,
    _knowns: *const fmi2ValueReference,
    _n_known: usize,
    _dv_known: *const fmi2Real,
    _dv_unknown: *mut fmi2Real,
) -> fmi2Status {
    unsupported(
        c,
        "fmi2GetDirectionalDerivative",
        "providesDirectionalDerivative is false",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _n: usize,
    _order: *const fmi2Integer,
    _value: *const fmi2Real,
) -> fmi2Status {
    unsupported(
        c,
        "fmi2SetRealInputDerivatives",
        "canInterpolateInputs is false",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetRealOutputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _n: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    unsupported(
        c,
        "fmi2GetRealOutputDerivatives",
        "maxOutputDerivativeOrder is 0",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2DoStep(
    c: fmi2Component,
    t: fmi2Real,
    h: fmi2Real,
    _no_set_prior: fmi2Boolean,
) -> fmi2Status {
    with(c, "fmi2DoStep", |comp| comp.inst.do_step(t, h))
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    unsupported(
        c,
        "fmi2CancelStep",
        "doStep is synchronous (canRunAsynchronuously is false)",
    )
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetStatus(
    c: fmi2Component,
    _kind: fmi2StatusKind,
    _value: *mut fmi2Status,
) -> fmi2Status {
    unsupported(c, "fmi2GetStatus", "doStep never returns fmi2Pending")
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealStatus(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2Real,
) -> fmi2Status {
    with(c, "fmi2GetRealStatus", |comp| {
        // fmi2LastSuccessfulTime = 2
        if kind != 2 || value.is_null() {
            return Err(FmiError::error(format!(
                "status kind {kind} is not available (only fmi2LastSuccessfulTime)"
            )));
        }
        // SAFETY: valid out-pointer.
        unsafe { *value = comp.inst.time_s() };
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetIntegerStatus(
    c: fmi2Component,
    _kind: fmi2StatusKind,
    _value: *mut fmi2Integer,
) -> fmi2Status {
    unsupported(
        c,
        "fmi2GetIntegerStatus",
        "no integer status is defined for co-simulation",
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    with(c, "fmi2GetBooleanStatus", |_| {
        // fmi2Terminated = 3: the plant never asks to stop.
        if kind != 3 || value.is_null() {
            return Err(FmiError::error(format!(
                "status kind {kind} is not available (only fmi2Terminated)"
            )));
        }
        // SAFETY: valid out-pointer.
        unsafe { *value = 0 };
        Ok(())
    })
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetStringStatus(
    c: fmi2Component,
    _kind: fmi2StatusKind,
    _value: *mut fmi2String,
) -> fmi2Status {
    unsupported(c, "fmi2GetStringStatus", "doStep never returns fmi2Pending")
}
