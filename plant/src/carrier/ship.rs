//! The ship carrier: the mean track ([`super::track`]) plus sea-state motion ([`super::waves`]).
//!
//! Attitude C_c^n = R_z(−(ψ + ψ_w))·R_x(θ_w)·R_y(φ_w) (course ψ clockwise from north, wave yaw
//! ψ_w, pitch θ_w, roll φ_w; carrier axes x starboard, y bow, z up). Surge s and sway w displace
//! the reference point along the course frame: east = w cos ψ + s sin ψ, north = −w sin ψ + s cos ψ;
//! heave displaces it up. Velocities and accelerations are the exact time derivatives of these
//! (with the course rate ψ̇ in the frame terms).
//!
//! The sea-state jet is evaluated with phasors once per tick; inside a tick the six degrees of
//! freedom are quintic Hermite interpolants of the jets at the tick ends (error O((ωh)⁶), below
//! 1e-13 of the amplitude at 100 Hz for wave periods above 2 s). Inside a tick no sine, cosine
//! or square root is taken (see [`Ship::advance`]).

use nalgebra::{Matrix3, Vector3};

use super::carrier_state::{CarrierState, quintic_basis};
use super::spec::ShipSpec;
use super::track::{Track, TrackPoint, TrackPosition};
use super::waves::{JET_LEN, SeaJet, Waves, dof};
use crate::earth::{EarthPoint, LocalEarth};
use crate::trig::{SMALL_STEP_RAD, WIDE_STEP_RAD, sin_cos_step, sin_cos_step_wide};
use crate::units::DEG;

/// The ship, advanced tick by tick.
#[derive(Clone, Debug)]
pub struct Ship {
    pub(super) track: Track,
    pub(super) waves: Option<Waves>,
    /// True when the waves are drawn from the run's seed ([`super::SeaRealisation::PerRun`]).
    pub(super) waves_per_run: bool,
    pub(super) height_m: f64,
    pub(super) tick_s: f64,
    pub(super) start: TrackPosition,
    /// Mean-track position at tick `tick`.
    pub(super) pos: TrackPosition,
    pub(super) tick: u64,
    pub(super) leg_hint: usize,
    /// Sea jet at tick `tick`.
    pub(super) jet_now: SeaJet,
    /// Earth quantities about the mean-track position at tick `tick` (a function of it).
    pub(super) earth: LocalEarth,
    /// Those at that position.
    pub(super) earth_now: EarthPoint,
    /// The composition angles at tick `tick` with their exact sines and cosines.
    pub(super) trig_now: Trig,
    /// In-tick evaluation points, fractions of a tick.
    offsets: Vec<f64>,
    /// Quintic Hermite weights at those points, per output (value, rate, acceleration) and per
    /// end datum (x₀, ẋ₀, ẍ₀, x₁, ẋ₁, ẍ₁), with the tick length folded in.
    basis: Vec<[[f64; 6]; 3]>,
    /// The segment rule's state (`None`: the exact per-tick path).
    pub(super) seg: Option<Box<super::segment::SegState>>,
}

impl Ship {
    /// The ship for ticks of `tick_s`, with in-tick evaluation points at the fractions `offsets`.
    pub fn new(spec: &ShipSpec, seed: u64, tick_s: f64, offsets: &[f64]) -> Self {
        let start = TrackPosition {
            lat_rad: spec.lat_deg * DEG,
            lon_rad: spec.lon_deg * DEG,
        };
        let waves = Waves::new(&spec.sea, spec.sea.realisation_seed(seed), tick_s, &[]);
        let jet_now = waves.as_ref().map(|w| w.jet(None)).unwrap_or_default();
        let h = tick_s;
        let scale = [
            [1.0, h, h * h],
            [1.0 / h, 1.0, h],
            [1.0 / (h * h), 1.0 / h, 1.0],
        ];
        let basis = offsets
            .iter()
            .map(|&t| {
                let b = quintic_basis(t);
                std::array::from_fn(|r| std::array::from_fn(|m| b[r][m] * scale[r][m % 3]))
            })
            .collect();
        let mut me = Self {
            track: Track::new(spec),
            waves,
            waves_per_run: spec.sea.realisation == super::SeaRealisation::PerRun,
            height_m: spec.height_m,
            tick_s,
            start,
            pos: start,
            tick: 0,
            leg_hint: 0,
            jet_now,
            earth: LocalEarth::near(start.lat_rad),
            earth_now: LocalEarth::near(start.lat_rad).at(start.lat_rad),
            trig_now: Trig::default(),
            offsets: offsets.to_vec(),
            basis,
            seg: None,
        };
        me.set_position(0, start);
        me
    }

