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
//! 1e-13 of the amplitude at 100 Hz for wave periods above 2 s).

use nalgebra::{Matrix3, Vector3};

use super::spec::ShipSpec;
use super::state::{CarrierState, quintic_basis};
use super::track::{Track, TrackPoint, TrackPosition};
use super::waves::{SeaJet, Waves, dof};
use crate::earth::radii_of_curvature;
use crate::units::DEG;

/// The ship, advanced tick by tick.
#[derive(Clone, Debug)]
pub struct Ship {
    track: Track,
    waves: Option<Waves>,
    height_m: f64,
    tick_s: f64,
    start: TrackPosition,
    /// Mean-track position at tick `tick`.
    pos: TrackPosition,
    tick: u64,
    leg_hint: usize,
    /// Sea jet at tick `tick`.
    jet_now: SeaJet,
    /// In-tick evaluation points, fractions of a tick.
    offsets: Vec<f64>,
    /// Quintic basis at those points.
    basis: Vec<[[f64; 6]; 3]>,
}

impl Ship {
    /// The ship for ticks of `tick_s`, with in-tick evaluation points at the fractions `offsets`.
    pub fn new(spec: &ShipSpec, seed: u64, tick_s: f64, offsets: &[f64]) -> Self {
        let start = TrackPosition {
            lat_rad: spec.lat_deg * DEG,
            lon_rad: spec.lon_deg * DEG,
        };
        let waves = Waves::new(&spec.sea, seed, tick_s, &[]);
        let jet_now = waves.as_ref().map(|w| w.jet(None)).unwrap_or_default();
        Self {
            track: Track::new(spec),
            waves,
            height_m: spec.height_m,
            tick_s,
            start,
            pos: start,
            tick: 0,
            leg_hint: 0,
            jet_now,
            offsets: offsets.to_vec(),
            basis: offsets.iter().map(|&t| quintic_basis(t)).collect(),
        }
    }

    /// The mean track.
    pub fn track(&self) -> &Track {
        &self.track
    }

    /// The sea state, if any.
    pub fn waves(&self) -> Option<&Waves> {
        self.waves.as_ref()
    }

    /// Mean-track position at the current tick and that tick (for the state codec).
    pub fn position(&self) -> (u64, TrackPosition) {
        (self.tick, self.pos)
    }

    /// Restores the mean-track position at `tick` (from [`Ship::position`]).
    pub fn set_position(&mut self, tick: u64, pos: TrackPosition) {
        self.tick = tick;
        self.pos = pos;
        self.leg_hint = 0;
        if let Some(w) = self.waves.as_mut() {
            w.seek(tick);
            self.jet_now = w.jet(None);
        }
    }

    fn track_at(&mut self, t_s: f64) -> TrackPoint {
        self.leg_hint = self.track.leg_at(t_s, self.leg_hint);
        self.track.eval(self.leg_hint, t_s)
    }

    /// State at the current tick.
    pub fn state_now(&mut self) -> CarrierState {
        let t = self.tick as f64 * self.tick_s;
        let tp = self.track_at(t);
        compose(&tp, self.pos, self.height_m, &self.jet_now)
    }

    /// Advances from tick k = the current tick to k + 1; returns the states at the in-tick
    /// offsets (in `nodes`) and at tick k + 1.
    pub fn advance(&mut self, nodes: &mut [CarrierState]) -> CarrierState {
        let (k, h) = (self.tick, self.tick_s);
        let t0 = k as f64 * h;
        // Mean-track displacement over the tick: Gauss–Legendre on the closed-form velocity.
        let g = 3f64.sqrt() / 6.0;
        let gl = [t0 + (0.5 - g) * h, t0 + (0.5 + g) * h];
        let gl_tp = gl.map(|t| self.track_at(t));
        let d = 0.5 * h * (gl_tp[0].v_n() + gl_tp[1].v_n());
        let p0 = self.pos;
        let (dlat, dlon) = self.pos.advance(d.y, d.x, self.height_m);
        self.tick = k + 1;
        let jet1 = match self.waves.as_mut() {
            Some(w) => {
                w.seek(k + 1);
                w.jet(None)
            }
            None => SeaJet::default(),
        };
        let jet0 = self.jet_now;
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
                hermite_jet(&self.basis[j], &jet0, &jet1, h)
            } else {
                SeaJet::default()
            };
            *node = compose(&tp, pos, self.height_m, &jet);
        }
        self.jet_now = jet1;
        let tp1 = self.track_at((k + 1) as f64 * h);
        compose(&tp1, self.pos, self.height_m, &jet1)
    }

    /// Restarts from tick 0 (for re-runs).
    pub fn reset(&mut self) {
        self.set_position(0, self.start);
    }
}

/// The jet at an in-tick point from the jets at the tick ends.
fn hermite_jet(b: &[[f64; 6]; 3], j0: &SeaJet, j1: &SeaJet, h: f64) -> SeaJet {
    let mut out = SeaJet::default();
    for d in 0..6 {
        let y = [
            j0.x[d],
            j0.xd[d] * h,
            j0.xdd[d] * h * h,
            j1.x[d],
            j1.xd[d] * h,
            j1.xdd[d] * h * h,
        ];
        let dot = |w: &[f64; 6]| w.iter().zip(&y).map(|(a, b)| a * b).sum::<f64>();
        out.x[d] = dot(&b[0]);
        out.xd[d] = dot(&b[1]) / h;
        out.xdd[d] = dot(&b[2]) / (h * h);
    }
    out
}

/// The carrier state from the mean track (course, speed, position) and the sea jet.
pub fn compose(tp: &TrackPoint, pos: TrackPosition, h0_m: f64, jet: &SeaJet) -> CarrierState {
    let (sp, cp) = tp.psi_rad.sin_cos();
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
    let (rm, rn) = radii_of_curvature(pos.lat_rad);
    let lat = pos.lat_rad + dn / (rm + height);
    let lon = pos.lon_rad + de / ((rn + height) * lat.cos());
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
    let a = -(tp.psi_rad + jet.x[dof::YAW]);
    let (ad, add) = (-(w + jet.xd[dof::YAW]), -(wd + jet.xdd[dof::YAW]));
    let (b, bd, bdd) = (jet.x[dof::PITCH], jet.xd[dof::PITCH], jet.xdd[dof::PITCH]);
    let (c, cd, cdd) = (jet.x[dof::ROLL], jet.xd[dof::ROLL], jet.xdd[dof::ROLL]);
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let (sc, cc) = c.sin_cos();
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
