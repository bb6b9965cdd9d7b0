//! The general position-dependent bias b_i(u), i = x, y, z: each gyro's bias as a function of
//! the whole up direction u in the IMU frame, expanded to second order in u's components and
//! their products. A real unit's bias changes with every axis's tilt (temperature
//! distribution, dither load, gravity on the cavity), not with u_z alone as the plant's δβ
//! model (Eq. 9) has it.
//!
//! Each basis function is written as a declared effect (`[[sensor.gyro.custom]]`, regressor
//! `u_y*u_z` and so on), so the analysis evaluates it through the plant's own declared-effect
//! plans and a worst case found here runs in the plant unchanged.

use rins_plant::effects::custom::{Axis, CustomKind, CustomSpec};

/// The monomials of u up to second order, without the constant (that is the constant bias,
/// a catalogue effect): as regressor text and as short names. Σu_i² = 1 ties the squares
/// together; they are kept apart because each axis's coefficient on each is its own.
pub const MONOMIALS: [(&str, &str); 9] = [
    ("u_x", "ux"),
    ("u_y", "uy"),
    ("u_z", "uz"),
    ("u_x^2", "ux2"),
    ("u_y^2", "uy2"),
    ("u_z^2", "uz2"),
    ("u_x*u_y", "uxuy"),
    ("u_x*u_z", "uxuz"),
    ("u_y*u_z", "uyuz"),
];

/// Value of monomial `k` of [`MONOMIALS`] at `u`.
pub fn monomial(k: usize, u: &nalgebra::Vector3<f64>) -> f64 {
    match k {
        0 => u.x,
        1 => u.y,
        2 => u.z,
        3 => u.x * u.x,
        4 => u.y * u.y,
        5 => u.z * u.z,
        6 => u.x * u.y,
        7 => u.x * u.z,
        8 => u.y * u.z,
        _ => panic!("second-order basis has 9 monomials"),
    }
}

/// Name of the basis effect of gyro `axis` (0–2) on monomial `k`, e.g. `bz_uz2`.
pub fn name(axis: usize, k: usize) -> String {
    format!("b{}_{}", ["x", "y", "z"][axis], MONOMIALS[k].1)
}

/// The declared effect b_axis(u) = coef_dph · monomial k.
pub fn spec(axis: usize, k: usize, coef_dph: f64) -> CustomSpec {
    let mut coef = [0.0; 3];
    coef[axis] = coef_dph;
    CustomSpec {
        name: name(axis, k),
        enabled: true,
        kind: CustomKind::Bias,
        regressor: MONOMIALS[k].0.into(),
        unit: "1".into(),
        axes: vec![Axis::of(axis)],
        coef,
    }
}

/// All 27 basis effects, 1 °/h each, axis-major.
pub fn all_unit() -> Vec<CustomSpec> {
    (0..3)
        .flat_map(|axis| (0..MONOMIALS.len()).map(move |k| spec(axis, k, 1.0)))
        .collect()
}

/// The worst-case coefficients as declared effects, one per monomial with the three axes'
/// coefficients together (zero entries dropped), ready for `[[sensor.gyro.custom]]`.
pub fn as_declared(coef_dph: &[[f64; 9]; 3]) -> Vec<CustomSpec> {
    (0..MONOMIALS.len())
        .filter_map(|k| {
            let coef = [coef_dph[0][k], coef_dph[1][k], coef_dph[2][k]];
            let axes: Vec<Axis> = (0..3).filter(|&i| coef[i] != 0.0).map(Axis::of).collect();
            (!axes.is_empty()).then(|| CustomSpec {
                name: format!("b_{}", MONOMIALS[k].1),
                enabled: true,
                kind: CustomKind::Bias,
                regressor: MONOMIALS[k].0.into(),
                unit: "1".into(),
                axes,
                coef,
            })
        })
        .collect()
}
