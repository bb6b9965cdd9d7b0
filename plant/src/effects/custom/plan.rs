//! The flat evaluation plan of one sensor's declared effects.
//!
//! Every regressor is compiled once into one entry of a value array: the first
//! [`SLOTS`] entries are the signal frame (filled once per interval, whatever the number of
//! terms), then the gradients (`temp:A − temp:B`), then the values of the factors with memory
//! (`lag`, `exp`, advanced by the caller's [`super::MemoryState`]), then the products and powers, each
//! computed once per interval and shared by every term that reads it (`u_x*u_z` in ten
//! effects is one multiplication). A term is then one row (coefficients, value index, kind):
//! no branch on signal names, no allocation, `time` a frame entry like any other.
//!
//! The arithmetic is the one of the per-effect product ([`super::model`]'s `product`, used by
//! the diagnosis) operation for operation: factors multiplied left to right, a power by
//! repeated squaring in the order of `f64::powi`, rows summed in plan order. The plan's
//! results are therefore the same bits.

use nalgebra::Vector3;
use std::collections::HashMap;

use super::signals::SLOTS;

/// An entry of the value array while the plan is built: frame slot, gradient or product
/// (gradients and products are renumbered once all are known: gradients first).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
enum Val {
    Frame(u32),
    Diff(u32),
    Mem(u32),
    Mul(u32),
}

/// One term: `out_i += (coef_si[i] · value) · m_i`, with m the interval length (bias) or
/// the true increment of axis i (scale factor).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Row {
    coef_si: [f64; 3],
    value: u32,
    /// 0 bias, 1 scale factor: the row of the multiplier table.
    scale: u32,
}

/// The compiled plan.
#[derive(Clone, Debug, PartialEq, Default)]
pub(super) struct Plan {
    /// `values[SLOTS + k] = values[a] − values[b]`.
    diffs: Vec<[u32; 2]>,
    /// Memory values copied to `values[SLOTS + diffs.len() + k]`.
    mems: u32,
    /// `values[SLOTS + diffs.len() + mems + k] = values[a] · values[b]`, in dependency order.
    muls: Vec<[u32; 2]>,
    rows: Vec<Row>,
}

/// Builds a [`Plan`], sharing every gradient and product.
#[derive(Default)]
pub(super) struct PlanBuilder {
    diffs: Vec<[Val; 2]>,
    muls: Vec<[Val; 2]>,
    rows: Vec<(Val, [f64; 3], bool)>,
    memo: HashMap<(bool, Val, Val), Val>,
}

/// One factor of a regressor as the builder reads it: `(frame[a] − frame[b])^power` when
/// `b` is given, else `frame[a]^power`.
#[derive(Clone, Copy, Debug)]
pub(super) struct FactorRef {
    /// Frame slot.
    pub a: usize,
    /// Frame slot subtracted (a gradient).
    pub b: Option<usize>,
    /// Power, ≥ 1.
    pub power: i32,
    /// The memory value of this input (a lag or decay), when the factor has one: the value
    /// read instead of the frame.
    pub mem: Option<usize>,
}

impl PlanBuilder {
    fn diff(&mut self, a: usize, b: usize) -> Val {
        let (a, b) = (Val::Frame(a as u32), Val::Frame(b as u32));
        let n = self.diffs.len() as u32;
        *self.memo.entry((false, a, b)).or_insert_with(|| {
            self.diffs.push([a, b]);
            Val::Diff(n)
        })
    }

    fn mul(&mut self, a: Val, b: Val) -> Val {
        // x·y and y·x are the same bits: one entry for both orders.
        let key = if a <= b { (true, a, b) } else { (true, b, a) };
        let n = self.muls.len() as u32;
        *self.memo.entry(key).or_insert_with(|| {
            self.muls.push([a, b]);
            Val::Mul(n)
        })
    }

    /// `v^p` by repeated squaring, the order of `f64::powi` (`r = 1; if bit: r *= a;
    /// a *= a`), without the leading `1 ·` (exact).
    fn power(&mut self, v: Val, p: i32) -> Val {
        let (mut a, mut p, mut r) = (v, p, None);
        loop {
            if p & 1 == 1 {
                r = Some(match r {
                    None => a,
                    Some(r) => self.mul(r, a),
                });
            }
            p >>= 1;
            if p == 0 {
                break;
            }
            a = self.mul(a, a);
        }
        r.expect("a power of at least 1")
    }

