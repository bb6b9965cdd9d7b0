//! Property test of the dwell cache's invariant (issue 44): the plant reuses a held dwell's
//! interval only for terms whose contribution is the same every tick of the dwell, as each
//! catalogue term declares (`DwellDependence`) and each declared effect says
//! (`varies_in_dwell`). Run with the cache and without it (`Plant::set_dwell_cache(false)`),
//! every output sample and the whole truth must be the same bits: for every catalogue term
//! alone and in random combinations, for every declared-effect signal family plain, through
//! `lag(SIGNAL, TAU)` and, for the clocks, through `exp(-CLOCK/TAU)`, and for random products
//! of them, each on random step lists and the built-in schemes.
//!
//! Fixed seeds (ChaCha8): a failure prints the case and its configuration to replay.

use rand::seq::IndexedRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rins_plant::effects::custom::{
    Axis, CustomKind, CustomSpec, FAMILIES, Factor, Op, Signal, regressor_text, unit_of,
};
use rins_plant::effects::gyro::Transition;
use rins_plant::effects::{AccelSpec, AccelTerm, GyroSpec, GyroTerm};
use rins_plant::table::{GimbalAxis, RotationStep, SchemeKind, SchemeSpec};
use rins_plant::{GimbalCommand, ImuSample, Plant, PlantConfig, Truth};

const SEED: u64 = 0x5eed_0044;
/// Random combinations of catalogue terms.
const CATALOGUE_MIXES: usize = 32;
/// Random products of declared-effect factors, with random catalogue terms beside them.
const DECLARED_MIXES: usize = 32;
/// Cases per signal family and operator (each its own signal of the family, e.g. a node).
const PER_FAMILY: usize = 2;
/// Output samples per case, at most (the run also ends with its scheme's first cycle or so).
const MAX_SAMPLES: usize = 3000;

/// Values in ±`scale`, one per axis.
fn axes3(rng: &mut ChaCha8Rng, scale: f64) -> [f64; 3] {
    std::array::from_fn(|_| rng.random_range(-scale..scale))
}

/// Positive values in (0.1, 1]·`scale`, one per axis.
fn positive3(rng: &mut ChaCha8Rng, scale: f64) -> [f64; 3] {
    std::array::from_fn(|_| rng.random_range(0.1..1.0) * scale)
}

/// Switches gyro term `t` on with random parameters of a navigation-grade size. No wildcard
/// arm: a new catalogue term does not compile here until the test draws its parameters.
fn randomise_gyro(rng: &mut ChaCha8Rng, g: &mut GyroSpec, t: GyroTerm) {
    g.set_enabled(t, true);
    match t {
        GyroTerm::Bias => g.bias.dph = axes3(rng, 0.02),
        GyroTerm::ScaleFactor => g.scale_factor.ppm = axes3(rng, 10.0),
        GyroTerm::ScaleFactorAsymmetry => g.scale_factor_asymmetry.ppm = axes3(rng, 2.0),
        GyroTerm::Misalignment => {
            g.misalignment.arcsec = std::array::from_fn(|_| rng.random_range(-10.0..10.0))
        }
        GyroTerm::TemperatureBias => {
            let p = &mut g.temperature_bias;
            p.ref_temp_c = rng.random_range(15.0..35.0);
            p.per_k = axes3(rng, 3e-4);
            p.per_k2 = axes3(rng, 1e-5);
            p.per_k3 = axes3(rng, 2e-7);
        }
        GyroTerm::TemperatureGradientBias => {
            g.temperature_gradient_bias.dph_per_k = axes3(rng, 0.003)
        }
        GyroTerm::GSensitivity => {
            g.g_sensitivity.dph_per_g = std::array::from_fn(|_| axes3(rng, 0.002))
        }
        GyroTerm::PositionBias => {
            let p = &mut g.position_bias;
            p.dph = axes3(rng, 0.02);
            p.transition = *[Transition::Cosine, Transition::Step].choose(rng).unwrap();
            p.ref_temp_c = rng.random_range(15.0..35.0);
            p.dph_per_k = axes3(rng, 2e-4);
            p.dph_per_k2 = axes3(rng, 5e-6);
            p.dph_per_k3 = axes3(rng, 1e-7);
        }
        GyroTerm::DitherBias => {
            g.dither_bias.amplitude_change = axes3(rng, 0.05);
            g.dither_bias.dph_per_amplitude = axes3(rng, 0.1);
        }
        GyroTerm::NavFieldBias => {
            g.nav_field_bias.dph_enu = std::array::from_fn(|_| axes3(rng, 0.01))
        }
        GyroTerm::AngleRandomWalk => g.angle_random_walk.dpsh = positive3(rng, 0.005),
        GyroTerm::BiasInstability => {
            g.bias_instability.sigma_dph = positive3(rng, 0.003);
            g.bias_instability.tau_s = positive3(rng, 3600.0);
        }
        GyroTerm::RateRandomWalk => g.rate_random_walk.dph_per_sqrth = positive3(rng, 0.001),
        GyroTerm::Quantization => g.quantization.pulse = positive3(rng, 0.2),
    }
}

