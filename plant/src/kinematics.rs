//! True increments of the table-mounted IMU over one interval: the one definition used by the
//! plant and by the model-vs-measurement replay (rins-mvm), so both integrate the same physics.

use nalgebra::{Matrix3, Vector3};

use crate::table::GimbalFrame;

/// Error-free increments over one interval, with the specific force the effects see.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableIncrements {
    /// ∫ω_ib^b dt, rad.
    pub dtheta_rad: Vector3<f64>,
    /// ∫f^b dt, m/s.
    pub dv_mps: Vector3<f64>,
    /// Specific force at the midpoint, body axes, m/s².
    pub f_b_mps2: Vector3<f64>,
}

/// Increments of an IMU on the dual-axis table with C_b^n = C_v^n·R_z(outer)·R_x(inner), over an
/// interval of `dt_s` in which the gimbals turn by `d_outer_rad` and `d_inner_rad`:
///
/// * gimbal part from the exact angle differences: [Δinner, sin(inner)·Δouter, cos(inner)·Δouter]
///   with the inner angle at the midpoint (exact when one gimbal moves at a time, as the schemes
///   of Eq. 5–6 do);
/// * Earth rate C_n^b·ω_ie^n·Δt and specific force C_n^b·f^n through the midpoint attitude
///   `c_nb_mid` (C_n^b).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn table_increments(
    c_nb_mid: &Matrix3<f64>,
    sin_inner_mid: f64,
    cos_inner_mid: f64,
    d_outer_rad: f64,
    d_inner_rad: f64,
    omega_ie_n: &Vector3<f64>,
    f_n: &Vector3<f64>,
    dt_s: f64,
) -> TableIncrements {
    let gimbal = Vector3::new(
        d_inner_rad,
        sin_inner_mid * d_outer_rad,
        cos_inner_mid * d_outer_rad,
    );
    let f_b = c_nb_mid * f_n;
    TableIncrements {
        dtheta_rad: gimbal + c_nb_mid * omega_ie_n * dt_s,
        dv_mps: f_b * dt_s,
        f_b_mps2: f_b,
    }
}

/// The carrier reference point's motion as the IMU's sensors see it, at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CarrierPoint {
    /// Inertial rate of the carrier, carrier axes, ω_ic^c = C_n^c·(ω_ie^n + ω_en^n) + ω_nc^c, rad/s.
    pub omega_ic_c: Vector3<f64>,
    /// Specific force at the IMU (the lever arm's end), carrier axes, m/s².
    pub f_c: Vector3<f64>,
}

/// Earth rate ω_ie^n = Ω·[0, cos L, sin L] and transport rate
/// ω_en^n = [−v_N/(R_M + h), v_E/(R_N + h), v_E·tan L/(R_N + h)] (ENU), rad/s.
#[inline]
pub fn frame_rates(
    lat_rad: f64,
    height_m: f64,
    v_n: &Vector3<f64>,
    rotation: bool,
) -> (Vector3<f64>, Vector3<f64>) {
    let (sl, cl) = lat_rad.sin_cos();
    let (rm, rn) = crate::earth::radii_of_curvature(lat_rad);
    let omega = if rotation {
        crate::earth::OMEGA_IE_RPS
    } else {
        0.0
    };
    let rnh = rn + height_m;
    (
        Vector3::new(0.0, omega * cl, omega * sl),
        Vector3::new(-v_n.y / (rm + height_m), v_n.x / rnh, v_n.x * sl / cl / rnh),
    )
}

/// Sensed motion of a carrier point (see [`CarrierPoint`]):
///
/// * f^n = v̇^n + (2ω_ie^n + ω_en^n) × v^n − g^n at the reference point (Coriolis and the
///   transport term; g^n = [0, 0, −γ(L, h)], WGS-84 normal gravity at the current latitude and
///   height, centrifugal part included);
/// * at the IMU, r^c from the reference point: f^c = C_n^c·f^n + α_ic^c × r + ω_ic^c × (ω_ic^c × r),
///   α_ic^c = α_nc^c − ω_nc^c × (C_n^c·ω_in^n) (the slow change of ω_in^n itself is neglected, and
///   so is the gravity gradient over the lever arm: below 3e-6 s⁻²·|r|).
#[inline]
pub fn carrier_point(
    s: &crate::carrier::CarrierState,
    rotation: bool,
    gravity: bool,
    lever_c_m: &Vector3<f64>,
) -> CarrierPoint {
    let earth = crate::earth::LocalEarth::about(s.lat_rad);
    carrier_point_near(s, &earth, rotation, gravity, lever_c_m)
}