    /// The mean track.
    pub fn track(&self) -> &Track {
        &self.track
    }

    /// Tick length, s.
    pub fn tick_s(&self) -> f64 {
        self.tick_s
    }

    /// The sea state, if any.
    pub fn waves(&self) -> Option<&Waves> {
        self.waves.as_ref()
    }

    /// Mean-track position at the current tick and that tick (for the state codec).
    pub fn position(&self) -> (u64, TrackPosition) {
        (self.tick, self.pos)
    }

    /// The Earth expansion the ship uses now (it covers the carrier's recent states).
    pub fn earth(&self) -> &LocalEarth {
        &self.earth
    }

    /// Restores the mean-track position at `tick` (from [`Ship::position`]).
    pub fn set_position(&mut self, tick: u64, pos: TrackPosition) {
        self.tick = tick;
        self.pos = pos;
        self.leg_hint = 0;
        self.earth = LocalEarth::near(pos.lat_rad);
        self.earth_now = self.earth.at(pos.lat_rad);
        // The sines and cosines as `advance` carried them from the last resync tick.
        for t in tick - tick % TRIG_RESYNC_TICKS..=tick {
            let ang = self.angles_at(t);
            self.trig_now = self.carry_trig(t, ang);
        }
    }

    /// Moves the sea state to tick `t` (setting the jet) and returns the composition angles there.
    fn angles_at(&mut self, t: u64) -> [f64; 4] {
        if let Some(w) = self.waves.as_mut() {
            w.seek(t);
            self.jet_now = w.jet(None);
        }
        let tp = self.track_at(t as f64 * self.tick_s);
        angles(&tp, &self.jet_now)
    }

    /// Sines and cosines of the angles `ang` at tick `t`: exact at multiples of
    /// [`TRIG_RESYNC_TICKS`], else carried from the previous tick's by the series of
    /// [`Trig::near`]. So they depend on the tick alone, and the carried rounding (an ulp or two
    /// per tick) is bounded: below 1e-14 after 63 ticks.
    fn carry_trig(&self, t: u64, ang: [f64; 4]) -> Trig {
        if t.is_multiple_of(TRIG_RESYNC_TICKS) {
            Trig::exact(ang)
        } else {
            self.trig_now.near(ang)
        }
    }

    pub(super) fn track_at(&mut self, t_s: f64) -> TrackPoint {
        self.leg_hint = self.track.leg_at(t_s, self.leg_hint);
        self.track.eval(self.leg_hint, t_s)
    }

    /// State at the current tick (from the tick, the position and what `advance` or
    /// `set_position` derived from them: a restored ship continues bit for bit).
    pub fn state_now(&mut self) -> CarrierState {
        if let Some(s) = self.segment_state_now() {
            return s;
        }
        let t = self.tick as f64 * self.tick_s;
        let tp = self.track_at(t);
        compose_with(
            &tp,
            self.pos,
            self.height_m,
            &self.jet_now,
            &self.earth,
            &self.earth_now,
            &self.trig_now,
        )
    }

