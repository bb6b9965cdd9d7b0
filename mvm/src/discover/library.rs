//! The library of candidate regressors discovery searches, and their window sums.
//!
//! The terms are built from the documented signals a declared effect reads, as the signals
//! table ([`rins_plant::effects::custom::signals::FAMILIES`]) lists them and says how the
//! library uses each (a new signal there is in the library with no change here): the acting axis's block temperature and the
//! housing's, their time derivatives, the block-to-housing gradient, the body up direction
//! u_x, u_y, u_z, the body rates and their absolute values, the gimbal angles and the time since
//! the run's start; every one of them and every product of two (squares included), each as a
//! bias and as a scale-factor term, per channel; plus one bias indicator per static table
//! position. A term is written exactly as a declared effect's regressor (`"u_x*u_z"`,
//! `"dtemp_dt:block"`), so a proposal is a ready `[[sensor.gyro.custom]]` block.
//!
//! One pass over the rows (in parallel over segments, rows assigned to the replay's windows)
//! sums each signal times the row's weight (Δt, the true Δθ_i or Δv_i) per window, exactly,
//! and the products of two up components exactly. A product of two signals is formed from those
//! sums as (Σ a·w)·(Σ b·Δt)/(Σ Δt), with b the signal that stays constant while the table
//! dwells (u, rates, gimbal angles) when there is one: exact in a dwell for the products the
//! tests plant (u·u exactly, temperature × attitude exactly, a degree-one term always exactly).
//! For two signals that both vary in a window (temperature products) it misses exactly
//! W·cov_w(a, b): W³·ρ_a·ρ_b/12 for two ramps at rates ρ, never more than W·range_a·range_b/4.
//! A 1 K/min chamber ramp gives 0.021 K² against T² ≈ 625 K² at 25 °C (3e-5); the 37-run
//! campaign is soaked (|dT/dt| < 2e-14 K/s over 30 s), so there it is exact. Tests:
//! `library_tests.rs`, against closed forms.

use rayon::prelude::*;
#[cfg(doc)]
use rins_plant::effects::custom::signals::Family;
use rins_plant::effects::custom::signals::{
    ArgKind, Args, FAMILIES, Library, NodeRef, SLOTS, Signal, UP, Unit,
};
use rins_plant::effects::custom::{CustomKind, Factor, Op, decay_value, lag_step, lag_weights};
use rins_plant::thermal::node;

use crate::custom::RowSignals;
use crate::history::History;
use crate::replay::{Kinematics, Window};
use crate::rows::{Rows, RowsInfo};

/// Weights a signal is summed with: Δt, Δθ_x..z, Δv_x..z.
const WEIGHTS: usize = 7;

/// A library term: a regressor of one or two factors, as a bias or a scale factor, or a
/// position indicator.
#[derive(Clone, Debug, PartialEq)]
pub enum Term {
    /// `signal` or `signal_a*signal_b` (the same twice: a square), as a declared effect.
    Product {
        /// The factors (one or two).
        factors: Vec<Signal>,
        /// Bias or scale factor.
        kind: CustomKind,
    },
    /// A bias only while the table dwells at one static position (mean up direction).
    Position {
        /// The position's up direction in body axes, rounded to 0.01.
        up: [f64; 3],
    },
    /// A bias through an operator with memory, `lag(signal, τ)` or `exp(-clock/τ)`, at one
    /// time constant (of [`tau_grid`], or refined by the search).
    Memory {
        /// The signal.
        signal: Signal,
        /// The operator with its time constant.
        op: Op,
    },
}

/// Time constants the library's memory terms are searched at, s: log-spaced from 10 s to
/// 3 h, six per decade (19 points, neighbours 1.474× apart), refined around the best by the
/// search.
pub fn tau_grid() -> Vec<f64> {
    const LO: f64 = 10.0;
    const HI: f64 = 10_800.0;
    let n = ((HI / LO).log10() * 6.0).round() as usize;
    (0..=n)
        .map(|k| LO * (HI / LO).powf(k as f64 / n as f64))
        .collect()
}

