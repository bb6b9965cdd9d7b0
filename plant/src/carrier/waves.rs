//! Sea-state motion: a seeded realisation of a wave spectrum through the vessel's response
//! amplitude operators, evaluated with phasors advanced by a fixed complex rotation per tick.
//!
//! Component i has frequency ω_i (one per equal band of [band₀, band₁]·ω_p, jittered inside its
//! band so the record does not repeat), amplitude a_i = √(2 S(ω_i) Δω) and a uniform random phase
//! ε_i; all drawn from the carrier's own random stream [`SEA_STATE_STREAM`] of the run seed, so
//! no existing noise stream moves. Degree of freedom d responds with the complex amplitude
//! c_{d,i} = a_i · gain_d · dir_d(β) · F_d(ω_i) · H_d(ω_i) (see [`super::spec::RaoSpec`]), and
//! x_d(t) = Σ_i Re(c_{d,i} z_i(t)), z_i(t) = exp(i(ω_i t + ε_i)).
//!
//! z_i at tick k+1 is z_i at tick k times exp(iω_i h): one complex product per component and
//! tick instead of a sine and cosine. Every [`RESYNC_TICKS`] ticks the phasors are recomputed
//! from the exact phase ω_i·t + ε_i, so z at tick k is a function of k alone (rounding cannot
//! accumulate, and a restored plant gets the same bits).

use nalgebra::Complex;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::spec::{SeaSpec, SpectrumKind};
use crate::simd::{LANES, NodeJetInputs, jet_sum, node_jets};
use crate::units::DEG;

/// Random stream of the sea-state realisation (distinct from the sensor noise streams).
pub const SEA_STATE_STREAM: u64 = 0x5EA5_7A7E;

/// Phasors are recomputed exactly at every multiple of this tick count.
pub const RESYNC_TICKS: u64 = 4096;

// Standard gravity of the deep-water dispersion k = ω²/g, m/s².
use super::spec::G_WAVE_MPS2;

/// Degrees of freedom, in the order of [`SeaJet`]'s arrays.
pub mod dof {
    /// Roll about the bow (y) axis, rad.
    pub const ROLL: usize = 0;
    /// Pitch about the starboard (x) axis, rad.
    pub const PITCH: usize = 1;
    /// Yaw about up, rad.
    pub const YAW: usize = 2;
    /// Heave (up), m.
    pub const HEAVE: usize = 3;
    /// Surge (along the bow), m.
    pub const SURGE: usize = 4;
    /// Sway (to starboard), m.
    pub const SWAY: usize = 5;
}

pub use super::widths::JET_LEN;

/// Values, rates and accelerations of the six degrees of freedom at one instant
/// (rad, rad/s, rad/s² for roll, pitch, yaw; m, m/s, m/s² for heave, surge, sway).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct SeaJet {
    /// Displacements.
    pub x: [f64; 6],
    /// First derivatives.
    pub xd: [f64; 6],
    /// Second derivatives.
    pub xdd: [f64; 6],
}

impl SeaJet {
    /// From the flat order x₀…x₅, ẋ₀…ẋ₅, ẍ₀…ẍ₅.
    #[inline]
    pub fn from_flat(f: &[f64; JET_LEN]) -> Self {
        let part = |o: usize| std::array::from_fn(|d| f[o + d]);
        Self {
            x: part(0),
            xd: part(6),
            xdd: part(12),
        }
    }

    /// In the flat order of [`SeaJet::from_flat`].
    #[inline]
    pub fn flat(&self) -> [f64; JET_LEN] {
        std::array::from_fn(|j| match j / 6 {
            0 => self.x[j],
            1 => self.xd[j - 6],
            _ => self.xdd[j - 12],
        })
    }
}

/// Pierson–Moskowitz spectrum (ITTC two-parameter form), m²·s: S(ω) = (5/16)·H_s²·ω_p⁴·ω⁻⁵·
/// exp(−(5/4)(ω_p/ω)⁴); its integral over all ω is H_s²/16.
pub fn pierson_moskowitz(omega: f64, hs_m: f64, omega_p: f64) -> f64 {
    let r4 = (omega_p / omega).powi(4);
    5.0 / 16.0 * hs_m * hs_m * r4 / omega * (-1.25 * r4).exp()
}

