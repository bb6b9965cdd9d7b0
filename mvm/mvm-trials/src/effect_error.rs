//! The increment error each hidden effect adds over a row: rates integrated over the row's
//! quadrature nodes (exact temperatures and attitude), rate-proportional terms on the exact
//! true increment, and the temperature-rate bias as K·ΔT_b,i.

use nalgebra::Vector3;

use crate::hidden::HiddenEffect;
use crate::row::{Node, Row};
use crate::thermal::RunThermal;
use crate::units::{ARCSEC, DEG, DPH, G0, PPM, REF_TEMP_C, UG};

/// The error of `effect` over `row`: (gyro, rad; accelerometer, m/s).
///
/// # Panics
/// For a [`HiddenEffect::LaggedTempBias`] whose lag `thermal` was not built with.
pub fn row_error(
    effect: &HiddenEffect,
    row: &Row,
    thermal: &RunThermal,
    gravity_mps2: f64,
) -> (Vector3<f64>, Vector3<f64>) {
    use HiddenEffect::*;
    let dt = row.t1 - row.t0;
    let zero = Vector3::zeros();
    // ∫ rate dt per axis, the rate given per node and axis in the coefficient's unit.
    let integral = |rate: &dyn Fn(&Node, usize) -> f64| -> Vector3<f64> {
        let mut s = Vector3::zeros();
        for n in &row.nodes {
            for i in 0..3 {
                s[i] += n.w * rate(n, i);
            }
        }
        s
    };
    let per_axis = |c: &[f64; 3], x: &Vector3<f64>| Vector3::from_fn(|i, _| c[i] * x[i]);
    // The specific force over g₀ at a node (static: f^b = g·u^b).
    let f_g0 = |n: &Node, j: usize| gravity_mps2 * n.c_nb[(j, 2)] / G0;
    let block = |n: &Node, i: usize| n.temps.block[i] - REF_TEMP_C;
    match effect {
        GyroBias { dph } => (Vector3::from(*dph) * (DPH * dt), zero),
        GyroScaleFactor { ppm } => (per_axis(ppm, &row.dtheta) * PPM, zero),
        GyroScaleFactorAsymmetry { ppm } => (per_axis(ppm, &row.dtheta.abs()) * PPM, zero),
        GyroMisalignment { axis, from, arcsec } => {
            let mut e = Vector3::zeros();
            e[*axis] = arcsec * ARCSEC * row.dtheta[*from];
            (e, zero)
        }
        GyroTemperatureBias { per_k, per_k2 } => (
            integral(&|n, i| {
                let x = block(n, i);
                (per_k[i] * x + per_k2[i] * x * x) * DPH
            }),
            zero,
        ),
        GyroGradientBias { dph_per_k } => (
            integral(&|n, i| dph_per_k[i] * (n.temps.block[i] - n.temps.housing) * DPH),
            zero,
        ),
        GyroGSensitivity {
            axis,
            from,
            dph_per_g,
        } => {
            let s = integral(&|n, _| dph_per_g * f_g0(n, *from) * DPH);
            let mut e = Vector3::zeros();
            e[*axis] = s[*axis];
            (e, zero)
        }
        GyroPositionBias { dph, dph_per_k } => (
            integral(&|n, i| {
                (dph[i] + dph_per_k[i] * block(n, i)) * (1.0 - n.c_nb[(2, 2)]) / 2.0 * DPH
            }),
            zero,
        ),
        GyroDitherBias { dph } => (
            integral(&|n, i| dph[i] * (f_g0(n, i).powi(2) - 1.0 / 3.0) * DPH),
            zero,
        ),
        AccelBias { ug } => (zero, Vector3::from(*ug) * (UG * dt)),
        AccelScaleFactor { ppm } => (zero, per_axis(ppm, &row.dv) * PPM),
        AccelMisalignment { axis, from, arcsec } => {
            let mut e = Vector3::zeros();
            e[*axis] = arcsec * ARCSEC * row.dv[*from];
            (zero, e)
        }
        AccelTemperatureBias { ug_per_k } => (
            zero,
            integral(&|n, i| ug_per_k[i] * (n.temps.accel - REF_TEMP_C) * UG),
        ),
        ScaleFactorTempLinear { ppm_per_k, ppm } => (
            per_axis(ppm, &row.dtheta) * PPM
                + integral(&|n, i| ppm_per_k[i] * block(n, i) * n.omega_b[i] * PPM),
            zero,
        ),
        ScaleFactorTempQuadratic { ppm_per_k2 } => (
            integral(&|n, i| ppm_per_k2[i] * block(n, i).powi(2) * n.omega_b[i] * PPM),
            zero,
        ),
        TempRateBias { dph_per_k_per_s } => (
            Vector3::from_fn(|i, _| {
                dph_per_k_per_s[i] * DPH * (row.temps_end.block[i] - row.temps_start.block[i])
            }),
            zero,
        ),
        UpProductBias { a, b, dph } => (
            integral(&|n, i| dph[i] * n.c_nb[(*a, 2)] * n.c_nb[(*b, 2)] * DPH),
            zero,
        ),
        NavFieldBias {
            dph,
            inclination_deg,
            declination_deg,
        } => {
            let (si, ci) = (inclination_deg * DEG).sin_cos();
            let (sd, cd) = (declination_deg * DEG).sin_cos();
            // ENU components of the unit field.
            let m_n = Vector3::new(ci * sd, ci * cd, -si);
            (integral(&|n, i| dph[i] * (n.c_nb * m_n)[i] * DPH), zero)
        }
        PostMoveTransient { dph, tau_s } => (
            integral(&|n, i| dph[i] * (-n.since_stop / tau_s).exp() * DPH),
            zero,
        ),
        LaggedTempBias { dph_per_k, tau_s } => {
            let k = thermal
                .lag_index(*tau_s)
                .expect("the run's thermal solution has the effect's lag");
            (
                integral(&|n, i| {
                    dph_per_k[i] * (thermal.lag_on(n.leg, k, i, n.t) - REF_TEMP_C) * DPH
                }),
                zero,
            )
        }
    }
}
