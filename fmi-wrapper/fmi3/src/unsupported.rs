//! FMI 3.0 entry points the co-simulation FMUs do not provide (Model Exchange, Scheduled
//! Execution, clocks, intervals, derivatives, event and configuration modes): each logs why and
//! returns `fmi3Error`.

use rins_fmi::model::Model;

use crate::*;

/// fmi3EnterEventMode.
pub unsafe fn enter_event_mode<M: Model>(c: fmi3Instance) -> fmi3Status {
    refuse::<M>(c, "fmi3EnterEventMode", "hasEventMode is false")
}

/// fmi3GetClock.
pub unsafe fn get_clock<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _values: *mut fmi3Boolean,
) -> fmi3Status {
    refuse::<M>(c, "fmi3GetClock", "this FMU has no clocks")
}

/// fmi3SetClock.
pub unsafe fn set_clock<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _values: *const fmi3Boolean,
) -> fmi3Status {
    refuse::<M>(c, "fmi3SetClock", "this FMU has no clocks")
}

/// fmi3GetNumberOfVariableDependencies.
pub unsafe fn get_number_of_variable_dependencies<M: Model>(
    c: fmi3Instance,
    _vr: fmi3ValueReference,
    _n: *mut usize,
) -> fmi3Status {
    refuse::<M>(
        c,
        "fmi3GetNumberOfVariableDependencies",
        "providesPerElementDependencies is false",
    )
}

/// fmi3GetVariableDependencies.
pub unsafe fn get_variable_dependencies<M: Model>(
    c: fmi3Instance,
    _dependent: fmi3ValueReference,
    _elem_dep: *mut usize,
    _independents: *mut fmi3ValueReference,
    _elem_ind: *mut usize,
    _kinds: *mut i32,
    _n: usize,
) -> fmi3Status {
    refuse::<M>(
        c,
        "fmi3GetVariableDependencies",
        "providesPerElementDependencies is false",
    )
}

/// fmi3GetDirectionalDerivative.
pub unsafe fn get_directional_derivative<M: Model>(
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
    refuse::<M>(
        c,
        "fmi3GetDirectionalDerivative",
        "providesDirectionalDerivatives is false",
    )
}

/// fmi3GetAdjointDerivative.
pub unsafe fn get_adjoint_derivative<M: Model>(
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
    refuse::<M>(
        c,
        "fmi3GetAdjointDerivative",
        "providesAdjointDerivatives is false",
    )
}

/// fmi3EnterConfigurationMode.
pub unsafe fn enter_configuration_mode<M: Model>(c: fmi3Instance) -> fmi3Status {
    refuse::<M>(
        c,
        "fmi3EnterConfigurationMode",
        "this FMU has no structural parameters",
    )
}

/// fmi3ExitConfigurationMode.
pub unsafe fn exit_configuration_mode<M: Model>(c: fmi3Instance) -> fmi3Status {
    refuse::<M>(
        c,
        "fmi3ExitConfigurationMode",
        "this FMU has no structural parameters",
    )
}

/// fmi3GetIntervalDecimal.
pub unsafe fn get_interval_decimal<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _intervals: *mut f64,
    _q: *mut i32,
) -> fmi3Status {
    refuse::<M>(c, "fmi3GetIntervalDecimal", "this FMU has no clocks")
}

/// fmi3GetIntervalFraction.
pub unsafe fn get_interval_fraction<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *mut u64,
    _res: *mut u64,
    _q: *mut i32,
) -> fmi3Status {
    refuse::<M>(c, "fmi3GetIntervalFraction", "this FMU has no clocks")
}

/// fmi3GetShiftDecimal.
pub unsafe fn get_shift_decimal<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _shifts: *mut f64,
) -> fmi3Status {
    refuse::<M>(c, "fmi3GetShiftDecimal", "this FMU has no clocks")
}

/// fmi3GetShiftFraction.
pub unsafe fn get_shift_fraction<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *mut u64,
    _res: *mut u64,
) -> fmi3Status {
    refuse::<M>(c, "fmi3GetShiftFraction", "this FMU has no clocks")
}

/// fmi3SetIntervalDecimal.
pub unsafe fn set_interval_decimal<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _intervals: *const f64,
) -> fmi3Status {
    refuse::<M>(c, "fmi3SetIntervalDecimal", "this FMU has no clocks")
}

/// fmi3SetIntervalFraction.
pub unsafe fn set_interval_fraction<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *const u64,
    _res: *const u64,
) -> fmi3Status {
    refuse::<M>(c, "fmi3SetIntervalFraction", "this FMU has no clocks")
}

/// fmi3SetShiftDecimal.
pub unsafe fn set_shift_decimal<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _shifts: *const f64,
) -> fmi3Status {
    refuse::<M>(c, "fmi3SetShiftDecimal", "this FMU has no clocks")
}

/// fmi3SetShiftFraction.
pub unsafe fn set_shift_fraction<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *const u64,
    _res: *const u64,
) -> fmi3Status {
    refuse::<M>(c, "fmi3SetShiftFraction", "this FMU has no clocks")
}

/// fmi3EvaluateDiscreteStates.
pub unsafe fn evaluate_discrete_states<M: Model>(c: fmi3Instance) -> fmi3Status {
    refuse::<M>(
        c,
        "fmi3EvaluateDiscreteStates",
        "providesEvaluateDiscreteStates is false",
    )
}