/// JONSWAP spectrum (DNV-RP-C205 §3.5.5): (1 − 0.287 ln γ)·S_PM(ω)·γ^exp(−(ω−ω_p)²/(2σ²ω_p²)),
/// σ = 0.07 below the peak and 0.09 above.
pub fn jonswap(omega: f64, hs_m: f64, omega_p: f64, gamma: f64) -> f64 {
    let sigma = if omega <= omega_p { 0.07 } else { 0.09 };
    let e = (-(omega - omega_p).powi(2) / (2.0 * sigma * sigma * omega_p * omega_p)).exp();
    (1.0 - 0.287 * gamma.ln()) * pierson_moskowitz(omega, hs_m, omega_p) * gamma.powf(e)
}

/// The realised sea state.
#[derive(Clone, Debug)]
pub struct Waves {
    omega_rps: Vec<f64>,
    phase_rad: Vec<f64>,
    /// c_{d,i}, one array of six per component.
    coef: Vec<[Complex<f64>; 6]>,
    /// Per component, the jet's complex factors C_j (jet value j = Re(C_j·z_i)) in the order of
    /// [`SeaJet::from_flat`]: c_d, iω·c_d, −ω²·c_d; real and imaginary parts apart so the sum
    /// over the 18 values vectorises.
    jet_re: Vec<[f64; JET_LEN]>,
    jet_im: Vec<[f64; JET_LEN]>,
    rot_tick: Vec<Complex<f64>>,
    /// Rotations from the tick start to each in-tick offset of `offsets`.
    rot_offsets: Vec<Vec<Complex<f64>>>,
    z: Vec<Complex<f64>>,
    tick: u64,
    tick_s: f64,
    /// Segment stride of [`Waves::seek_segment`], ticks (0: not set), and exp(iω_i·stride·h).
    stride: u64,
    rot_stride: Vec<Complex<f64>>,
    /// True when `z` was last carried by strides (then a one-tick step must not continue it).
    by_stride: bool,
    /// The segment's node rotations (`rot_offsets` after [`Waves::set_segment`]) as blocks of
    /// [`LANES`] nodes, component after component in a block, real and imaginary parts apart
    /// (padded with zeros): what [`Waves::node_jets`] streams through.
    rot_nodes_re: Vec<[f64; LANES]>,
    rot_nodes_im: Vec<[f64; LANES]>,
    /// Scratch of [`Waves::node_jets`]: per block of nodes, the jet values, each over the block.
    node_jet_blocks: Vec<[f64; LANES]>,
}

impl Waves {
    /// Realises `spec` for ticks of `tick_s`, with extra evaluation points at the fractions
    /// `offsets` of a tick (the quadrature nodes). `None` when the spectrum is `none` or H_s = 0.
    pub fn new(spec: &SeaSpec, seed: u64, tick_s: f64, offsets: &[f64]) -> Option<Self> {
        let (hs, tp) = spec.hs_tp();
        if spec.spectrum == SpectrumKind::None || hs <= 0.0 {
            return None;
        }
        let wp = 2.0 * std::f64::consts::PI / tp;
        let n = spec.components.max(1) as usize;
        let (w0, w1) = (spec.band[0] * wp, spec.band[1] * wp);
        let dw = (w1 - w0) / n as f64;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(SEA_STATE_STREAM);
        let beta = spec.heading_to_waves_deg * DEG;
        let r = &spec.rao;
        let rao = [r.roll, r.pitch, r.yaw, r.heave, r.surge, r.sway];
        let dir = [
            beta.sin().abs(),
            beta.cos().abs(),
            (2.0 * beta).sin().abs(),
            1.0,
            beta.cos().abs(),
            beta.sin().abs(),
        ];
        let (mut omega_rps, mut phase_rad, mut coef) = (vec![], vec![], vec![]);
        for i in 0..n {
            let w = w0 + (i as f64 + rng.random::<f64>()) * dw;
            let eps = 2.0 * std::f64::consts::PI * rng.random::<f64>();
            let s = match spec.spectrum {
                SpectrumKind::Jonswap => jonswap(w, hs, wp, spec.gamma),
                _ => pierson_moskowitz(w, hs, wp),
            };
            let a = (2.0 * s * dw).sqrt();
            let slope = w * w / G_WAVE_MPS2;
            let mut c = [Complex::new(0.0, 0.0); 6];
            for d in 0..6 {
                let h = if rao[d].natural_period_s > 0.0 {
                    let q = w * rao[d].natural_period_s / (2.0 * std::f64::consts::PI);
                    Complex::new(1.0 - q * q, 2.0 * rao[d].damping * q).inv()
                } else {
                    Complex::new(1.0, 0.0)
                };
                // Angles follow the wave slope, a quarter period ahead of the elevation.
                let forcing = if d < 3 {
                    Complex::new(0.0, slope)
                } else {
                    Complex::new(1.0, 0.0)
                };
                c[d] = forcing * h * (a * rao[d].gain * dir[d]);
            }
            omega_rps.push(w);
            phase_rad.push(eps);
            coef.push(c);
        }
        let rot = |f: f64| -> Vec<Complex<f64>> {
            omega_rps
                .iter()
                .map(|w| Complex::from_polar(1.0, w * f * tick_s))
                .collect()
        };
        let factors = |w: f64, c: &[Complex<f64>; 6]| -> [Complex<f64>; JET_LEN] {
            std::array::from_fn(|j| match j / 6 {
                0 => c[j],
                1 => Complex::new(0.0, w) * c[j - 6],
                _ => -(w * w) * c[j - 12],
            })
        };
        let jets: Vec<_> = omega_rps
            .iter()
            .zip(&coef)
            .map(|(w, c)| factors(*w, c))
            .collect();
        let mut me = Self {
            jet_re: jets.iter().map(|f| f.map(|c| c.re)).collect(),
            jet_im: jets.iter().map(|f| f.map(|c| c.im)).collect(),
            rot_tick: rot(1.0),
            rot_offsets: offsets.iter().map(|&f| rot(f)).collect(),
            z: vec![Complex::new(1.0, 0.0); n],
            omega_rps,
            phase_rad,
            coef,
            tick: 0,
            tick_s,
            stride: 0,
            rot_stride: vec![],
            by_stride: false,
            rot_nodes_re: vec![],
            rot_nodes_im: vec![],
            node_jet_blocks: vec![],
        };
        me.resync(0);
        Some(me)
    }

