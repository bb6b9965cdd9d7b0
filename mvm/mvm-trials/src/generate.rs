//! The measured log of a design: the exact increments, the model-as-given terms (bias, scale
//! factor, white noise), the hidden effects, the gimbal angles and the temperature readings.

use nalgebra::Vector3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rins_mvm::{Attitude, History};
use rins_plant::PlantConfig;
use rins_plant::carrier::CarrierKind;
use serde::Serialize;

use crate::design::{Design, RUN_GAP_S};
use crate::effect_error::row_error;
use crate::hidden::HiddenEffect;
use crate::row::{Row, RunRows, Setup};
use crate::units::{DPH, DPSH, PPM, UG};

/// ChaCha8 stream of the gyro angle random walk.
pub const GYRO_NOISE_STREAM: u64 = 0x7472_6961_6c67;
/// ChaCha8 stream of the accelerometer velocity random walk.
pub const ACCEL_NOISE_STREAM: u64 = 0x7472_6961_6c61;
/// Resolution of the temperature readings, K (the sensors' 1/16 K LSB).
pub const TEMP_LSB_K: f64 = 0.0625;

/// What a trial hid: the model as given to the diagnosis, and the effects it lacks.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Truth {
    /// The model (with the design's roll and rate, [`Design::model_for`]).
    pub model: PlantConfig,
    /// The hidden effects.
    pub hidden: Vec<HiddenEffect>,
}

/// Whether the generator represents every term `model` has on: a static carrier and, of the
/// sensor terms, only gyro bias, scale factor and ARW and accelerometer bias, scale factor and
/// VRW (what the benchmark's base models enable). Anything else would be silently missing from
/// the data, so it is refused with the list of terms.
pub fn check_model(model: &PlantConfig) -> Result<(), String> {
    let (g, a) = (&model.sensor.gyro, &model.sensor.accel);
    let mut other = Vec::new();
    let mut on = |name: &str, enabled: bool| {
        if enabled {
            other.push(name.to_string());
        }
    };
    on(
        "carrier (not static)",
        model.carrier.kind != CarrierKind::Static,
    );
    on(
        "gyro.scale_factor_asymmetry",
        g.scale_factor_asymmetry.enabled,
    );
    on("gyro.misalignment", g.misalignment.enabled);
    on("gyro.temperature_bias", g.temperature_bias.enabled);
    on(
        "gyro.temperature_gradient_bias",
        g.temperature_gradient_bias.enabled,
    );
    on("gyro.g_sensitivity", g.g_sensitivity.enabled);
    on("gyro.position_bias", g.position_bias.enabled);
    on("gyro.dither_bias", g.dither_bias.enabled);
    on("gyro.bias_instability", g.bias_instability.enabled);
    on("gyro.rate_random_walk", g.rate_random_walk.enabled);
    on("gyro.quantization", g.quantization.enabled);
    on("gyro.custom", g.custom.iter().any(|c| c.enabled));
    on("accel.misalignment", a.misalignment.enabled);
    on("accel.temperature_bias", a.temperature_bias.enabled);
    on("accel.quantization", a.quantization.enabled);
    on("accel.custom", a.custom.iter().any(|c| c.enabled));
    if other.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "the trial generator writes only gyro bias/scale factor/ARW and accelerometer bias/scale factor/VRW on a static carrier; the model also has: {}",
            other.join(", ")
        ))
    }
}

/// The model's terms as numbers in SI: bias (rad/s, m/s²), scale factor (1), white noise
/// density (rad/√s, m/s/√s); zero where off.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ModelTerms {
    pub gyro_bias: Vector3<f64>,
    pub gyro_sf: Vector3<f64>,
    pub arw: Vector3<f64>,
    pub accel_bias: Vector3<f64>,
    pub accel_sf: Vector3<f64>,
    pub vrw: Vector3<f64>,
}

impl ModelTerms {
    pub(crate) fn of(model: &PlantConfig) -> Self {
        let (g, a) = (&model.sensor.gyro, &model.sensor.accel);
        let v = |on: bool, x: [f64; 3], unit: f64| {
            if on {
                Vector3::from(x) * unit
            } else {
                Vector3::zeros()
            }
        };
        Self {
            gyro_bias: v(g.bias.enabled, g.bias.dph, DPH),
            gyro_sf: v(g.scale_factor.enabled, g.scale_factor.ppm, PPM),
            arw: v(g.angle_random_walk.enabled, g.angle_random_walk.dpsh, DPSH),
            accel_bias: v(a.bias.enabled, a.bias.ug, UG),
            accel_sf: v(a.scale_factor.enabled, a.scale_factor.ppm, PPM),
            vrw: v(
                a.velocity_random_walk.enabled,
                a.velocity_random_walk.ug_per_sqrthz,
                UG,
            ),
        }
    }
}

