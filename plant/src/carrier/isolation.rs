//! Azimuth isolation: the outer gimbal counter-rotates the carrier's yaw so that the
//! rotation scheme stays fixed in the navigation frame, as the table of a real RINS on a ship
//! does (docs/carrier.md, "Azimuth isolation").
//!
//! The loop sees only what the navigation computer sees: the IMU's measured increments (plus
//! the scheme's own commanded outer angle). It keeps a measured attitude C_b^n by integrating
//! the measured Δθ (two-sample coning correction, the navigation frame turned by ω_in^n), forms
//! the measured azimuth of the outer gimbal frame C_o^n = C_b^n·R_x(inner)ᵀ (the x axis, which
//! R_x leaves where it is: the inner encoder is not needed for it), and counter-rotates its error from the scheme's azimuth exactly
//! over the next output interval (a one-sample servo: the outer offset ramps linearly from its
//! value to the corrected one). The error left is the carrier's yaw during one interval,
//! |ψ̇|·Δt, plus the drift of the measured attitude (the gyros' errors, as any heading).
//!
//! ω_in^n = ω_ie^n + ω_en^n needs the ship's latitude and velocity: a real RINS takes them from
//! its own navigation solution or the ship's log; here they come from the carrier state (their
//! errors would enter as Ω·cos L·δL, below 1e-9 rad/s for a nautical mile). The yaw itself is
//! never taken from the truth; the loop starts from the attitude at the moment it is switched
//! on (as the navigator starts aligned from truth).

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

use crate::attitude::quat_from_rotvec;
use crate::earth::{OMEGA_IE_RPS, radii_of_curvature_sin2};
use crate::table::gimbal::rot_x;
use crate::trig::AngleTrig;

/// Azimuth (counter-clockwise from east, rad) of the x axis of the frame `c` (to ENU), from its
/// horizontal projection.
pub fn azimuth_rad(c: &Matrix3<f64>) -> f64 {
    c[(1, 0)].atan2(c[(0, 0)])
}

/// The horizontal components (C₀₀ east, C₁₀ north) of the x axis of the outer gimbal frame
/// C_o^n = C_b^n·R_x(inner)ᵀ of the body attitude `q_bn`. Its x axis is the body's: R_x leaves
/// the x axis where it is, so the product's first column is C_b^n's and the inner angle drops
/// out. Only the two elements are formed, with the operations of nalgebra's
/// `UnitQuaternion::to_rotation_matrix` (C₀₀ = w² + i² − j² − k², C₁₀ = 2wk + 2ij).
fn outer_x_horizontal(q_bn: &UnitQuaternion<f64>) -> (f64, f64) {
    let [i, j, k, w] = [q_bn.i, q_bn.j, q_bn.k, q_bn.w];
    (w * w + i * i - j * j - k * k, w * k * 2.0 + i * j * 2.0)
}

/// Azimuth of the outer gimbal frame of `q_bn` ([`azimuth_rad`] of C_o^n, bit for bit).
#[cfg(test)]
fn outer_azimuth_rad(q_bn: &UnitQuaternion<f64>) -> f64 {
    let (c00, c10) = outer_x_horizontal(q_bn);
    c10.atan2(c00)
}

/// Azimuth of the outer gimbal frame of `q_bn` ([`outer_x_horizontal`]) less `target_rad`,
/// wrapped into (−π, π]: the angle of the frame's horizontal x direction turned back by the
/// target. The loop holds that error to a yaw step (below 1e-2 rad), where an odd series of
/// the arctangent to r⁹ (next term below 1e-20 relative) replaces atan2; larger errors take
/// atan2.
#[cfg(test)]
fn outer_azimuth_error_rad(q_bn: &UnitQuaternion<f64>, target_rad: f64) -> f64 {
    outer_azimuth_error_from(q_bn, target_rad.sin_cos())
}

/// [`outer_azimuth_error_rad`] with the target's sine and cosine `(st, ct)` given.
#[inline]
fn outer_azimuth_error_from(q_bn: &UnitQuaternion<f64>, (st, ct): (f64, f64)) -> f64 {
    let (c00, c10) = outer_x_horizontal(q_bn);
    let (x, y) = (c00 * ct + c10 * st, c10 * ct - c00 * st);
    if x > 0.0 && y.abs() <= 1e-3 * x {
        // Below a milliradian (the loop's usual error) to r⁵: the next term is below 2e-19
        // relative.
        let r = y / x;
        let r2 = r * r;
        r * (1.0 - r2 * (1.0 / 3.0 - r2 * (1.0 / 5.0)))
    } else if x > 0.0 && y.abs() <= 1e-2 * x {
        let r = y / x;
        let r2 = r * r;
        r * (1.0 - r2 * (1.0 / 3.0 - r2 * (1.0 / 5.0 - r2 * (1.0 / 7.0 - r2 * (1.0 / 9.0)))))
    } else {
        y.atan2(x)
    }
}