/// The memory terms of the library over the time constants `taus`: a decay of each
/// [`Library::Decay`] clock (a transient after each table move, since it stopped or started),
/// and a lag of the acting axis's block temperature and, when measured, the housing's.
pub fn memory_terms(info: &RowsInfo, taus: &[f64]) -> Vec<Term> {
    let mut base: Vec<(Signal, bool)> = FAMILIES
        .iter()
        .enumerate()
        .filter(|(_, f)| f.library == Library::Decay)
        .flat_map(|(i, _)| Signal::all_of(i))
        .map(|s| (s, true))
        .collect();
    base.push((Signal::Temp(NodeRef::Block), false));
    if info.housing {
        base.push((Signal::Temp(NodeRef::Node(node::HOUSING)), false));
    }
    let mut out = Vec::new();
    for (signal, decay) in base {
        for &tau_s in taus {
            out.push(Term::Memory {
                signal,
                op: if decay {
                    Op::Decay { tau_s }
                } else {
                    Op::Lag { tau_s }
                },
            });
        }
    }
    out
}

/// Regressor notation of a signal, as a declared effect writes it.
pub fn signal_name(s: Signal) -> String {
    s.name()
}

impl Term {
    /// The regressor as a declared effect writes it (`None` for a position indicator).
    pub fn regressor(&self) -> Option<String> {
        match self {
            Term::Product { factors, .. } => Some(match factors.as_slice() {
                [a, b] if a == b => format!("{}^2", signal_name(*a)),
                f => f
                    .iter()
                    .map(|s| signal_name(*s))
                    .collect::<Vec<_>>()
                    .join("*"),
            }),
            Term::Position { .. } => None,
            Term::Memory { signal, op } => Some(
                Factor {
                    signal: *signal,
                    power: 1,
                    op: *op,
                }
                .text(),
            ),
        }
    }

    /// The time constant of a memory term.
    pub fn tau_s(&self) -> Option<f64> {
        match self {
            Term::Memory { op, .. } => op.tau_s(),
            _ => None,
        }
    }

    /// The same memory term at another time constant (other terms unchanged).
    pub fn with_tau(&self, tau_s: f64) -> Term {
        match self {
            Term::Memory { signal, op } => Term::Memory {
                signal: *signal,
                op: match op {
                    Op::Lag { .. } => Op::Lag { tau_s },
                    Op::Decay { .. } => Op::Decay { tau_s },
                    Op::Plain => Op::Plain,
                },
            },
            t => t.clone(),
        }
    }

    /// Whether two terms are the same but for the time constant (one memory family).
    pub fn same_family(&self, o: &Term) -> bool {
        match (self, o) {
            (Term::Memory { signal: a, op: p }, Term::Memory { signal: b, op: q }) => {
                a == b && std::mem::discriminant(p) == std::mem::discriminant(q)
            }
            _ => self == o,
        }
    }

    /// Parameters beyond the coefficient: the time constant of a memory term.
    pub fn extra_params(&self) -> usize {
        usize::from(self.tau_s().is_some())
    }

    /// The regressor's unit (`1` for an indicator).
    pub fn unit(&self) -> Unit {
        match self {
            Term::Product { factors, .. } => {
                factors.iter().fold(Unit::ONE, |u, s| u.times(s.unit()))
            }
            Term::Position { .. } => Unit::ONE,
            Term::Memory { signal, op } => Factor {
                signal: *signal,
                power: 1,
                op: *op,
            }
            .unit(),
        }
    }

    /// 0 for one signal, 1 for a product of two, a position indicator or a term with memory
    /// (one more parameter, its time constant): the selection prefers the simpler of two terms
    /// the data cannot tell apart.
    pub fn complexity(&self) -> u8 {
        match self {
            Term::Product { factors, .. } if factors.len() == 1 => 0,
            _ => 1,
        }
    }

    /// Bias or scale factor.
    pub fn kind(&self) -> CustomKind {
        match self {
            Term::Product { kind, .. } => *kind,
            Term::Position { .. } | Term::Memory { .. } => CustomKind::Bias,
        }
    }