    /// Adds a term: `coef_si · Π factors`, times Δt (bias) or the axis's true increment
    /// (`scale`).
    pub(super) fn term(&mut self, factors: &[FactorRef], coef_si: [f64; 3], scale: bool) {
        let mut r = None;
        for f in factors {
            let v = match (f.mem, f.b) {
                (Some(k), _) => Val::Mem(k as u32),
                (None, Some(b)) => self.diff(f.a, b),
                (None, None) => Val::Frame(f.a as u32),
            };
            let v = if f.power == 1 {
                v
            } else {
                self.power(v, f.power)
            };
            // The product starts at 1: the first factor is taken as is (1 · v = v).
            r = Some(match r {
                None => v,
                Some(r) => self.mul(r, v),
            });
        }
        self.rows.push((
            r.expect("a regressor of at least one factor"),
            coef_si,
            scale,
        ));
    }

    /// The plan over `mems` memory values, with gradients numbered before them and them
    /// before products.
    pub(super) fn finish(self, mems: usize) -> Plan {
        let nd = self.diffs.len() as u32;
        let nm = mems as u32;
        let index = |v: Val| match v {
            Val::Frame(i) => i,
            Val::Diff(k) => SLOTS as u32 + k,
            Val::Mem(k) => SLOTS as u32 + nd + k,
            Val::Mul(k) => SLOTS as u32 + nd + nm + k,
        };
        Plan {
            mems: nm,
            diffs: self.diffs.iter().map(|d| d.map(index)).collect(),
            muls: self.muls.iter().map(|m| m.map(index)).collect(),
            rows: self
                .rows
                .iter()
                .map(|&(v, coef_si, scale)| Row {
                    coef_si,
                    value: index(v),
                    scale: scale as u32,
                })
                .collect(),
        }
    }
}

impl Plan {
    /// Length of the value array the plan reads and writes (the frame first).
    pub(super) fn values_len(&self) -> usize {
        SLOTS + self.diffs.len() + self.mems as usize + self.muls.len()
    }

    /// Whether the plan has a term.
    pub(super) fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Number of terms (rows).
    #[cfg(test)]
    pub(super) fn len(&self) -> usize {
        self.rows.len()
    }