/// The quaternion of a sample's small rotation `v` (the coning-corrected increment): the
/// series of [`quat_from_rotvec`] with products by the reciprocals of its constants instead of
/// divisions (a few ulp apart), the closed form beyond 1e-2 rad.
#[inline]
fn small_rotation(v: &Vector3<f64>) -> UnitQuaternion<f64> {
    let n2 = v.norm_squared();
    if n2 > 1e-4 {
        return UnitQuaternion::from_scaled_axis(*v);
    }
    let c = 1.0 - n2 * (1.0 / 8.0) + n2 * n2 * (1.0 / 384.0);
    let s = 0.5 - n2 * (1.0 / 48.0) + n2 * n2 * (1.0 / 3840.0);
    UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(c, s * v.x, s * v.y, s * v.z))
}

/// The navigation frame's turn over an output interval of `dt_s`, as the quaternion that
/// carries an attitude C_b^n over it: the rotation vector −ω_in^n·Δt, with
/// ω_in^n = ω_ie^n + ω_en^n at latitude `lat_rad`, height `height_m` and velocity `v_n` (ENU).
pub fn nav_frame_turn(
    lat_rad: f64,
    height_m: f64,
    v_n: &Vector3<f64>,
    dt_s: f64,
) -> UnitQuaternion<f64> {
    // One sine for both (`f64::sin_cos` is `(sin, cos)`: the radii's own `sin` bits).
    let (sl, cl) = lat_rad.sin_cos();
    let (rm, rn) = radii_of_curvature_sin2(sl * sl);
    let w_in = Vector3::new(
        -v_n.y / (rm + height_m),
        OMEGA_IE_RPS * cl + v_n.x / (rn + height_m),
        OMEGA_IE_RPS * sl + v_n.x * sl / cl / (rn + height_m),
    );
    quat_from_rotvec(&(-w_in * dt_s))
}

/// The outer offset over one output interval of a loop: what a seed's own table needs from
/// it, and from the reference table's loop, to turn the reference's increments
/// (`crate::carrier::own_table`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntervalOffset {
    /// The offset at the interval's middle, rad.
    pub mid_rad: f64,
    /// Its change over the interval, rad.
    pub step_rad: f64,
    /// The offset at the interval's end, rad.
    pub end_rad: f64,
    /// Its rate at the interval's end, rad/s.
    pub end_rps: f64,
}

/// The isolation loop's state (no `PartialEq`: it holds a cache).
#[derive(Clone, Debug)]
pub struct Isolation {
    /// Counter-rotating (true) or holding the last offset (switched off by a command).
    pub active: bool,
    /// Measured body attitude q_b^n.
    q_bn: UnitQuaternion<f64>,
    /// Previous measured Δθ (coning correction), rad.
    prev_dtheta: Vector3<f64>,
    /// Azimuth of the outer frame at scheme angle 0, rad: the target is az0 + scheme outer.
    az0_rad: f64,
    /// Outer offset at the start and end of the current output interval, rad.
    from_rad: f64,
    to_rad: f64,
    /// Offset rate at the start and end of the current interval, rad/s.
    from_rps: f64,
    to_rps: f64,
    /// Internal tick at which the current interval starts.
    start_tick: u64,
    /// The target azimuth's sine and cosine, held while the scheme's outer angle holds (a
    /// cache: not part of the saved state).
    target: AngleTrig,
}

impl Isolation {
    /// A loop started at internal tick `tick` with body attitude `c_bn`, inner angle
    /// `inner_rad`, scheme outer angle `scheme_outer_rad` and the outer offset already applied
    /// `offset_rad` (held as the target: the table stays where it is in the navigation frame).
    pub fn new(
        c_bn: &Matrix3<f64>,
        inner_rad: f64,
        scheme_outer_rad: f64,
        offset_rad: f64,
        tick: u64,
    ) -> Self {
        let c_on = c_bn * rot_x(inner_rad).transpose();
        Self {
            active: true,
            // The loop's own (measured) attitude starts from the matrix it is given.
            q_bn: crate::attitude::quaternion_of(c_bn),
            prev_dtheta: Vector3::zeros(),
            az0_rad: azimuth_rad(&c_on) - scheme_outer_rad,
            from_rad: offset_rad,
            to_rad: offset_rad,
            from_rps: 0.0,
            to_rps: 0.0,
            start_tick: tick,
            target: AngleTrig::default(),
        }
    }

