//! The strapdown equations of one update interval, written once over [`Real`]: for one
//! navigator ([`crate::Strapdown`], `f64`) and for several side by side
//! ([`crate::StrapdownLanes`], [`rins_plant::real::Lanes`]).
//!
//! The operations and their order are those of the nalgebra expressions the navigator was first
//! written with (cross products, `Quaternion` products, `UnitQuaternion::to_rotation_matrix`,
//! matrix-vector products accumulated column by column, `renormalize_fast`), so its results did
//! not change bit for bit; `strapdown::tests` keeps that form as the reference. No closures:
//! a closure does not inherit the target features of the vector build it is inlined into, and
//! its vector operations would become calls.

use nalgebra::{UnitQuaternion, Vector3};
use rins_plant::earth::{OMEGA_IE_RPS, radii_and_gravity_sin2};
use rins_plant::real::{Divisor, Real, Reciprocal};
use rins_plant::trig::GridTrig;

use serde::{Deserialize, Serialize};

/// How the unstable vertical channel is handled.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "mode")]
pub enum VerticalChannel {
    /// Height held at `ref_height_m`, vertical velocity zero (the usual choice for static and
    /// marine INS tests; accelerometer errors then do not reach the vertical).
    Hold {
        /// Reference height, m.
        ref_height_m: f64,
    },
    /// Second-order loop to the reference height: ḣ = v_U − (2/τ)·δh, v̇_U = a_U − δh/τ²
    /// (critically damped, time constant τ).
    Damped {
        /// Reference height, m.
        ref_height_m: f64,
        /// Loop time constant, s.
        tau_s: f64,
    },
}

/// One navigator's solution as the equations use it, and the previous interval's increments
/// (for the coning and sculling terms).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Solution<T> {
    /// q_b^n in nalgebra's storage order (i, j, k, w).
    pub q: [T; 4],
    /// Velocity in ENU, m/s.
    pub v: [T; 3],
    /// Geodetic latitude, rad.
    pub lat: T,
    /// Longitude, rad.
    pub lon: T,
    /// Height, m.
    pub h: T,
    /// Δθ of the previous interval, rad.
    pub prev_dtheta: [T; 3],
    /// Δv of the previous interval, m/s.
    pub prev_dv: [T; 3],
    /// The latitude's grid point for its sine and cosine.
    pub lat_trig: GridTrig<T>,
}

#[inline(always)]
pub(crate) fn cross<T: Real>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
pub(crate) fn add<T: Real>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline(always)]
pub(crate) fn scale<T: Real>(a: &[T; 3], s: T) -> [T; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

#[inline(always)]
fn divide<T: Real>(a: &[T; 3], d: Divisor) -> [T; 3] {
    [a[0].div_by(d), a[1].div_by(d), a[2].div_by(d)]
}

/// The constant divisors of the equations.
const TWELVE: Divisor = Divisor::new(12.0);
const EIGHT: Divisor = Divisor::new(8.0);
const FORTY_EIGHT: Divisor = Divisor::new(48.0);
const SERIES_C4: Divisor = Divisor::new(384.0);
const SERIES_S4: Divisor = Divisor::new(3840.0);

/// Hamilton product a ⊗ b, (i, j, k, w) order.
#[inline(always)]
fn quat_mul<T: Real>(a: &[T; 4], b: &[T; 4]) -> [T; 4] {
    [
        a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
        a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
        a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
        a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2],
    ]
}

/// Rotation vector to quaternion by its series, exact to O(|v|⁶)
/// ([`crate::strapdown::quat_from_rotvec`]); a lane whose rotation exceeds 1e-2 rad takes the
/// closed form.
#[inline(always)]
fn quat_from_rotvec<T: Real>(v: &[T; 3]) -> [T; 4] {
    let n2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let c = T::splat(1.0) - n2.div_by(EIGHT) + (n2 * n2).div_by(SERIES_C4);
    let s = T::splat(0.5) - n2.div_by(FORTY_EIGHT) + (n2 * n2).div_by(SERIES_S4);
    let mut q = [s * v[0], s * v[1], s * v[2], c];
    if !n2.any_above(1e-4) {
        return q;
    }
    for l in 0..T::LANES {
        if n2.lane(l) > 1e-4 {
            let exact = UnitQuaternion::from_scaled_axis(Vector3::new(
                v[0].lane(l),
                v[1].lane(l),
                v[2].lane(l),
            ));
            for (qi, e) in q.iter_mut().zip(exact.coords.iter()) {
                qi.set_lane(l, *e);
            }
        }
    }
    q
}