/// The time constants of the extra temperature lags the effects read, without repeats.
pub(crate) fn lag_taus(hidden: &[HiddenEffect]) -> Vec<f64> {
    let mut taus: Vec<f64> = Vec::new();
    for t in hidden.iter().filter_map(HiddenEffect::lag_tau_s) {
        if !taus.contains(&t) {
            taus.push(t);
        }
    }
    taus
}

/// A temperature as the sensor reads it: rounded to [`TEMP_LSB_K`].
pub fn reading(t_c: f64) -> f64 {
    (t_c / TEMP_LSB_K).round() * TEMP_LSB_K
}

/// The measured log of `design` for a unit that is `model` (its terms read by value, the
/// design's mount roll) plus `hidden`. One segment per run ("run1", …); row k of a run covers
/// ((k − 1)/rate, k/rate] of its run time (every row carries its true increments; the
/// diagnosis uses the first only for the start attitude); `t_s` continues across runs with a
/// gap of [`RUN_GAP_S`]. Gimbal angles at the end of each row (exact encoders); temperatures as
/// read (true values rounded to 1/16 K): gyro blocks, housing, accelerometer node. The white
/// noise comes from `ChaCha8Rng::seed_from_u64(seed)` on the streams [`GYRO_NOISE_STREAM`]
/// and [`ACCEL_NOISE_STREAM`], three normals per row each whatever the effects, so the same
/// seed gives the same noise with or without hidden effects.
///
/// # Panics
/// If [`check_model`] refuses the model, or the design is malformed (a chamber profile not
/// starting with a hold, a rate that is not positive).
pub fn generate(
    model: &PlantConfig,
    design: &Design,
    hidden: &[HiddenEffect],
    seed: u64,
) -> History {
    if let Err(e) = check_model(model) {
        panic!("{e}");
    }
    let setup = Setup::new(model, design);
    let terms = ModelTerms::of(model);
    let taus = lag_taus(hidden);
    let mut gyro_rng = ChaCha8Rng::seed_from_u64(seed);
    gyro_rng.set_stream(GYRO_NOISE_STREAM);
    let mut accel_rng = ChaCha8Rng::seed_from_u64(seed);
    accel_rng.set_stream(ACCEL_NOISE_STREAM);
    let mut h = History {
        t_s: Vec::new(),
        dtheta_rad: Default::default(),
        dv_mps: Default::default(),
        attitude: Attitude::Gimbal {
            outer_rad: Vec::new(),
            inner_rad: Vec::new(),
        },
        gyro_temp_c: Default::default(),
        housing_temp_c: Some(Vec::new()),
        accel_temp_c: Vec::new(),
        run: Vec::new(),
        run_names: Vec::new(),
        segments: Vec::new(),
        source: design.name.clone(),
    };
    let (mut outer, mut inner, mut housing) = (Vec::new(), Vec::new(), Vec::new());
    let mut t_start = 0.0;
    let mut row = Row::default();
    for (r, run) in design.runs.iter().enumerate() {
        let mut rows = RunRows::new(setup, design, run, &taus);
        let first = h.t_s.len();
        h.run_names.push(format!("run{}", r + 1));
        for k in 1..=rows.rows {
            rows.row(k, &mut row);
            let dt = row.t1 - row.t0;
            let sq = dt.sqrt();
            let mut g =
                row.dtheta + terms.gyro_bias * dt + terms.gyro_sf.component_mul(&row.dtheta);
            let mut a = row.dv + terms.accel_bias * dt + terms.accel_sf.component_mul(&row.dv);
            for e in hidden {
                let (eg, ea) = row_error(e, &row, &rows.thermal, setup.gravity_mps2);
                g += eg;
                a += ea;
            }
            for i in 0..3 {
                let n: f64 = StandardNormal.sample(&mut gyro_rng);
                h.dtheta_rad[i].push(g[i] + terms.arw[i] * sq * n);
            }
            for i in 0..3 {
                let n: f64 = StandardNormal.sample(&mut accel_rng);
                h.dv_mps[i].push(a[i] + terms.vrw[i] * sq * n);
            }
            h.t_s.push(t_start + k as f64 * rows.dt);
            outer.push(row.angles_end.0);
            inner.push(row.angles_end.1);
            for i in 0..3 {
                h.gyro_temp_c[i].push(reading(row.temps_end.block[i]));
            }
            housing.push(reading(row.temps_end.housing));
            h.accel_temp_c.push(reading(row.temps_end.accel));
            h.run.push(r as u32);
        }
        h.segments.push(first..h.t_s.len());
        t_start += run.duration_s + RUN_GAP_S;
    }
    h.attitude = Attitude::Gimbal {
        outer_rad: outer,
        inner_rad: inner,
    };
    h.housing_temp_c = Some(housing);
    h
}
