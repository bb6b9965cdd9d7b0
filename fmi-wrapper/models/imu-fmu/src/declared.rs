//! Declared effects (docs/effects.md, `[[sensor.gyro.custom]]`) as FMU parameters. FMI has no
//! strings a master can be relied on to set, so each sensor has [`SLOTS`] slots of numbers
//! (`sensor.gyro.slot[k].*`): kind, up to two factors (signal code, node or axis, second node
//! of a gradient, power) and the coefficient per axis. They map onto the plant's declared
//! effects through [`crate::slots`], so the plant compiles and simulates
//! a slot with the same code as the same block of a scenario file.

use crate::slots::{
    BLOCK_CODE, FACTORS, OP_CODE_MAX, SIGNAL_CODE_MAX, Slot, TAU_START_S, signal_codes,
};
use rins_fmi::vars::{Causality, Kind, ScalarVar, Value};
use rins_plant::PlantConfig;
use rins_plant::effects::CustomSpec;
use rins_plant::effects::custom::{MAX_TAU_S, MIN_TAU_S};

/// Slots per sensor.
pub const SLOTS: usize = 4;

/// A field of a slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Field {
    Enabled,
    Kind,
    Signal(usize),
    NodeOrAxis(usize),
    NodeB(usize),
    Power(usize),
    Op(usize),
    TauS(usize),
    Coef(usize),
}

/// One per-factor field: name, its [`Field`], start value, range, description.
type FactorField = (&'static str, fn(usize) -> Field, u64, (f64, f64), String);

/// Where a slot variable belongs: sensor (accelerometers when true), slot, field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SlotVar {
    pub accel: bool,
    pub slot: usize,
    pub field: Field,
}

fn prefix(accel: bool, k: usize) -> String {
    format!("sensor.{}.slot[{k}]", if accel { "accel" } else { "gyro" })
}

/// The variables of every slot, in table order (gyro slots, then accelerometer slots).
pub(crate) fn vars() -> Vec<(ScalarVar, SlotVar)> {
    let mut out = Vec::new();
    for accel in [false, true] {
        let coef_unit = if accel { "ug" } else { "deg/h" };
        for k in 0..SLOTS {
            let p = prefix(accel, k);
            let mut push =
                |field: Field, name: String, array: String, kind, start, range, d: String| {
                    out.push((
                        ScalarVar {
                            name,
                            array,
                            kind,
                            causality: Causality::Parameter,
                            unit: None,
                            start,
                            range,
                            description: d,
                        },
                        SlotVar {
                            accel,
                            slot: k,
                            field,
                        },
                    ))
                };
            let scalar = |f: &str| (format!("{p}.{f}"), format!("{p}.{f}"));
            let (n, a) = scalar("enabled");
            push(
                Field::Enabled,
                n,
                a,
                Kind::Boolean,
                Value::Boolean(false),
                None,
                "declared effect in this slot on (docs/fmu.md, \"Declared effects (slots)\")"
                    .into(),
            );
            let (n, a) = scalar("kind");
            push(
                Field::Kind,
                n,
                a,
                Kind::Integer,
                Value::Integer(1),
                Some((1.0, 2.0)),
                "1 bias, 2 scale-factor".into(),
            );
            let fields: [FactorField; 4] = [
                (
                    "signal",
                    Field::Signal,
                    0,
                    (0.0, SIGNAL_CODE_MAX as f64),
                    format!("signal of factor j: 0 none, {}", signal_codes()),
                ),
                (
                    "node_or_axis",
                    Field::NodeOrAxis,
                    0,
                    (0.0, BLOCK_CODE as f64),
                    "node of temp, dtemp_dt, grad (0 board, 1 gyro_x, 2 gyro_y, 3 gyro_z, 4 accel, 5 housing, 6 block) or axis of u, w, abs_w (0 x, 1 y, 2 z)".into(),
                ),
                (
                    "node_b",
                    Field::NodeB,
                    0,
                    (0.0, BLOCK_CODE as f64),
                    "second node B of grad (temp:A - temp:B), codes as node_or_axis".into(),
                ),
                (
                    "power",
                    Field::Power,
                    1,
                    (1.0, 8.0),
                    "integer power of factor j".into(),
                ),
            ];
            for (f, field, start, range, d) in fields {
                for j in 0..FACTORS {
                    push(
                        field(j),
                        format!("{p}.{f}[{j}]"),
                        format!("{p}.{f}"),
                        Kind::Integer,
                        Value::Integer(start),
                        Some(range),
                        d.clone(),
                    );
                }
            }
            // Appended after the fields above, so their value references do not move.
            for j in 0..FACTORS {
                push(
                    Field::Op(j),
                    format!("{p}.op[{j}]"),
                    format!("{p}.op"),
                    Kind::Integer,
                    Value::Integer(0),
                    Some((0.0, OP_CODE_MAX as f64)),
                    "operator on factor j: 0 none, 1 lag(signal, tau_s), 2 exp(-signal/tau_s) (signal a clock: time, since_move, since_start)".into(),
                );
            }
            for j in 0..FACTORS {
                push(
                    Field::TauS(j),
                    format!("{p}.tau_s[{j}]"),
                    format!("{p}.tau_s"),
                    Kind::Real,
                    Value::Real(TAU_START_S),
                    Some((MIN_TAU_S, MAX_TAU_S)),
                    "time constant of the operator on factor j, s (read only when op[j] is 1 or 2)"
                        .into(),
                );
            }
            for i in 0..3 {
                push(
                    Field::Coef(i),
                    format!("{p}.coef[{i}]"),
                    format!("{p}.coef"),
                    Kind::Real,
                    Value::Real(0.0),
                    Some((-1e9, 1e9)),
                    format!(
                        "coefficient on x, y, z: {coef_unit} (bias) or ppm (scale-factor) per unit of the regressor"
                    ),
                );
            }
        }
    }
    out
}

