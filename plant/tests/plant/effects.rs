//! Each sensor effect checked against an independent closed form, with the plant otherwise ideal.

use approx::assert_relative_eq;
use nalgebra::Vector3;
use rins_plant::effects::{AccelTerm, GyroTerm, TermContext};
use rins_plant::table::{GimbalAxis, RotationStep, SchemeKind, SchemeSpec};
use rins_plant::units::{ARCSEC, DPH, DPSH, G0, PPM, UG};
use rins_plant::{Plant, PlantConfig};

/// Ideal plant: no Earth rate, thermal network off, table static at the given angles.
fn ideal(outer_deg: f64, inner_deg: f64) -> PlantConfig {
    let mut c = PlantConfig::default();
    c.earth.rotation = false;
    c.thermal.enabled = false;
    c.scheme = SchemeSpec {
        kind: SchemeKind::Static,
        initial_outer_deg: outer_deg,
        initial_inner_deg: inner_deg,
        ..SchemeSpec::default()
    };
    c
}

/// One 180° move of `axis` at 10°/s with constant rate, then a dwell; table otherwise static.
fn one_turn(axis: GimbalAxis, angle_deg: f64) -> SchemeSpec {
    SchemeSpec {
        kind: SchemeKind::Steps,
        accel_dps2: f64::INFINITY,
        lead_dwell_s: 1.0,
        repeat: false,
        steps: vec![RotationStep {
            axis,
            angle_deg,
            rate_dps: 10.0,
            dwell_s: 1.0,
        }],
        ..SchemeSpec::default()
    }
}

/// Runs `seconds` and returns (Σ gyro error, Σ accel error, Σ true Δθ, Σ true Δv). Errors are
/// accumulated per step (output minus truth) so large sums do not swamp them in roundoff.
fn run(
    cfg: &PlantConfig,
    seconds: f64,
) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let mut p = Plant::new(cfg).expect("valid config");
    let n = (seconds * cfg.rate_hz).round() as u64;
    let (mut th_err, mut v_err, mut th_true, mut v_true) = (
        Vector3::zeros(),
        Vector3::zeros(),
        Vector3::zeros(),
        Vector3::zeros(),
    );
    for _ in 0..n {
        let s = p.step();
        th_err += s.dtheta_rad - p.truth().dtheta_true_rad;
        v_err += s.dv_mps - p.truth().dv_true_mps;
        th_true += p.truth().dtheta_true_rad;
        v_true += p.truth().dv_true_mps;
    }
    (th_err, v_err, th_true, v_true)
}

#[test]
fn static_increments_equal_earth_rate_and_gravity_in_body_axes() {
    let mut cfg = ideal(30.0, 180.0);
    cfg.earth.rotation = true;
    let mut p = Plant::new(&cfg).unwrap();
    let s = p.step();
    let c_nb = p.attitude_c_bn().transpose();
    let lat = 36.6f64.to_radians();
    let w = 7.292_115e-5;
    let expect_w = c_nb * Vector3::new(0.0, w * lat.cos(), w * lat.sin()) * 0.01;
    let g = rins_plant::earth::normal_gravity(lat, 0.0);
    let expect_v = c_nb * Vector3::new(0.0, 0.0, g) * 0.01;
    assert_relative_eq!(s.dtheta_rad, expect_w, epsilon = 1e-18);
    assert_relative_eq!(s.dv_mps, expect_v, epsilon = 1e-15);
    // Inner 180° puts body z down: specific force along -z.
    assert!(s.dv_mps.z < 0.0);
}

#[test]
fn constant_bias_and_accel_bias() {
    let mut cfg = ideal(0.0, 0.0);
    let g = &mut cfg.sensor.gyro;
    g.bias.enabled = true;
    g.bias.dph = [0.01, -0.02, 0.03];
    cfg.sensor.accel.bias.enabled = true;
    cfg.sensor.accel.bias.ug = [50.0, -20.0, 10.0];
    let (th, v, _, _) = run(&cfg, 100.0);
    assert_relative_eq!(
        th,
        Vector3::new(0.01, -0.02, 0.03) * DPH * 100.0,
        epsilon = 1e-15
    );
    assert_relative_eq!(
        v,
        Vector3::new(50.0, -20.0, 10.0) * UG * 100.0,
        epsilon = 1e-11
    );
}