    /// A name for the proposal (letters, digits, `_`; ≤ 32 characters): `b_` (bias) or `sf_`
    /// (scale factor) and the factors (`b_dtdt_block`, `b_u_x_u_z`, `sf_t_block`).
    pub fn name(&self) -> String {
        match self {
            Term::Product { factors, kind } => {
                let k = if *kind == CustomKind::Bias { "b" } else { "sf" };
                let f = match factors.as_slice() {
                    [a, b] if a == b => format!("{}_sq", a.short()),
                    f => f.iter().map(|s| s.short()).collect::<Vec<_>>().join("_"),
                };
                format!("{k}_{f}")
            }
            Term::Position { up } => format!(
                "pos_{}_{}_{}",
                (up[0] * 100.0).round() as i64,
                (up[1] * 100.0).round() as i64,
                (up[2] * 100.0).round() as i64
            )
            .replace('-', "m"),
            Term::Memory { signal, op } => {
                let tau = op.tau_s().unwrap_or(0.0);
                let t = if tau >= 1.0 {
                    format!("{}", tau.round() as i64)
                } else {
                    format!("{tau:.3}").replace('.', "p")
                };
                match op {
                    Op::Decay { .. } => format!("b_exp_{}_{t}", signal.short()),
                    _ => format!("b_lag_{}_{t}", signal.short()),
                }
            }
        }
    }

    /// Human-readable description.
    pub fn describe(&self) -> String {
        match self {
            Term::Product { kind, .. } => format!(
                "{} ∝ {}",
                if *kind == CustomKind::Bias {
                    "bias"
                } else {
                    "scale factor"
                },
                self.regressor().unwrap_or_default()
            ),
            Term::Position { up } => format!(
                "bias only at the static position with up = ({:.2}, {:.2}, {:.2}) in body axes",
                up[0], up[1], up[2]
            ),
            Term::Memory { .. } => format!("bias ∝ {}", self.regressor().unwrap_or_default()),
        }
    }
}

/// The signals the library is built from on a history, from the signals table
/// ([`FAMILIES`]) in its order: the temperature families of the acting axis's block, then,
/// when the housing is measured, the housing's and the block-to-housing difference; then every
/// [`Library::Products`] family over its axes, those that [`Family::needs_gimbal`] only with a
/// gimbal attitude.
pub fn library_signals(info: &RowsInfo) -> Vec<Signal> {
    let housing = NodeRef::Node(node::HOUSING);
    let products = || {
        FAMILIES
            .iter()
            .enumerate()
            .filter(|(_, f)| f.library == Library::Products)
    };
    let mut v: Vec<Signal> = products()
        .filter(|(_, f)| f.arg == ArgKind::Node)
        .filter_map(|(i, _)| Signal::from_parts(i, Args::Node(NodeRef::Block)))
        .collect();
    if info.housing {
        v.extend(products().filter_map(|(i, f)| match f.arg {
            ArgKind::Node => Signal::from_parts(i, Args::Node(housing)),
            ArgKind::NodePair => Signal::from_parts(i, Args::NodePair(NodeRef::Block, housing)),
            _ => None,
        }));
    }
    for (i, f) in products() {
        if matches!(f.arg, ArgKind::Axis | ArgKind::None) && (info.gimbal || !f.needs_gimbal) {
            v.extend(Signal::all_of(i));
        }
    }
    v
}

/// Every product term of the library over `sig`: each signal, each product of two (squares
/// included), as a bias and as a scale factor.
pub fn product_terms(sig: &[Signal]) -> Vec<Term> {
    let mut out: Vec<Term> = Vec::new();
    for kind in [CustomKind::Bias, CustomKind::ScaleFactor] {
        for (i, a) in sig.iter().enumerate() {
            out.push(Term::Product {
                factors: vec![*a],
                kind,
            });
            for b in &sig[i..] {
                out.push(Term::Product {
                    factors: vec![*a, *b],
                    kind,
                });
            }
        }
    }
    out
}

