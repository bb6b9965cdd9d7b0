//! FMI 3.0 getters and setters: one value reference per variable (arrays are one reference
//! for all their elements, `nValues` counts elements); `time` is value reference 0.

use rins_fmi::ffi::{slice, slice_mut};
use rins_fmi::instance::{FmiError, Mode};
use rins_fmi::model::Model;
use rins_fmi::standard::FmiVersion;
use rins_fmi::vars::{Kind, Value, with_article};

use crate::*;

/// Slots of FMI 3 value reference `vr` (0 is `time`, which has none).
fn slots<M: Model>(comp: &Fmi3<M>, vr: u32) -> Result<std::ops::Range<usize>, FmiError> {
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

/// A call of the wrong type: what the variable is, what the call takes (`wanted`: the FMI 3
/// type, with a remark when this FMU has no variable of it) and the call that reads or sets it.
fn type_error<M: Model>(comp: &Fmi3<M>, vr: u32, wanted: &str, set: bool) -> FmiError {
    let a = &comp.inst.table().arrays[vr as usize - 1];
    let kind = comp.inst.table().scalars[a.slots.start].kind;
    FmiError::error(format!(
        "value reference {vr} ({}) is {} variable, not {}: {} it with fmi3{}{}",
        a.name,
        kind.described(FmiVersion::V3),
        with_article(wanted),
        if set { "set" } else { "read" },
        if set { "Set" } else { "Get" },
        kind.accessor(FmiVersion::V3)
    ))
}

/// Shared body of the fmi3Get* functions: walks the value references, checks `nValues`.
fn get_typed<M: Model, T: Copy>(
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
    with::<M>(c, what, |comp| {
        if comp.inst.mode() == Mode::Instantiated {
            return Err(FmiError::error(
                "values can be read from initialization mode on",
            ));
        }
        // SAFETY: the standard gives `n_vr` references and room for `n_values` values.
        let (vrs, out) = unsafe { (slice(vr, n_vr)?, slice_mut(out, n_values)?) };
        // Count and type-check first: a too-small nValues or a wrong type writes nothing
        // (ecos reads arrays as scalars and ignores the status, so a partial write would be
        // taken for the values).
        let mut k = 0;
        for &r in vrs {
            if r == 0 && time.is_some() {
                k += 1;
                continue;
            }
            let s = slots(comp, r)?;
            if conv(comp.inst.get_slot(s.start)).is_none() {
                return Err(type_error(comp, r, wanted, false));
            }
            k += s.len();
        }
        if k != n_values {
            return Err(FmiError::error(format!(
                "nValues = {n_values}, but the value references hold {k} values (nothing was written)"
            )));
        }
        let mut k = 0;
        for &r in vrs {
            if r == 0
                && let Some(t) = time
            {
                out[k] = t(comp.inst.time_s());
                k += 1;
                continue;
            }
            for slot in slots(comp, r)? {
                out[k] = conv(comp.inst.get_slot(slot))
                    .ok_or_else(|| type_error(comp, r, wanted, false))?;
                k += 1;
            }
        }
        Ok(())
    })
}

/// Shared body of the fmi3Set* functions.
fn set_typed<M: Model, T: Copy>(
    c: fmi3Instance,
    what: &str,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    vals: *const T,
    n_values: usize,
    conv: fn(Kind, T) -> Option<Value>,
    wanted: &'static str,
) -> fmi3Status {
    with::<M>(c, what, |comp| {
        // SAFETY: as in get_typed.
        let (vrs, vals) = unsafe { (slice(vr, n_vr)?, slice(vals, n_values)?) };
        // Every value is converted and checked (count, type, range, mode) before any is set:
        // a refused call changes nothing.
        let mut total = 0;
        for &r in vrs {
            total += slots(comp, r)?.len();
        }
        if total != n_values {
            return Err(FmiError::error(format!(
                "nValues = {n_values}, but the value references hold {total} values (nothing was set)"
            )));
        }
        // Two passes (no allocation on the per-step input path): check all, then set.
        for pass in 0..2 {
            let mut k = 0;
            for &r in vrs {
                for slot in slots(comp, r)? {
                    let kind = comp.inst.table().scalars[slot].kind;
                    let v = conv(kind, vals[k]).ok_or_else(|| type_error(comp, r, wanted, true))?;
                    if pass == 0 {
                        comp.inst.check_set(slot, v)?;
                    } else {
                        comp.inst.set_slot(slot, v)?;
                    }
                    k += 1;
                }
            }
        }
        Ok(())
    })
}

/// fmi3GetFloat64.
pub unsafe fn get_float64<M: Model>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *mut f64,
    n_values: usize,
) -> fmi3Status {
    get_typed::<M, _>(
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

/// fmi3SetFloat64.
pub unsafe fn set_float64<M: Model>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *const f64,
    n_values: usize,
) -> fmi3Status {
    set_typed::<M, _>(
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

/// fmi3GetUInt64.
pub unsafe fn get_uint64<M: Model>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *mut u64,
    n_values: usize,
) -> fmi3Status {
    get_typed::<M, _>(
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

/// fmi3SetUInt64.
pub unsafe fn set_uint64<M: Model>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *const u64,
    n_values: usize,
) -> fmi3Status {
    set_typed::<M, _>(
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

/// fmi3GetInt64.
pub unsafe fn get_int64<M: Model>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *mut i64,
    n_values: usize,
) -> fmi3Status {
    get_typed::<M, _>(
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
        "Int64 (this FMU's Int64 variables are its Enumerations)",
    )
}

/// fmi3SetInt64.
pub unsafe fn set_int64<M: Model>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *const i64,
    n_values: usize,
) -> fmi3Status {
    set_typed::<M, _>(
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
        "Int64 (this FMU's Int64 variables are its Enumerations)",
    )
}

/// fmi3GetBoolean.
pub unsafe fn get_boolean<M: Model>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *mut fmi3Boolean,
    n_values: usize,
) -> fmi3Status {
    get_typed::<M, _>(
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

/// fmi3SetBoolean.
pub unsafe fn set_boolean<M: Model>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *const fmi3Boolean,
    n_values: usize,
) -> fmi3Status {
    set_typed::<M, _>(
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

/// Getters and setters of types the models have no variables of: fine for zero references,
/// an error naming the type otherwise.
macro_rules! absent_type {
    ($get:ident, $set:ident, $t:ty, $cget:literal, $cset:literal, $name:literal) => {
        #[doc = concat!($cget, ": no variables of this type.")]
        pub unsafe fn $get<M: Model>(
            c: fmi3Instance,
            vr: *const fmi3ValueReference,
            n_vr: usize,
            values: *mut $t,
            n_values: usize,
        ) -> fmi3Status {
            get_typed::<M, _>(
                c,
                $cget,
                vr,
                n_vr,
                values,
                n_values,
                None,
                |_| None,
                concat!($name, " (this FMU has no ", $name, " variables)"),
            )
        }
        #[doc = concat!($cset, ": no variables of this type.")]
        pub unsafe fn $set<M: Model>(
            c: fmi3Instance,
            vr: *const fmi3ValueReference,
            n_vr: usize,
            values: *const $t,
            n_values: usize,
        ) -> fmi3Status {
            set_typed::<M, _>(
                c,
                $cset,
                vr,
                n_vr,
                values,
                n_values,
                |_, _| None,
                concat!($name, " (this FMU has no ", $name, " variables)"),
            )
        }
    };
}

absent_type!(
    get_float32,
    set_float32,
    f32,
    "fmi3GetFloat32",
    "fmi3SetFloat32",
    "Float32"
);
absent_type!(get_int8, set_int8, i8, "fmi3GetInt8", "fmi3SetInt8", "Int8");
absent_type!(
    get_uint8,
    set_uint8,
    u8,
    "fmi3GetUInt8",
    "fmi3SetUInt8",
    "UInt8"
);
absent_type!(
    get_int16,
    set_int16,
    i16,
    "fmi3GetInt16",
    "fmi3SetInt16",
    "Int16"
);
absent_type!(
    get_uint16,
    set_uint16,
    u16,
    "fmi3GetUInt16",
    "fmi3SetUInt16",
    "UInt16"
);
absent_type!(
    get_int32,
    set_int32,
    i32,
    "fmi3GetInt32",
    "fmi3SetInt32",
    "Int32"
);
absent_type!(
    get_uint32,
    set_uint32,
    u32,
    "fmi3GetUInt32",
    "fmi3SetUInt32",
    "UInt32"
);
absent_type!(
    get_string,
    set_string,
    fmi3String,
    "fmi3GetString",
    "fmi3SetString",
    "String"
);

/// fmi3GetBinary: no Binary variables.
pub unsafe fn get_binary<M: Model>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    _sizes: *mut usize,
    values: *mut fmi3Binary,
    n_values: usize,
) -> fmi3Status {
    get_typed::<M, _>(
        c,
        "fmi3GetBinary",
        vr,
        n_vr,
        values,
        n_values,
        None,
        |_| None,
        "Binary (this FMU has no Binary variables)",
    )
}

/// fmi3SetBinary: no Binary variables.
pub unsafe fn set_binary<M: Model>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n_vr: usize,
    _sizes: *const usize,
    values: *const fmi3Binary,
    n_values: usize,
) -> fmi3Status {
    set_typed::<M, _>(
        c,
        "fmi3SetBinary",
        vr,
        n_vr,
        values,
        n_values,
        |_, _| None,
        "Binary (this FMU has no Binary variables)",
    )
}