/// C_b^n of q (`UnitQuaternion::to_rotation_matrix`), rows.
#[inline(always)]
fn rotation<T: Real>(q: &[T; 4]) -> [[T; 3]; 3] {
    let [i, j, k, w] = *q;
    let two = T::splat(2.0);
    let (ww, ii, jj, kk) = (w * w, i * i, j * j, k * k);
    let (ij, wk, wj) = (i * j * two, w * k * two, w * j * two);
    let (ik, jk, wi) = (i * k * two, j * k * two, w * i * two);
    [
        [ww + ii - jj - kk, ij - wk, wj + ik],
        [wk + ij, ww - ii + jj - kk, jk - wi],
        [ik - wj, wi + jk, ww - ii - jj + kk],
    ]
}

/// r·x, summed in order.
#[inline(always)]
fn dot<T: Real>(r: &[T; 3], x: &[T; 3]) -> T {
    r[0] * x[0] + r[1] * x[1] + r[2] * x[2]
}

/// m·x accumulated column by column, as nalgebra's matrix-vector product does.
#[inline(always)]
fn mat_vec<T: Real>(m: &[[T; 3]; 3], x: &[T; 3]) -> [T; 3] {
    [dot(&m[0], x), dot(&m[1], x), dot(&m[2], x)]
}

/// The body up direction C_n^b·(0, 0, 1) of attitude q: the operations of nalgebra's
/// `q.inverse_transform_vector(&Vector3::z())` (t = 2·(q̄_v × u), u + w·t + q̄_v × t with the
/// conjugate's vector part q̄_v = −q_v), so the same bits.
#[inline(always)]
pub(crate) fn up_in_body<T: Real>(q: &[T; 4]) -> [T; 3] {
    let (zero, one, two) = (T::splat(0.0), T::splat(1.0), T::splat(2.0));
    let qv = [-q[0], -q[1], -q[2]];
    let up = [zero, zero, one];
    let t = scale(&cross(&qv, &up), two);
    let c = cross(&qv, &t);
    [
        t[0] * q[3] + c[0] + up[0],
        t[1] * q[3] + c[1] + up[1],
        t[2] * q[3] + c[2] + up[2],
    ]
}

/// The body frame's part of one update: its rotation vector φ and the specific-force velocity
/// increment Δv_sf (rotation and sculling corrected), in body axes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BodyIncrement<T> {
    /// Coning-corrected rotation of the body, rad.
    pub phi: [T; 3],
    /// Specific-force velocity increment, m/s.
    pub dv_sf: [T; 3],
}

/// Integrates one interval's increments Δθ (rad) and Δv (m/s) over `dt_s` (the equations of
/// [`crate::strapdown`]).
#[inline(always)]
pub(crate) fn update<T: Real>(
    s: &mut Solution<T>,
    dtheta: &[T; 3],
    dv: &[T; 3],
    dt_s: f64,
    vertical: VerticalChannel,
) {
    let body = one_plus_previous(s, dtheta, dv);
    update_frame(s, &body, dt_s, vertical);
}

/// Coning and sculling of one interval with the previous one (which it then becomes).
#[inline(always)]
fn one_plus_previous<T: Real>(
    s: &mut Solution<T>,
    dtheta: &[T; 3],
    dv: &[T; 3],
) -> BodyIncrement<T> {
    let half = T::splat(0.5);
    let (pth, pdv) = (s.prev_dtheta, s.prev_dv);
    let phi = add(dtheta, &divide(&cross(&pth, dtheta), TWELVE));
    let dv_sf_b = add(
        &add(dv, &scale(&cross(dtheta, dv), half)),
        &divide(&add(&cross(&pth, dv), &cross(&pdv, dtheta)), TWELVE),
    );
    s.prev_dtheta = *dtheta;
    s.prev_dv = *dv;
    BodyIncrement {
        phi,
        dv_sf: dv_sf_b,
    }
}