    /// Outer offset at (fractional) internal tick `tick`, with `ticks` internal ticks per output
    /// interval of `dt_s`: the cubic Hermite between the interval's end offsets with the rate
    /// carried over from the previous interval at its start and the interval's mean rate at its
    /// end, so the offset's rate is continuous (a rate step at every sample would excite the
    /// navigator's coning and sculling algorithms at sea).
    pub fn offset_at(&self, tick: f64, ticks: f64, dt_s: f64) -> f64 {
        let x = ((tick - self.start_tick as f64) / ticks).clamp(0.0, 1.0);
        let (x2, x3) = (x * x, x * x * x);
        (2.0 * x3 - 3.0 * x2 + 1.0) * self.from_rad
            + (x3 - 2.0 * x2 + x) * dt_s * self.from_rps
            + (3.0 * x2 - 2.0 * x3) * self.to_rad
            + (x3 - x2) * dt_s * self.to_rps
    }

    /// Rate of [`Isolation::offset_at`], rad/s.
    pub fn rate_at(&self, tick: f64, ticks: f64, dt_s: f64) -> f64 {
        let x = ((tick - self.start_tick as f64) / ticks).clamp(0.0, 1.0);
        let x2 = x * x;
        ((6.0 * x2 - 6.0 * x) * self.from_rad + (6.0 * x - 6.0 * x2) * self.to_rad) / dt_s
            + (3.0 * x2 - 4.0 * x + 1.0) * self.from_rps
            + (3.0 * x2 - 2.0 * x) * self.to_rps
    }

    /// Outer offset at internal tick `tick` (between output intervals: the table's offset now),
    /// with `ticks` internal ticks per output interval, rad.
    pub fn offset_rad(&self, tick: u64, ticks: u64) -> f64 {
        let x = (tick.saturating_sub(self.start_tick)) as f64 / ticks as f64;
        if x >= 1.0 {
            self.to_rad
        } else if x <= 0.0 {
            self.from_rad
        } else {
            self.offset_at(tick as f64, ticks as f64, 1.0)
        }
    }

    /// The offset over the current output interval of `dt_s`, before [`Isolation::update`]
    /// closes it.
    #[inline]
    pub fn interval_offset(&self, dt_s: f64) -> IntervalOffset {
        IntervalOffset {
            // [`Isolation::offset_at`] at the middle, x = ½: the Hermite basis there is ½, ⅛,
            // ½, −⅛.
            mid_rad: 0.5 * (self.from_rad + self.to_rad)
                + 0.125 * dt_s * (self.from_rps - self.to_rps),
            step_rad: self.to_rad - self.from_rad,
            end_rad: self.to_rad,
            end_rps: self.to_rps,
        }
    }

    /// Outer offset rate at internal tick `tick` between output intervals, rad/s.
    pub fn rate_rps(&self, tick: u64) -> f64 {
        if tick > self.start_tick {
            self.to_rps
        } else {
            self.from_rps
        }
    }

    /// One output interval of `dt_s` has ended at internal tick `tick`: integrates the
    /// measured `dtheta_rad`, measures the outer frame's azimuth and sets the offset at the end of the next interval to cancel its error against the
    /// scheme's commanded outer angle. `lat_rad`, `height_m`, `v_n` give ω_in^n.
    #[allow(clippy::too_many_arguments)]
    pub fn update(
        &mut self,
        dtheta_rad: &Vector3<f64>,
        scheme_outer_rad: f64,
        lat_rad: f64,
        height_m: f64,
        v_n: &Vector3<f64>,
        dt_s: f64,
        tick: u64,
    ) {
        let nav = nav_frame_turn(lat_rad, height_m, v_n, dt_s);
        self.update_with(dtheta_rad, &nav, scheme_outer_rad, dt_s, tick);
    }