/// Switches accelerometer term `t` on with random parameters (see [`randomise_gyro`]).
fn randomise_accel(rng: &mut ChaCha8Rng, a: &mut AccelSpec, t: AccelTerm) {
    a.set_enabled(t, true);
    match t {
        AccelTerm::Bias => a.bias.ug = axes3(rng, 100.0),
        AccelTerm::ScaleFactor => a.scale_factor.ppm = axes3(rng, 100.0),
        AccelTerm::Misalignment => {
            a.misalignment.arcsec = std::array::from_fn(|_| rng.random_range(-10.0..10.0))
        }
        AccelTerm::TemperatureBias => {
            let p = &mut a.temperature_bias;
            p.ref_temp_c = rng.random_range(15.0..35.0);
            p.per_k = axes3(rng, 3.0);
            p.per_k2 = axes3(rng, 0.1);
            p.per_k3 = axes3(rng, 0.002);
        }
        AccelTerm::VelocityRandomWalk => {
            a.velocity_random_walk.ug_per_sqrthz = positive3(rng, 20.0)
        }
        AccelTerm::Quantization => a.quantization.pulse = positive3(rng, 2e-5),
    }
}

/// A random step list: axes, signed angles, rates, accelerations and dwells (zero, shorter
/// than an output interval, not a whole number of them, or several seconds).
fn random_steps(rng: &mut ChaCha8Rng) -> SchemeSpec {
    let steps = (0..rng.random_range(1..6))
        .map(|_| RotationStep {
            axis: *[GimbalAxis::Outer, GimbalAxis::Inner].choose(rng).unwrap(),
            angle_deg: rng.random_range(5.0..270.0) * if rng.random_bool(0.5) { 1.0 } else { -1.0 },
            rate_dps: rng.random_range(5.0..100.0),
            dwell_s: match rng.random_range(0..4) {
                0 => 0.0,
                1 => rng.random_range(0.0..0.2),
                _ => rng.random_range(0.5..8.0),
            },
        })
        .collect();
    SchemeSpec {
        kind: SchemeKind::Steps,
        accel_dps2: if rng.random_bool(0.5) {
            f64::INFINITY
        } else {
            rng.random_range(20.0..500.0)
        },
        lead_dwell_s: rng.random_range(0.0..5.0),
        initial_outer_deg: rng.random_range(-180.0..180.0),
        initial_inner_deg: rng.random_range(-180.0..180.0),
        repeat: rng.random_bool(0.7),
        steps,
        ..SchemeSpec::default()
    }
}

/// A built-in scheme (mostly the 16-position one) sped up to a short cycle.
fn random_builtin(rng: &mut ChaCha8Rng) -> SchemeSpec {
    let kind = *[
        SchemeKind::SixteenPosition,
        SchemeKind::SixteenPosition,
        SchemeKind::EightPosition,
        SchemeKind::ZUpCalibration,
        SchemeKind::ZDownCalibration,
        SchemeKind::Static,
    ]
    .choose(rng)
    .unwrap();
    builtin(rng, kind)
}