/// The rest of an update over `dt_s` from the body's part: velocity, position and attitude in
/// the navigation frame.
#[inline(always)]
pub(crate) fn update_frame<T: Real>(
    s: &mut Solution<T>,
    body: &BodyIncrement<T>,
    dt_s: f64,
    vertical: VerticalChannel,
) {
    let dt = T::splat(dt_s);
    let (half, two) = (T::splat(0.5), T::splat(2.0));
    let (phi, dv_sf_b) = (body.phi, body.dv_sf);

    // The latitude's terms: WGS-84 radii of curvature and normal gravity. Its sine and cosine
    // step from a grid point ([`GridTrig`]: libm there, a series from it): vector operations
    // in every lane, the same bits in a lane as alone, within an ulp of libm.
    let (sl, cl) = s.lat_trig.sin_cos(s.lat);
    let sin2 = sl * sl;
    let (rm, rn, g) = radii_and_gravity_sin2(sin2, s.h);
    let h0 = s.h;
    let v0 = s.v;

    // Earth and transport rates.
    let zero = T::splat(0.0);
    let w_ie = [
        zero,
        T::splat(OMEGA_IE_RPS) * cl,
        T::splat(OMEGA_IE_RPS) * sl,
    ];
    // Divisors used twice: each divides through its reciprocal in a vector build.
    let rmh = Reciprocal::of(rm + h0);
    let rnh = Reciprocal::of(rn + h0);
    let w_en = [
        (-v0[1]).div_rec(&rmh),
        v0[0].div_rec(&rnh),
        (v0[0] * sl / cl).div_rec(&rnh),
    ];
    let zeta = scale(&add(&w_ie, &w_en), dt);

    // Specific force to the navigation frame: (I − ½[ζ×])·C_b^n·Δv_sf.
    let c_bn = rotation(&s.q);
    let f = mat_vec(&c_bn, &dv_sf_b);
    let hz = [half * zeta[0], half * zeta[1], half * zeta[2]];
    let one = T::splat(1.0);
    let turn = [
        [one - half * zero, zero - half * -zeta[2], zero - hz[1]],
        [zero - hz[2], one - half * zero, zero - half * -zeta[0]],
        [zero - half * -zeta[1], zero - hz[0], one - half * zero],
    ];
    let dv_sf_n = mat_vec(&turn, &f);
    let coriolis = cross(&add(&scale(&w_ie, two), &w_en), &v0);
    let g_n = [zero, zero, -g];
    let mut v = [
        v0[0] + dv_sf_n[0] + (g_n[0] - coriolis[0]) * dt,
        v0[1] + dv_sf_n[1] + (g_n[1] - coriolis[1]) * dt,
        v0[2] + dv_sf_n[2] + (g_n[2] - coriolis[2]) * dt,
    ];

    let mut h = h0;
    match vertical {
        VerticalChannel::Hold { ref_height_m } => {
            v[2] = zero;
            h = T::splat(ref_height_m);
        }
        VerticalChannel::Damped {
            ref_height_m,
            tau_s,
        } => {
            let dh = h - T::splat(ref_height_m);
            v[2] = v[2] - dh / T::splat(tau_s * tau_s) * dt;
            h = h + (half * (v0[2] + v[2]) - two * dh / T::splat(tau_s)) * dt;
        }
    }
    let (v_mid_e, v_mid_n) = (half * (v0[0] + v[0]), half * (v0[1] + v[1]));
    s.lat = s.lat + v_mid_n.div_rec(&rmh) * dt;
    s.lon = s.lon + v_mid_e / (rnh.value * cl) * dt;

    let q = quat_mul(
        &quat_mul(&quat_from_rotvec(&[-zeta[0], -zeta[1], -zeta[2]]), &s.q),
        &quat_from_rotvec(&phi),
    );
    // `renormalize_fast`: q·½(3 − |q|²), |q|² summed as nalgebra's 4-vector dot product.
    let n2 = (q[0] * q[0] + q[2] * q[2]) + (q[1] * q[1] + q[3] * q[3]);
    let k = half * (T::splat(3.0) - n2);
    s.q = [q[0] * k, q[1] * k, q[2] * k, q[3] * k];
    s.v = v;
    s.h = h;
}