    /// [`Isolation::update`] with the navigation frame's turn over the interval already formed
    /// ([`nav_frame_turn`]): the loops of several seeds on one carrier share it.
    #[inline(always)]
    pub fn update_with(
        &mut self,
        dtheta_rad: &Vector3<f64>,
        nav: &UnitQuaternion<f64>,
        scheme_outer_rad: f64,
        dt_s: f64,
        tick: u64,
    ) {
        self.from_rad = self.to_rad;
        self.from_rps = self.to_rps;
        self.start_tick = tick;
        if !self.active {
            self.to_rps = 0.0;
            return;
        }
        // Two-sample coning correction (the wave motion cones at ~1e-3 rad/s).
        // Products by reciprocals, no division: the loop closes a chain from one sample to the
        // next (the offset it sets moves the next increment), where a division's latency counts.
        let phi = dtheta_rad + self.prev_dtheta.cross(dtheta_rad) * (1.0 / 12.0);
        self.prev_dtheta = *dtheta_rad;
        let q = nav * self.q_bn * small_rotation(&phi);
        // The azimuth from the product before it is renormalised: C₀₀ and C₁₀ scale alike with
        // |q|², so their ratio, all the error reads, is the same, and the renormalisation is
        // off the chain to the next offset.
        let target = self.target.at(self.az0_rad + scheme_outer_rad);
        let err = outer_azimuth_error_from(&q, target);
        self.q_bn = q;
        self.q_bn.renormalize_fast();
        self.to_rad -= err;
        // The end rate: the interval's mean rate (the ramp of a one-sample servo).
        self.to_rps = (self.to_rad - self.from_rad) * (1.0 / dt_s);
    }

    /// Writes the loop's state (see [`Isolation::read`]).
    pub(crate) fn write(&self, w: &mut crate::state::Writer) {
        w.u64(self.active as u64);
        for x in [self.q_bn.w, self.q_bn.i, self.q_bn.j, self.q_bn.k] {
            w.f64(x);
        }
        for x in self.prev_dtheta.iter() {
            w.f64(*x);
        }
        w.f64(self.az0_rad);
        w.f64(self.from_rad);
        w.f64(self.to_rad);
        w.f64(self.from_rps);
        w.f64(self.to_rps);
        w.u64(self.start_tick);
    }

    /// Reads what [`Isolation::write`] wrote.
    pub(crate) fn read(r: &mut crate::state::Reader<'_>) -> Result<Self, crate::state::StateError> {
        let active = r.u64()? != 0;
        let (w, i, j, k) = (r.f64()?, r.f64()?, r.f64()?, r.f64()?);
        let q_bn = UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(w, i, j, k));
        let prev_dtheta = Vector3::new(r.f64()?, r.f64()?, r.f64()?);
        Ok(Self {
            active,
            q_bn,
            prev_dtheta,
            az0_rad: r.f64()?,
            from_rad: r.f64()?,
            to_rad: r.f64()?,
            from_rps: r.f64()?,
            to_rps: r.f64()?,
            start_tick: r.u64()?,
            target: AngleTrig::default(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `x` wrapped into [-π, π).
    fn wrap(x: f64) -> f64 {
        (x + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
    }

    /// The azimuth error by the series equals the wrapped difference of the azimuths to a few
    /// ulp of π, small and large, across the ±π seam.
    #[test]
    fn the_azimuth_error_is_the_wrapped_difference_of_the_azimuths() {
        for k in 0..20_000u32 {
            let a = f64::from(k);
            let q = UnitQuaternion::from_euler_angles(
                (a * 0.61).sin() * 0.2,
                (a * 0.37).cos() * 0.2,
                (a * 0.13).sin() * 3.1,
            );
            // Targets within a yaw step of the azimuth (the series), and anywhere (atan2).
            let az = outer_azimuth_rad(&q);
            for target in [
                az + (a * 0.71).sin() * 1e-2,
                az - 3e-5,
                (a * 0.29).cos() * 3.2,
            ] {
                let want = wrap(az - target);
                let got = outer_azimuth_error_rad(&q, target);
                let d = wrap(got - want).abs();
                assert!(d < 4e-15, "{k}: {got} against {want}");
            }
        }
    }

    /// The azimuth from two elements of C_b^n is the azimuth of the whole outer frame
    /// C_b^n·R_x(inner)ᵀ, bit for bit, for attitudes all round and any inner angle.
    #[test]
    fn the_outer_azimuth_from_two_elements_equals_the_whole_frames() {
        for k in 0..20_000u32 {
            let a = f64::from(k);
            let q = UnitQuaternion::from_euler_angles(
                (a * 0.61).sin() * 3.1,
                (a * 0.37).cos() * 1.5,
                (a * 0.13).sin() * 3.1,
            );
            let inner = (a * 0.07).sin() * 6.0;
            let whole = q.to_rotation_matrix().into_inner() * rot_x(inner).transpose();
            assert_eq!(
                outer_azimuth_rad(&q).to_bits(),
                azimuth_rad(&whole).to_bits(),
                "{k}"
            );
        }
    }
}