/// The slots the values describe: `[gyro, accel]`, each [`SLOTS`] long.
pub(crate) fn read<'a>(
    values: impl IntoIterator<Item = (&'a SlotVar, Value)>,
) -> [[Slot; SLOTS]; 2] {
    let mut slots = [[Slot::default(); SLOTS]; 2];
    for (v, value) in values {
        let s = &mut slots[v.accel as usize][v.slot];
        let int = |x: Value| if let Value::Integer(u) = x { u } else { 0 };
        match (v.field, value) {
            (Field::Enabled, Value::Boolean(b)) => s.enabled = b,
            (Field::Kind, x) => s.kind = int(x),
            (Field::Signal(j), x) => s.factors[j].signal = int(x),
            (Field::NodeOrAxis(j), x) => s.factors[j].node_or_axis = int(x),
            (Field::NodeB(j), x) => s.factors[j].node_b = int(x),
            (Field::Power(j), x) => s.factors[j].power = int(x),
            (Field::Op(j), x) => s.factors[j].op = int(x),
            (Field::TauS(j), Value::Real(x)) => s.factors[j].tau_s = x,
            (Field::Coef(i), Value::Real(x)) => s.coef[i] = x,
            _ => {}
        }
    }
    slots
}

/// Adds the enabled slots to `cfg` as declared effects named `fmu_gyro_slot_K` /
/// `fmu_accel_slot_K` (names are unique over both sensors), after the ones it
/// has; a bad code is an error naming the variable and the valid values.
pub(crate) fn apply(cfg: &mut PlantConfig, slots: &[[Slot; SLOTS]; 2]) -> Result<(), String> {
    for (accel, list) in [false, true].into_iter().zip(slots) {
        for (k, slot) in list.iter().enumerate().filter(|(_, s)| s.enabled) {
            let spec = slot
                .to_spec(&format!(
                    "fmu_{}_slot_{k}",
                    if accel { "accel" } else { "gyro" }
                ))
                .map_err(|e| format!("{}.{} {}", prefix(accel, k), e.field, e.message))?;
            let sensor = if accel {
                &mut cfg.sensor.accel.custom
            } else {
                &mut cfg.sensor.gyro.custom
            };
            sensor.push(spec);
        }
    }
    Ok(())
}

/// The FMU parameter values (`(name, value)`) that put a scenario's declared effects
/// `gyro` and `accel` into the slots, or why they do not fit (more than [`SLOTS`] per
/// sensor, or a regressor of more than two factors).
pub fn slot_values(
    gyro: &[CustomSpec],
    accel: &[CustomSpec],
) -> Result<Vec<(String, Value)>, String> {
    let mut out = Vec::new();
    for (is_accel, specs) in [(false, gyro), (true, accel)] {
        if specs.len() > SLOTS {
            return Err(format!(
                "{} declared {} effects; the FMU has {SLOTS} slots",
                specs.len(),
                if is_accel { "accelerometer" } else { "gyro" }
            ));
        }
        for (k, spec) in specs.iter().enumerate() {
            // Axes not listed carry a zero coefficient (checked when the scenario is read).
            let slot = Slot::from_spec(spec)?;
            let p = prefix(is_accel, k);
            out.push((format!("{p}.enabled"), Value::Boolean(slot.enabled)));
            out.push((format!("{p}.kind"), Value::Integer(slot.kind)));
            for (j, f) in slot.factors.iter().enumerate() {
                out.push((format!("{p}.signal[{j}]"), Value::Integer(f.signal)));
                out.push((
                    format!("{p}.node_or_axis[{j}]"),
                    Value::Integer(f.node_or_axis),
                ));
                out.push((format!("{p}.node_b[{j}]"), Value::Integer(f.node_b)));
                out.push((format!("{p}.power[{j}]"), Value::Integer(f.power.max(1))));
                out.push((format!("{p}.op[{j}]"), Value::Integer(f.op)));
                out.push((format!("{p}.tau_s[{j}]"), Value::Real(f.tau_s)));
            }
            for (i, c) in slot.coef.iter().enumerate() {
                out.push((format!("{p}.coef[{i}]"), Value::Real(*c)));
            }
        }
    }
    Ok(out)
}