/// [`carrier_point`] with the Earth quantities from an expansion `earth` near the point (no
/// sine, cosine or square root: the ship's nodes are within metres of its expansion).
#[inline]
pub fn carrier_point_near(
    s: &crate::carrier::CarrierState,
    earth: &crate::earth::LocalEarth,
    rotation: bool,
    gravity: bool,
    lever_c_m: &Vector3<f64>,
) -> CarrierPoint {
    let e = earth.at(s.lat_rad);
    let omega = if rotation {
        crate::earth::OMEGA_IE_RPS
    } else {
        0.0
    };
    // Two divisions: v_E/(R_N + h) = v_E·cos L/((R_N + h)·cos L).
    let i_rmh = 1.0 / (e.rm_m + s.height_m);
    let i_rnh_cos = 1.0 / ((e.rn_m + s.height_m) * e.cos_lat);
    let w_ie = Vector3::new(0.0, omega * e.cos_lat, omega * e.sin_lat);
    let w_en = Vector3::new(
        -s.v_n.y * i_rmh,
        s.v_n.x * e.cos_lat * i_rnh_cos,
        s.v_n.x * e.sin_lat * i_rnh_cos,
    );
    let g = if gravity {
        e.gravity_mps2(s.height_m)
    } else {
        0.0
    };
    let f_n = s.a_n + (2.0 * w_ie + w_en).cross(&s.v_n) + Vector3::new(0.0, 0.0, g);
    let w_in_c = s.c_cn.tr_mul(&(w_ie + w_en));
    let omega = w_in_c + s.omega_nc_c;
    let mut f_c = s.c_cn.tr_mul(&f_n);
    if *lever_c_m != Vector3::zeros() {
        let alpha = s.alpha_nc_c - s.omega_nc_c.cross(&w_in_c);
        f_c += alpha.cross(lever_c_m) + omega.cross(&omega.cross(lever_c_m));
    }
    CarrierPoint {
        omega_ic_c: omega,
        f_c,
    }
}

/// The carrier points of a tick's nodes: through the ship's Earth expansion on a ship (see
/// [`carrier_point_near`]), exactly otherwise.
#[inline]
pub fn carrier_points(
    carrier: &crate::carrier::Carrier,
    nodes: &[crate::carrier::CarrierState; 2],
    rotation: bool,
    gravity: bool,
    lever_c_m: &Vector3<f64>,
) -> [CarrierPoint; 2] {
    match carrier {
        crate::carrier::Carrier::Ship(ship) => {
            nodes.map(|n| carrier_point_near(&n, ship.earth(), rotation, gravity, lever_c_m))
        }
        _ => nodes.map(|n| carrier_point(&n, rotation, gravity, lever_c_m)),
    }
}

/// Increments over one interval of `dt_s` on a moving carrier, from the carrier points at the
/// two Gauss–Legendre instants, in the table mount's axes (C_c^v already applied), and the gimbal
/// frames there: Δθ = gimbal part + (Δt/2)·Σ_j C_v^b(t_j)·ω_ic^v(t_j),
/// Δv = (Δt/2)·Σ_j C_v^b(t_j)·f^v(t_j). The quadrature errs by Δt⁵·max|d⁴(·)/dt⁴|/4320 (for ship
/// motion at 100 Hz below 1e-13 rad and m/s per step, see docs/carrier.md); the gimbal part is
/// the exact angle difference of [`table_increments`].
#[inline]
pub fn moving_base_increments(
    frames: &[GimbalFrame; 2],
    pts: &[CarrierPoint; 2],
    gimbal_rad: Vector3<f64>,
    dt_s: f64,
) -> TableIncrements {
    let (w, f) = if frames[0] == frames[1] {
        // The table dwells: one rotation of the sums.
        (
            frames[0].to_body(&(pts[0].omega_ic_c + pts[1].omega_ic_c)),
            frames[0].to_body(&(pts[0].f_c + pts[1].f_c)),
        )
    } else {
        (
            frames[0].to_body(&pts[0].omega_ic_c) + frames[1].to_body(&pts[1].omega_ic_c),
            frames[0].to_body(&pts[0].f_c) + frames[1].to_body(&pts[1].f_c),
        )
    };
    TableIncrements {
        dtheta_rad: gimbal_rad + 0.5 * dt_s * w,
        dv_mps: 0.5 * dt_s * f,
        f_b_mps2: 0.5 * f,
    }
}

/// [`moving_base_increments`] while the table dwells, from the carrier part's means over the
/// interval already in body axes (the ship's segment rule turns its node values into the body
/// frame): Δθ = gimbal part + Δt·ω̄_ib^b, Δv = Δt·f̄^b.
#[inline]
pub fn dwell_increments(
    gimbal_rad: Vector3<f64>,
    mean_omega_b: Vector3<f64>,
    mean_f_b: Vector3<f64>,
    dt_s: f64,
) -> TableIncrements {
    TableIncrements {
        dtheta_rad: gimbal_rad + dt_s * mean_omega_b,
        dv_mps: dt_s * mean_f_b,
        f_b_mps2: mean_f_b,
    }
}