/// fmi3UpdateDiscreteStates.
pub unsafe fn update_discrete_states<M: Model>(
    c: fmi3Instance,
    _need_update: *mut fmi3Boolean,
    _terminate: *mut fmi3Boolean,
    _nominals_changed: *mut fmi3Boolean,
    _values_changed: *mut fmi3Boolean,
    _next_defined: *mut fmi3Boolean,
    _next_time: *mut f64,
) -> fmi3Status {
    refuse::<M>(c, "fmi3UpdateDiscreteStates", "hasEventMode is false")
}

/// fmi3EnterStepMode.
pub unsafe fn enter_step_mode<M: Model>(c: fmi3Instance) -> fmi3Status {
    refuse::<M>(
        c,
        "fmi3EnterStepMode",
        "hasEventMode is false: exitInitializationMode enters step mode",
    )
}

/// fmi3GetOutputDerivatives.
pub unsafe fn get_output_derivatives<M: Model>(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _orders: *const i32,
    _values: *mut f64,
    _n_values: usize,
) -> fmi3Status {
    refuse::<M>(
        c,
        "fmi3GetOutputDerivatives",
        "maxOutputDerivativeOrder is 0",
    )
}

/// fmi3ActivateModelPartition.
pub unsafe fn activate_model_partition<M: Model>(
    c: fmi3Instance,
    _clock: fmi3ValueReference,
    _time: f64,
) -> fmi3Status {
    refuse::<M>(
        c,
        "fmi3ActivateModelPartition",
        "Scheduled Execution is not provided",
    )
}

/// fmi3EnterContinuousTimeMode: Model Exchange only.
pub unsafe fn enter_continuous_time_mode<M: Model>(c: fmi3Instance) -> fmi3Status {
    refuse::<M>(
        c,
        "fmi3EnterContinuousTimeMode",
        "Model Exchange is not provided (co-simulation only)",
    )
}

/// fmi3CompletedIntegratorStep: Model Exchange only.
pub unsafe fn completed_integrator_step<M: Model>(
    c: fmi3Instance,
    no_set_prior: fmi3Boolean,
    enter_event: *mut fmi3Boolean,
    terminate: *mut fmi3Boolean,
) -> fmi3Status {
    let _ = no_set_prior;
    let _ = enter_event;
    let _ = terminate;
    refuse::<M>(
        c,
        "fmi3CompletedIntegratorStep",
        "Model Exchange is not provided (co-simulation only)",
    )
}

/// fmi3SetTime: Model Exchange only.
pub unsafe fn set_time<M: Model>(c: fmi3Instance, time: f64) -> fmi3Status {
    let _ = time;
    refuse::<M>(
        c,
        "fmi3SetTime",
        "Model Exchange is not provided (co-simulation only)",
    )
}

/// fmi3SetContinuousStates: Model Exchange only.
pub unsafe fn set_continuous_states<M: Model>(
    c: fmi3Instance,
    x: *const f64,
    n: usize,
) -> fmi3Status {
    let _ = x;
    let _ = n;
    refuse::<M>(
        c,
        "fmi3SetContinuousStates",
        "Model Exchange is not provided (co-simulation only)",
    )
}

/// fmi3GetContinuousStateDerivatives: Model Exchange only.
pub unsafe fn get_continuous_state_derivatives<M: Model>(
    c: fmi3Instance,
    dx: *mut f64,
    n: usize,
) -> fmi3Status {
    let _ = dx;
    let _ = n;
    refuse::<M>(
        c,
        "fmi3GetContinuousStateDerivatives",
        "Model Exchange is not provided (co-simulation only)",
    )
}

/// fmi3GetEventIndicators: Model Exchange only.
pub unsafe fn get_event_indicators<M: Model>(c: fmi3Instance, z: *mut f64, n: usize) -> fmi3Status {
    let _ = z;
    let _ = n;
    refuse::<M>(
        c,
        "fmi3GetEventIndicators",
        "Model Exchange is not provided (co-simulation only)",
    )
}

/// fmi3GetContinuousStates: Model Exchange only.
pub unsafe fn get_continuous_states<M: Model>(
    c: fmi3Instance,
    x: *mut f64,
    n: usize,
) -> fmi3Status {
    let _ = x;
    let _ = n;
    refuse::<M>(
        c,
        "fmi3GetContinuousStates",
        "Model Exchange is not provided (co-simulation only)",
    )
}

/// fmi3GetNominalsOfContinuousStates: Model Exchange only.
pub unsafe fn get_nominals_of_continuous_states<M: Model>(
    c: fmi3Instance,
    nominals: *mut f64,
    n: usize,
) -> fmi3Status {
    let _ = nominals;
    let _ = n;
    refuse::<M>(
        c,
        "fmi3GetNominalsOfContinuousStates",
        "Model Exchange is not provided (co-simulation only)",
    )
}

/// fmi3GetNumberOfEventIndicators: Model Exchange only.
pub unsafe fn get_number_of_event_indicators<M: Model>(
    c: fmi3Instance,
    n: *mut usize,
) -> fmi3Status {
    let _ = n;
    refuse::<M>(
        c,
        "fmi3GetNumberOfEventIndicators",
        "Model Exchange is not provided (co-simulation only)",
    )
}

/// fmi3GetNumberOfContinuousStates: Model Exchange only.
pub unsafe fn get_number_of_continuous_states<M: Model>(
    c: fmi3Instance,
    n: *mut usize,
) -> fmi3Status {
    let _ = n;
    refuse::<M>(
        c,
        "fmi3GetNumberOfContinuousStates",
        "Model Exchange is not provided (co-simulation only)",
    )
}