/// The built-in scheme `kind` at a random rate, acceleration limit and dwell, sped up so that
/// a cycle fits a short run.
fn builtin(rng: &mut ChaCha8Rng, kind: SchemeKind) -> SchemeSpec {
    SchemeSpec {
        kind,
        rate_dps: rng.random_range(20.0..90.0),
        accel_dps2: if rng.random_bool(0.5) {
            f64::INFINITY
        } else {
            rng.random_range(50.0..500.0)
        },
        dwell_s: rng.random_range(0.3..6.0),
        lead_dwell_s: rng.random_range(0.0..3.0),
        ..SchemeSpec::default()
    }
}

/// A configuration with nothing on but the readout's encoders and temperature sensors, at a
/// random rate, substep count, thermal step, chamber ramp and site, on a random scheme.
fn base(rng: &mut ChaCha8Rng) -> PlantConfig {
    let mut c = PlantConfig {
        rate_hz: *[10.0, 20.0, 50.0, 100.0].choose(rng).unwrap(),
        substeps: rng.random_range(1..4),
        seed: rng.random_range(0..1000),
        ..PlantConfig::default()
    };
    c.site.lat_deg = rng.random_range(-70.0..70.0);
    c.scheme = if rng.random_bool(0.6) {
        random_steps(rng)
    } else {
        random_builtin(rng)
    };
    c.thermal.enabled = rng.random_bool(0.8);
    c.thermal.step_s = rng.random_range(1..40) as f64 / c.rate_hz;
    c.thermal.start_steady = rng.random_bool(0.5);
    let t0 = rng.random_range(15.0..30.0);
    c.thermal.chamber.profile = vec![[0.0, t0], [60.0, t0 + rng.random_range(-15.0..15.0)]];
    let s = &mut c.sensor;
    s.encoder.scale_factor.enabled = true;
    s.encoder.scale_factor.ppm = [rng.random_range(-50.0..50.0), rng.random_range(-50.0..50.0)];
    s.encoder.offset.enabled = true;
    s.encoder.offset.arcsec = [rng.random_range(-20.0..20.0), rng.random_range(-20.0..20.0)];
    s.encoder.quantization.enabled = rng.random_bool(0.5);
    s.temperature.offset.enabled = true;
    s.temperature.offset.k = std::array::from_fn(|_| rng.random_range(-0.5..0.5));
    s.temperature.noise.enabled = true;
    s.temperature.noise.sigma_k = std::array::from_fn(|_| rng.random_range(0.0..0.05));
    s.temperature.resolution.enabled = rng.random_bool(0.5);
    c
}

/// Some catalogue terms of both sensors switched on with random parameters.
fn random_catalogue(rng: &mut ChaCha8Rng, c: &mut PlantConfig, p: f64) {
    for t in GyroTerm::ALL {
        if rng.random_bool(p) {
            randomise_gyro(rng, &mut c.sensor.gyro, t);
        }
    }
    for t in AccelTerm::ALL {
        if rng.random_bool(p) {
            randomise_accel(rng, &mut c.sensor.accel, t);
        }
    }
}

/// A factor of a signal of row `family` of the signals table with operator `op` (a time
/// constant drawn when `op` has one).
fn factor(rng: &mut ChaCha8Rng, family: usize, op: Op) -> Factor {
    let signal = *Signal::all_of(family).choose(rng).unwrap();
    let tau_s = *[0.05, 0.7, 3.0, 20.0, 300.0].choose(rng).unwrap() * rng.random_range(0.8..1.25);
    Factor {
        signal,
        power: rng.random_range(1..3),
        op: match op {
            Op::Plain => Op::Plain,
            Op::Lag { .. } => Op::Lag { tau_s },
            Op::Decay { .. } => Op::Decay { tau_s },
        },
    }
}

