//! FMI 3.0 FMU state functions: thin C-typed wrappers over the shared helpers in
//! [`rins_fmi::ffi`] (the same code serves FMI 2).

use rins_fmi::ffi;
use rins_fmi::model::Model;

use crate::*;

/// fmi3GetFMUState.
pub unsafe fn get_fmu_state<M: Model>(c: fmi3Instance, state: *mut fmi3FMUState) -> fmi3Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi3GetFMUState", |comp| unsafe {
        ffi::get_state(&comp.inst, state)
    })
}

/// fmi3SetFMUState.
pub unsafe fn set_fmu_state<M: Model>(c: fmi3Instance, state: fmi3FMUState) -> fmi3Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi3SetFMUState", |comp| unsafe {
        ffi::set_state(&mut comp.inst, state)
    })
}

/// fmi3FreeFMUState.
pub unsafe fn free_fmu_state<M: Model>(c: fmi3Instance, state: *mut fmi3FMUState) -> fmi3Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi3FreeFMUState", |_| unsafe {
        ffi::free_state::<M>(state)
    })
}

/// fmi3SerializedFMUStateSize.
pub unsafe fn serialized_fmu_state_size<M: Model>(
    c: fmi3Instance,
    state: fmi3FMUState,
    size: *mut usize,
) -> fmi3Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi3SerializedFMUStateSize", |_| unsafe {
        ffi::state_size::<M>(state, size)
    })
}

/// fmi3SerializeFMUState.
pub unsafe fn serialize_fmu_state<M: Model>(
    c: fmi3Instance,
    state: fmi3FMUState,
    bytes: *mut fmi3Byte,
    size: usize,
) -> fmi3Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi3SerializeFMUState", |_| unsafe {
        ffi::serialize_state::<M>(state, bytes, size)
    })
}

/// fmi3DeserializeFMUState.
pub unsafe fn deserialize_fmu_state<M: Model>(
    c: fmi3Instance,
    bytes: *const fmi3Byte,
    size: usize,
    state: *mut fmi3FMUState,
) -> fmi3Status {
    // SAFETY: the standard's pointer contracts.
    with::<M>(c, "fmi3DeserializeFMUState", |_| unsafe {
        ffi::deserialize_state::<M>(bytes, size, state)
    })
}
