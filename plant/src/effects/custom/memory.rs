//! Factors with memory: `lag(SIGNAL, τ)` (a first-order lag of a signal) and `exp(-CLOCK/τ)` (a
//! decay in a clock such as the time since the table last stopped). Their value over an
//! interval depends on what came before, so each sensor's compiled effects keep a
//! [`MemoryState`] that the caller advances once per interval: the plant per tick, the
//! diagnosis per measured row (within a segment, from its first row).
//!
//! The lag is discretised exactly for an input x held over the interval h (temperatures are
//! held between thermal steps, rates over the tick): with a = e^(−h/τ),
//! y(t₀ + h) = x + (y(t₀) − x)·a, and the factor's value is the lag's mean over the interval,
//! x + (y(t₀) − x)·τ/h·(1 − a), so a term's increment is the exact integral of the lagged
//! signal. The lag starts at its input (y = x on the first interval: a unit that has stood
//! still). A decay is taken at the interval's middle: exp(−s_mid/τ), whose mean over an
//! interval in which the clock runs differs by a factor sinh(h/2τ)/(h/2τ), below
//! 1 + (h/τ)²/24.

use super::expr::Op;
use super::signals::Frame;

/// The weights of a lag of time constant `tau_s` over an interval of `h_s`: (e^(−h/τ),
/// τ/h·(1 − e^(−h/τ))), the decay of the state and the weight of the start state in the mean.
#[inline]
pub fn lag_weights(h_s: f64, tau_s: f64) -> (f64, f64) {
    let r = h_s / tau_s;
    // τ/h·(1 − e^(−h/τ)) = −expm1(−r)/r, accurate for h ≪ τ.
    ((-r).exp(), -(-r).exp_m1() / r)
}

/// One interval of a lag with weights `w` ([`lag_weights`]) and input `x` held over it:
/// updates the state `y_end` (NaN before the first interval: the lag starts at its input) and
/// returns the lag's mean over the interval.
#[inline]
pub fn lag_step(y_end: &mut f64, x: f64, w: (f64, f64)) -> f64 {
    let y0 = if y_end.is_nan() { x } else { *y_end };
    let d = y0 - x;
    *y_end = x + d * w.0;
    x + d * w.1
}

/// The decay exp(−x/τ) of a clock value `x`.
#[inline]
pub fn decay_value(x: f64, tau_s: f64) -> f64 {
    (-x / tau_s).exp()
}

/// One distinct memory value of a sensor's effects: an operator on a frame slot (or on the
/// difference of two, a gradient), resolved for an axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct MemoryTerm {
    /// Frame slot read.
    pub a: u8,
    /// Frame slot subtracted (a gradient).
    pub b: Option<u8>,
    /// The operator (never [`Op::Plain`]).
    pub op: Op,
}

impl MemoryTerm {
    #[inline]
    fn input(&self, frame: &Frame) -> f64 {
        let v = frame[self.a as usize];
        match self.b {
            Some(b) => v - frame[b as usize],
            None => v,
        }
    }
}

/// What the memory terms remember between intervals, and their values over the last one.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct MemoryState {
    /// Lag outputs at the end of the last interval (NaN before the first).
    lag_end: Vec<f64>,
    /// Each term's value over the last interval (what the regressors read).
    value: Vec<f64>,
    /// The interval the lag weights were computed for, and per term (e^(−h/τ), τ/h·(1 − e^(−h/τ))).
    weights_h_s: f64,
    weights: Vec<(f64, f64)>,
}

impl MemoryState {
    /// A state for `terms` memory terms, before the first interval.
    pub(super) fn new(terms: usize) -> Self {
        MemoryState {
            lag_end: vec![f64::NAN; terms],
            value: vec![0.0; terms],
            weights_h_s: f64::NAN,
            weights: vec![(0.0, 0.0); terms],
        }
    }

    /// Each term's value over the last interval.
    #[inline]
    pub(super) fn values(&self) -> &[f64] {
        &self.value
    }

    /// Whether there is anything to remember.
    pub fn is_empty(&self) -> bool {
        self.value.is_empty()
    }

    /// The lag outputs at the end of the last interval (NaN before the first), for a saved
    /// plant state.
    pub fn lag_ends(&self) -> &[f64] {
        &self.lag_end
    }

    /// Restores the lag outputs (a saved plant state); the values follow at the next interval.
    pub fn restore_lag_ends(&mut self, ends: &[f64]) {
        self.lag_end.copy_from_slice(ends);
    }

    /// Advances every term over an interval of `h_s` whose signals are `frame`.
    #[inline]
    pub(super) fn advance(&mut self, terms: &[MemoryTerm], frame: &Frame, h_s: f64) {
        if h_s.to_bits() != self.weights_h_s.to_bits() {
            for (w, t) in self.weights.iter_mut().zip(terms) {
                if let Op::Lag { tau_s } = t.op {
                    *w = lag_weights(h_s, tau_s);
                }
            }
            self.weights_h_s = h_s;
        }
        for (k, t) in terms.iter().enumerate() {
            let x = t.input(frame);
            self.value[k] = match t.op {
                Op::Lag { .. } => lag_step(&mut self.lag_end[k], x, self.weights[k]),
                Op::Decay { tau_s } => decay_value(x, tau_s),
                Op::Plain => x,
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::custom::signals::SLOTS;

    /// A lag of a constant input from a different start: the exact solution's interval means,
    /// against the closed form y(t) = x + (y₀ − x)·e^(−t/τ) integrated over each interval.
    #[test]
    fn lag_means_equal_the_closed_form_integral() {
        let terms = [MemoryTerm {
            a: 0,
            b: None,
            op: Op::Lag { tau_s: 40.0 },
        }];
        let mut st = MemoryState::new(1);
        let mut f = [0.0; SLOTS];
        f[0] = 20.0;
        st.advance(&terms, &f, 0.1);
        assert_eq!(st.values()[0], 20.0, "starts at its input");
        f[0] = 30.0;
        let (tau, h, y0) = (40.0f64, 0.1f64, 20.0f64);
        for k in 0..2000 {
            st.advance(&terms, &f, h);
            let (t0, t1) = (k as f64 * h, (k + 1) as f64 * h);
            let integral = 30.0 * h + (y0 - 30.0) * tau * ((-t0 / tau).exp() - (-t1 / tau).exp());
            let mean = integral / h;
            assert!(
                (st.values()[0] - mean).abs() < 1e-11,
                "{k}: {} vs {mean}",
                st.values()[0]
            );
        }
    }

    /// A decay at the interval's middle, and a gradient's lag reads the difference.
    #[test]
    fn decays_and_gradient_lags() {
        let terms = [
            MemoryTerm {
                a: 3,
                b: None,
                op: Op::Decay { tau_s: 60.0 },
            },
            MemoryTerm {
                a: 1,
                b: Some(2),
                op: Op::Lag { tau_s: 1e8 },
            },
        ];
        let mut st = MemoryState::new(2);
        let mut f = [0.0; SLOTS];
        f[3] = 90.0;
        f[1] = 31.0;
        f[2] = 25.0;
        st.advance(&terms, &f, 0.01);
        assert_eq!(st.values()[0], (-1.5f64).exp());
        assert_eq!(st.values()[1], 6.0);
    }
}
