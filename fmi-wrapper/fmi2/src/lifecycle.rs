//! FMI 2.0 instance life and co-simulation stepping: instantiate, setup, initialisation,
//! doStep, terminate, reset, free, and the status and derivative functions this FMU refuses.

use std::ffi::c_char;

use rins_fmi::ffi::{check_log_categories, check_token, text};
use rins_fmi::instance::{FmiError, Instance, Status};
use rins_fmi::model::Model;
use rins_fmi::standard::FmiVersion;

use crate::*;

const FMI2_COSIMULATION: fmi2Type = 1;

/// fmi2GetTypesPlatform.
pub unsafe fn get_types_platform<M: Model>() -> *const c_char {
    c"default".as_ptr()
}

/// fmi2GetVersion.
pub unsafe fn get_version<M: Model>() -> *const c_char {
    c"2.0".as_ptr()
}

/// fmi2SetDebugLogging.
pub unsafe fn set_debug_logging<M: Model>(
    c: fmi2Component,
    logging_on: fmi2Boolean,
    n: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    with::<M>(c, "fmi2SetDebugLogging", |comp| {
        // SAFETY: `categories` holds `n` C strings per the standard.
        unsafe { check_log_categories(categories, n)? };
        comp.logging_on = logging_on != 0;
        Ok(())
    })
}

/// fmi2Instantiate: co-simulation only, and only with this binary's GUID.
pub unsafe fn instantiate<M: Model>(
    instance_name: fmi2String,
    fmu_type: fmi2Type,
    guid: fmi2String,
    _resource_location: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    logging_on: fmi2Boolean,
) -> fmi2Component {
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        // SAFETY: the standard gives these as a struct / C strings (NULL-checked inside).
        let logger = unsafe { Fmi2Logger::new(functions, instance_name) };
        let given = unsafe { text(guid) };
        let refusal = if fmu_type != FMI2_COSIMULATION {
            Err(
                "this FMU supports co-simulation only (fmuType must be fmi2CoSimulation)"
                    .to_string(),
            )
        } else {
            check_token::<M>(FmiVersion::V2, given)
        };
        if let Err(msg) = refusal {
            logger.emit(
                Status::Error,
                "logStatusError",
                &format!("fmi2Instantiate: {msg}"),
            );
            return std::ptr::null_mut();
        }
        let comp = Fmi2::<M> {
            inst: Instance::new(),
            logger,
            logging_on: logging_on != 0,
        };
        comp.log(Status::Ok, "logEvents", "instantiated");
        comp.into_handle()
    }));
    r.unwrap_or(std::ptr::null_mut())
}

/// fmi2FreeInstance: a second free, or a pointer that is no live instance, does nothing
/// (the host would otherwise abort on a double free).
pub unsafe fn free_instance<M: Model>(c: fmi2Component) {
    // SAFETY: only a live handle from fmi2Instantiate of this library is freed.
    unsafe { Fmi2::<M>::free_handle(c) }
}

/// fmi2SetupExperiment: the start time, right after instantiation only.
pub unsafe fn setup_experiment<M: Model>(
    c: fmi2Component,
    _tol_defined: fmi2Boolean,
    _tol: fmi2Real,
    start: fmi2Real,
    stop_defined: fmi2Boolean,
    stop: fmi2Real,
) -> fmi2Status {
    with::<M>(c, "fmi2SetupExperiment", |comp| {
        if stop_defined != 0 && !(stop >= start) {
            return Err(FmiError::error(format!(
                "stop time {stop} is before start time {start}"
            )));
        }
        comp.inst.setup(start)
    })
}

/// fmi2EnterInitializationMode.
pub unsafe fn enter_initialization_mode<M: Model>(c: fmi2Component) -> fmi2Status {
    with::<M>(c, "fmi2EnterInitializationMode", |comp| {
        comp.inst.enter_initialization()?;
        comp.log(Status::Ok, "logEvents", "initialization mode");
        Ok(())
    })
}

/// fmi2ExitInitializationMode: the model is built from its parameters.
pub unsafe fn exit_initialization_mode<M: Model>(c: fmi2Component) -> fmi2Status {
    with::<M>(c, "fmi2ExitInitializationMode", |comp| {
        comp.inst.exit_initialization()?;
        comp.log(Status::Ok, "logEvents", "initialized; step mode");
        Ok(())
    })
}

