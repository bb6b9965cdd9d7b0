//! Declared effects compiled once into a flat evaluation plan.

// Three axes indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use nalgebra::Vector3;

use super::expr::{Factor, Op, bound_of, parse_regressor, unit_of};
use super::memory::{MemoryState, MemoryTerm};
use super::plan::{FactorRef, Plan, PlanBuilder};
use super::signals::{Frame, SLOTS, Signal, Unit};
use super::{CustomKind, CustomSpec};
use crate::config::ConfigError;
use crate::units::{DPH, PPM, UG};

/// One factor resolved for one axis: `(frame[a] − frame[b])^power` when `diff`, else
/// `frame[a]^power`; with memory, memory term `mem` (of that input) to the power.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Slot {
    a: u8,
    b: u8,
    diff: bool,
    power: i32,
    mem: Option<u16>,
}

/// A declared effect after checking.
#[derive(Clone, Debug, PartialEq)]
pub struct CompiledEffect {
    /// Name.
    pub name: String,
    /// Term on.
    pub enabled: bool,
    /// Bias or scale factor.
    pub kind: CustomKind,
    /// The regressor as written.
    pub regressor: String,
    /// Its unit.
    pub unit: Unit,
    /// Whether it acts on x, y, z.
    pub axes: [bool; 3],
    /// Coefficients in SI (rad/s, m/s², or fraction per unit of the regressor).
    pub coef_si: [f64; 3],
    /// SI size of one file unit of the coefficient (°/h, µg or ppm).
    pub file_unit_si: f64,
    /// The parsed factors.
    pub factors: Vec<Factor>,
    /// Resolved factors per axis.
    slots: [Vec<Slot>; 3],
}

impl CompiledEffect {
    /// The signals the regressor reads.
    pub fn signals(&self) -> impl Iterator<Item = Signal> + '_ {
        self.factors.iter().map(|f| f.signal)
    }
}

/// The declared effects of one sensor (gyros or accelerometers), compiled.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct CustomModel {
    accel: bool,
    effects: Vec<CompiledEffect>,
    plan: Plan,
    /// A switched-on effect changes within a dwell (it reads `time`, a motion clock, or has
    /// memory).
    varies_in_dwell: bool,
    /// The distinct memory values of every effect (switched on or not: the diagnosis reads
    /// the regressors of all), per resolved input.
    memory: Vec<MemoryTerm>,
}

/// Scenario key of the coefficient of declared effect `index` on `axis`.
pub fn custom_coefficient_key(accel: bool, index: usize, axis: usize) -> String {
    let s = if accel { "accel" } else { "gyro" };
    format!("sensor.{s}.custom[{index}].coef[{axis}]")
}

/// The factors resolved for `axis`, each memory operator added to `memory` once.
fn resolve(
    factors: &[Factor],
    accel: bool,
    axis: usize,
    memory: &mut Vec<MemoryTerm>,
) -> Vec<Slot> {
    factors
        .iter()
        .map(|f| {
            let (a, b) = f.signal.slots(accel, axis);
            let mem = (f.op != Op::Plain).then(|| {
                let t = MemoryTerm {
                    a: a as u8,
                    b: b.map(|b| b as u8),
                    op: f.op,
                };
                let k = memory.iter().position(|m| *m == t).unwrap_or_else(|| {
                    memory.push(t);
                    memory.len() - 1
                });
                k as u16
            });
            let (b, diff) = (b.unwrap_or(0), b.is_some());
            Slot {
                a: a as u8,
                b: b as u8,
                diff,
                power: f.power,
                mem,
            }
        })
        .collect()
}

#[inline]
fn product(slots: &[Slot], frame: &Frame, mem: &[f64]) -> f64 {
    let mut r = 1.0;
    for s in slots {
        let v = match s.mem {
            Some(k) => mem[k as usize],
            None if s.diff => frame[s.a as usize] - frame[s.b as usize],
            None => frame[s.a as usize],
        };
        r *= if s.power == 1 { v } else { v.powi(s.power) };
    }
    r
}