    /// Advances from tick k = the current tick to k + 1; returns the states at the in-tick
    /// offsets (in `nodes`) and at tick k + 1.
    ///
    /// No sine, cosine or square root is taken (but one tick in [`TRIG_RESYNC_TICKS`]): the
    /// angles' sines and cosines are series about their values at tick k (the angles move by
    /// < 0.01 rad in a tick; beyond that they are exact), the Earth quantities come from the
    /// [`LocalEarth`] expansion and the sea state inside the tick from the quintic Hermite of
    /// the jets at k and k + 1. Everything is a function of (k + 1, position) alone.
    pub fn advance(&mut self, nodes: &mut [CarrierState]) -> CarrierState {
        let (k, h) = (self.tick, self.tick_s);
        let t0 = k as f64 * h;
        // Mean-track displacement over the tick: Gauss–Legendre on the closed-form velocity.
        let g = 3f64.sqrt() / 6.0;
        let gl = [t0 + (0.5 - g) * h, t0 + (0.5 + g) * h];
        let gl_tp = gl.map(|t| self.track_at(t));
        let gl_sc = gl_tp.map(|tp| self.trig_now.near_one(0, tp.psi_rad));
        let v = |tp: &TrackPoint, (s, c): (f64, f64)| (tp.speed_mps * s, tp.speed_mps * c);
        let (v0, v1) = (v(&gl_tp[0], gl_sc[0]), v(&gl_tp[1], gl_sc[1]));
        let (d_e, d_n) = (0.5 * h * (v0.0 + v1.0), 0.5 * h * (v0.1 + v1.1));
        let p0 = self.pos;
        let (dlat, dlon, mid) =
            self.pos
                .advance_from(&self.earth, &self.earth_now, d_n, d_e, self.height_m);
        self.tick = k + 1;
        let jet1 = match self.waves.as_mut() {
            Some(w) => {
                w.seek(k + 1);
                w.jet(None)
            }
            None => SeaJet::default(),
        };
        let jet0 = self.jet_now;
        let (f0, f1) = (jet0.flat(), jet1.flat());
        for (j, node) in nodes.iter_mut().enumerate() {
            let tau = self.offsets[j];
            // The nodes are usually the Gauss–Legendre points just evaluated.
            let t = t0 + tau * h;
            let tp = match gl.iter().position(|&x| x == t) {
                Some(i) => gl_tp[i],
                None => self.track_at(t),
            };
            let pos = TrackPosition {
                lat_rad: p0.lat_rad + tau * dlat,
                lon_rad: p0.lon_rad + tau * dlon,
            };
            let jet = if self.waves.is_some() {
                hermite_jet(&self.basis[j], &f0, &f1)
            } else {
                SeaJet::default()
            };
            let trig = self.trig_now.near(angles(&tp, &jet));
            // The radii at the mid-tick latitude: they differ from those at the node's by
            // < 2e-10 relative, which moves the node's latitude (a wave displacement of metres
            // over R) by < 1e-16 rad.
            *node = compose_with(&tp, pos, self.height_m, &jet, &self.earth, &mid, &trig);
        }
        self.jet_now = jet1;
        let tp1 = self.track_at(self.tick as f64 * h);
        self.trig_now = self.carry_trig(self.tick, angles(&tp1, &jet1));
        if self.earth.lat0_rad() != LocalEarth::grid_lat_rad(self.pos.lat_rad) {
            self.earth = LocalEarth::near(self.pos.lat_rad);
        }
        self.earth_now = self.earth.at(self.pos.lat_rad);
        compose_with(
            &tp1,
            self.pos,
            self.height_m,
            &jet1,
            &self.earth,
            &self.earth_now,
            &self.trig_now,
        )
    }

    /// Restarts from tick 0 (for re-runs).
    pub fn reset(&mut self) {
        self.set_position(0, self.start);
        self.restart_segments();
    }
}

/// The composition angles: course ψ, a = −(ψ + ψ_w), pitch θ_w, roll φ_w.
#[inline]
pub(super) fn angles(tp: &TrackPoint, jet: &SeaJet) -> [f64; 4] {
    [
        tp.psi_rad,
        -(tp.psi_rad + jet.x[dof::YAW]),
        jet.x[dof::PITCH],
        jet.x[dof::ROLL],
    ]
}

/// The composition angles' sines and cosines are exact at multiples of this tick count and
/// carried tick to tick by `Trig::near` in between.
pub const TRIG_RESYNC_TICKS: u64 = 64;