#[test]
fn scale_factor_misalignment_and_asymmetry_over_a_half_turn() {
    // Outer 180° turn at Z-up: body rate about +z only. Errors: SF_z·π on z,
    // misalignment β_xz·π on x and β_yz·π on y; asymmetry a_z·|π|.
    let mut cfg = ideal(0.0, 0.0);
    cfg.scheme = one_turn(GimbalAxis::Outer, 180.0);
    let g = &mut cfg.sensor.gyro;
    g.scale_factor.enabled = true;
    g.scale_factor.ppm = [0.0, 0.0, 5.0];
    g.misalignment.enabled = true;
    g.misalignment.arcsec = [0.0, 3.0, 0.0, -4.0, 0.0, 0.0];
    g.scale_factor_asymmetry.enabled = true;
    g.scale_factor_asymmetry.ppm = [0.0, 0.0, 2.0];
    let (th, _, th_t, _) = run(&cfg, 20.0);
    let pi = std::f64::consts::PI;
    assert_relative_eq!(th_t.z, pi, epsilon = 1e-12);
    assert_relative_eq!(
        th,
        Vector3::new(3.0 * ARCSEC * pi, -4.0 * ARCSEC * pi, 7.0 * PPM * pi),
        epsilon = 1e-15
    );
    // The reverse turn flips SF and misalignment but not the asymmetry.
    cfg.scheme = one_turn(GimbalAxis::Outer, -180.0);
    let (th2, _, _, _) = run(&cfg, 20.0);
    assert_relative_eq!(
        (th) + th2,
        Vector3::new(0.0, 0.0, 4.0 * PPM * pi),
        epsilon = 1e-15
    );
}

#[test]
fn accel_scale_factor_and_misalignment_under_gravity() {
    let mut cfg = ideal(0.0, 0.0);
    let a = &mut cfg.sensor.accel;
    a.scale_factor.enabled = true;
    a.scale_factor.ppm = [0.0, 0.0, 50.0];
    a.misalignment.enabled = true;
    a.misalignment.arcsec = [0.0, 5.0, 0.0, 7.0, 0.0, 0.0];
    let (_, v, _, v_t) = run(&cfg, 10.0);
    let g = v_t.z;
    assert_relative_eq!(
        v,
        Vector3::new(5.0 * ARCSEC * g, 7.0 * ARCSEC * g, 50.0 * PPM * g),
        epsilon = 1e-13
    );
}

#[test]
fn temperature_polynomial_bias_at_chamber_temperature() {
    let mut cfg = ideal(0.0, 0.0);
    cfg.thermal.chamber.temp_c = 45.0; // thermal off: blocks follow the chamber
    let t = &mut cfg.sensor.gyro.temperature_bias;
    t.enabled = true;
    t.ref_temp_c = 25.0;
    t.per_k = [1e-3, 0.0, 0.0];
    t.per_k2 = [0.0, 1e-5, 0.0];
    t.per_k3 = [0.0, 0.0, 1e-7];
    let a = &mut cfg.sensor.accel.temperature_bias;
    a.enabled = true;
    a.per_k = [1.0, 0.0, 0.0];
    let (th, v, _, _) = run(&cfg, 10.0);
    let x = 20.0;
    assert_relative_eq!(
        (th) / 10.0,
        Vector3::new(1e-3 * x, 1e-5 * x * x, 1e-7 * x * x * x) * DPH,
        epsilon = 1e-18
    );
    assert_relative_eq!((v).x / 10.0, 20.0 * UG, epsilon = 1e-12);
}

#[test]
fn gradient_bias_follows_the_thermal_network() {
    let mut cfg = ideal(0.0, 0.0);
    cfg.thermal.enabled = true;
    cfg.sensor.gyro.temperature_gradient_bias.enabled = true;
    cfg.sensor.gyro.temperature_gradient_bias.dph_per_k = [0.002, 0.003, -0.001];
    let mut p = Plant::new(&cfg).unwrap();
    p.step();
    let tr = p.truth();
    let grad = tr.temps.gyro_gradient_k();
    assert!(
        grad.x > 0.1,
        "self-heated blocks are warmer than the housing"
    );
    let expect = Vector3::new(0.002 * grad.x, 0.003 * grad.y, -0.001 * grad.z) * DPH * 0.01;
    assert_relative_eq!(
        tr.gyro_terms_rad[GyroTerm::TemperatureGradientBias as usize],
        expect,
        epsilon = 1e-20
    );
}