/// Per-window sums of every signal slot times each weight, of the up products, and of the
/// memory terms as biases.
#[derive(Clone, Debug)]
pub struct Moments {
    /// `[window][slot * WEIGHTS + weight]`: Σ frame[slot]·w over the window's rows (slot
    /// [`SLOTS`] is the constant 1).
    pub m: Vec<Vec<f64>>,
    /// `[window][a * 3 + b]`: Σ u_a·u_b·Δt.
    pub uu: Vec<[f64; 9]>,
    /// Mean up direction of each window.
    pub up: Vec<[f64; 3]>,
    /// The memory terms summed ([`Term::Memory`]).
    pub memory_terms: Vec<Term>,
    /// `[window][term * 6 + channel]`: Σ value·Δt of each memory term on each channel.
    pub mem: Vec<Vec<f64>>,
}

/// The distinct inputs of memory terms over the channels: each (frame slot, subtracted slot,
/// operator) once, and per term and channel the input it reads.
struct MemoryUnits {
    units: Vec<(usize, Option<usize>, Op)>,
    of: Vec<usize>,
}

impl MemoryUnits {
    fn new(terms: &[Term]) -> Self {
        let mut units: Vec<(usize, Option<usize>, Op)> = Vec::new();
        let mut of = Vec::with_capacity(terms.len() * 6);
        for t in terms {
            let Term::Memory { signal, op } = t else {
                of.extend([usize::MAX; 6]);
                continue;
            };
            for c in 0..6 {
                let (a, b) = signal.slots(c >= 3, c % 3);
                let u = (a, b, *op);
                let k = units.iter().position(|x| *x == u).unwrap_or_else(|| {
                    units.push(u);
                    units.len() - 1
                });
                of.push(k);
            }
        }
        MemoryUnits { units, of }
    }
}

/// The memory inputs of one segment as it is walked: lag states, and the last decay value
/// to continue within a dwell by one multiplication.
struct MemoryWalk {
    lag_end: Vec<f64>,
    last: Vec<(f64, f64)>,
    weights_dt: f64,
    weights: Vec<(f64, f64)>,
    value: Vec<f64>,
}

impl MemoryWalk {
    fn new(n: usize) -> Self {
        MemoryWalk {
            lag_end: vec![f64::NAN; n],
            last: vec![(f64::NAN, f64::NAN); n],
            weights_dt: f64::NAN,
            weights: vec![(0.0, 0.0); n],
            value: vec![0.0; n],
        }
    }

    /// Each unit's value over a row of `dt` with signals `f`: the plant's lag step
    /// ([`lag_step`]) and decay ([`decay_value`]); a decay whose clock ran on by exactly the
    /// row continues from the last value (one multiplication instead of an exponential, to
    /// 1e-15 relative per row).
    fn step(&mut self, units: &MemoryUnits, f: &[f64], dt: f64) {
        if dt.to_bits() != self.weights_dt.to_bits() {
            for (w, (_, _, op)) in self.weights.iter_mut().zip(&units.units) {
                *w = match op {
                    Op::Lag { tau_s } => lag_weights(dt, *tau_s),
                    Op::Decay { tau_s } => ((-dt / tau_s).exp(), 0.0),
                    Op::Plain => (1.0, 1.0),
                };
            }
            self.weights_dt = dt;
        }
        for (k, (a, b, op)) in units.units.iter().enumerate() {
            let x = f[*a] - b.map_or(0.0, |b| f[b]);
            self.value[k] = match op {
                Op::Lag { .. } => lag_step(&mut self.lag_end[k], x, self.weights[k]),
                Op::Decay { tau_s } => {
                    let (x0, v0) = self.last[k];
                    let v = if (x - (x0 + dt)).abs() <= 1e-12 * x.abs().max(1.0) {
                        v0 * self.weights[k].0
                    } else {
                        decay_value(x, *tau_s)
                    };
                    self.last[k] = (x, v);
                    v
                }
                Op::Plain => x,
            };
        }
    }
}