    /// Sum of the terms over an interval of `dt_s` with the true increment `input`;
    /// `values` holds the frame in its first [`SLOTS`] entries and is at least
    /// [`Plan::values_len`] long (the gradients, memory values and products are written after
    /// the frame); `mem` holds the memory values over the interval.
    #[inline]
    pub(super) fn evaluate(
        &self,
        values: &mut [f64],
        mem: &[f64],
        dt_s: f64,
        input: &Vector3<f64>,
    ) -> Vector3<f64> {
        let values = &mut values[..self.values_len()];
        let mut k = SLOTS;
        for &[a, b] in &self.diffs {
            values[k] = values[a as usize] - values[b as usize];
            k += 1;
        }
        if self.mems > 0 {
            values[k..k + self.mems as usize].copy_from_slice(&mem[..self.mems as usize]);
            k += self.mems as usize;
        }
        for &[a, b] in &self.muls {
            values[k] = values[a as usize] * values[b as usize];
            k += 1;
        }
        let m = [[dt_s; 3], [input.x, input.y, input.z]];
        let mut out = [0.0; 3];
        for r in &self.rows {
            let v = values[r.value as usize];
            let m = &m[r.scale as usize & 1];
            for i in 0..3 {
                out[i] += (r.coef_si[i] * v) * m[i];
            }
        }
        Vector3::from(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::custom::{Axis, CustomKind, CustomModel, CustomSpec};
    use crate::effects::custom::{expr, signals};
    use rand::{Rng, SeedableRng};

    fn spec(k: usize, regressor: &str, coef: [f64; 3], kind: CustomKind) -> CustomSpec {
        let factors = expr::parse_regressor(regressor).unwrap();
        CustomSpec {
            name: format!("e{k}"),
            enabled: k % 7 != 3,
            kind,
            regressor: regressor.into(),
            unit: expr::unit_of(&factors).to_string(),
            axes: vec![Axis::X, Axis::Y, Axis::Z],
            coef,
        }
    }

    /// Every signal, powers 1 to 8, products of up to three factors, repeated regressors (in
    /// both orders) and the per-axis `block`: the plan's sum equals, bit for bit, the sum of
    /// the per-effect products of the diagnosis (`CustomModel::regressor`, `f64::powi`) in
    /// file order.
    #[test]
    fn plan_equals_the_per_effect_products_bit_for_bit() {
        let names = [
            "temp:block",
            "temp:housing",
            "dtemp_dt:block",
            "dtemp_dt:board",
            "grad:gyro_z-housing",
            "grad:block-board",
            "u_x",
            "u_y",
            "u_z",
            "w_x",
            "w_z",
            "abs_w_y",
            "gimbal_outer",
            "gimbal_inner",
            "time",
            "n_x",
            "n_z",
            "e_y",
            "since_move",
            "lag(temp:block,900)",
            "lag(grad:gyro_z-housing,60.5)",
            "lag(abs_w_y,0.02)",
            "exp(-since_move/120)",
            "exp(-since_start/7.25)",
        ];
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(29);
        for accel in [false, true] {
            let mut specs: Vec<CustomSpec> = Vec::new();
            for k in 0..120 {
                let nf = 1 + k % 3;
                let mut f: Vec<String> = (0..nf)
                    .map(|_| {
                        let n = names[rng.random_range(0..names.len())];
                        match rng.random_range(1..=8) {
                            p if p <= 3 => n.to_string(),
                            p => format!("{n}^{p}"),
                        }
                    })
                    .collect();
                if k % 10 == 9 {
                    // A regressor already used, its factors reversed.
                    f = specs[k - 5]
                        .regressor
                        .split('*')
                        .rev()
                        .map(String::from)
                        .collect::<Vec<String>>();
                }
                let coef = [0, 1, 2].map(|i| {
                    if (k + i) % 4 == 0 {
                        0.0
                    } else {
                        rng.random_range(-5.0..5.0)
                    }
                });
                let kind = if k % 3 == 1 {
                    CustomKind::ScaleFactor
                } else {
                    CustomKind::Bias
                };
                specs.push(spec(k, &f.join("*"), coef, kind));
            }
            let m = CustomModel::new(&specs, accel).unwrap();
            let mut mem = m.memory_state();
            for _ in 0..200 {
                let mut frame = [0.0; signals::SLOTS];
                // The same model's memory runs on from one interval to the next.
                for v in frame.iter_mut() {
                    *v = rng.random_range(-3.0..3.0);
                }
                frame[signals::TIME] = rng.random_range(0.0..5e3);
                let dt_s = rng.random_range(1e-3..2e-2);
                let input = Vector3::from_fn(|_, _| rng.random_range(-1e-3..1e-3));
                let got = m.increment_error(&frame, &mut mem, dt_s, &input);
                let mut want = [0.0f64; 3];
                for (k, e) in m.effects().iter().enumerate() {
                    for i in (0..3).filter(|&i| e.enabled && e.coef_si[i] != 0.0) {
                        // dt = 1, input = 1: the product alone (·1 is exact).
                        let r = m.regressor(k, i, &frame, &mem, 1.0, &Vector3::repeat(1.0));
                        let mult = match e.kind {
                            CustomKind::Bias => dt_s,
                            CustomKind::ScaleFactor => input[i],
                        };
                        want[i] += (e.coef_si[i] * r) * mult;
                    }
                }
                for i in 0..3 {
                    assert_eq!(
                        got[i].to_bits(),
                        want[i].to_bits(),
                        "axis {i}: {got} vs {want:?}"
                    );
                }
            }
        }
    }

    /// A product and its reverse are one entry; `x^8` is three squarings; `temp:block` is one
    /// row per axis.
    #[test]
    fn shared_values_are_computed_once() {
        let specs = [
            spec(0, "u_x*u_z", [1.0; 3], CustomKind::Bias),
            spec(1, "u_z*u_x", [2.0; 3], CustomKind::Bias),
            spec(2, "temp:housing^8", [1.0; 3], CustomKind::Bias),
            spec(
                4,
                "grad:gyro_x-housing*u_x*u_z",
                [1.0, 0.0, 0.0],
                CustomKind::Bias,
            ),
            spec(5, "temp:block", [1.0; 3], CustomKind::ScaleFactor),
        ];
        let m = CustomModel::new(&specs, false).unwrap();
        // u_x·u_z; h², h⁴, h⁸; grad·u_x, (grad·u_x)·u_z (left to right, as written).
        assert_eq!(m.values_len(), signals::SLOTS + 1 + 6);
        assert_eq!(m.plan_rows(), 4 + 3);
    }
}
