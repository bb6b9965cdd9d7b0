//! Declared effects as fixed-size slots of numbers, for interfaces without strings (FMU
//! parameters: FMI has no String parameters a master can be relied on to set). Only the FMU
//! uses them, so they live here; the plant knows declared effects by their scenario form
//! ([`CustomSpec`]) alone.
//!
//! A slot holds one declared effect whose regressor has at most [`FACTORS`] factors: per
//! factor an Integer signal code (the rows of the signals table [`FAMILIES`], numbered from 1;
//! 0 = no factor; the codes follow the table, so a new signal has its code with no change
//! here), the node or axis it reads, the second node of a gradient and the power. A slot
//! converts to and from the [`CustomSpec`] of a scenario file ([`Slot::to_spec`],
//! [`Slot::from_spec`]): the plant compiles and evaluates it with the same code as a declared
//! effect read from a file, so a slot and the same `[[sensor.gyro.custom]]` block simulate the
//! same numbers.

use rins_plant::effects::Axes3;
use rins_plant::effects::custom::signals::{ArgKind, Args, FAMILIES, NodeRef};
use rins_plant::effects::custom::{
    Axis, CustomKind, CustomSpec, MAX_POWER, MAX_TAU_S, MIN_TAU_S, Op, parse_regressor, unit_of,
};
use rins_plant::thermal::node;

/// Factors per slot.
pub const FACTORS: usize = 2;
/// Highest signal code (the rows of the signals table [`FAMILIES`]).
pub const SIGNAL_CODE_MAX: u64 = FAMILIES.len() as u64;
/// The node code of `block` (the acting axis's own block); 0…5 are the nodes of [`node`].
pub const BLOCK_CODE: u64 = node::COUNT as u64;

/// Operator codes of a factor: 0 none, 1 `lag(SIGNAL, TAU)`, 2 `exp(-CLOCK/TAU)`.
pub const OP_CODE_MAX: u64 = 2;
/// The start value of a factor's time constant (read only with an operator).
pub const TAU_START_S: f64 = 60.0;

/// One factor of a slot, as numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlotFactor {
    /// Signal: 0 none, else the row of [`FAMILIES`] + 1 (1 temp, 2 dtemp_dt, 3 grad, 4 u,
    /// 5 w, 6 abs_w, 7 gimbal_outer, 8 gimbal_inner, 9 time, 10 n, 11 e: [`signal_codes`]).
    pub signal: u64,
    /// Node (0 board, 1 gyro_x, 2 gyro_y, 3 gyro_z, 4 accel, 5 housing, 6 block) for temp,
    /// dtemp_dt and the first node of grad; axis (0 x, 1 y, 2 z) for u, w, abs_w, n and e.
    pub node_or_axis: u64,
    /// Second node of grad (A − B), as `node_or_axis`.
    pub node_b: u64,
    /// Power, 1 … 8.
    pub power: u64,
    /// Operator: 0 none, 1 first-order lag, 2 decay exp(−signal/τ) (docs/effects.md).
    pub op: u64,
    /// The operator's time constant, s.
    pub tau_s: f64,
}

impl Default for SlotFactor {
    fn default() -> Self {
        SlotFactor {
            signal: 0,
            node_or_axis: 0,
            node_b: 0,
            power: 1,
            op: 0,
            tau_s: TAU_START_S,
        }
    }
}

/// One declared effect as numbers.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Slot {
    /// In use.
    pub enabled: bool,
    /// 1 bias, 2 scale factor.
    pub kind: u64,
    /// The regressor's factors (signal 0: unused).
    pub factors: [SlotFactor; FACTORS],
    /// Coefficient per axis in the unit of the file: °/h (gyro bias), µg (accelerometer bias)
    /// or ppm (scale factor) per unit of the regressor.
    pub coef: Axes3,
}

/// A field of a slot that holds a bad value: which field (`kind`, `signal[1]`, …) and why,
/// with the valid values.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SlotError {
    /// Field, relative to the slot: `kind`, `signal[j]`, `node_or_axis[j]`, `node_b[j]`,
    /// `power[j]`.
    pub field: String,
    /// The value and the valid range.
    pub message: String,
}