    /// Component frequencies, rad/s.
    pub fn omega_rps(&self) -> &[f64] {
        &self.omega_rps
    }

    /// Complex amplitudes c_{d,i} of component i.
    pub fn coef(&self, i: usize) -> &[Complex<f64>; 6] {
        &self.coef[i]
    }

    /// Phases ε_i, rad.
    pub fn phase_rad(&self) -> &[f64] {
        &self.phase_rad
    }

    /// Highest component frequency, rad/s.
    pub fn omega_top_rps(&self) -> f64 {
        self.omega_rps.iter().fold(0.0, |a, &w| a.max(w))
    }

    /// Sets the segment stride of [`Waves::seek_segment`] (a divisor of [`RESYNC_TICKS`]) and
    /// the in-segment offsets (in ticks from the segment start) that `jet(Some(j))` evaluates.
    pub fn set_segment(&mut self, stride: u64, offsets_ticks: &[f64]) {
        assert!(
            stride > 0 && RESYNC_TICKS.is_multiple_of(stride),
            "stride {stride}"
        );
        self.stride = stride;
        let h = self.tick_s;
        let rot = |f: f64| -> Vec<Complex<f64>> {
            self.omega_rps
                .iter()
                .map(|w| Complex::from_polar(1.0, w * f * h))
                .collect()
        };
        self.rot_stride = rot(stride as f64);
        self.rot_offsets = offsets_ticks.iter().map(|&f| rot(f)).collect();
        let blocks = offsets_ticks.len().div_ceil(LANES);
        let part = |b: usize, i: usize, re: bool| -> [f64; LANES] {
            std::array::from_fn(|l| {
                self.rot_offsets
                    .get(b * LANES + l)
                    .map_or(0.0, |r| if re { r[i].re } else { r[i].im })
            })
        };
        let nc = self.omega_rps.len();
        let pairs = || (0..blocks).flat_map(|b| (0..nc).map(move |i| (b, i)));
        self.rot_nodes_re = pairs().map(|(b, i)| part(b, i, true)).collect();
        self.rot_nodes_im = pairs().map(|(b, i)| part(b, i, false)).collect();
        self.by_stride = false;
        self.resync(0);
    }

    /// Moves the phasors to segment start `tick` (a multiple of the stride): one product per
    /// component from the previous segment, else from the last resynchronisation point by
    /// strides. So z there is a function of the tick alone (not the same bits as [`Waves::seek`]
    /// carries, which is why a one-tick step never continues a stride-carried z).
    pub fn seek_segment(&mut self, tick: u64) {
        let m = self.stride;
        debug_assert!(m > 0 && tick.is_multiple_of(m));
        if self.by_stride && tick == self.tick {
            return;
        }
        let step = |me: &mut Self| {
            me.z.iter_mut()
                .zip(&me.rot_stride)
                .for_each(|(z, r)| *z *= r);
            me.tick += m;
        };
        if self.by_stride && tick == self.tick.wrapping_add(m) && !tick.is_multiple_of(RESYNC_TICKS)
        {
            step(self);
            return;
        }
        self.resync(tick - tick % RESYNC_TICKS);
        while self.tick < tick {
            step(self);
        }
        self.by_stride = true;
    }

