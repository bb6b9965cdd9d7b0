//! The one entry on a synthetic history with a known hidden effect: a constant z-gyro bias the
//! model lacks, under white noise at the model's own densities. `analyse` must accept the bias
//! with the injected value inside its 95 % interval, carry per-window predictions equal to that
//! bias, a comparison after it at the noise floor, and the `--apply` model with the bias fitted;
//! the reports it carries must agree with each other.

use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use rins_mvm::replay::gimbal_true_increments;
use rins_mvm::{Attitude, Effect, History, Options, analyse};
use rins_plant::PlantConfig;
use rins_plant::earth::Site;
use rins_plant::effects::GyroTerm;
use rins_plant::table::GimbalAngles;
use rins_plant::units::{DPH, DPSH, UG};

const ARW_DPSH: f64 = 0.0005;
const VRW_UG_PER_SQRTHZ: f64 = 20.0;
const HIDDEN_BIAS_DPH: f64 = 0.02;

/// The model: ideal sensor with white noise only.
fn model() -> PlantConfig {
    let mut m = PlantConfig::default();
    m.sensor.gyro.angle_random_walk.enabled = true;
    m.sensor.gyro.angle_random_walk.dpsh = [ARW_DPSH; 3];
    m.sensor.accel.velocity_random_walk.enabled = true;
    m.sensor.accel.velocity_random_walk.ug_per_sqrthz = [VRW_UG_PER_SQRTHZ; 3];
    m
}

/// Three runs at 10, 25 and 40 °C, each a 600 s dwell at Z-up, tilted (inner 90°, body z
/// horizontal) and Z-down at 100 Hz: true increments plus the hidden z-gyro bias plus seeded white
/// noise. The tilted dwell tells the bias from the effects that also are constant while body z
/// stays vertical (dither bias, ∝ g_z² − 1/3).
fn history(m: &PlantConfig) -> History {
    let site = Site::new(&m.site, &m.earth);
    let (c_vn, f_n) = (
        m.vehicle.c_vn(),
        nalgebra::Vector3::new(0.0, 0.0, site.gravity_mps2),
    );
    let dt: f64 = 0.01;
    let rows = 60_000;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
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
    let Attitude::Gimbal {
        outer_rad,
        inner_rad,
    } = &mut h.attitude
    else {
        unreachable!()
    };
    let sigma_gyro = ARW_DPSH * DPSH * dt.sqrt();
    let sigma_accel = VRW_UG_PER_SQRTHZ * UG * dt.sqrt();
    for (run, temp_c) in [10.0, 25.0, 40.0].into_iter().enumerate() {
        h.run_names.push(format!("run{run}"));
        for (seg, inner) in [0.0, std::f64::consts::FRAC_PI_2, std::f64::consts::PI]
            .into_iter()
            .enumerate()
        {
            let start = h.t_s.len();
            let a = GimbalAngles::new(0.0, inner);
            for k in 0..rows {
                let t = (seg * rows + k + 1) as f64 * dt;
                let kin = gimbal_true_increments(&c_vn, &site.omega_ie_n, &f_n, a, a, dt);
                for i in 0..3 {
                    let n: f64 = StandardNormal.sample(&mut rng);
                    let bias = if i == 2 {
                        HIDDEN_BIAS_DPH * DPH * dt
                    } else {
                        0.0
                    };
                    h.dtheta_rad[i].push(kin.dtheta_rad[i] + bias + sigma_gyro * n);
                    let n: f64 = StandardNormal.sample(&mut rng);
                    h.dv_mps[i].push(kin.dv_mps[i] + sigma_accel * n);
                    h.gyro_temp_c[i].push(temp_c);
                }
                h.t_s.push(t);
                outer_rad.push(0.0);
                inner_rad.push(inner);
                h.accel_temp_c.push(temp_c);
                h.run.push(run as u32);
            }
            h.segments.push(start..h.t_s.len());
        }
    }
    h
}

#[test]
fn a_hidden_bias_is_found_predicted_and_applied_from_one_analysis() {
    let m = model();
    let h = history(&m);
    let opts = Options {
        diagnose: true,
        apply: vec![Effect::Gyro(GyroTerm::Bias)],
        ..Options::default()
    };
    let an = analyse(&m, &h, &opts);
    let d = an.diagnosis.as_ref().expect("asked for");
    let r = &d.report;

    // The bias is accepted on gyro x, with the injected value inside its 95 % interval.
    let acc = r
        .accepted
        .iter()
        .find(|e| e.channel == "gyro_z")
        .unwrap_or_else(|| panic!("nothing accepted on gyro_z: {:#?}", r.accepted));
    assert_eq!(acc.effect, "gyro.bias");
    let ci = acc.ci95[0];
    assert!(
        ci[0] <= HIDDEN_BIAS_DPH && HIDDEN_BIAS_DPH <= ci[1],
        "{HIDDEN_BIAS_DPH} outside {ci:?}"
    );

    // The carried predictions are that bias in every window (rate = prediction / duration).
    let pred = an.predictions().expect("diagnosis");
    assert_eq!(pred.len(), 6);
    assert_eq!(pred[2].len(), an.replay.windows.len());
    let half = 0.5 * (ci[1] - ci[0]);
    for (p, w) in pred[2].iter().zip(&an.replay.windows) {
        let rate_dph = p / w.duration_s / DPH;
        assert!(
            (rate_dph - HIDDEN_BIAS_DPH).abs() <= 2.0 * half,
            "window at {} s: {rate_dph} deg/h",
            w.t_mid_s
        );
    }

    // Before: the bias shows in the map; after: gyro z is at its noise floor, nothing flagged.
    assert!(
        an.comparison
            .flagged_cells
            .iter()
            .any(|c| c.channel == "gyro_z")
    );
    assert!(r.residual_rms_after["gyro_z"] <= 1.1 * r.noise_floor_rms["gyro_z"]);
    assert!(r.residual_rms_before["gyro_z"] > 2.0 * r.noise_floor_rms["gyro_z"]);
    assert!(r.flagged_cells_after.iter().all(|c| c.channel != "gyro_z"));

    // The reports the result carries agree: the report's before/after are the comparisons.
    let after = an.after().expect("diagnosis");
    assert_eq!(r.flagged_cells.len(), an.comparison.flagged_cells.len());
    assert_eq!(r.flagged_cells_after.len(), after.flagged_cells.len());
    for c in &after.channels {
        assert_eq!(r.residual_rms_after[&c.channel], c.residual_rms);
    }
    for c in &an.comparison.channels {
        assert_eq!(r.residual_rms_before[&c.channel], c.residual_rms);
    }

    // --apply: the fitted model carries the bias, inside the same interval.
    let applied = an.applied.as_ref().expect("asked for").as_ref().unwrap();
    let b = applied.model.sensor.gyro.bias.dph[2];
    assert!(applied.model.sensor.gyro.bias.enabled);
    assert!(ci[0] <= b && b <= ci[1], "{b} outside {ci:?}");
    // Replaying the applied model leaves gyro z at the floor.
    let again = analyse(&applied.model, &h, &Options::default());
    let x = again
        .comparison
        .channels
        .iter()
        .find(|c| c.channel == "gyro_z")
        .expect("gyro_z");
    assert!(x.residual_rms <= 1.1 * x.noise_floor_rms, "{x:#?}");
}
