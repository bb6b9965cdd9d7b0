//! The unit's temperatures over a run, exactly: the chamber c(t) is piecewise linear (holds and
//! ramps); the housing T_h lags it (τ_h); each gyro block T_b,i lags T_h + s_i (τ_b,i); the
//! accelerometer node T_a lags T_h + s_a (τ_a); and each requested extra lag L_i (time constant
//! τ_L, for the lagged-temperature effect) lags T_b,i. On every chamber leg each node is an
//! [`ExpPoly`] of the time since the leg's start, its start value the previous leg's end value;
//! the run starts in the steady state (T_h = c(0), T_b,i = c(0) + s_i, T_a = c(0) + s_a,
//! L_i = T_b,i).

use crate::design::{ChamberLeg, UnitThermal};
use crate::exp_poly::ExpPoly;

/// Temperatures at one instant, °C.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Temps {
    /// Chamber.
    pub chamber: f64,
    /// Housing T_h.
    pub housing: f64,
    /// Gyro blocks T_b,i.
    pub block: [f64; 3],
    /// Accelerometer node T_a.
    pub accel: f64,
}

/// One chamber leg with every node's closed form on it.
#[derive(Clone, Debug)]
struct Leg {
    /// Start, s of run time.
    t0: f64,
    /// End (infinite for the last leg: the chamber holds).
    t1: f64,
    chamber: ExpPoly,
    housing: ExpPoly,
    block: [ExpPoly; 3],
    accel: ExpPoly,
    /// Per requested lag time constant, per axis.
    lag: Vec<[ExpPoly; 3]>,
}

/// The closed-form temperatures of one run.
#[derive(Clone, Debug)]
pub struct RunThermal {
    legs: Vec<Leg>,
    lag_taus: Vec<f64>,
}

impl RunThermal {
    /// The temperatures of a run with chamber profile `chamber` (its first leg a
    /// [`ChamberLeg::Hold`]) of unit `unit`, with extra lags of the blocks at the time
    /// constants `lag_taus_s`.
    ///
    /// # Panics
    /// If the profile is empty, starts with a ramp, or has a ramp rate that is not positive.
    pub fn new(chamber: &[ChamberLeg], unit: &UnitThermal, lag_taus_s: &[f64]) -> Self {
        let c0 = match chamber.first() {
            Some(ChamberLeg::Hold { temp_c, .. }) => *temp_c,
            _ => panic!("a chamber profile starts with a hold (its start temperature)"),
        };
        // Steady state at the start.
        let mut c = c0;
        let mut h = c0;
        let mut b = [0, 1, 2].map(|i| c0 + unit.block_offset_k[i]);
        let mut a = c0 + unit.accel_offset_k;
        let mut l: Vec<[f64; 3]> = lag_taus_s.iter().map(|_| b).collect();
        let mut legs = Vec::new();
        let mut t = 0.0;
        // Each chamber leg as (start temperature, slope K/s, duration), then the final hold.
        let mut pieces: Vec<(f64, f64, f64)> = Vec::new();
        for leg in chamber {
            match *leg {
                ChamberLeg::Hold { temp_c, dur_s } => {
                    pieces.push((temp_c, 0.0, dur_s.max(0.0)));
                    c = temp_c;
                }
                ChamberLeg::Ramp {
                    to_c,
                    rate_k_per_min,
                } => {
                    assert!(rate_k_per_min > 0.0, "a ramp rate is positive");
                    let dur = (to_c - c).abs() / rate_k_per_min * 60.0;
                    let slope = (to_c - c).signum() * rate_k_per_min / 60.0;
                    pieces.push((c, slope, dur));
                    c = to_c;
                }
            }
        }
        pieces.push((c, 0.0, f64::INFINITY));
        for (start_c, slope, dur) in pieces {
            if dur == 0.0 {
                continue;
            }
            let chamber = ExpPoly::linear(start_c, slope);
            let housing = chamber.lag(unit.tau_housing_s, 0.0, h);
            let block =
                [0, 1, 2].map(|i| housing.lag(unit.tau_block_s[i], unit.block_offset_k[i], b[i]));
            let accel = housing.lag(unit.tau_accel_s, unit.accel_offset_k, a);
            let lag: Vec<[ExpPoly; 3]> = lag_taus_s
                .iter()
                .zip(&l)
                .map(|(tau, l0)| [0, 1, 2].map(|i| block[i].lag(*tau, 0.0, l0[i])))
                .collect();
            if dur.is_finite() {
                h = housing.value(dur);
                b = [0, 1, 2].map(|i| block[i].value(dur));
                a = accel.value(dur);
                l = lag
                    .iter()
                    .map(|x| [0, 1, 2].map(|i| x[i].value(dur)))
                    .collect();
            }
            legs.push(Leg {
                t0: t,
                t1: t + dur,
                chamber,
                housing,
                block,
                accel,
                lag,
            });
            t += dur;
        }
        Self {
            legs,
            lag_taus: lag_taus_s.to_vec(),
        }
    }

    /// Index of the leg that holds time `t` (the later leg at a boundary), searching on from
    /// `hint` (a leg at or before it).
    pub fn leg_at(&self, t: f64, hint: usize) -> usize {
        let mut k = hint.min(self.legs.len() - 1);
        while k > 0 && t < self.legs[k].t0 {
            k -= 1;
        }
        while k + 1 < self.legs.len() && t >= self.legs[k].t1 {
            k += 1;
        }
        k
    }

    /// End of leg `leg`, s (infinite for the last).
    pub fn leg_end(&self, leg: usize) -> f64 {
        self.legs[leg].t1
    }

    /// Temperatures at time `t` on leg `leg` ([`RunThermal::leg_at`]).
    pub fn temps_on(&self, leg: usize, t: f64) -> Temps {
        let l = &self.legs[leg];
        let u = t - l.t0;
        Temps {
            chamber: l.chamber.value(u),
            housing: l.housing.value(u),
            block: [0, 1, 2].map(|i| l.block[i].value(u)),
            accel: l.accel.value(u),
        }
    }

    /// Temperatures at time `t`.
    pub fn temps(&self, t: f64) -> Temps {
        self.temps_on(self.leg_at(t, 0), t)
    }

    /// dT_b,i/dt of gyro block `axis` at time `t`, K/s.
    pub fn block_rate(&self, axis: usize, t: f64) -> f64 {
        let l = &self.legs[self.leg_at(t, 0)];
        l.block[axis].rate(t - l.t0)
    }

    /// The index of the extra lag with time constant `tau_s`, if it was requested.
    pub fn lag_index(&self, tau_s: f64) -> Option<usize> {
        self.lag_taus.iter().position(|t| *t == tau_s)
    }

    /// Extra lag `k` of gyro block `axis` at time `t` on leg `leg`, °C.
    pub fn lag_on(&self, leg: usize, k: usize, axis: usize, t: f64) -> f64 {
        let l = &self.legs[leg];
        l.lag[k][axis].value(t - l.t0)
    }

    /// Extra lag `k` of gyro block `axis` at time `t`, °C.
    pub fn lag(&self, k: usize, axis: usize, t: f64) -> f64 {
        self.lag_on(self.leg_at(t, 0), k, axis, t)
    }
}