/// Angles with their sines and cosines.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trig {
    ang: [f64; 4],
    pub(super) sin: [f64; 4],
    pub(super) cos: [f64; 4],
}

impl Default for Trig {
    /// No angle known (NaN angles match nothing in `Trig::exact`).
    fn default() -> Self {
        Self {
            ang: [f64::NAN; 4],
            sin: [f64::NAN; 4],
            cos: [f64::NAN; 4],
        }
    }
}

impl Trig {
    /// Exact sines and cosines.
    pub(super) fn exact(ang: [f64; 4]) -> Self {
        let mut t = Self {
            ang,
            ..Self::default()
        };
        for (i, a) in ang.iter().enumerate() {
            (t.sin[i], t.cos[i]) = a.sin_cos();
        }
        t
    }

    /// sin and cos of `a` from those of angle `i` by the addition theorem with the series of
    /// the small step δ = a − angᵢ (exact sin_cos beyond [`SMALL_STEP_RAD`]; within a tick the
    /// angles move by |rate|·h: below 5e-3 rad for ship motion at 100 Hz).
    #[inline]
    fn near_one(&self, i: usize, a: f64) -> (f64, f64) {
        let d = a - self.ang[i];
        if d == 0.0 {
            // The course on a straight leg, a degree of freedom without motion: the series
            // would give these bits too.
            return (self.sin[i], self.cos[i]);
        }
        if d.abs() > SMALL_STEP_RAD {
            return a.sin_cos();
        }
        sin_cos_step(self.sin[i], self.cos[i], d)
    }

    /// All four angles up to [`WIDE_STEP_RAD`] from these, by the series of
    /// [`sin_cos_step_wide`] (exact sin_cos beyond): the ship's segment nodes, each from the one
    /// before.
    pub(super) fn near_wide(&self, ang: [f64; 4]) -> Self {
        let mut t = Self {
            ang,
            ..Self::default()
        };
        for (i, a) in ang.iter().enumerate() {
            let d = a - self.ang[i];
            (t.sin[i], t.cos[i]) = if d == 0.0 {
                (self.sin[i], self.cos[i])
            } else if d.abs() <= WIDE_STEP_RAD {
                sin_cos_step_wide(self.sin[i], self.cos[i], d)
            } else {
                a.sin_cos()
            };
        }
        t
    }

    /// All four angles near these (see [`Trig::near_one`]).
    #[inline]
    fn near(&self, ang: [f64; 4]) -> Self {
        let mut t = Self {
            ang,
            ..Self::default()
        };
        for (i, a) in ang.iter().enumerate() {
            (t.sin[i], t.cos[i]) = self.near_one(i, *a);
        }
        t
    }
}

/// The jet at an in-tick point from the flat jets at the tick ends ([`SeaJet::flat`]) and the
/// point's Hermite weights.
#[inline]
fn hermite_jet(b: &[[f64; 6]; 3], j0: &[f64; JET_LEN], j1: &[f64; JET_LEN]) -> SeaJet {
    let mut out = [0.0; JET_LEN];
    for (r, w) in b.iter().enumerate() {
        for d in 0..6 {
            out[6 * r + d] = w[0] * j0[d]
                + w[1] * j0[6 + d]
                + w[2] * j0[12 + d]
                + w[3] * j1[d]
                + w[4] * j1[6 + d]
                + w[5] * j1[12 + d];
        }
    }
    SeaJet::from_flat(&out)
}

/// The carrier state from the mean track (course, speed, position) and the sea jet, with exact
/// sines and cosines.
pub fn compose(tp: &TrackPoint, pos: TrackPosition, h0_m: f64, jet: &SeaJet) -> CarrierState {
    let trig = Trig::exact(angles(tp, jet));
    let earth = LocalEarth::about(pos.lat_rad);
    compose_with(tp, pos, h0_m, jet, &earth, &earth.at(pos.lat_rad), &trig)
}