fn node_name(code: u64) -> Option<&'static str> {
    match code {
        c if c < BLOCK_CODE => Some(node::NAMES[c as usize]),
        BLOCK_CODE => Some("block"),
        _ => None,
    }
}

fn node_code(n: NodeRef) -> u64 {
    match n {
        NodeRef::Node(i) => i as u64,
        NodeRef::Block => BLOCK_CODE,
    }
}

const NODES: &str = "0 board, 1 gyro_x, 2 gyro_y, 3 gyro_z, 4 accel, 5 housing, 6 block";
const AXES: &str = "0 x, 1 y, 2 z";

impl Slot {
    /// The regressor text of the slot's factors (`dtemp_dt:block`, `u_x*u_z^2`), or the
    /// first bad field.
    pub fn regressor(&self) -> Result<String, SlotError> {
        let mut parts = Vec::new();
        for (j, f) in self.factors.iter().enumerate() {
            let bad = |field: &str, message: String| SlotError {
                field: format!("{field}[{j}]"),
                message,
            };
            if f.signal == 0 {
                continue;
            }
            let node = |code: u64, field: &str| {
                node_name(code).ok_or_else(|| {
                    bad(
                        field,
                        format!("= {code} is not a node (valid: 0…{BLOCK_CODE}: {NODES})"),
                    )
                })
            };
            let axis = |code: u64| {
                ["x", "y", "z"].get(code as usize).copied().ok_or_else(|| {
                    bad(
                        "node_or_axis",
                        format!("= {code} is not an axis (valid: 0…2: {AXES})"),
                    )
                })
            };
            let Some(family) = (f.signal as usize)
                .checked_sub(1)
                .filter(|i| *i < FAMILIES.len())
            else {
                return Err(bad(
                    "signal",
                    format!(
                        "= {} is not a signal code (valid: 0…{SIGNAL_CODE_MAX}: {})",
                        f.signal,
                        signal_codes()
                    ),
                ));
            };
            let p = FAMILIES[family].prefix;
            let name = match FAMILIES[family].arg {
                ArgKind::None => p.to_string(),
                ArgKind::Node => format!("{p}{}", node(f.node_or_axis, "node_or_axis")?),
                ArgKind::NodePair => format!(
                    "{p}{}-{}",
                    node(f.node_or_axis, "node_or_axis")?,
                    node(f.node_b, "node_b")?
                ),
                ArgKind::Axis => format!("{p}{}", axis(f.node_or_axis)?),
            };
            if !(1..=MAX_POWER as u64).contains(&f.power) {
                return Err(bad(
                    "power",
                    format!("= {} is not a power (valid: 1…{})", f.power, MAX_POWER),
                ));
            }
            if f.op != 0 && !(MIN_TAU_S..=MAX_TAU_S).contains(&f.tau_s) {
                return Err(bad(
                    "tau_s",
                    format!(
                        "= {} s is not a time constant (valid: {MIN_TAU_S:e}…{MAX_TAU_S:e} s)",
                        f.tau_s
                    ),
                ));
            }
            // The time constant in Rust's shortest round-trip form: parsed back to its bits.
            let name = match f.op {
                0 => name,
                1 => format!("lag({name},{})", f.tau_s),
                2 => format!("exp(-{name}/{})", f.tau_s),
                code => {
                    return Err(bad(
                        "op",
                        format!(
                            "= {code} is not an operator (valid: 0…{OP_CODE_MAX}: 0 none, 1 lag, 2 exp decay)"
                        ),
                    ));
                }
            };
            parts.push(if f.power == 1 {
                name
            } else {
                format!("{name}^{}", f.power)
            });
        }
        if parts.is_empty() {
            return Err(SlotError {
                field: "signal[0]".into(),
                message: format!(
                    "= 0: an enabled slot needs at least one signal (valid: 1…{SIGNAL_CODE_MAX}: {})",
                    signal_codes()
                ),
            });
        }
        Ok(parts.join("*"))
    }