    fn resync(&mut self, tick: u64) {
        let t = tick as f64 * self.tick_s;
        for ((z, w), e) in self.z.iter_mut().zip(&self.omega_rps).zip(&self.phase_rad) {
            *z = Complex::from_polar(1.0, w * t + e);
        }
        self.tick = tick;
    }

    /// Moves the phasors to tick `tick`: one product per component when stepping forward by one
    /// tick; otherwise from the last resynchronisation point.
    pub fn seek(&mut self, tick: u64) {
        if tick == self.tick && !self.by_stride {
            return;
        }
        if !self.by_stride
            && tick == self.tick.wrapping_add(1)
            && !tick.is_multiple_of(RESYNC_TICKS)
        {
            self.z
                .iter_mut()
                .zip(&self.rot_tick)
                .for_each(|(z, r)| *z *= r);
            self.tick = tick;
            return;
        }
        let base = tick - tick % RESYNC_TICKS;
        self.resync(base);
        self.by_stride = false;
        while self.tick < tick {
            self.z
                .iter_mut()
                .zip(&self.rot_tick)
                .for_each(|(z, r)| *z *= r);
            self.tick += 1;
        }
    }

    /// The jet at the current tick (`offset = None`) or at in-tick offset number `offset`.
    pub fn jet(&self, offset: Option<usize>) -> SeaJet {
        let rot = offset.map(|o| &self.rot_offsets[o][..]);
        SeaJet::from_flat(&jet_sum(&self.z, rot, &self.jet_re, &self.jet_im))
    }

    /// The jets at every in-segment offset of [`Waves::set_segment`] into `out`: the values
    /// `jet(Some(j))` gives, bit for bit, with the nodes side by side in the vector lanes.
    pub fn node_jets(&mut self, out: &mut Vec<SeaJet>) {
        let n = self.rot_offsets.len();
        let blocks = n.div_ceil(LANES);
        self.node_jet_blocks.resize(blocks * JET_LEN, [0.0; LANES]);
        let x = NodeJetInputs {
            z: &self.z,
            rot_re: &self.rot_nodes_re,
            rot_im: &self.rot_nodes_im,
            re: &self.jet_re,
            im: &self.jet_im,
        };
        node_jets(&x, &mut self.node_jet_blocks);
        out.clear();
        out.extend((0..n).map(|j| {
            let (b, l) = (j / LANES, j % LANES);
            let flat = std::array::from_fn(|v| self.node_jet_blocks[b * JET_LEN + v][l]);
            SeaJet::from_flat(&flat)
        }));
    }

    /// The jet at an arbitrary time (sines and cosines: for checks and trajectory export).
    pub fn jet_at_time(&self, t_s: f64) -> SeaJet {
        let z: Vec<Complex<f64>> = self
            .omega_rps
            .iter()
            .zip(&self.phase_rad)
            .map(|(w, e)| Complex::from_polar(1.0, w * t_s + e))
            .collect();
        SeaJet::from_flat(&jet_sum(&z, None, &self.jet_re, &self.jet_im))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::carrier::segment::{SEGMENT_NODES, SegmentRule};

    #[test]
    fn node_jets_side_by_side_are_each_nodes_jet_bit_for_bit() {
        let spec = SeaSpec {
            spectrum: SpectrumKind::Jonswap,
            sea_state: 5,
            ..SeaSpec::default()
        };
        let mut w = Waves::new(&spec, 7, 0.01, &[]).expect("a sea");
        // 13 nodes: the last block of lanes is part padding.
        for n in [SEGMENT_NODES, 13] {
            let rule = SegmentRule::new(n, 128);
            w.set_segment(128, &rule.node_ticks);
            for tick in [0, 128, 4096 + 256] {
                w.seek_segment(tick);
                let mut jets = Vec::new();
                w.node_jets(&mut jets);
                assert_eq!(jets.len(), n);
                for (j, jet) in jets.iter().enumerate() {
                    let one = w.jet(Some(j));
                    assert_eq!(
                        jet.flat().map(f64::to_bits),
                        one.flat().map(f64::to_bits),
                        "{n} nodes, tick {tick}, node {j}"
                    );
                    assert!(one.x.iter().any(|&x| x != 0.0));
                }
            }
        }
    }
}