#[test]
fn g_sensitivity_and_dither_bias_at_z_up_and_z_down() {
    for (inner, sign) in [(0.0, 1.0), (180.0, -1.0)] {
        let mut cfg = ideal(0.0, inner);
        let g = &mut cfg.sensor.gyro;
        g.g_sensitivity.enabled = true;
        g.g_sensitivity.dph_per_g = [[0.0, 0.0, 0.01], [0.0, 0.0, 0.0], [0.0, 0.0, 0.02]];
        let (th, _, _, v_t) = run(&cfg, 10.0);
        let fz = v_t.z / 10.0;
        assert_relative_eq!(
            fz,
            sign * rins_plant::earth::normal_gravity(36.6f64.to_radians(), 0.0),
            epsilon = 1e-9
        );
        assert_relative_eq!(
            (th) / 10.0,
            Vector3::new(0.01, 0.0, 0.02) * DPH * fz / G0,
            epsilon = 1e-18
        );

        let mut cfg = ideal(0.0, inner);
        let d = &mut cfg.sensor.gyro.dither_bias;
        d.enabled = true;
        d.amplitude_change = [0.02; 3];
        d.dph_per_amplitude = [0.5; 3];
        let (th, _, _, _) = run(&cfg, 10.0);
        let l = fz / G0;
        let expect = Vector3::new(-1.0 / 3.0, -1.0 / 3.0, l * l - 1.0 / 3.0) * 0.5 * 0.02 * DPH;
        assert_relative_eq!((th) / 10.0, expect, epsilon = 1e-18);
    }
}

#[test]
fn position_bias_is_zero_at_z_up_full_at_z_down_and_follows_temperature() {
    for (inner, w) in [(0.0, 0.0), (180.0, 1.0), (90.0, 0.5)] {
        let mut cfg = ideal(0.0, inner);
        cfg.thermal.chamber.temp_c = 35.0;
        let pb = &mut cfg.sensor.gyro.position_bias;
        pb.enabled = true;
        pb.dph = [0.015, 0.0, 0.004];
        pb.ref_temp_c = 25.0;
        pb.dph_per_k = [1e-4, 0.0, 0.0];
        let (th, _, _, _) = run(&cfg, 10.0);
        let expect = Vector3::new(0.015 + 1e-3, 0.0, 0.004) * DPH * w;
        assert_relative_eq!((th) / 10.0, expect, epsilon = 1e-18);
    }
}