/// [`compose`] with the angles' sines and cosines, the Earth expansion and the Earth quantities
/// `e_track` at the mean-track position given.
#[inline]
pub(super) fn compose_with(
    tp: &TrackPoint,
    pos: TrackPosition,
    h0_m: f64,
    jet: &SeaJet,
    earth: &LocalEarth,
    e_track: &EarthPoint,
    trig: &Trig,
) -> CarrierState {
    let (sp, cp) = (trig.sin[0], trig.cos[0]);
    let (u, ud) = (tp.speed_mps, tp.speed_rate_mps2);
    let (w, wd) = (tp.psi_rate_rps, tp.psi_acc_rps2);
    // Surge/sway displacement in the course frame and its derivatives.
    let (s, sd, sdd) = (jet.x[dof::SURGE], jet.xd[dof::SURGE], jet.xdd[dof::SURGE]);
    let (y, yd, ydd) = (jet.x[dof::SWAY], jet.xd[dof::SWAY], jet.xdd[dof::SWAY]);
    // H(ψ)·(sway, surge) = (sway cos ψ + surge sin ψ, −sway sin ψ + surge cos ψ).
    let hmap = |sw: f64, su: f64| (sw * cp + su * sp, -sw * sp + su * cp);
    // J(sway, surge) = (surge, −sway): dH/dψ · x = H · J x.
    let (de, dn) = hmap(y, s);
    let (ve1, vn1) = hmap(yd, sd);
    let (ve2, vn2) = hmap(s, -y);
    let (ae1, an1) = hmap(ydd, sdd);
    let (ae2, an2) = hmap(sd, -yd);
    let height = h0_m + jet.x[dof::HEAVE];
    let lat = pos.lat_rad + dn / (e_track.rm_m + height);
    // Wrapped across the antimeridian (the same bits within ±π).
    let lon = super::track::wrap_lon_rad(
        pos.lon_rad + de / ((e_track.rn_m + height) * earth.sin_cos(lat).1),
    );
    // Mean track: v = u·[sin ψ, cos ψ], v̇ = u̇·[sin ψ, cos ψ] + u·ψ̇·[cos ψ, −sin ψ].
    let v_track = Vector3::new(u * sp, u * cp, 0.0);
    let a_track = Vector3::new(ud * sp + u * w * cp, ud * cp - u * w * sp, 0.0);
    let v_n = v_track + Vector3::new(ve1 + w * ve2, vn1 + w * vn2, jet.xd[dof::HEAVE]);
    let a_n = a_track
        + Vector3::new(
            ae1 + 2.0 * w * ae2 + wd * ve2 - w * w * de,
            an1 + 2.0 * w * an2 + wd * vn2 - w * w * dn,
            jet.xdd[dof::HEAVE],
        );
    // Euler angles of C_c^n = R_z(a)·R_x(b)·R_y(c).
    let (ad, add) = (-(w + jet.xd[dof::YAW]), -(wd + jet.xdd[dof::YAW]));
    let (bd, bdd) = (jet.xd[dof::PITCH], jet.xdd[dof::PITCH]);
    let (cd, cdd) = (jet.xd[dof::ROLL], jet.xdd[dof::ROLL]);
    let (sa, ca) = (trig.sin[1], trig.cos[1]);
    let (sb, cb) = (trig.sin[2], trig.cos[2]);
    let (sc, cc) = (trig.sin[3], trig.cos[3]);
    let (omega, alpha) = euler_zxy_rates([sb, cb, sc, cc], ad, add, bd, bdd, cd, cdd);
    // R_z(a)·R_x(b)·R_y(c) written out.
    let c_cn = Matrix3::new(
        ca * cc - sa * sb * sc,
        -sa * cb,
        ca * sc + sa * sb * cc,
        sa * cc + ca * sb * sc,
        ca * cb,
        sa * sc - ca * sb * cc,
        -cb * sc,
        sb,
        cb * cc,
    );
    CarrierState {
        lat_rad: lat,
        lon_rad: lon,
        height_m: height,
        v_n,
        a_n,
        c_cn,
        omega_nc_c: omega,
        alpha_nc_c: alpha,
    }
}

