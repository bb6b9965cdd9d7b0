//! FMI 3.0 instance life and co-simulation stepping: instantiate (co-simulation only),
//! initialisation, doStep, terminate, reset, free.

use std::ffi::c_char;

use rins_fmi::ffi::{check_log_categories, check_token, text};
use rins_fmi::instance::{FmiError, Instance, Status};
use rins_fmi::model::Model;
use rins_fmi::standard::FmiVersion;

use crate::*;

/// fmi3GetVersion.
pub unsafe fn get_version<M: Model>() -> *const c_char {
    c"3.0".as_ptr()
}

/// fmi3SetDebugLogging.
pub unsafe fn set_debug_logging<M: Model>(
    c: fmi3Instance,
    logging_on: fmi3Boolean,
    n: usize,
    categories: *const fmi3String,
) -> fmi3Status {
    with::<M>(c, "fmi3SetDebugLogging", |comp| {
        // SAFETY: `categories` holds `n` C strings.
        unsafe { check_log_categories(categories, n)? };
        comp.logging_on = logging_on;
        Ok(())
    })
}

fn refuse_instantiate(logger: &Fmi3Logger, what: &str, why: &str) -> fmi3Instance {
    logger.emit(Status::Error, "logStatusError", &format!("{what}: {why}"));
    std::ptr::null_mut()
}

/// fmi3InstantiateModelExchange: refused (co-simulation only).
pub unsafe fn instantiate_model_exchange<M: Model>(
    _name: fmi3String,
    _token: fmi3String,
    _resources: fmi3String,
    _visible: fmi3Boolean,
    _logging_on: fmi3Boolean,
    env: fmi3InstanceEnvironment,
    logger: fmi3LogMessageCallback,
) -> fmi3Instance {
    let logger = Fmi3Logger {
        callback: logger,
        env,
    };
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        refuse_instantiate(
            &logger,
            "fmi3InstantiateModelExchange",
            "this FMU supports co-simulation only",
        )
    }))
    .unwrap_or(std::ptr::null_mut())
}

/// fmi3InstantiateScheduledExecution: refused (co-simulation only).
pub unsafe fn instantiate_scheduled_execution<M: Model>(
    _name: fmi3String,
    _token: fmi3String,
    _resources: fmi3String,
    _visible: fmi3Boolean,
    _logging_on: fmi3Boolean,
    env: fmi3InstanceEnvironment,
    logger: fmi3LogMessageCallback,
    _clock_update: fmi3Callback,
    _lock: fmi3Callback,
    _unlock: fmi3Callback,
) -> fmi3Instance {
    let logger = Fmi3Logger {
        callback: logger,
        env,
    };
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        refuse_instantiate(
            &logger,
            "fmi3InstantiateScheduledExecution",
            "this FMU supports co-simulation only",
        )
    }))
    .unwrap_or(std::ptr::null_mut())
}

/// fmi3InstantiateCoSimulation: without event mode, and only with this binary's token.
pub unsafe fn instantiate_co_simulation<M: Model>(
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
    logger: fmi3LogMessageCallback,
    _intermediate_update: fmi3Callback,
) -> fmi3Instance {
    let logger = Fmi3Logger {
        callback: logger,
        env,
    };
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        const WHAT: &str = "fmi3InstantiateCoSimulation";
        if event_mode_used {
            return refuse_instantiate(
                &logger,
                WHAT,
                "hasEventMode is false: instantiate with eventModeUsed = false",
            );
        }
        // SAFETY: NULL or a C string per the standard.
        if let Err(why) = check_token::<M>(FmiVersion::V3, unsafe { text(token) }) {
            return refuse_instantiate(&logger, WHAT, &why);
        }
        let comp = Fmi3::<M> {
            inst: Instance::new(),
            logger: Fmi3Logger {
                callback: logger.callback,
                env: logger.env,
            },
            logging_on,
        };
        comp.log(Status::Ok, "logEvents", "instantiated");
        comp.into_handle()
    }))
    .unwrap_or(std::ptr::null_mut())
}

/// fmi3FreeInstance: a second free, or a pointer that is no live instance, does nothing
/// (the host would otherwise abort on a double free).
pub unsafe fn free_instance<M: Model>(c: fmi3Instance) {
    // SAFETY: only a live handle from fmi3InstantiateCoSimulation of this library is freed.
    unsafe { Fmi3::<M>::free_handle(c) }
}

/// fmi3EnterInitializationMode: records the start time, then enters initialization mode.
pub unsafe fn enter_initialization_mode<M: Model>(
    c: fmi3Instance,
    _tol_defined: fmi3Boolean,
    _tol: f64,
    start: f64,
    stop_defined: fmi3Boolean,
    stop: f64,
) -> fmi3Status {
    with::<M>(c, "fmi3EnterInitializationMode", |comp| {
        if stop_defined && !(stop >= start) {
            return Err(FmiError::error(format!(
                "stop time {stop} is before start time {start}"
            )));
        }
        comp.inst.enter_initialization_at(start)?;
        comp.log(Status::Ok, "logEvents", "initialization mode");
        Ok(())
    })
}

/// fmi3ExitInitializationMode: the model is built from its parameters; step mode follows.
pub unsafe fn exit_initialization_mode<M: Model>(c: fmi3Instance) -> fmi3Status {
    with::<M>(c, "fmi3ExitInitializationMode", |comp| {
        comp.inst.exit_initialization()?;
        comp.log(Status::Ok, "logEvents", "initialized; step mode");
        Ok(())
    })
}

/// fmi3Terminate.
pub unsafe fn terminate<M: Model>(c: fmi3Instance) -> fmi3Status {
    with::<M>(c, "fmi3Terminate", |comp| {
        comp.inst.terminate()?;
        comp.log(Status::Ok, "logEvents", "terminated");
        Ok(())
    })
}

/// fmi3Reset.
pub unsafe fn reset<M: Model>(c: fmi3Instance) -> fmi3Status {
    with::<M>(c, "fmi3Reset", |comp| {
        comp.inst.reset();
        comp.log(
            Status::Ok,
            "logEvents",
            "reset: instantiated mode, start values",
        );
        Ok(())
    })
}

/// fmi3DoStep: never returns early, never asks for events or termination.
pub unsafe fn do_step<M: Model>(
    c: fmi3Instance,
    t: f64,
    h: f64,
    _no_set_prior: fmi3Boolean,
    event_handling_needed: *mut fmi3Boolean,
    terminate_simulation: *mut fmi3Boolean,
    early_return: *mut fmi3Boolean,
    last_successful_time: *mut f64,
) -> fmi3Status {
    with::<M>(c, "fmi3DoStep", |comp| {
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
        r?;
        if comp.logging_on {
            comp.log_step(t, h);
        }
        Ok(())
    })
}