#[test]
// The axis is an argument of the regressors and coefficients as well as an index.
#[allow(clippy::needless_range_loop)]
fn regressors_times_coefficients_reproduce_each_term() {
    let mut spec = rins_plant::presets::nav_grade_full();
    // The navigation-field term is off in every preset (it needs a field's value).
    spec.gyro.nav_field_bias.enabled = true;
    spec.gyro.nav_field_bias.dph_enu = [
        [0.002, -0.004, 0.003],
        [0.001, 0.005, -0.002],
        [-0.003, 0.002, 0.004],
    ];
    let gm = rins_plant::effects::GyroModel::new(&spec.gyro);
    let am = rins_plant::effects::AccelModel::new(&spec.accel);
    let ctx = TermContext {
        dt_s: 0.01,
        dtheta_rad: Vector3::new(3e-4, -2e-4, 1e-6),
        dv_mps: Vector3::new(0.02, -0.05, 0.09),
        f_b_mps2: Vector3::new(2.0, -5.0, 8.9),
        up_b: Vector3::new(0.2, -0.5, 0.84).normalize(),
        north_b: Vector3::new(0.1, 0.9, 0.3).normalize(),
        east_b: Vector3::new(0.95, -0.1, 0.2).normalize(),
        gyro_temp_c: Vector3::new(31.0, 17.0, 44.0),
        gyro_gradient_k: Vector3::new(1.5, -0.5, 2.5),
        accel_temp_c: 39.0,
    };
    let mut terms = [Vector3::zeros(); rins_plant::effects::gyro::GYRO_TERMS];
    gm.increment_error(&ctx, &mut terms);
    for &term in GyroTerm::DETERMINISTIC {
        for axis in 0..3 {
            let mut phi = Vec::new();
            gm.regressors(term, &ctx, axis, &mut phi);
            let theta = gm.coefficients(term, axis);
            assert_eq!(phi.len(), theta.len(), "{term:?}");
            let sum: f64 = phi.iter().zip(&theta).map(|(a, b)| a * b).sum();
            assert_relative_eq!(
                sum,
                terms[term as usize][axis],
                epsilon = 1e-22,
                max_relative = 1e-12
            );
            assert!(
                terms[term as usize][axis] != 0.0,
                "{term:?} axis {axis} should be active in nav-grade-full"
            );
        }
    }
    let mut aterms = [Vector3::zeros(); 6];
    am.increment_error(&ctx, &mut aterms);
    for &term in AccelTerm::DETERMINISTIC {
        for axis in 0..3 {
            let mut phi = Vec::new();
            am.regressors(term, &ctx, axis, &mut phi);
            let sum: f64 = phi
                .iter()
                .zip(am.coefficients(term, axis))
                .map(|(a, b)| a * b)
                .sum();
            assert_relative_eq!(
                sum,
                aterms[term as usize][axis],
                epsilon = 1e-22,
                max_relative = 1e-12
            );
        }
    }
}

#[test]
fn quantized_output_sums_to_analog_within_one_pulse() {
    let mut cfg = ideal(0.0, 0.0);
    cfg.earth.rotation = true;
    cfg.sensor.gyro.quantization.enabled = true;
    cfg.sensor.gyro.quantization.pulse = [0.5; 3];
    let (th, _, th_t, _) = run(&cfg, 60.0);
    for i in 0..3 {
        let e = th[i];
        assert!(e <= 1e-15 && e > -0.5 * ARCSEC, "axis {i}: {e}");
    }
    // 60 s of Earth rate on z is ~ 25 pulses: quantised, yet not lost.
    assert!(th_t.z > 20.0 * 0.5 * ARCSEC);
}