/// Body rate and its derivative for C = R_z(a)·R_x(b)·R_y(c):
/// ω = R_y(c)ᵀ·u + ċ·e_y with u = [ḃ, ȧ sin b, ȧ cos b];
/// ω̇ = R_y(c)ᵀ·u̇ − ċ·e_y × (R_y(c)ᵀ·u) + c̈·e_y.
/// `sc` holds sin b, cos b, sin c, cos c.
pub fn euler_zxy_rates(
    sc: [f64; 4],
    ad: f64,
    add: f64,
    bd: f64,
    bdd: f64,
    cd: f64,
    cdd: f64,
) -> (Vector3<f64>, Vector3<f64>) {
    let [sb, cb, s_c, c_c] = sc;
    let u = Vector3::new(bd, ad * sb, ad * cb);
    let ud = Vector3::new(bdd, add * sb + ad * bd * cb, add * cb - ad * bd * sb);
    // R_y(c)ᵀ = R_y(−c).
    let ryt = Matrix3::new(c_c, 0.0, -s_c, 0.0, 1.0, 0.0, s_c, 0.0, c_c);
    let ru = ryt * u;
    let ey = Vector3::y();
    let omega = ru + cd * ey;
    let alpha = ryt * ud - cd * ey.cross(&ru) + cdd * ey;
    (omega, alpha)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::carrier::spec::{LegSpec, SpectrumKind};

    /// Sea state 6 (the largest motion) with a turn at the 10°/s limit and a speed change.
    fn rough_ship() -> Ship {
        let mut spec = ShipSpec {
            legs: vec![
                LegSpec {
                    heading_deg: 10.0,
                    speed_kn: 12.0,
                    duration_s: 60.0,
                },
                LegSpec {
                    heading_deg: 250.0,
                    speed_kn: 25.0,
                    duration_s: 1e5,
                },
            ],
            turn_rate_dps: 10.0,
            ..ShipSpec::default()
        };
        spec.sea.spectrum = SpectrumKind::Jonswap;
        spec.sea.sea_state = 6;
        Ship::new(&spec, 7, 0.01, &super::super::GL_OFFSETS)
    }

    #[test]
    // One index into the carried angles, sines, cosines and the angles before the tick.
    #[allow(clippy::needless_range_loop)]
    fn carried_sines_and_tick_end_states_match_the_exact_composition() {
        // The tick-end state against `compose` (libm sines and cosines, the closed-form radii)
        // from the same track point and jet; and the carried sines against libm.
        let mut ship = rough_ship();
        let mut nodes = [ship.state_now(); 2];
        let (mut trig, mut att, mut lat, mut vel) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        let mut step = 0.0f64;
        for _ in 0..120_000 {
            let before = ship.trig_now.ang;
            let s = ship.advance(&mut nodes);
            let t = &ship.trig_now;
            for i in 0..4 {
                let (si, co) = t.ang[i].sin_cos();
                trig = trig.max((t.sin[i] - si).abs()).max((t.cos[i] - co).abs());
                step = step.max((t.ang[i] - before[i]).abs());
            }
            let tp = ship
                .track
                .eval(ship.leg_hint, ship.tick as f64 * ship.tick_s);
            let exact = compose(&tp, ship.pos, ship.height_m, &ship.jet_now);
            att = att.max((s.c_cn - exact.c_cn).amax());
            lat = lat
                .max((s.lat_rad - exact.lat_rad).abs())
                .max((s.lon_rad - exact.lon_rad).abs());
            vel = vel.max((s.v_n - exact.v_n).amax());
        }
        println!(
            "carried sines {trig:.1e} (angle steps up to {step:.1e} rad); tick end vs exact: \
             C_c^n {att:.1e}, lat/lon {lat:.1e} rad, v {vel:.1e} m/s"
        );
        assert!(step > 1e-3, "the ship moved: {step:e}");
        assert!(trig < 1e-14 && att < 1e-14, "{trig:e} {att:e}");
        assert!(lat < 1e-15 && vel < 1e-13, "{lat:e} {vel:e}");
    }
}