/// Sums the signals of `rows` over the replay's `windows` (one pass over the chunks, in
/// parallel over a chunk's segments; the windows follow the segments in order, each row after a
/// segment's first in the next window until its `rows` are used), with the memory terms
/// `memory_terms` as biases.
pub(crate) fn moments(
    kin: &Kinematics,
    rows: &(impl Rows + ?Sized),
    windows: &[Window],
    memory_terms: &[Term],
) -> Moments {
    let info = rows.info();
    let units = MemoryUnits::new(memory_terms);
    let mut per: Vec<Vec<WindowSums>> = Vec::new();
    // The next segment's first window.
    let mut w = 0usize;
    rows.for_each_chunk(&mut |h| {
        let rs = RowSignals::all(h, &info.run_start_s);
        // The first window of each segment.
        let mut first = Vec::with_capacity(h.segments.len());
        for seg in &h.segments {
            first.push(w);
            let mut rows = seg.len().saturating_sub(1);
            while rows > 0 && w < windows.len() {
                rows = rows.saturating_sub(windows[w].rows as usize);
                w += 1;
            }
        }
        per.par_extend(chunk_moments(kin, h, &rs, windows, &first, &units));
    });
    let mut m = Vec::with_capacity(windows.len());
    let mut uu = Vec::with_capacity(windows.len());
    let mut mem = Vec::with_capacity(windows.len());
    for s in per.into_iter().flatten() {
        m.push(s.m);
        uu.push(s.uu);
        mem.push(s.mem);
    }
    let up = m
        .iter()
        .map(|a| {
            let d = a[SLOTS * WEIGHTS].max(f64::MIN_POSITIVE);
            [0, 1, 2].map(|i| a[(UP + i) * WEIGHTS] / d)
        })
        .collect();
    Moments {
        m,
        uu,
        up,
        memory_terms: memory_terms.to_vec(),
        mem,
    }
}

/// One window's sums.
struct WindowSums {
    m: Vec<f64>,
    uu: [f64; 9],
    mem: Vec<f64>,
}

/// Per segment of chunk `h` (whose first windows are `first`), the per-window sums.
fn chunk_moments<'a>(
    kin: &'a Kinematics,
    h: &'a History,
    rs: &'a RowSignals,
    windows: &'a [Window],
    first: &'a [usize],
    units: &'a MemoryUnits,
) -> impl IndexedParallelIterator<Item = Vec<WindowSums>> + 'a {
    h.segments
        .par_iter()
        .zip(first.par_iter())
        .map(|(seg, &w0)| {
            let fresh = || WindowSums {
                m: vec![0.0; (SLOTS + 1) * WEIGHTS],
                uu: [0.0; 9],
                mem: vec![0.0; units.of.len()],
            };
            let mut out = Vec::new();
            let mut wi = w0;
            let mut left = 0usize;
            let mut acc = fresh();
            let mut walk = MemoryWalk::new(units.units.len());
            for k in seg.start + 1..seg.end {
                if left == 0 {
                    if k > seg.start + 1 {
                        out.push(std::mem::replace(&mut acc, fresh()));
                    }
                    left = windows.get(wi).map_or(usize::MAX, |w| w.rows as usize);
                    wi += 1;
                }
                left -= 1;
                let dt = h.t_s[k] - h.t_s[k - 1];
                let r = kin.row(h, seg, k, dt);
                let f = rs.frame(h, k, dt, &r.c_nb, &r.dtheta_rad, &r.dv_mps);
                let wts = [
                    dt,
                    r.dtheta_rad[0],
                    r.dtheta_rad[1],
                    r.dtheta_rad[2],
                    r.dv_mps[0],
                    r.dv_mps[1],
                    r.dv_mps[2],
                ];
                for s in 0..SLOTS {
                    let v = f[s];
                    let row = &mut acc.m[s * WEIGHTS..(s + 1) * WEIGHTS];
                    for (a, w) in row.iter_mut().zip(&wts) {
                        *a += v * w;
                    }
                }
                let row = &mut acc.m[SLOTS * WEIGHTS..];
                for (a, w) in row.iter_mut().zip(&wts) {
                    *a += w;
                }
                for a in 0..3 {
                    for b in a..3 {
                        acc.uu[a * 3 + b] += f[UP + a] * f[UP + b] * dt;
                    }
                }
                if !units.units.is_empty() {
                    walk.step(units, &f, dt);
                    for (a, &u) in acc.mem.iter_mut().zip(&units.of) {
                        if u != usize::MAX {
                            *a += walk.value[u] * dt;
                        }
                    }
                }
            }
            if seg.len() > 1 {
                out.push(acc);
            }
            out
        })
}