fn sample_std(xs: &[f64]) -> f64 {
    let n = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / n;
    (xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
}

#[test]
fn angle_and_velocity_random_walk_have_the_specified_density() {
    let mut cfg = ideal(0.0, 0.0);
    cfg.sensor.gyro.angle_random_walk.enabled = true;
    cfg.sensor.gyro.angle_random_walk.dpsh = [0.003; 3];
    cfg.sensor.accel.velocity_random_walk.enabled = true;
    cfg.sensor.accel.velocity_random_walk.ug_per_sqrthz = [10.0; 3];
    let mut p = Plant::new(&cfg).unwrap();
    let n = 40_000;
    let (mut gx, mut az) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for _ in 0..n {
        let s = p.step();
        gx.push(s.dtheta_rad.x - p.truth().dtheta_true_rad.x);
        az.push(s.dv_mps.z - p.truth().dv_true_mps.z);
    }
    // 1-sigma of a sample std over n draws is sigma/sqrt(2n) ~ 0.35 %: allow 5 sigma.
    assert_relative_eq!(sample_std(&gx), 0.003 * DPSH * 0.1, max_relative = 0.018);
    assert_relative_eq!(sample_std(&az), 10.0 * UG * 0.1, max_relative = 0.018);
}

#[test]
fn bias_instability_is_stationary_with_the_specified_correlation_time() {
    // Stationary variance sigma^2 and lag-tau autocorrelation e^-1, from many 1-s updates.
    let mut cfg = ideal(0.0, 0.0);
    cfg.rate_hz = 1.0;
    let b = &mut cfg.sensor.gyro.bias_instability;
    b.enabled = true;
    b.sigma_dph = [0.01; 3];
    b.tau_s = [50.0; 3];
    let mut p = Plant::new(&cfg).unwrap();
    let xs: Vec<f64> = (0..200_000).map(|_| p.step().dtheta_rad.x / DPH).collect();
    let sd = sample_std(&xs);
    assert_relative_eq!(sd, 0.01, max_relative = 0.05);
    let m = xs.iter().sum::<f64>() / xs.len() as f64;
    let lag = 50;
    let c: f64 = xs
        .windows(lag + 1)
        .map(|w| (w[0] - m) * (w[lag] - m))
        .sum::<f64>()
        / (xs.len() - lag) as f64;
    assert_relative_eq!(c / (sd * sd), (-1.0f64).exp(), epsilon = 0.05);
}

#[test]
fn rate_random_walk_variance_grows_linearly() {
    // Across seeds, Var[b(T)] = K^2 T.
    let k = 0.01; // deg/h/sqrt(h)
    let t_end = 3600.0;
    let ends: Vec<f64> = (0..400)
        .map(|seed| {
            let mut cfg = ideal(0.0, 0.0);
            cfg.rate_hz = 1.0;
            cfg.seed = seed;
            cfg.sensor.gyro.rate_random_walk.enabled = true;
            cfg.sensor.gyro.rate_random_walk.dph_per_sqrth = [k; 3];
            let mut p = Plant::new(&cfg).unwrap();
            let mut last = 0.0;
            for _ in 0..=(t_end as usize) {
                last = p.step().dtheta_rad.y;
            }
            last / DPH
        })
        .collect();
    // sigma(T) = K sqrt(T/h) in deg/h; sample std over 400 seeds within 15 %.
    assert_relative_eq!(
        sample_std(&ends),
        k * (t_end / 3600.0f64).sqrt(),
        max_relative = 0.15
    );
}

#[test]
fn same_seed_is_bit_identical_and_another_seed_differs() {
    let mut cfg = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    };
    let sample_bits = |cfg: &PlantConfig| {
        let mut p = Plant::new(cfg).unwrap();
        (0..30_000)
            .flat_map(|_| {
                let s = p.step();
                [
                    s.dtheta_rad.x,
                    s.dtheta_rad.y,
                    s.dtheta_rad.z,
                    s.dv_mps.x,
                    s.dv_mps.y,
                    s.dv_mps.z,
                ]
                .map(f64::to_bits)
            })
            .collect::<Vec<u64>>()
    };
    let a = sample_bits(&cfg);
    assert_eq!(a, sample_bits(&cfg));
    cfg.seed = 2;
    let b = sample_bits(&cfg);
    assert_ne!(a, b);
}

#[test]
fn switching_one_noise_term_off_leaves_the_others_realisation() {
    let mut cfg = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    };
    let arw = |cfg: &PlantConfig| {
        let mut p = Plant::new(cfg).unwrap();
        (0..1000)
            .map(|_| {
                p.step();
                p.truth().gyro_terms_rad[GyroTerm::AngleRandomWalk as usize]
            })
            .collect::<Vec<_>>()
    };
    let a = arw(&cfg);
    cfg.sensor.accel.velocity_random_walk.enabled = false;
    cfg.sensor.gyro.bias_instability.enabled = false;
    assert_eq!(a, arw(&cfg));
}

/// The noise-free configuration keeps no seed-dependent term: two seeds give the same
/// increments bit for bit, while the full configuration's seeds differ, and the deterministic
/// errors are still there (the samples differ from those of an ideal IMU).
#[test]
fn a_noise_free_configuration_gives_every_seed_the_same_increments() {
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.thermal.enabled = true;
    let increments = |cfg: &PlantConfig, seed: u64| {
        let mut p = Plant::new(&PlantConfig {
            seed,
            ..cfg.clone()
        })
        .unwrap();
        (0..3000)
            .map(|_| {
                let s = p.step();
                (s.dtheta_rad, s.dv_mps)
            })
            .collect::<Vec<_>>()
    };
    assert_ne!(increments(&cfg, 1), increments(&cfg, 2));
    let quiet = cfg.noise_free();
    let one = increments(&quiet, 1);
    assert_eq!(one, increments(&quiet, 2));
    let mut ideal = quiet.clone();
    ideal.sensor = PlantConfig::default().sensor;
    assert_ne!(one, increments(&ideal, 1));
}

