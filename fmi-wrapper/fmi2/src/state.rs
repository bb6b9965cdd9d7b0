//! FMI 2.0 FMU state functions: thin C-typed wrappers over the shared helpers in
//! [`rins_fmi::ffi`] (the same code serves FMI 3).

use rins_fmi::ffi;
use rins_fmi::model::Model;

use crate::*;

/// fmi2GetFMUstate.
pub unsafe fn get_fmu_state<M: Model>(c: fmi2Component, state: *mut fmi2FMUstate) -> fmi2Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi2GetFMUstate", |comp| unsafe {
        ffi::get_state(&comp.inst, state)
    })
}

/// fmi2SetFMUstate.
pub unsafe fn set_fmu_state<M: Model>(c: fmi2Component, state: fmi2FMUstate) -> fmi2Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi2SetFMUstate", |comp| unsafe {
        ffi::set_state(&mut comp.inst, state)
    })
}

/// fmi2FreeFMUstate.
pub unsafe fn free_fmu_state<M: Model>(c: fmi2Component, state: *mut fmi2FMUstate) -> fmi2Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi2FreeFMUstate", |_| unsafe {
        ffi::free_state::<M>(state)
    })
}

/// fmi2SerializedFMUstateSize.
pub unsafe fn serialized_fmu_state_size<M: Model>(
    c: fmi2Component,
    state: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi2SerializedFMUstateSize", |_| unsafe {
        ffi::state_size::<M>(state, size)
    })
}

/// fmi2SerializeFMUstate.
pub unsafe fn serialize_fmu_state<M: Model>(
    c: fmi2Component,
    state: fmi2FMUstate,
    bytes: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi2SerializeFMUstate", |_| unsafe {
        ffi::serialize_state::<M>(state, bytes as *mut u8, size)
    })
}

/// fmi2DeSerializeFMUstate.
pub unsafe fn deserialize_fmu_state<M: Model>(
    c: fmi2Component,
    bytes: *const fmi2Byte,
    size: usize,
    state: *mut fmi2FMUstate,
) -> fmi2Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi2DeSerializeFMUstate", |_| unsafe {
        ffi::deserialize_state::<M>(bytes as *const u8, size, state)
    })
}