/// A declared effect named `name` with regressor `factors`, on random axes with random
/// coefficients, a bias or a scale factor.
fn declared(rng: &mut ChaCha8Rng, name: &str, factors: &[Factor]) -> CustomSpec {
    let mut axes: Vec<Axis> = (0..3)
        .filter(|_| rng.random_bool(0.6))
        .map(Axis::of)
        .collect();
    if axes.is_empty() {
        axes.push(Axis::of(rng.random_range(0..3)));
    }
    let mut coef = [0.0; 3];
    for a in &axes {
        coef[a.index()] = rng.random_range(-0.01..0.01);
    }
    CustomSpec {
        name: name.into(),
        enabled: true,
        kind: if rng.random_bool(0.7) {
            CustomKind::Bias
        } else {
            CustomKind::ScaleFactor
        },
        regressor: regressor_text(factors),
        unit: unit_of(factors).to_string(),
        axes,
        coef,
    }
}

/// The operators a signal of row `family` may take: plain and lag always, a decay for a clock.
fn operators(family: usize) -> Vec<Op> {
    let mut ops = vec![Op::Plain, Op::Lag { tau_s: 1.0 }];
    if FAMILIES[family].clock {
        ops.push(Op::Decay { tau_s: 1.0 });
    }
    ops
}

/// Every bit of a sample and of the truth beside it.
fn bits(s: &ImuSample, t: &Truth) -> Vec<u64> {
    let mut v = vec![s.index, s.t_s.to_bits()];
    let mut f = |x: f64| v.push(x.to_bits());
    s.dtheta_rad.iter().chain(&s.dv_mps).for_each(|x| f(*x));
    f(s.encoder.outer_rad);
    f(s.encoder.inner_rad);
    s.temps_c.iter().for_each(|x| f(*x));
    let g = &t.gimbal;
    [
        g.angles.outer_rad,
        g.angles.inner_rad,
        g.outer_rate_rps,
        g.inner_rate_rps,
    ]
    .into_iter()
    .for_each(&mut f);
    f(g.step_index as f64);
    f(g.moving as u8 as f64);
    t.dtheta_true_rad
        .iter()
        .chain(&t.dv_true_mps)
        .for_each(|x| f(*x));
    t.temps.nodes_c.iter().for_each(|x| f(*x));
    f(t.temps.chamber_c);
    t.gyro_terms_rad
        .iter()
        .chain(&t.accel_terms_mps)
        .flat_map(|x| x.iter())
        .for_each(|x| f(*x));
    f(t.position_weight);
    t.custom_gyro_rad
        .iter()
        .chain(&t.custom_accel_mps)
        .for_each(|x| f(*x));
    let c = &t.carrier;
    [c.lat_rad, c.lon_rad, c.height_m]
        .into_iter()
        .for_each(&mut f);
    c.v_n
        .iter()
        .chain(c.q_cn.coords.iter())
        .chain(&c.omega_nc_c)
        .for_each(|x| f(*x));
    v
}

/// Runs `cfg` with the dwell cache and without it, side by side (a gimbal command in the
/// middle of the run half the time), and asserts every sample and truth the same bits.
fn assert_cache_invisible(rng: &mut ChaCha8Rng, label: &str, cfg: &PlantConfig) {
    let mut cached = Plant::new(cfg).unwrap_or_else(|e| panic!("{label}: {e:?}\n{cfg:#?}"));
    let mut worked = Plant::new(cfg).unwrap();
    worked.set_dwell_cache(false);
    // The lead dwell, a cycle of moves and a dwell after it, or half the most for a table
    // that never moves.
    let s = cached.schedule();
    let cycle = ((s.lead_s() + s.cycle_s()) * cfg.rate_hz).ceil();
    let n = if s.cycle_s() > 0.0 {
        (cycle as usize + 100).min(MAX_SAMPLES)
    } else {
        MAX_SAMPLES / 2
    };
    let command = rng.random_bool(0.5).then(|| {
        (
            rng.random_range(0..n),
            GimbalCommand::MoveTo {
                outer_rad: rng.random_range(-3.0..3.0),
                inner_rad: rng.random_range(-3.0..3.0),
                rate_rps: rng.random_range(0.2..1.5),
            },
        )
    });
    for k in 0..n {
        if let Some((at, cmd)) = &command
            && *at == k
        {
            cached.command_gimbal(cmd).unwrap();
            worked.command_gimbal(cmd).unwrap();
        }
        let (a, b) = (cached.step(), worked.step());
        let (ta, tb) = (cached.truth(), worked.truth());
        if bits(&a, &ta) != bits(&b, &tb) {
            panic!(
                "{label}: sample {k} differs with the dwell cache\n cached {a:?}\n worked {b:?}\n \
                 truth cached {ta:?}\n truth worked {tb:?}\n{cfg:#?}"
            );
        }
    }
}

