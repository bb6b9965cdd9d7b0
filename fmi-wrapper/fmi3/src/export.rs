//! [`export_fmi3!`](crate::export_fmi3): the 75 functions of `fmi3Functions.h`, exported under
//! their C names for one model.

/// Exports the FMI 3.0 API for the model type given, from a cdylib crate:
/// `rins_fmi3::export_fmi3!(my_crate::MyModel);`. Use it once per library.
#[macro_export]
macro_rules! export_fmi3 {
    ($model:ty) => {
        $crate::__rins_fmi::forward_c_functions! {
            fmi3GetVersion() -> *const ::std::ffi::c_char = $crate::lifecycle::get_version::<$model>;
            fmi3SetDebugLogging(c: $crate::fmi3Instance, logging_on: $crate::fmi3Boolean, n: usize, categories: *const $crate::fmi3String) -> $crate::fmi3Status = $crate::lifecycle::set_debug_logging::<$model>;
            fmi3InstantiateModelExchange(name: $crate::fmi3String, token: $crate::fmi3String, resources: $crate::fmi3String, visible: $crate::fmi3Boolean, logging_on: $crate::fmi3Boolean, env: $crate::fmi3InstanceEnvironment, logger: $crate::fmi3LogMessageCallback) -> $crate::fmi3Instance = $crate::lifecycle::instantiate_model_exchange::<$model>;
            fmi3InstantiateScheduledExecution(name: $crate::fmi3String, token: $crate::fmi3String, resources: $crate::fmi3String, visible: $crate::fmi3Boolean, logging_on: $crate::fmi3Boolean, env: $crate::fmi3InstanceEnvironment, logger: $crate::fmi3LogMessageCallback, clock_update: $crate::fmi3Callback, lock: $crate::fmi3Callback, unlock: $crate::fmi3Callback) -> $crate::fmi3Instance = $crate::lifecycle::instantiate_scheduled_execution::<$model>;
            fmi3InstantiateCoSimulation(name: $crate::fmi3String, token: $crate::fmi3String, resources: $crate::fmi3String, visible: $crate::fmi3Boolean, logging_on: $crate::fmi3Boolean, event_mode_used: $crate::fmi3Boolean, early_return_allowed: $crate::fmi3Boolean, required_intermediate: *const $crate::fmi3ValueReference, n_required_intermediate: usize, env: $crate::fmi3InstanceEnvironment, logger: $crate::fmi3LogMessageCallback, intermediate_update: $crate::fmi3Callback) -> $crate::fmi3Instance = $crate::lifecycle::instantiate_co_simulation::<$model>;
            fmi3FreeInstance(c: $crate::fmi3Instance) -> () = $crate::lifecycle::free_instance::<$model>;
            fmi3EnterInitializationMode(c: $crate::fmi3Instance, tol_defined: $crate::fmi3Boolean, tol: f64, start: f64, stop_defined: $crate::fmi3Boolean, stop: f64) -> $crate::fmi3Status = $crate::lifecycle::enter_initialization_mode::<$model>;
            fmi3ExitInitializationMode(c: $crate::fmi3Instance) -> $crate::fmi3Status = $crate::lifecycle::exit_initialization_mode::<$model>;
            fmi3Terminate(c: $crate::fmi3Instance) -> $crate::fmi3Status = $crate::lifecycle::terminate::<$model>;
            fmi3Reset(c: $crate::fmi3Instance) -> $crate::fmi3Status = $crate::lifecycle::reset::<$model>;
            fmi3DoStep(c: $crate::fmi3Instance, t: f64, h: f64, no_set_prior: $crate::fmi3Boolean, event_handling_needed: *mut $crate::fmi3Boolean, terminate_simulation: *mut $crate::fmi3Boolean, early_return: *mut $crate::fmi3Boolean, last_successful_time: *mut f64) -> $crate::fmi3Status = $crate::lifecycle::do_step::<$model>;
            fmi3GetFloat64(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut f64, n_values: usize) -> $crate::fmi3Status = $crate::values::get_float64::<$model>;
            fmi3SetFloat64(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const f64, n_values: usize) -> $crate::fmi3Status = $crate::values::set_float64::<$model>;
            fmi3GetUInt64(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut u64, n_values: usize) -> $crate::fmi3Status = $crate::values::get_uint64::<$model>;
            fmi3SetUInt64(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const u64, n_values: usize) -> $crate::fmi3Status = $crate::values::set_uint64::<$model>;
            fmi3GetInt64(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut i64, n_values: usize) -> $crate::fmi3Status = $crate::values::get_int64::<$model>;
            fmi3SetInt64(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const i64, n_values: usize) -> $crate::fmi3Status = $crate::values::set_int64::<$model>;
            fmi3GetBoolean(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut $crate::fmi3Boolean, n_values: usize) -> $crate::fmi3Status = $crate::values::get_boolean::<$model>;
            fmi3SetBoolean(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const $crate::fmi3Boolean, n_values: usize) -> $crate::fmi3Status = $crate::values::set_boolean::<$model>;
            fmi3GetBinary(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, sizes: *mut usize, values: *mut $crate::fmi3Binary, n_values: usize) -> $crate::fmi3Status = $crate::values::get_binary::<$model>;
            fmi3SetBinary(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, sizes: *const usize, values: *const $crate::fmi3Binary, n_values: usize) -> $crate::fmi3Status = $crate::values::set_binary::<$model>;
            fmi3GetFMUState(c: $crate::fmi3Instance, state: *mut $crate::fmi3FMUState) -> $crate::fmi3Status = $crate::state::get_fmu_state::<$model>;
            fmi3SetFMUState(c: $crate::fmi3Instance, state: $crate::fmi3FMUState) -> $crate::fmi3Status = $crate::state::set_fmu_state::<$model>;
            fmi3FreeFMUState(c: $crate::fmi3Instance, state: *mut $crate::fmi3FMUState) -> $crate::fmi3Status = $crate::state::free_fmu_state::<$model>;
            fmi3SerializedFMUStateSize(c: $crate::fmi3Instance, state: $crate::fmi3FMUState, size: *mut usize) -> $crate::fmi3Status = $crate::state::serialized_fmu_state_size::<$model>;
            fmi3SerializeFMUState(c: $crate::fmi3Instance, state: $crate::fmi3FMUState, bytes: *mut $crate::fmi3Byte, size: usize) -> $crate::fmi3Status = $crate::state::serialize_fmu_state::<$model>;
            fmi3DeserializeFMUState(c: $crate::fmi3Instance, bytes: *const $crate::fmi3Byte, size: usize, state: *mut $crate::fmi3FMUState) -> $crate::fmi3Status = $crate::state::deserialize_fmu_state::<$model>;
            fmi3EnterEventMode(c: $crate::fmi3Instance) -> $crate::fmi3Status = $crate::unsupported::enter_event_mode::<$model>;
            fmi3GetClock(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, values: *mut $crate::fmi3Boolean) -> $crate::fmi3Status = $crate::unsupported::get_clock::<$model>;
            fmi3SetClock(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, values: *const $crate::fmi3Boolean) -> $crate::fmi3Status = $crate::unsupported::set_clock::<$model>;
            fmi3GetNumberOfVariableDependencies(c: $crate::fmi3Instance, vr: $crate::fmi3ValueReference, n: *mut usize) -> $crate::fmi3Status = $crate::unsupported::get_number_of_variable_dependencies::<$model>;
            fmi3GetVariableDependencies(c: $crate::fmi3Instance, dependent: $crate::fmi3ValueReference, elem_dep: *mut usize, independents: *mut $crate::fmi3ValueReference, elem_ind: *mut usize, kinds: *mut i32, n: usize) -> $crate::fmi3Status = $crate::unsupported::get_variable_dependencies::<$model>;
            fmi3GetDirectionalDerivative(c: $crate::fmi3Instance, unknowns: *const $crate::fmi3ValueReference, n_unknowns: usize, knowns: *const $crate::fmi3ValueReference, n_knowns: usize, seed: *const f64, n_seed: usize, sensitivity: *mut f64, n_sensitivity: usize) -> $crate::fmi3Status = $crate::unsupported::get_directional_derivative::<$model>;
            fmi3GetAdjointDerivative(c: $crate::fmi3Instance, unknowns: *const $crate::fmi3ValueReference, n_unknowns: usize, knowns: *const $crate::fmi3ValueReference, n_knowns: usize, seed: *const f64, n_seed: usize, sensitivity: *mut f64, n_sensitivity: usize) -> $crate::fmi3Status = $crate::unsupported::get_adjoint_derivative::<$model>;
            fmi3EnterConfigurationMode(c: $crate::fmi3Instance) -> $crate::fmi3Status = $crate::unsupported::enter_configuration_mode::<$model>;
            fmi3ExitConfigurationMode(c: $crate::fmi3Instance) -> $crate::fmi3Status = $crate::unsupported::exit_configuration_mode::<$model>;
            fmi3GetIntervalDecimal(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, intervals: *mut f64, q: *mut i32) -> $crate::fmi3Status = $crate::unsupported::get_interval_decimal::<$model>;
            fmi3GetIntervalFraction(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, counters: *mut u64, res: *mut u64, q: *mut i32) -> $crate::fmi3Status = $crate::unsupported::get_interval_fraction::<$model>;
            fmi3GetShiftDecimal(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, shifts: *mut f64) -> $crate::fmi3Status = $crate::unsupported::get_shift_decimal::<$model>;
            fmi3GetShiftFraction(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, counters: *mut u64, res: *mut u64) -> $crate::fmi3Status = $crate::unsupported::get_shift_fraction::<$model>;
            fmi3SetIntervalDecimal(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, intervals: *const f64) -> $crate::fmi3Status = $crate::unsupported::set_interval_decimal::<$model>;
            fmi3SetIntervalFraction(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, counters: *const u64, res: *const u64) -> $crate::fmi3Status = $crate::unsupported::set_interval_fraction::<$model>;
            fmi3SetShiftDecimal(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, shifts: *const f64) -> $crate::fmi3Status = $crate::unsupported::set_shift_decimal::<$model>;
            fmi3SetShiftFraction(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, counters: *const u64, res: *const u64) -> $crate::fmi3Status = $crate::unsupported::set_shift_fraction::<$model>;
            fmi3EvaluateDiscreteStates(c: $crate::fmi3Instance) -> $crate::fmi3Status = $crate::unsupported::evaluate_discrete_states::<$model>;
            fmi3UpdateDiscreteStates(c: $crate::fmi3Instance, need_update: *mut $crate::fmi3Boolean, terminate: *mut $crate::fmi3Boolean, nominals_changed: *mut $crate::fmi3Boolean, values_changed: *mut $crate::fmi3Boolean, next_defined: *mut $crate::fmi3Boolean, next_time: *mut f64) -> $crate::fmi3Status = $crate::unsupported::update_discrete_states::<$model>;
            fmi3EnterStepMode(c: $crate::fmi3Instance) -> $crate::fmi3Status = $crate::unsupported::enter_step_mode::<$model>;
            fmi3GetOutputDerivatives(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n: usize, orders: *const i32, values: *mut f64, n_values: usize) -> $crate::fmi3Status = $crate::unsupported::get_output_derivatives::<$model>;
            fmi3ActivateModelPartition(c: $crate::fmi3Instance, clock: $crate::fmi3ValueReference, time: f64) -> $crate::fmi3Status = $crate::unsupported::activate_model_partition::<$model>;
            fmi3EnterContinuousTimeMode(c: $crate::fmi3Instance) -> $crate::fmi3Status = $crate::unsupported::enter_continuous_time_mode::<$model>;
            fmi3CompletedIntegratorStep(c: $crate::fmi3Instance, no_set_prior: $crate::fmi3Boolean, enter_event: *mut $crate::fmi3Boolean, terminate: *mut $crate::fmi3Boolean) -> $crate::fmi3Status = $crate::unsupported::completed_integrator_step::<$model>;
            fmi3SetTime(c: $crate::fmi3Instance, time: f64) -> $crate::fmi3Status = $crate::unsupported::set_time::<$model>;
            fmi3SetContinuousStates(c: $crate::fmi3Instance, x: *const f64, n: usize) -> $crate::fmi3Status = $crate::unsupported::set_continuous_states::<$model>;
            fmi3GetContinuousStateDerivatives(c: $crate::fmi3Instance, dx: *mut f64, n: usize) -> $crate::fmi3Status = $crate::unsupported::get_continuous_state_derivatives::<$model>;
            fmi3GetEventIndicators(c: $crate::fmi3Instance, z: *mut f64, n: usize) -> $crate::fmi3Status = $crate::unsupported::get_event_indicators::<$model>;
            fmi3GetContinuousStates(c: $crate::fmi3Instance, x: *mut f64, n: usize) -> $crate::fmi3Status = $crate::unsupported::get_continuous_states::<$model>;
            fmi3GetNominalsOfContinuousStates(c: $crate::fmi3Instance, nominals: *mut f64, n: usize) -> $crate::fmi3Status = $crate::unsupported::get_nominals_of_continuous_states::<$model>;
            fmi3GetNumberOfEventIndicators(c: $crate::fmi3Instance, n: *mut usize) -> $crate::fmi3Status = $crate::unsupported::get_number_of_event_indicators::<$model>;
            fmi3GetNumberOfContinuousStates(c: $crate::fmi3Instance, n: *mut usize) -> $crate::fmi3Status = $crate::unsupported::get_number_of_continuous_states::<$model>;
            fmi3GetFloat32(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut f32, n_values: usize) -> $crate::fmi3Status = $crate::values::get_float32::<$model>;
            fmi3SetFloat32(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const f32, n_values: usize) -> $crate::fmi3Status = $crate::values::set_float32::<$model>;
            fmi3GetInt8(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut i8, n_values: usize) -> $crate::fmi3Status = $crate::values::get_int8::<$model>;
            fmi3SetInt8(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const i8, n_values: usize) -> $crate::fmi3Status = $crate::values::set_int8::<$model>;
            fmi3GetUInt8(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut u8, n_values: usize) -> $crate::fmi3Status = $crate::values::get_uint8::<$model>;
            fmi3SetUInt8(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const u8, n_values: usize) -> $crate::fmi3Status = $crate::values::set_uint8::<$model>;
            fmi3GetInt16(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut i16, n_values: usize) -> $crate::fmi3Status = $crate::values::get_int16::<$model>;
            fmi3SetInt16(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const i16, n_values: usize) -> $crate::fmi3Status = $crate::values::set_int16::<$model>;
            fmi3GetUInt16(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut u16, n_values: usize) -> $crate::fmi3Status = $crate::values::get_uint16::<$model>;
            fmi3SetUInt16(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const u16, n_values: usize) -> $crate::fmi3Status = $crate::values::set_uint16::<$model>;
            fmi3GetInt32(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut i32, n_values: usize) -> $crate::fmi3Status = $crate::values::get_int32::<$model>;
            fmi3SetInt32(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const i32, n_values: usize) -> $crate::fmi3Status = $crate::values::set_int32::<$model>;
            fmi3GetUInt32(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut u32, n_values: usize) -> $crate::fmi3Status = $crate::values::get_uint32::<$model>;
            fmi3SetUInt32(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const u32, n_values: usize) -> $crate::fmi3Status = $crate::values::set_uint32::<$model>;
            fmi3GetString(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *mut $crate::fmi3String, n_values: usize) -> $crate::fmi3Status = $crate::values::get_string::<$model>;
            fmi3SetString(c: $crate::fmi3Instance, vr: *const $crate::fmi3ValueReference, n_vr: usize, values: *const $crate::fmi3String, n_values: usize) -> $crate::fmi3Status = $crate::values::set_string::<$model>;
        }
    };
}