    /// The declared effect the slot describes, named `name`, on every axis (a coefficient of
    /// 0 leaves an axis untouched).
    pub fn to_spec(&self, name: &str) -> Result<CustomSpec, SlotError> {
        let kind = match self.kind {
            1 => CustomKind::Bias,
            2 => CustomKind::ScaleFactor,
            k => {
                return Err(SlotError {
                    field: "kind".into(),
                    message: format!("= {k} is not a kind (valid: 1 bias, 2 scale-factor)"),
                });
            }
        };
        let regressor = self.regressor()?;
        let factors = parse_regressor(&regressor).map_err(|e| SlotError {
            field: if e.contains("exp(") {
                // A decay of a signal that is not a clock: the operator's field.
                (0..FACTORS)
                    .find(|&j| self.factors[j].op == 2)
                    .map_or("signal[0]".into(), |j| format!("signal[{j}]"))
            } else {
                "signal[0]".into()
            },
            message: e,
        })?;
        Ok(CustomSpec {
            name: name.into(),
            enabled: self.enabled,
            kind,
            unit: unit_of(&factors).to_string(),
            regressor,
            axes: vec![Axis::X, Axis::Y, Axis::Z],
            coef: self.coef,
        })
    }

    /// The slot of a declared effect, or why it does not fit one (more than [`FACTORS`]
    /// factors, or a regressor that does not parse).
    pub fn from_spec(spec: &CustomSpec) -> Result<Slot, String> {
        let factors =
            parse_regressor(&spec.regressor).map_err(|e| format!("{}: {e}", spec.name))?;
        if factors.len() > FACTORS {
            return Err(format!(
                "{}: {} factors in {:?}; an FMU slot holds at most {FACTORS}",
                spec.name,
                factors.len(),
                spec.regressor
            ));
        }
        let mut slot = Slot {
            enabled: spec.enabled,
            kind: match spec.kind {
                CustomKind::Bias => 1,
                CustomKind::ScaleFactor => 2,
            },
            coef: spec.coef,
            ..Slot::default()
        };
        for (f, out) in factors.iter().zip(slot.factors.iter_mut()) {
            let (family, args) = f.signal.parts();
            let (a, b) = match args {
                Args::None => (0, 0),
                Args::Node(n) => (node_code(n), 0),
                Args::NodePair(x, y) => (node_code(x), node_code(y)),
                Args::Axis(i) => (i as u64, 0),
            };
            let signal = family as u64 + 1;
            let (op, tau_s) = match f.op {
                Op::Plain => (0, TAU_START_S),
                Op::Lag { tau_s } => (1, tau_s),
                Op::Decay { tau_s } => (2, tau_s),
            };
            *out = SlotFactor {
                signal,
                node_or_axis: a,
                node_b: b,
                power: f.power as u64,
                op,
                tau_s,
            };
        }
        Ok(slot)
    }
}