#[test]
fn every_catalogue_term_alone_is_the_same_bits_with_and_without_the_dwell_cache() {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    // Each term on a random scheme, then on the 16-position one.
    for sixteen in [false, true] {
        for t in GyroTerm::ALL {
            let mut c = base(&mut rng);
            if sixteen {
                c.scheme = builtin(&mut rng, SchemeKind::SixteenPosition);
            }
            randomise_gyro(&mut rng, &mut c.sensor.gyro, t);
            assert_cache_invisible(&mut rng, &format!("gyro {}", t.key()), &c);
        }
        for t in AccelTerm::ALL {
            let mut c = base(&mut rng);
            if sixteen {
                c.scheme = builtin(&mut rng, SchemeKind::SixteenPosition);
            }
            randomise_accel(&mut rng, &mut c.sensor.accel, t);
            assert_cache_invisible(&mut rng, &format!("accel {}", t.key()), &c);
        }
    }
}

#[test]
fn random_combinations_of_catalogue_terms_are_the_same_bits_with_and_without_the_dwell_cache() {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED + 1);
    for case in 0..CATALOGUE_MIXES {
        let mut c = base(&mut rng);
        random_catalogue(&mut rng, &mut c, 0.5);
        assert_cache_invisible(&mut rng, &format!("catalogue mix {case}"), &c);
    }
}

#[test]
fn every_declared_signal_family_and_operator_is_the_same_bits_with_and_without_the_dwell_cache() {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED + 2);
    for (family, f) in FAMILIES.iter().enumerate() {
        let ops = operators(family);
        for (k, op) in ops.into_iter().flat_map(|op| [op; PER_FAMILY]).enumerate() {
            let mut c = base(&mut rng);
            // Every other case on the 16-position scheme.
            if k % 2 == 1 {
                c.scheme = builtin(&mut rng, SchemeKind::SixteenPosition);
            }
            let g = [factor(&mut rng, family, op)];
            let a = [factor(&mut rng, family, op)];
            c.sensor.gyro.custom = vec![declared(&mut rng, "g", &g)];
            c.sensor.accel.custom = vec![declared(&mut rng, "a", &a)];
            let label = format!(
                "declared {} ({}, {})",
                f.doc_name, c.sensor.gyro.custom[0].regressor, c.sensor.accel.custom[0].regressor
            );
            assert_cache_invisible(&mut rng, &label, &c);
        }
    }
}

#[test]
fn declared_products_beside_catalogue_terms_are_the_same_bits_with_and_without_the_dwell_cache() {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED + 3);
    for case in 0..DECLARED_MIXES {
        let mut c = base(&mut rng);
        random_catalogue(&mut rng, &mut c, 0.3);
        let product = |rng: &mut ChaCha8Rng| -> Vec<Factor> {
            (0..rng.random_range(1..4))
                .map(|_| {
                    let family = rng.random_range(0..FAMILIES.len());
                    let op = *operators(family).choose(rng).unwrap();
                    factor(rng, family, op)
                })
                .collect()
        };
        for (k, accel) in [(0, false), (1, false), (2, true), (3, true)] {
            let factors = product(&mut rng);
            let spec = declared(&mut rng, &format!("e{k}"), &factors);
            if accel {
                c.sensor.accel.custom.push(spec);
            } else {
                c.sensor.gyro.custom.push(spec);
            }
        }
        assert_cache_invisible(&mut rng, &format!("declared mix {case}"), &c);
    }
}