#[test]
fn true_increments_integrate_to_the_true_attitude_over_a_cycle() {
    // Second method: integrate the truth increments as rotation vectors and compare with the
    // attitude from the gimbal angles, over a full 16-position cycle with accel limits.
    let mut cfg = PlantConfig::default();
    cfg.earth.rotation = false;
    cfg.thermal.enabled = false;
    let mut p = Plant::new(&cfg).unwrap();
    let mut c = p.attitude_c_bn();
    let cycle = (p.schedule().cycle_s() * 100.0).round() as usize;
    for _ in 0..cycle + 12_345 {
        p.step();
        let d = p.truth().dtheta_true_rad;
        c *= nalgebra::Rotation3::from_scaled_axis(d).into_inner();
    }
    let err = (c.transpose() * p.attitude_c_bn() - nalgebra::Matrix3::identity())
        .abs()
        .max();
    assert!(err < 1e-9, "attitude mismatch {err}");
}

#[test]
fn dwell_cache_is_bit_identical_to_recomputing() {
    let cfg = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        substeps: 2,
        ..PlantConfig::default()
    };
    let mut a = Plant::new(&cfg).unwrap();
    let mut b = Plant::new(&cfg).unwrap();
    b.set_dwell_cache(false);
    let cycle = (a.schedule().cycle_s() * cfg.rate_hz) as usize;
    for k in 0..cycle + 5000 {
        let (sa, sb) = (a.step(), b.step());
        assert_eq!(sa, sb, "sample {k}");
        assert_eq!(a.truth(), b.truth(), "truth {k}");
    }
}

#[test]
fn coefficient_keys_round_trip_every_deterministic_coefficient() {
    // Writing each SI coefficient back through its scenario key (value / unit) and compiling
    // the spec again gives the same coefficients: the diagnosis can add fitted effects to files.
    use rins_plant::effects::{AccelModel, AccelTerm, GyroModel, GyroTerm, accel, gyro};
    use rins_plant::params::{ParamValue, apply, flatten};
    let cfg = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    };
    let (gm, am) = (
        GyroModel::new(&cfg.sensor.gyro),
        AccelModel::new(&cfg.sensor.accel),
    );
    let mut pairs: Vec<(String, ParamValue)> = Vec::new();
    for axis in 0..3 {
        for t in GyroTerm::DETERMINISTIC
            .iter()
            .filter(|t| **t != GyroTerm::DitherBias)
        {
            let keys = gyro::coefficient_keys(*t, axis);
            let coefs = gm.coefficients(*t, axis);
            assert_eq!(keys.len(), coefs.len(), "{t:?}");
            for ((k, unit), c) in keys.into_iter().zip(coefs) {
                pairs.push((k, ParamValue::Real(c / unit * 2.0)));
            }
        }
        for t in AccelTerm::DETERMINISTIC {
            for ((k, unit), c) in accel::coefficient_keys(*t, axis)
                .into_iter()
                .zip(am.coefficients(*t, axis))
            {
                pairs.push((k, ParamValue::Real(c / unit * 2.0)));
            }
        }
    }
    let known: Vec<String> = flatten(&cfg).into_iter().map(|p| p.path).collect();
    for (k, _) in &pairs {
        assert!(known.contains(k), "{k} is not a scenario key");
    }
    let doubled = apply(&cfg, pairs.iter().map(|(k, v)| (k.as_str(), v.clone()))).unwrap();
    let (g2, a2) = (
        GyroModel::new(&doubled.sensor.gyro),
        AccelModel::new(&doubled.sensor.accel),
    );
    for axis in 0..3 {
        for t in GyroTerm::DETERMINISTIC
            .iter()
            .filter(|t| **t != GyroTerm::DitherBias)
        {
            for (a, b) in gm
                .coefficients(*t, axis)
                .iter()
                .zip(g2.coefficients(*t, axis))
            {
                approx::assert_relative_eq!(2.0 * a, b, max_relative = 1e-12);
            }
        }
        for t in AccelTerm::DETERMINISTIC {
            for (a, b) in am
                .coefficients(*t, axis)
                .iter()
                .zip(a2.coefficients(*t, axis))
            {
                approx::assert_relative_eq!(2.0 * a, b, max_relative = 1e-12);
            }
        }
    }
}
