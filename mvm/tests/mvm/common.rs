//! Synthetic measured histories written from closed-form physics (not through the replay's
//! regressors): a dual-axis table cycling through Z-up, both tilts and Z-down with constant-rate
//! single-gimbal moves, white noise at given densities and an optional hidden gyro
//! g-sensitivity or temperature-rate bias. `to_quaternion` writes the same realisation with the
//! IMU attitude as a quaternion instead of gimbal angles.

#![allow(dead_code)]

use nalgebra::{Rotation3, UnitQuaternion, Vector3};
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use rins_mvm::{Attitude, History};
use rins_plant::PlantConfig;
use rins_plant::earth::Site;
use rins_plant::table::{GimbalAngles, body_to_nav};
use rins_plant::units::{DPH, DPSH, G0, UG};

/// Model noise densities.
pub const ARW_DPSH: f64 = 0.0005;
/// Accelerometer white noise, µg/√Hz.
pub const VRW_UG_PER_SQRTHZ: f64 = 20.0;

/// Gauss–Legendre nodes and weights on [−1, 1], five points.
const GAUSS5: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// The model: ideal sensor with white noise only (`noise = false`: no noise terms at all).
pub fn model(noise: bool) -> PlantConfig {
    let mut m = PlantConfig::default();
    m.sensor.gyro.angle_random_walk.enabled = noise;
    m.sensor.gyro.angle_random_walk.dpsh = [ARW_DPSH; 3];
    m.sensor.accel.velocity_random_walk.enabled = noise;
    m.sensor.accel.velocity_random_walk.ug_per_sqrthz = [VRW_UG_PER_SQRTHZ; 3];
    m
}

/// What the synthetic unit has that the model lacks.
#[derive(Clone, Copy, Debug)]
pub struct Hidden {
    /// Gyro g-sensitivity, °/h/g, row = gyro axis, column = specific-force axis.
    pub g_sens_dph_per_g: [[f64; 3]; 3],
    /// Gyro bias per block temperature rate, °/h per K/s, per axis.
    pub temp_rate_dph_per_kps: [f64; 3],
    /// White noise on (`false`: noise-free data).
    pub noise: bool,
    /// Temperature swing within each run, K (a slow sine over the run).
    pub temp_swing_k: f64,
}

impl Default for Hidden {
    fn default() -> Self {
        Self {
            g_sens_dph_per_g: [[0.0; 3]; 3],
            temp_rate_dph_per_kps: [0.0; 3],
            noise: true,
            temp_swing_k: 0.0,
        }
    }
}

/// One table step: which gimbal turns by how much (deg).
const STEPS: [(bool, f64); 12] = [
    (true, 180.0),
    (false, 90.0),
    (false, 90.0),
    (true, 180.0),
    (false, 90.0),
    (false, 90.0),
    (false, -90.0),
    (false, -90.0),
    (true, -180.0),
    (false, -90.0),
    (false, -90.0),
    (true, -180.0),
];

