//! What a per-cycle residual does to a static navigator after N days: the linear free-inertial
//! error model (psi-angle form, states φ_E, φ_N, φ_U, δv_E, δv_N, δL, δλ; the vertical channel
//! held) driven by the residual's mean, propagated exactly and averaged over the Schuler
//! period that ends at the end, as the verification's closed forms are (`rins verify ins`).

use nalgebra::{DMatrix, SMatrix, SVector, Vector3};
use rins_plant::earth::{normal_gravity, radii_of_curvature};
use serde::Serialize;

/// Propagation step, s (|F·h| ≈ 0.08 at the Schuler rate: the 14-term series is exact to
/// rounding).
const STEP_S: f64 = 60.0;

type M7 = SMatrix<f64, 7, 7>;
type M75 = SMatrix<f64, 7, 5>;

/// Navigation errors after the run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct NavAfter {
    /// North position error, m.
    pub north_m: f64,
    /// East position error, m (longitude error × R_N cos L).
    pub east_m: f64,
    /// Horizontal position error, m.
    pub horizontal_m: f64,
    /// Azimuth error φ_U, arcmin.
    pub heading_arcmin: f64,
}

/// The static navigator's Schuler-averaged response at one latitude and duration to constant
/// navigation-frame errors: gyro drift ε (E, N, U; rad/s) and accelerometer error ∇ (E, N;
/// m/s²). Linear: one matrix, applied to any residual.
#[derive(Clone, Debug, PartialEq)]
pub struct StaticResponse {
    /// Latitude, rad.
    pub lat_rad: f64,
    /// Duration, days.
    pub days: f64,
    /// Rows: north m, east m, azimuth rad; columns: ε_E, ε_N, ε_U, ∇_E, ∇_N.
    pub matrix: SMatrix<f64, 3, 5>,
}

fn model(lat: f64) -> (M7, M75, f64, f64, f64) {
    let (rm, rn) = radii_of_curvature(lat);
    let r = (rm * rn).sqrt();
    let g = normal_gravity(lat, 0.0);
    let c = lat.cos();
    let f = rins_verification::ins::static_error_matrix(lat);
    let mut b = M75::zeros();
    for i in 0..3 {
        b[(i, i)] = -1.0;
    }
    b[(3, 3)] = 1.0;
    b[(4, 4)] = 1.0;
    let schuler_s = std::f64::consts::TAU / (g / r).sqrt();
    (f, b, rm, rn * c, schuler_s)
}

/// Φ = e^{F·h} and Γ = ∫₀ʰ e^{F·s} ds·B by the series (|F·h| ≤ 0.08 for h ≤ 60 s).
fn discretise(f: &M7, b: &M75, h: f64) -> (M7, M75) {
    let fh = f * h;
    let mut phi = M7::identity();
    let mut gamma = M7::identity() * h;
    let mut term = M7::identity();
    for k in 1..14 {
        term = term * fh / k as f64;
        phi += term;
        gamma += term * (h / (k + 1) as f64);
    }
    (phi, gamma * b)
}

/// The static navigator's errors after `days` at `lat_rad` for inputs that repeat every cycle:
/// `inputs[c][k]` is channel c's mean over step k of the cycle (k = 0..K−1, each `step_s`
/// long) as (ε_E, ε_N, ε_U, ∇_E, ∇_N). Unlike the mean drift this keeps what happens inside a
/// cycle: an attitude error that builds up over a move and is undone only later tilts the
/// navigator meanwhile, and a forcing near the Schuler period is not averaged away.
pub fn periodic_response(
    lat_rad: f64,
    days: f64,
    step_s: f64,
    inputs: &[Vec<[f64; 5]>],
) -> Vec<NavAfter> {
    let (f, b, rm, rn_cos, schuler_s) = model(lat_rad);
    let (phi, gamma) = discretise(&f, &b, step_s);
    let phi = DMatrix::from_column_slice(7, 7, phi.as_slice());
    let gamma = DMatrix::from_column_slice(7, 5, gamma.as_slice());
    let channels = inputs.len();
    let k_len = inputs.first().map_or(1, Vec::len).max(1);
    // One 5 × C input matrix per step of the cycle, the states of every channel side by side.
    let u: Vec<DMatrix<f64>> = (0..k_len)
        .map(|k| DMatrix::from_fn(5, channels, |r, c| inputs[c][k][r]))
        .collect();
    let gu: Vec<DMatrix<f64>> = u.iter().map(|m| &gamma * m).collect();
    let end_s = days * 86_400.0;
    let steps = (end_s / step_s).round() as usize;
    let mut x = DMatrix::<f64>::zeros(7, channels);
    let mut sum = DMatrix::<f64>::zeros(7, channels);
    let mut n = 0usize;
    for k in 0..steps {
        x = &phi * &x + &gu[k % k_len];
        if (k + 1) as f64 * step_s > end_s - schuler_s {
            sum += &x;
            n += 1;
        }
    }
    let mean = sum / n.max(1) as f64;
    (0..channels)
        .map(|c| {
            let (north, east) = (mean[(5, c)] * rm, mean[(6, c)] * rn_cos);
            NavAfter {
                north_m: north,
                east_m: east,
                horizontal_m: north.hypot(east),
                heading_arcmin: mean[(2, c)].to_degrees() * 60.0,
            }
        })
        .collect()
}

impl StaticResponse {
    /// The response after `days` at latitude `lat_rad`.
    pub fn new(lat_rad: f64, days: f64) -> Self {
        let (f, b, rm, rn_cos, schuler_s) = model(lat_rad);
        let (phi, gamma) = discretise(&f, &b, STEP_S);
        let end_s = days * 86_400.0;
        let steps = (end_s / STEP_S).round() as usize;
        let mut x = M75::zeros();
        let mut sum = M75::zeros();
        let mut n = 0usize;
        for k in 1..=steps {
            x = phi * x + gamma;
            let t = k as f64 * STEP_S;
            if t > end_s - schuler_s {
                sum += x;
                n += 1;
            }
        }
        let mean = sum / n.max(1) as f64;
        let mut m = SMatrix::<f64, 3, 5>::zeros();
        for j in 0..5 {
            m[(0, j)] = mean[(5, j)] * rm;
            m[(1, j)] = mean[(6, j)] * rn_cos;
            m[(2, j)] = mean[(2, j)];
        }
        Self {
            lat_rad,
            days,
            matrix: m,
        }
    }

    /// Errors for a mean gyro drift `eps_rps` (E, N, U) and accelerometer error `acc_mps2`
    /// (E, N; its vertical part drives the held vertical channel only).
    pub fn apply(&self, eps_rps: &Vector3<f64>, acc_mps2: &Vector3<f64>) -> NavAfter {
        let u = SVector::<f64, 5>::new(eps_rps.x, eps_rps.y, eps_rps.z, acc_mps2.x, acc_mps2.y);
        let y = self.matrix * u;
        NavAfter {
            north_m: y[0],
            east_m: y[1],
            horizontal_m: y[0].hypot(y[1]),
            heading_arcmin: y[2].to_degrees() * 60.0,
        }
    }

    /// North and east position (m) per unit gyro drift component `axis` (rad/s).
    pub fn position_per_drift(&self, axis: usize) -> [f64; 2] {
        [self.matrix[(0, axis)], self.matrix[(1, axis)]]
    }
}