/// `1 temp:NODE, 2 dtemp_dt:NODE, …`: the signal codes, for messages and docs.
pub fn signal_codes() -> String {
    FAMILIES
        .iter()
        .enumerate()
        .map(|(i, f)| format!("{} {}", i + 1, f.doc_name))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use rins_plant::effects::custom::CustomModel;
    use rins_plant::effects::custom::signals::Signal;

    fn spec(regressor: &str, kind: CustomKind) -> CustomSpec {
        CustomSpec {
            name: "t".into(),
            enabled: true,
            kind,
            regressor: regressor.into(),
            unit: unit_of(&parse_regressor(regressor).unwrap()).to_string(),
            axes: vec![Axis::X, Axis::Y, Axis::Z],
            coef: [1.5, -2.0, 0.25],
        }
    }

    #[test]
    fn every_signal_round_trips_through_a_slot_and_compiles_the_same() {
        for (r, kind) in [
            ("dtemp_dt:block", CustomKind::Bias),
            ("u_x*u_z", CustomKind::Bias),
            ("temp:housing^2*w_y", CustomKind::ScaleFactor),
            ("grad:gyro_z-housing*abs_w_x^3", CustomKind::Bias),
            ("gimbal_outer*gimbal_inner", CustomKind::Bias),
            ("time", CustomKind::ScaleFactor),
            ("lag(temp:block,900)", CustomKind::Bias),
            (
                "exp(-since_move/37.5)*lag(grad:gyro_x-housing,0.125)^2",
                CustomKind::Bias,
            ),
            ("exp(-since_start/10000)", CustomKind::ScaleFactor),
        ] {
            let s = spec(r, kind);
            let slot = Slot::from_spec(&s).unwrap();
            let back = slot.to_spec("t").unwrap();
            assert_eq!(back, s, "{r}");
            assert_eq!(
                CustomModel::new(&[back], false).unwrap(),
                CustomModel::new(&[s], false).unwrap()
            );
        }
        assert!(
            Slot::from_spec(&spec("u_x*u_y*u_z", CustomKind::Bias))
                .unwrap_err()
                .contains("at most 2")
        );
    }

    /// Every signal of the signals table has a slot code (its row + 1) and comes back from a
    /// slot as itself: a signal added to the table needs no change here.
    #[test]
    fn every_signal_of_the_table_has_a_slot_code() {
        for family in 0..FAMILIES.len() {
            for sig in Signal::all_of(family) {
                let s = spec(&sig.name(), CustomKind::Bias);
                let slot = Slot::from_spec(&s).unwrap();
                assert_eq!(slot.factors[0].signal, family as u64 + 1, "{}", sig.name());
                assert_eq!(slot.to_spec("t").unwrap(), s, "{}", sig.name());
            }
        }
        // The codes are an interface: a new signal is appended, the existing ones keep theirs.
        assert!(signal_codes().starts_with(
            "1 temp:NODE, 2 dtemp_dt:NODE, 3 grad:A-B, 4 u_x, u_y, u_z, 5 w_x, w_y, w_z, \
             6 abs_w_x, abs_w_y, abs_w_z, 7 gimbal_outer, 8 gimbal_inner, 9 time, \
             10 n_x, n_y, n_z, 11 e_x, e_y, e_z, 12 since_move, 13 since_start"
        ));
    }

    #[test]
    fn bad_codes_name_the_field_and_the_valid_range() {
        let mut slot = Slot::from_spec(&spec("u_x*temp:block", CustomKind::Bias)).unwrap();
        slot.factors[0].node_or_axis = 3;
        let e = slot.to_spec("t").unwrap_err();
        assert_eq!(e.field, "node_or_axis[0]");
        assert!(e.message.contains("0…2"), "{}", e.message);
        slot.factors[0].node_or_axis = 0;
        slot.factors[1].signal = SIGNAL_CODE_MAX + 1;
        let e = slot.to_spec("t").unwrap_err();
        assert_eq!(e.field, "signal[1]");
        assert!(
            e.message.contains(&format!("0…{SIGNAL_CODE_MAX}")),
            "{}",
            e.message
        );
        slot.factors[1] = SlotFactor {
            signal: 3,
            node_or_axis: 6,
            node_b: 7,
            ..SlotFactor::default()
        };
        assert_eq!(slot.to_spec("t").unwrap_err().field, "node_b[1]");
        slot.factors[1].node_b = 5;
        slot.factors[1].power = 9;
        assert_eq!(slot.to_spec("t").unwrap_err().field, "power[1]");
        slot.factors[1].power = 1;
        slot.factors[1].op = 3;
        assert_eq!(slot.to_spec("t").unwrap_err().field, "op[1]");
        slot.factors[1].op = 1;
        slot.factors[1].tau_s = 0.0;
        assert_eq!(slot.to_spec("t").unwrap_err().field, "tau_s[1]");
        slot.factors[1].tau_s = 30.0;
        slot.factors[1].op = 2;
        // A decay of a gradient, which is no clock.
        let e = slot.to_spec("t").unwrap_err();
        assert_eq!(e.field, "signal[1]");
        assert!(e.message.contains("clock"), "{}", e.message);
        slot.factors[1].op = 0;
        slot.kind = 3;
        assert_eq!(slot.to_spec("t").unwrap_err().field, "kind");
        slot.kind = 1;
        slot.factors = [SlotFactor::default(); FACTORS];
        assert_eq!(slot.to_spec("t").unwrap_err().field, "signal[0]");
    }
}