/// Three runs (10, 30, 50 °C) of one 12-step table cycle at 20 Hz (60 s dwells, 10 °/s moves),
/// seeded by `seed`.
pub fn history(m: &PlantConfig, hidden: &Hidden, seed: u64) -> History {
    let site = Site::new(&m.site, &m.earth);
    let (c_vn, f_n) = (m.vehicle.c_vn(), Vector3::new(0.0, 0.0, site.gravity_mps2));
    let dt: f64 = 0.05;
    let rate = 10f64.to_radians();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut h = History {
        t_s: Vec::new(),
        dtheta_rad: Default::default(),
        dv_mps: Default::default(),
        attitude: Attitude::Gimbal {
            outer_rad: Vec::new(),
            inner_rad: Vec::new(),
        },
        gyro_temp_c: Default::default(),
        housing_temp_c: None,
        accel_temp_c: Vec::new(),
        run: Vec::new(),
        run_names: Vec::new(),
        segments: Vec::new(),
        source: "synthetic".into(),
    };
    let sigma_gyro = ARW_DPSH * DPSH * dt.sqrt();
    let sigma_accel = VRW_UG_PER_SQRTHZ * UG * dt.sqrt();
    let mut outer_v = Vec::new();
    let mut inner_v = Vec::new();
    for (run, temp0) in [10.0, 30.0, 50.0].into_iter().enumerate() {
        h.run_names.push(format!("run{run}"));
        let start = h.t_s.len();
        // Per row: the gimbal angles at the end of the row.
        let mut angles: Vec<GimbalAngles> = vec![GimbalAngles::new(0.0, 0.0)];
        for (outer, deg) in STEPS {
            for _ in 0..(60.0 / dt) as usize {
                angles.push(*angles.last().expect("non-empty"));
            }
            let n = (deg.abs().to_radians() / rate / dt).round() as usize;
            let step = deg.to_radians() / n as f64;
            for _ in 0..n {
                let a = *angles.last().expect("non-empty");
                angles.push(if outer {
                    GimbalAngles::new(a.outer_rad + step, a.inner_rad)
                } else {
                    GimbalAngles::new(a.outer_rad, a.inner_rad + step)
                });
            }
        }
        let rows = angles.len();
        let duration = rows as f64 * dt;
        let temp = |k: usize| {
            let t = k as f64 * dt;
            temp0 + hidden.temp_swing_k * (std::f64::consts::TAU * t / duration).sin()
        };
        for k in 0..rows {
            let (a0, a1) = (angles[k.saturating_sub(1)], angles[k]);
            let mid = GimbalAngles::new(
                0.5 * (a0.outer_rad + a1.outer_rad),
                0.5 * (a0.inner_rad + a1.inner_rad),
            );
            // Closed-form kinematics: gimbal rates in body axes (C_b^n = C_v^n R_z(o) R_x(i)),
            // Earth rate and gravity through the mid attitude.
            let c_nb = body_to_nav(&c_vn, mid).transpose();
            let (s, c) = mid.inner_rad.sin_cos();
            let (d_o, d_i) = (a1.outer_rad - a0.outer_rad, a1.inner_rad - a0.inner_rad);
            let gimbal = Vector3::new(d_i, s * d_o, c * d_o);
            // The Earth rate and gravity integrated over the row as the angles move through it
            // (linear in time): 5-point Gauss–Legendre, exact to rounding for these rows (a
            // real unit integrates them continuously).
            let _ = c_nb;
            let (mut earth, mut f_int) = (Vector3::zeros(), Vector3::zeros());
            for (x, w) in GAUSS5 {
                let u = 0.5 * (1.0 + x);
                let at = GimbalAngles::new(
                    a0.outer_rad + u * (a1.outer_rad - a0.outer_rad),
                    a0.inner_rad + u * (a1.inner_rad - a0.inner_rad),
                );
                let c = body_to_nav(&c_vn, at).transpose();
                earth += c * site.omega_ie_n * (0.5 * w * dt);
                f_int += c * f_n * (0.5 * w * dt);
            }
            let dtheta = gimbal + earth;
            let f_b = f_int / dt;
            let temp_rate = (temp(k + 1) - temp(k.saturating_sub(1))) / (2.0 * dt);
            for i in 0..3 {
                let gs: f64 = (0..3)
                    .map(|j| hidden.g_sens_dph_per_g[i][j] * f_b[j] / G0)
                    .sum();
                let bias = (gs + hidden.temp_rate_dph_per_kps[i] * temp_rate) * DPH * dt;
                let (ng, na): (f64, f64) = if hidden.noise {
                    (
                        StandardNormal.sample(&mut rng),
                        StandardNormal.sample(&mut rng),
                    )
                } else {
                    (0.0, 0.0)
                };
                h.dtheta_rad[i].push(dtheta[i] + bias + sigma_gyro * ng);
                h.dv_mps[i].push(f_b[i] * dt + sigma_accel * na);
                h.gyro_temp_c[i].push(temp(k));
            }
            h.t_s.push((k + 1) as f64 * dt);
            outer_v.push(a1.outer_rad);
            inner_v.push(a1.inner_rad);
            h.accel_temp_c.push(temp(k));
            h.run.push(run as u32);
        }
        h.segments.push(start..h.t_s.len());
    }
    h.attitude = Attitude::Gimbal {
        outer_rad: outer_v,
        inner_rad: inner_v,
    };
    h
}

/// The same realisation with the attitude written as the body-to-ENU quaternion a logger would
/// record (from the rotation matrix C_b^n of the gimbal angles).
pub fn to_quaternion(m: &PlantConfig, h: &History) -> History {
    let Attitude::Gimbal {
        outer_rad,
        inner_rad,
    } = &h.attitude
    else {
        panic!("gimbal attitude expected")
    };
    let c_vn = m.vehicle.c_vn();
    let q = outer_rad
        .iter()
        .zip(inner_rad)
        .map(|(o, i)| {
            let c = body_to_nav(&c_vn, GimbalAngles::new(*o, *i));
            let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(c));
            [q.w, q.i, q.j, q.k]
        })
        .collect();
    History {
        attitude: Attitude::Quaternion(q),
        ..h.clone()
    }
}
