//! [`export_fmi2!`](crate::export_fmi2): the 34 functions of `fmi2Functions.h` for a
//! co-simulation FMU, exported under their C names for one model.

/// Exports the FMI 2.0 co-simulation API for the model type given, from a cdylib crate:
/// `rins_fmi2::export_fmi2!(my_crate::MyModel);`. Use it once per library.
#[macro_export]
macro_rules! export_fmi2 {
    ($model:ty) => {
        $crate::__rins_fmi::forward_c_functions! {
            fmi2GetTypesPlatform() -> *const ::std::ffi::c_char = $crate::lifecycle::get_types_platform::<$model>;
            fmi2GetVersion() -> *const ::std::ffi::c_char = $crate::lifecycle::get_version::<$model>;
            fmi2SetDebugLogging(c: $crate::fmi2Component, on: $crate::fmi2Boolean, n: usize, cats: *const $crate::fmi2String) -> $crate::fmi2Status = $crate::lifecycle::set_debug_logging::<$model>;
            fmi2Instantiate(name: $crate::fmi2String, ty: $crate::fmi2Type, guid: $crate::fmi2String, res: $crate::fmi2String, f: *const $crate::fmi2CallbackFunctions, vis: $crate::fmi2Boolean, on: $crate::fmi2Boolean) -> $crate::fmi2Component = $crate::lifecycle::instantiate::<$model>;
            fmi2FreeInstance(c: $crate::fmi2Component) -> () = $crate::lifecycle::free_instance::<$model>;
            fmi2SetupExperiment(c: $crate::fmi2Component, tol_on: $crate::fmi2Boolean, tol: $crate::fmi2Real, start: $crate::fmi2Real, stop_on: $crate::fmi2Boolean, stop: $crate::fmi2Real) -> $crate::fmi2Status = $crate::lifecycle::setup_experiment::<$model>;
            fmi2EnterInitializationMode(c: $crate::fmi2Component) -> $crate::fmi2Status = $crate::lifecycle::enter_initialization_mode::<$model>;
            fmi2ExitInitializationMode(c: $crate::fmi2Component) -> $crate::fmi2Status = $crate::lifecycle::exit_initialization_mode::<$model>;
            fmi2Terminate(c: $crate::fmi2Component) -> $crate::fmi2Status = $crate::lifecycle::terminate::<$model>;
            fmi2Reset(c: $crate::fmi2Component) -> $crate::fmi2Status = $crate::lifecycle::reset::<$model>;
            fmi2GetReal(c: $crate::fmi2Component, vr: *const $crate::fmi2ValueReference, n: usize, v: *mut $crate::fmi2Real) -> $crate::fmi2Status = $crate::values::get_real::<$model>;
            fmi2GetInteger(c: $crate::fmi2Component, vr: *const $crate::fmi2ValueReference, n: usize, v: *mut $crate::fmi2Integer) -> $crate::fmi2Status = $crate::values::get_integer::<$model>;
            fmi2GetBoolean(c: $crate::fmi2Component, vr: *const $crate::fmi2ValueReference, n: usize, v: *mut $crate::fmi2Boolean) -> $crate::fmi2Status = $crate::values::get_boolean::<$model>;
            fmi2GetString(c: $crate::fmi2Component, vr: *const $crate::fmi2ValueReference, n: usize, v: *mut $crate::fmi2String) -> $crate::fmi2Status = $crate::values::get_string::<$model>;
            fmi2SetReal(c: $crate::fmi2Component, vr: *const $crate::fmi2ValueReference, n: usize, v: *const $crate::fmi2Real) -> $crate::fmi2Status = $crate::values::set_real::<$model>;
            fmi2SetInteger(c: $crate::fmi2Component, vr: *const $crate::fmi2ValueReference, n: usize, v: *const $crate::fmi2Integer) -> $crate::fmi2Status = $crate::values::set_integer::<$model>;
            fmi2SetBoolean(c: $crate::fmi2Component, vr: *const $crate::fmi2ValueReference, n: usize, v: *const $crate::fmi2Boolean) -> $crate::fmi2Status = $crate::values::set_boolean::<$model>;
            fmi2SetString(c: $crate::fmi2Component, vr: *const $crate::fmi2ValueReference, n: usize, v: *const $crate::fmi2String) -> $crate::fmi2Status = $crate::values::set_string::<$model>;
            fmi2GetFMUstate(c: $crate::fmi2Component, s: *mut $crate::fmi2FMUstate) -> $crate::fmi2Status = $crate::state::get_fmu_state::<$model>;
            fmi2SetFMUstate(c: $crate::fmi2Component, s: $crate::fmi2FMUstate) -> $crate::fmi2Status = $crate::state::set_fmu_state::<$model>;
            fmi2FreeFMUstate(c: $crate::fmi2Component, s: *mut $crate::fmi2FMUstate) -> $crate::fmi2Status = $crate::state::free_fmu_state::<$model>;
            fmi2SerializedFMUstateSize(c: $crate::fmi2Component, s: $crate::fmi2FMUstate, size: *mut usize) -> $crate::fmi2Status = $crate::state::serialized_fmu_state_size::<$model>;
            fmi2SerializeFMUstate(c: $crate::fmi2Component, s: $crate::fmi2FMUstate, b: *mut $crate::fmi2Byte, size: usize) -> $crate::fmi2Status = $crate::state::serialize_fmu_state::<$model>;
            fmi2DeSerializeFMUstate(c: $crate::fmi2Component, b: *const $crate::fmi2Byte, size: usize, s: *mut $crate::fmi2FMUstate) -> $crate::fmi2Status = $crate::state::deserialize_fmu_state::<$model>;
            fmi2GetDirectionalDerivative(c: $crate::fmi2Component, u: *const $crate::fmi2ValueReference, nu: usize, k: *const $crate::fmi2ValueReference, nk: usize, dk: *const $crate::fmi2Real, du: *mut $crate::fmi2Real) -> $crate::fmi2Status = $crate::lifecycle::get_directional_derivative::<$model>;
            fmi2SetRealInputDerivatives(c: $crate::fmi2Component, vr: *const $crate::fmi2ValueReference, n: usize, o: *const $crate::fmi2Integer, v: *const $crate::fmi2Real) -> $crate::fmi2Status = $crate::lifecycle::set_real_input_derivatives::<$model>;
            fmi2GetRealOutputDerivatives(c: $crate::fmi2Component, vr: *const $crate::fmi2ValueReference, n: usize, o: *const $crate::fmi2Integer, v: *mut $crate::fmi2Real) -> $crate::fmi2Status = $crate::lifecycle::get_real_output_derivatives::<$model>;
            fmi2DoStep(c: $crate::fmi2Component, t: $crate::fmi2Real, h: $crate::fmi2Real, nsp: $crate::fmi2Boolean) -> $crate::fmi2Status = $crate::lifecycle::do_step::<$model>;
            fmi2CancelStep(c: $crate::fmi2Component) -> $crate::fmi2Status = $crate::lifecycle::cancel_step::<$model>;
            fmi2GetStatus(c: $crate::fmi2Component, k: $crate::fmi2StatusKind, v: *mut $crate::fmi2Status) -> $crate::fmi2Status = $crate::lifecycle::get_status::<$model>;
            fmi2GetRealStatus(c: $crate::fmi2Component, k: $crate::fmi2StatusKind, v: *mut $crate::fmi2Real) -> $crate::fmi2Status = $crate::lifecycle::get_real_status::<$model>;
            fmi2GetIntegerStatus(c: $crate::fmi2Component, k: $crate::fmi2StatusKind, v: *mut $crate::fmi2Integer) -> $crate::fmi2Status = $crate::lifecycle::get_integer_status::<$model>;
            fmi2GetBooleanStatus(c: $crate::fmi2Component, k: $crate::fmi2StatusKind, v: *mut $crate::fmi2Boolean) -> $crate::fmi2Status = $crate::lifecycle::get_boolean_status::<$model>;
            fmi2GetStringStatus(c: $crate::fmi2Component, k: $crate::fmi2StatusKind, v: *mut $crate::fmi2String) -> $crate::fmi2Status = $crate::lifecycle::get_string_status::<$model>;
        }
    };
}
