//! Signals of the form x(u) = p₀ + p₁·u + Σ a·u^m·e^(−μu) and their exact first-order lag.
//!
//! A chamber leg is linear in time, and a first-order lag maps this family onto itself, so a
//! cascade of lags driven by a piecewise-linear chamber has an exact closed form on every leg:
//! the lag y' = (x + s − y)/τ of x, starting at y(0) = y₀, is
//!
//! * for p₀ + p₁·u: (p₀ + s − p₁τ) + p₁·u;
//! * for a·u^m·e^(−μu), μ ≠ λ = 1/τ: e^(−μu)·Σ_j q_j u^j with q_m = λa/(λ − μ) and
//!   q_j = −(j + 1)·q_{j+1}/(λ − μ) for j < m;
//! * for a·u^m·e^(−λu) (the lag's own rate): λa/(m + 1)·u^(m+1)·e^(−λu);
//!
//! plus C·e^(−λu) with C so that y(0) = y₀.

/// One term a·u^m·e^(−μu).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExpTerm {
    /// Coefficient a.
    pub a: f64,
    /// Power m of u.
    pub m: i32,
    /// Decay rate μ, 1/s.
    pub mu: f64,
}

/// x(u) = p₀ + p₁·u + Σ a·u^m·e^(−μu), u the time since the start of a leg.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ExpPoly {
    /// Constant part.
    pub p0: f64,
    /// Slope of the linear part, 1/s.
    pub p1: f64,
    /// Decaying terms.
    pub terms: Vec<ExpTerm>,
}

/// Rates closer than this (relative) are taken as equal: the two formulas meet there, and the
/// error of either (from u·Δμ, or from the cancellation of 1/(λ − μ)) stays below ~1e-7 of the
/// term for u/τ ≤ 40. Drawn time constants never come this close.
const SAME_RATE: f64 = 1e-8;

impl ExpPoly {
    /// The linear signal p₀ + p₁·u.
    pub fn linear(p0: f64, p1: f64) -> Self {
        Self {
            p0,
            p1,
            terms: Vec::new(),
        }
    }

    /// x(u).
    pub fn value(&self, u: f64) -> f64 {
        self.terms.iter().fold(self.p0 + self.p1 * u, |s, t| {
            s + t.a * u.powi(t.m) * (-t.mu * u).exp()
        })
    }

    /// dx/du.
    pub fn rate(&self, u: f64) -> f64 {
        self.terms.iter().fold(self.p1, |s, t| {
            let e = (-t.mu * u).exp();
            let d = if t.m == 0 {
                -t.mu
            } else {
                t.m as f64 * u.powi(t.m - 1) - t.mu * u.powi(t.m)
            };
            s + t.a * d * e
        })
    }

    /// The exact solution y of τ·y' = x + `offset` − y with y(0) = `y0`.
    pub fn lag(&self, tau_s: f64, offset: f64, y0: f64) -> Self {
        let lam = 1.0 / tau_s;
        let mut out = Self::linear(self.p0 + offset - self.p1 * tau_s, self.p1);
        for t in &self.terms {
            if (t.mu - lam).abs() <= SAME_RATE * lam {
                out.push(lam * t.a / (t.m + 1) as f64, t.m + 1, lam);
            } else {
                let d = lam - t.mu;
                let mut q = lam * t.a / d;
                out.push(q, t.m, t.mu);
                for j in (0..t.m).rev() {
                    q = -((j + 1) as f64) * q / d;
                    out.push(q, j, t.mu);
                }
            }
        }
        let c = y0 - out.value(0.0);
        out.push(c, 0, lam);
        out
    }

    /// Adds a·u^m·e^(−μu), merged into a term of the same power and rate if there is one.
    fn push(&mut self, a: f64, m: i32, mu: f64) {
        match self.terms.iter_mut().find(|t| t.m == m && t.mu == mu) {
            Some(t) => t.a += a,
            None => self.terms.push(ExpTerm { a, m, mu }),
        }
    }
}
