//! FMI 2.0 getters and setters: one value reference per scalar slot; Enumerations travel as
//! Integers numbered from 1.

use rins_fmi::ffi::{slice, slice_mut};
use rins_fmi::instance::{FmiError, Mode};
use rins_fmi::model::Model;
use rins_fmi::standard::FmiVersion;
use rins_fmi::vars::{Kind, Value};

use crate::*;

fn kind_of<M: Model>(comp: &Fmi2<M>, vr: u32) -> Result<Kind, FmiError> {
    let scalars = &comp.inst.table().scalars;
    scalars.get(vr as usize).map(|s| s.kind).ok_or_else(|| {
        FmiError::error(format!(
            "unknown value reference {vr} (valid: 0…{})",
            scalars.len() - 1
        ))
    })
}

/// A call of the wrong type: what the variable is, what the call takes (`wanted`, with its
/// article) and the call that reads or sets it.
fn type_error<M: Model>(comp: &Fmi2<M>, vr: u32, wanted: &str, set: bool) -> FmiError {
    let s = &comp.inst.table().scalars[vr as usize];
    FmiError::error(format!(
        "value reference {vr} ({}) is {} variable, not {wanted}: {} it with fmi2{}{}",
        s.name,
        s.kind.described(FmiVersion::V2),
        if set { "set" } else { "read" },
        if set { "Set" } else { "Get" },
        s.kind.accessor(FmiVersion::V2)
    ))
}

/// Shared body of the getters: `n` references, `n` values out.
fn get_values<M: Model, T: Copy>(
    c: fmi2Component,
    what: &str,
    vr: *const fmi2ValueReference,
    n: usize,
    out: *mut T,
    conv: impl Fn(&Fmi2<M>, u32, Value) -> Result<T, FmiError>,
) -> fmi2Status {
    with::<M>(c, what, |comp| {
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

/// Shared body of the setters: type-converted, then range- and mode-checked by the instance.
fn set_values<M: Model, T: Copy>(
    c: fmi2Component,
    what: &str,
    vr: *const fmi2ValueReference,
    n: usize,
    vals: *const T,
    conv: impl Fn(&Fmi2<M>, u32, T) -> Result<Value, FmiError>,
) -> fmi2Status {
    with::<M>(c, what, |comp| {
        // SAFETY: both arrays have `n` elements per the standard.
        let (vrs, vals) = unsafe { (slice(vr, n)?, slice(vals, n)?) };
        // All converted and checked before any is set (two passes, no allocation on the
        // per-step input path): a refused call changes nothing.
        let checked = vrs
            .iter()
            .zip(vals)
            .try_for_each(|(v, x)| comp.inst.check_vr(*v, conv(comp, *v, *x)?));
        if let Err(e) = checked {
            // Before the end of initialisation, exiting initialization mode will be refused
            // for it (a master that carries on would run with the start value).
            comp.inst.note_refused_set(format!("{what}: {}", e.message));
            return Err(e);
        }
        for (v, x) in vrs.iter().zip(vals) {
            let value = conv(comp, *v, *x)?;
            comp.inst.set(*v, value)?;
        }
        Ok(())
    })
}

/// fmi2GetReal.
pub unsafe fn get_real<M: Model>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    get_values::<M, _>(c, "fmi2GetReal", vr, n, value, |comp, r, v| match v {
        Value::Real(x) => Ok(x),
        _ => Err(type_error(comp, r, "a Real", false)),
    })
}

/// fmi2GetInteger (Integers and Enumerations).
pub unsafe fn get_integer<M: Model>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    get_values::<M, _>(c, "fmi2GetInteger", vr, n, value, |comp, r, v| match v {
        Value::Integer(u) => i32::try_from(u).map_err(|_| {
            FmiError::error(format!(
                "value reference {r} = {u} does not fit an fmi2Integer"
            ))
        }),
        Value::Enumeration(i) => Ok(i as i32 + 1),
        _ => Err(type_error(comp, r, "an Integer or Enumeration", false)),
    })
}

/// fmi2GetBoolean.
pub unsafe fn get_boolean<M: Model>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    get_values::<M, _>(c, "fmi2GetBoolean", vr, n, value, |comp, r, v| match v {
        Value::Boolean(b) => Ok(b as fmi2Boolean),
        _ => Err(type_error(comp, r, "a Boolean", false)),
    })
}

/// fmi2GetString: the models have no String variables; fine for zero references.
pub unsafe fn get_string<M: Model>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2String,
) -> fmi2Status {
    get_values::<M, _>(c, "fmi2GetString", vr, n, value, |comp, r, _| {
        Err(type_error(comp, r, "a String (this FMU has none)", false))
    })
}

/// fmi2SetReal.
pub unsafe fn set_real<M: Model>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    set_values::<M, _>(
        c,
        "fmi2SetReal",
        vr,
        n,
        value,
        |comp, r, x| match kind_of(comp, r)? {
            Kind::Real => Ok(Value::Real(x)),
            _ => Err(type_error(comp, r, "a Real", true)),
        },
    )
}

/// fmi2SetInteger (Integers ≥ 0 and Enumerations from 1).
pub unsafe fn set_integer<M: Model>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    set_values::<M, _>(c, "fmi2SetInteger", vr, n, value, |comp, r, x| {
        match kind_of(comp, r)? {
            Kind::Integer if x >= 0 => Ok(Value::Integer(x as u64)),
            Kind::Integer => Err(FmiError::error(format!(
                "{} = {x} must be ≥ 0",
                comp.inst.table().scalars[r as usize].name
            ))),
            Kind::Enumeration { .. } if x >= 1 => Ok(Value::Enumeration(x as usize - 1)),
            // Out of the items: the table check names the valid items.
            Kind::Enumeration { .. } => Ok(Value::Enumeration(usize::MAX)),
            _ => Err(type_error(comp, r, "an Integer or Enumeration", true)),
        }
    })
}

/// fmi2SetBoolean.
pub unsafe fn set_boolean<M: Model>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    set_values::<M, _>(
        c,
        "fmi2SetBoolean",
        vr,
        n,
        value,
        |comp, r, x| match kind_of(comp, r)? {
            Kind::Boolean => Ok(Value::Boolean(x != 0)),
            _ => Err(type_error(comp, r, "a Boolean", true)),
        },
    )
}

/// fmi2SetString: the models have no String variables; fine for zero references.
pub unsafe fn set_string<M: Model>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2String,
) -> fmi2Status {
    set_values::<M, _>(c, "fmi2SetString", vr, n, value, |comp, r, _| {
        Err(type_error(comp, r, "a String (this FMU has none)", true))
    })
}