impl Moments {
    /// Σ signal·weight over window `w`.
    fn lin(&self, w: usize, s: Signal, accel: bool, axis: usize, weight: usize) -> f64 {
        let m = &self.m[w];
        let (a, b) = s.slots(accel, axis);
        let v = m[a * WEIGHTS + weight];
        b.map_or(v, |b| v - m[b * WEIGHTS + weight])
    }

    /// Duration of window `w`, s (Σ Δt).
    fn duration(&self, w: usize) -> f64 {
        self.m[w][SLOTS * WEIGHTS]
    }

    /// The column of `term` on `channel` (0–2 gyro, 3–5 accelerometer) over the windows, in
    /// increment units per unit of the coefficient in SI (like the catalogue's regressors).
    pub fn column(&self, term: &Term, channel: usize, windows: &[Window]) -> Vec<f64> {
        let (accel, axis) = (channel >= 3, channel % 3);
        let weight = match term.kind() {
            CustomKind::Bias => 0,
            CustomKind::ScaleFactor if accel => 4 + axis,
            CustomKind::ScaleFactor => 1 + axis,
        };
        (0..self.m.len())
            .map(|w| match term {
                Term::Position { up } => {
                    let at = !windows[w].moving
                        && (0..3).all(|i| (self.up[w][i] - up[i]).abs() < 0.0051);
                    if at { self.duration(w) } else { 0.0 }
                }
                Term::Product { factors, .. } => match factors.as_slice() {
                    [a] => self.lin(w, *a, accel, axis, weight),
                    [Signal::Up(i), Signal::Up(j)] if weight == 0 => {
                        self.uu[w][(*i).min(*j) * 3 + (*i).max(*j)]
                    }
                    [a, b] => {
                        // The dwell-constant factor as the window mean.
                        let (var, mean) = if a.family().dwell_constant {
                            (*b, *a)
                        } else {
                            (*a, *b)
                        };
                        let d = self.duration(w);
                        if d > 0.0 {
                            self.lin(w, var, accel, axis, weight)
                                * self.lin(w, mean, accel, axis, 0)
                                / d
                        } else {
                            0.0
                        }
                    }
                    _ => 0.0,
                },
                Term::Memory { .. } => {
                    let k = self
                        .memory_terms
                        .iter()
                        .position(|t| t == term)
                        .expect("a memory term summed by the pass");
                    self.mem[w][k * 6 + channel]
                }
            })
            .collect()
    }

    /// The static positions the windows dwell at (rounded up directions), at most `max`, in
    /// order of first appearance.
    pub fn positions(&self, windows: &[Window], max: usize) -> Vec<[f64; 3]> {
        let mut out: Vec<[f64; 3]> = Vec::new();
        for (w, win) in windows.iter().enumerate() {
            if win.moving || out.len() >= max {
                continue;
            }
            let up = self.up[w].map(|x| (x * 100.0).round() / 100.0);
            if !out
                .iter()
                .any(|p| (0..3).all(|i| (p[i] - up[i]).abs() < 0.005))
            {
                out.push(up);
            }
        }
        out
    }
}

/// The file unit (SI) of a term's coefficient on a gyro (`accel = false`) or accelerometer.
pub fn file_unit_si(kind: CustomKind, accel: bool) -> f64 {
    use rins_plant::units::{DPH, PPM, UG};
    match (kind, accel) {
        (CustomKind::Bias, false) => DPH,
        (CustomKind::Bias, true) => UG,
        (CustomKind::ScaleFactor, _) => PPM,
    }
}

#[cfg(test)]
mod library_tests;