/// fmi2Terminate.
pub unsafe fn terminate<M: Model>(c: fmi2Component) -> fmi2Status {
    with::<M>(c, "fmi2Terminate", |comp| {
        comp.inst.terminate()?;
        comp.log(Status::Ok, "logEvents", "terminated");
        Ok(())
    })
}

/// fmi2Reset.
pub unsafe fn reset<M: Model>(c: fmi2Component) -> fmi2Status {
    with::<M>(c, "fmi2Reset", |comp| {
        comp.inst.reset();
        comp.log(
            Status::Ok,
            "logEvents",
            "reset: instantiated mode, start values",
        );
        Ok(())
    })
}

/// fmi2DoStep.
pub unsafe fn do_step<M: Model>(
    c: fmi2Component,
    t: fmi2Real,
    h: fmi2Real,
    _no_set_prior: fmi2Boolean,
) -> fmi2Status {
    with::<M>(c, "fmi2DoStep", |comp| {
        comp.inst.do_step(t, h)?;
        if comp.logging_on {
            comp.log_step(t, h);
        }
        Ok(())
    })
}

/// fmi2CancelStep.
pub unsafe fn cancel_step<M: Model>(c: fmi2Component) -> fmi2Status {
    unsupported::<M>(
        c,
        "fmi2CancelStep",
        "doStep is synchronous (canRunAsynchronuously is false)",
    )
}

/// fmi2GetStatus.
pub unsafe fn get_status<M: Model>(
    c: fmi2Component,
    _kind: fmi2StatusKind,
    _value: *mut fmi2Status,
) -> fmi2Status {
    unsupported::<M>(c, "fmi2GetStatus", "doStep never returns fmi2Pending")
}

/// fmi2GetRealStatus: fmi2LastSuccessfulTime only.
pub unsafe fn get_real_status<M: Model>(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2Real,
) -> fmi2Status {
    with::<M>(c, "fmi2GetRealStatus", |comp| {
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

/// fmi2GetIntegerStatus.
pub unsafe fn get_integer_status<M: Model>(
    c: fmi2Component,
    _kind: fmi2StatusKind,
    _value: *mut fmi2Integer,
) -> fmi2Status {
    unsupported::<M>(
        c,
        "fmi2GetIntegerStatus",
        "no integer status is defined for co-simulation",
    )
}

/// fmi2GetBooleanStatus: fmi2Terminated only (always false: the model never asks to stop).
pub unsafe fn get_boolean_status<M: Model>(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    with::<M>(c, "fmi2GetBooleanStatus", |_| {
        // fmi2Terminated = 3
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

/// fmi2GetStringStatus.
pub unsafe fn get_string_status<M: Model>(
    c: fmi2Component,
    _kind: fmi2StatusKind,
    _value: *mut fmi2String,
) -> fmi2Status {
    unsupported::<M>(c, "fmi2GetStringStatus", "doStep never returns fmi2Pending")
}

/// fmi2GetDirectionalDerivative.
pub unsafe fn get_directional_derivative<M: Model>(
    c: fmi2Component,
    _unknowns: *const fmi2ValueReference,
    _n_unknown: usize,
    _knowns: *const fmi2ValueReference,
    _n_known: usize,
    _dv_known: *const fmi2Real,
    _dv_unknown: *mut fmi2Real,
) -> fmi2Status {
    unsupported::<M>(
        c,
        "fmi2GetDirectionalDerivative",
        "providesDirectionalDerivative is false",
    )
}

/// fmi2SetRealInputDerivatives.
pub unsafe fn set_real_input_derivatives<M: Model>(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _n: usize,
    _order: *const fmi2Integer,
    _value: *const fmi2Real,
) -> fmi2Status {
    unsupported::<M>(
        c,
        "fmi2SetRealInputDerivatives",
        "canInterpolateInputs is false",
    )
}

/// fmi2GetRealOutputDerivatives.
pub unsafe fn get_real_output_derivatives<M: Model>(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _n: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    unsupported::<M>(
        c,
        "fmi2GetRealOutputDerivatives",
        "maxOutputDerivativeOrder is 0",
    )
}