impl CustomModel {
    /// Checks and compiles `specs` (the list under `sensor.gyro.custom`, or
    /// `sensor.accel.custom` when `accel`). Every problem is a [`ConfigError`] naming the key.
    pub fn new(specs: &[CustomSpec], accel: bool) -> Result<Self, Vec<ConfigError>> {
        let sensor = if accel { "accel" } else { "gyro" };
        let mut errors = Vec::new();
        let mut m = CustomModel {
            accel,
            ..Self::default()
        };
        for (k, s) in specs.iter().enumerate() {
            let at = |key: &str| format!("sensor.{sensor}.custom[{k}].{key}");
            let mut fail = |key: &str, expected: &str, got: String| {
                errors.push(ConfigError {
                    path: at(key),
                    expected: expected.into(),
                    got,
                })
            };
            let name_ok = !s.name.is_empty()
                && s.name.len() <= 32
                && s.name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_');
            if !name_ok {
                fail(
                    "name",
                    "a name of 1–32 letters, digits or _",
                    format!("{:?}", s.name),
                );
            } else if specs[..k].iter().any(|o| o.name == s.name) {
                fail(
                    "name",
                    "a name not used by another declared effect of this sensor",
                    format!("{:?} again", s.name),
                );
            }
            let factors = match parse_regressor(&s.regressor) {
                Ok(f) => f,
                Err(e) => {
                    fail("regressor", "a product of documented signals", e);
                    continue;
                }
            };
            let unit = unit_of(&factors);
            match Unit::parse(&s.unit) {
                Some(u) if u == unit => {}
                Some(u) => fail(
                    "unit",
                    &format!("{unit} (the unit of {:?})", s.regressor),
                    format!("{:?} = {u}", s.unit),
                ),
                None => fail(
                    "unit",
                    &format!(
                        "{unit} (the unit of {:?}; write K or degC, s, deg, ^N, * and one /)",
                        s.regressor
                    ),
                    format!("{:?}", s.unit),
                ),
            }
            let mut axes = [false; 3];
            for a in &s.axes {
                if axes[a.index()] {
                    fail("axes", "each axis once", format!("{a:?} twice"));
                }
                axes[a.index()] = true;
            }
            if s.axes.is_empty() {
                fail("axes", "at least one of \"x\", \"y\", \"z\"", "[]".into());
            }
            let file_unit_si = match (s.kind, accel) {
                (CustomKind::Bias, false) => DPH,
                (CustomKind::Bias, true) => UG,
                (CustomKind::ScaleFactor, _) => PPM,
            };
            // A scale-factor term multiplies the true increment; bound it by a full-rate second.
            let input_bound = match (s.kind, accel) {
                (CustomKind::Bias, _) => 1.0,
                (CustomKind::ScaleFactor, false) => 100f64.to_radians(),
                (CustomKind::ScaleFactor, true) => 100.0,
            };
            let bound = bound_of(&factors);
            if !bound.is_finite() {
                fail(
                    "regressor",
                    "a product that stays finite over the signals' ranges (docs/effects.md)",
                    format!("{:?} reaches {}", s.regressor, crate::message::Num(bound)),
                );
            }
            for i in 0..3 {
                let c = s.coef[i];
                if !axes[i] && c != 0.0 {
                    fail(
                        &format!("coef[{i}]"),
                        "0 on an axis not listed in axes",
                        crate::message::num(c),
                    );
                } else if bound.is_finite() && !(c * file_unit_si * bound * input_bound).is_finite()
                {
                    fail(
                        &format!("coef[{i}]"),
                        &format!(
                            "a coefficient whose contribution stays finite over the signals' ranges (|{}| ≤ {bound:e})",
                            s.regressor
                        ),
                        crate::message::num(c),
                    );
                }
            }
            let slots = [0, 1, 2].map(|i| resolve(&factors, accel, i, &mut m.memory));
            m.varies_in_dwell |= s.enabled
                && factors.iter().any(|f| {
                    f.signal == Signal::Time || f.signal.family().reads_motion || f.op != Op::Plain
                });
            m.effects.push(CompiledEffect {
                name: s.name.clone(),
                enabled: s.enabled,
                kind: s.kind,
                regressor: s.regressor.clone(),
                unit,
                axes,
                coef_si: s.coef.map(|c| c * file_unit_si),
                file_unit_si,
                factors,
                slots,
            });
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        let mut plan = PlanBuilder::default();
        for e in m.effects.iter().filter(|e| e.enabled) {
            let live: Vec<usize> = (0..3)
                .filter(|&i| e.axes[i] && e.coef_si[i] != 0.0)
                .collect();
            let shared = live.iter().all(|&i| e.slots[i] == e.slots[live[0]]);
            // One term for all axes when the regressor does not depend on the axis.
            let groups: Vec<Vec<usize>> = if shared && !live.is_empty() {
                vec![live]
            } else {
                live.into_iter().map(|i| vec![i]).collect()
            };
            for axes in groups {
                let factors: Vec<FactorRef> = e.slots[axes[0]]
                    .iter()
                    .map(|s| FactorRef {
                        a: s.a as usize,
                        b: s.diff.then_some(s.b as usize),
                        power: s.power,
                        mem: s.mem.map(|k| k as usize),
                    })
                    .collect();
                let mut coef_si = [0.0; 3];
                for i in axes {
                    coef_si[i] = e.coef_si[i];
                }
                plan.term(&factors, coef_si, e.kind == CustomKind::ScaleFactor);
            }
        }
        m.plan = plan.finish(m.memory.len());
        Ok(m)
    }

    /// The declared effects, in file order.
    pub fn effects(&self) -> &[CompiledEffect] {
        &self.effects
    }

    /// Whether the plan has anything to evaluate.
    pub fn is_active(&self) -> bool {
        !self.plan.is_empty()
    }

    /// Whether a switched-on effect changes within a dwell: it reads `time` or a motion clock
    /// (`since_move`, `since_start`), or has memory (`lag`, `exp`). The plant then redoes the
    /// declared part of each tick of a dwell rather than reusing the dwell's interval whole.
    pub fn varies_in_dwell(&self) -> bool {
        self.varies_in_dwell
    }

    /// A memory state for these effects, before their first interval.
    pub fn memory_state(&self) -> MemoryState {
        MemoryState::new(self.memory.len())
    }

    /// Whether an effect (switched on or not) has a factor with memory.
    pub fn has_memory(&self) -> bool {
        !self.memory.is_empty()
    }

    /// Advances `mem` over an interval of `dt_s` with the signals `frame`: call once per
    /// interval, before the regressors of that interval are read.
    #[inline]
    pub fn advance_memory(&self, mem: &mut MemoryState, frame: &Frame, dt_s: f64) {
        if !self.memory.is_empty() {
            mem.advance(&self.memory, frame, dt_s);
        }
    }

    /// Whether these are accelerometer effects.
    pub fn is_accel(&self) -> bool {
        self.accel
    }

    /// Sum of the switched-on effects' increment errors over an interval of `dt_s` with the
    /// signals `frame` and the true increment `input` (rad or m/s): rad or m/s. Advances `mem`
    /// over the interval first ([`CustomModel::advance_memory`]): call once per interval.
    #[inline]
    pub fn increment_error(
        &self,
        frame: &Frame,
        mem: &mut MemoryState,
        dt_s: f64,
        input: &Vector3<f64>,
    ) -> Vector3<f64> {
        /// Values that fit on the stack (larger plans take a vector per call).
        const STACK: usize = 96;
        self.advance_memory(mem, frame, dt_s);
        let n = self.plan.values_len();
        if n <= STACK {
            let mut values = [0.0; STACK];
            values[..SLOTS].copy_from_slice(frame);
            self.plan.evaluate(&mut values, mem.values(), dt_s, input)
        } else {
            let mut values = vec![0.0; n];
            values[..SLOTS].copy_from_slice(frame);
            self.plan.evaluate(&mut values, mem.values(), dt_s, input)
        }
    }

    /// Rows of the plan (terms after splitting per-axis regressors).
    #[cfg(test)]
    pub(super) fn plan_rows(&self) -> usize {
        self.plan.len()
    }

    /// Length of the value array [`CustomModel::evaluate`] needs.
    pub(super) fn values_len(&self) -> usize {
        self.plan.values_len()
    }

    /// As [`CustomModel::increment_error`], with the frame in the first [`SLOTS`] entries of
    /// `values` (at least [`CustomModel::values_len`] long; the entries after the frame are
    /// overwritten): no copy, no allocation.
    #[inline]
    pub(super) fn evaluate(
        &self,
        values: &mut [f64],
        mem: &mut MemoryState,
        dt_s: f64,
        input: &Vector3<f64>,
    ) -> Vector3<f64> {
        if !self.memory.is_empty() {
            let frame: &Frame = (&values[..SLOTS])
                .try_into()
                .expect("the frame comes first");
            mem.advance(&self.memory, frame, dt_s);
        }
        self.plan.evaluate(values, mem.values(), dt_s, input)
    }

    /// Regressor φ of effect `index` on `axis` in increment units (the effect's error there is
    /// `coef_si[axis]·φ`), whether or not it is switched on; `mem` as advanced over this
    /// interval ([`CustomModel::advance_memory`]).
    #[inline]
    pub fn regressor(
        &self,
        index: usize,
        axis: usize,
        frame: &Frame,
        mem: &MemoryState,
        dt_s: f64,
        input: &Vector3<f64>,
    ) -> f64 {
        let e = &self.effects[index];
        let r = product(&e.slots[axis], frame, mem.values());
        match e.kind {
            CustomKind::Bias => r * dt_s,
            CustomKind::ScaleFactor => r * input[axis],
        }
    }
}
