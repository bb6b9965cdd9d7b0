//! Declared effects end to end: a scenario declares `[[sensor.gyro.custom]]`, `rins diagnose`
//! tests it next to the catalogue and `--apply custom:NAME` fits it. The dataset is written
//! here from closed-form physics (not through the plant or its regressors): a unit at rest
//! whose blocks lag a housing that follows a chamber step, with a gyro bias proportional to
//! the block temperature rate dT/dt, Table-3-like bias and white noise.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rins_mvm::csv;
use rins_mvm::{Effect, History, Options, analyse, to_history};
use rins_plant::PlantConfig;
use rins_scenario::file::Scenario;

/// The model: the bias and noise are known; the temperature-rate term is declared with a zero
/// coefficient (a candidate, contributing nothing until fitted).
const MODEL: &str = r#"
[scenario]
name = "declared-model"
duration_s = 4000.0
[run]
rate_hz = 10.0
[sensor]
preset = "ideal"
gyro.bias = { enabled = true, dph = [0.01, -0.02, 0.015] }
gyro.angle_random_walk = { enabled = true, dpsh = [0.0005, 0.0005, 0.0005] }
accel.bias = { enabled = true, ug = [50.0, -30.0, 40.0] }

[[sensor.gyro.custom]]
name = "trate"
kind = "bias"
regressor = "dtemp_dt:block"
unit = "K/s"
axes = ["x", "y", "z"]
coef = [0.0, 0.0, 0.0]
"#;

/// Hidden: bias = K·dT_block/dt, °/h per K/s (x and z; y has none).
const K_DPH_PER_K_PER_S: [f64; 3] = [2.0, 0.0, -1.5];
const ARW_DPSH: f64 = 0.0005;
const VRW_UG_PER_SQRTHZ: f64 = 20.0;
const TAU_HOUSING_S: f64 = 1500.0;
const TAU_BLOCK_S: f64 = 400.0;
const RUN_S: f64 = 4000.0;
const RATE_HZ: f64 = 10.0;

/// A run: chamber step `from → to` at t = 0, table static at (outer, inner) degrees.
struct Run {
    from_c: f64,
    to_c: f64,
    outer_deg: f64,
    inner_deg: f64,
}

const RUNS: [Run; 4] = [
    Run {
        from_c: 20.0,
        to_c: 40.0,
        outer_deg: 0.0,
        inner_deg: 0.0,
    },
    Run {
        from_c: 40.0,
        to_c: 15.0,
        outer_deg: 180.0,
        inner_deg: 0.0,
    },
    Run {
        from_c: 10.0,
        to_c: 35.0,
        outer_deg: 180.0,
        inner_deg: 180.0,
    },
    Run {
        from_c: 45.0,
        to_c: 25.0,
        outer_deg: 0.0,
        inner_deg: 180.0,
    },
];

/// Housing after the step: first order, T_h = T1 + (T0 − T1)·e^(−t/τh).
fn housing_c(r: &Run, t: f64) -> f64 {
    r.to_c + (r.from_c - r.to_c) * (-t / TAU_HOUSING_S).exp()
}

/// Self-heating of the blocks above the housing, K: larger in a cold chamber (so the
/// block-minus-housing gradient differs from run to run by more than its transient part).
fn self_heating_k(r: &Run) -> f64 {
    2.0 - 0.08 * (r.to_c - 25.0)
}

/// A block lagging the housing with τb plus its self-heating:
/// T_b = T1 + ΔT_sh + (T0 − T1)·(τh·e^(−t/τh) − τb·e^(−t/τb))/(τh − τb).
fn block_c(r: &Run, t: f64) -> f64 {
    let (th, tb) = (TAU_HOUSING_S, TAU_BLOCK_S);
    r.to_c
        + self_heating_k(r)
        + (r.from_c - r.to_c) * (th * (-t / th).exp() - tb * (-t / tb).exp()) / (th - tb)
}

fn normal(rng: &mut ChaCha8Rng) -> f64 {
    // Box–Muller.
    let u1: f64 = rng.random::<f64>().max(1e-300);
    let u2: f64 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

/// The measurement CSV text of all runs.
fn dataset_text(model: &PlantConfig) -> String {
    let site = rins_plant::earth::Site::new(&model.site, &model.earth);
    let dph = std::f64::consts::PI / 180.0 / 3600.0;
    let bias = model.sensor.gyro.bias.dph.map(|b| b * dph);
    let abias = model.sensor.accel.bias.ug.map(|b| b * 1e-6 * 9.80665);
    let arw = ARW_DPSH * std::f64::consts::PI / 180.0 / 60.0;
    let vrw = VRW_UG_PER_SQRTHZ * 1e-6 * 9.80665;
    let dt = 1.0 / RATE_HZ;
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut out = String::from(
        "t_s,run,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps,outer_deg,inner_deg,temp_gyro_x_c,temp_gyro_y_c,temp_gyro_z_c,temp_accel_c,temp_housing_c\n",
    );
    for (i, r) in RUNS.iter().enumerate() {
        // C_b^n = R_z(outer)·R_x(inner) (level mount); C_n^b = its transpose.
        let (so, co) = r.outer_deg.to_radians().sin_cos();
        let (si, ci) = r.inner_deg.to_radians().sin_cos();
        let rz = nalgebra::Matrix3::new(co, -so, 0.0, so, co, 0.0, 0.0, 0.0, 1.0);
        let rx = nalgebra::Matrix3::new(1.0, 0.0, 0.0, 0.0, ci, -si, 0.0, si, ci);
        let c_nb = (rz * rx).transpose();
        let w_b = c_nb * site.omega_ie_n;
        let f_b = c_nb * nalgebra::Vector3::new(0.0, 0.0, site.gravity_mps2);
        let n = (RUN_S * RATE_HZ) as usize;
        for k in 0..=n {
            let t = k as f64 * dt;
            let tb = block_c(r, t);
            let mut dtheta = [0.0; 3];
            let mut dv = [0.0; 3];
            for a in 0..3 {
                // ∫ K·dT_b/dt dt over the row = K·(T_b(t) − T_b(t − Δt)), exactly.
                let hidden = if k == 0 {
                    0.0
                } else {
                    K_DPH_PER_K_PER_S[a] * dph * (tb - block_c(r, t - dt))
                };
                dtheta[a] =
                    w_b[a] * dt + bias[a] * dt + hidden + arw * dt.sqrt() * normal(&mut rng);
                dv[a] = f_b[a] * dt + abias[a] * dt + vrw * dt.sqrt() * normal(&mut rng);
            }
            out.push_str(&format!(
                "{:.1},run{i},{:e},{:e},{:e},{:e},{:e},{:e},{},{},{tb:.9},{tb:.9},{tb:.9},{tb:.9},{:.9}\n",
                t + dt,
                dtheta[0],
                dtheta[1],
                dtheta[2],
                dv[0],
                dv[1],
                dv[2],
                r.outer_deg,
                r.inner_deg,
                housing_c(r, t)
            ));
        }
    }
    out
}

fn model() -> PlantConfig {
    Scenario::from_toml(MODEL, "model").unwrap().plant
}

fn history(m: &PlantConfig) -> History {
    let text = dataset_text(m);
    to_history(csv::parse(&text, "dataset").unwrap(), "dataset").unwrap()
}

#[test]
fn declared_temperature_rate_term_is_found_fitted_and_beats_the_gradient_stand_in() {
    let m = model();
    let h = history(&m);
    let trate = Effect::parse_in(&m, "custom:trate").expect("declared");
    let an = analyse(
        &m,
        &h,
        &Options {
            diagnose: true,
            apply: vec![trate],
            ..Options::default()
        },
    );
    let report = an.diagnosis.as_ref().unwrap().report.clone();
    for (axis, ch) in [(0, "gyro_x"), (2, "gyro_z")] {
        let on: Vec<_> = report.ranking.iter().filter(|r| r.channel == ch).collect();
        let top = on[0];
        assert_eq!(top.effect, "custom:trate", "{ch}: {:#?}", &on[..3]);
        assert!(top.passes_gate, "{top:#?}");
        let k = K_DPH_PER_K_PER_S[axis];
        assert!(
            top.ci95[0][0] <= k && k <= top.ci95[0][1],
            "{ch}: true {k} outside {:?}",
            top.ci95[0]
        );
        assert_eq!(top.keys[0], format!("sensor.gyro.custom[0].coef[{axis}]"));
        // The catalogue stand-in: ranked below, named confusable with the declared term, and
        // not accepted.
        let grad = on
            .iter()
            .find(|r| r.effect == "gyro.temperature_gradient_bias")
            .expect("gradient ranked");
        assert!(grad.delta_bic > top.delta_bic, "{grad:#?}");
        assert!(
            grad.confusable_with
                .iter()
                .any(|c| c.effect.starts_with("custom:trate")),
            "{ch}: {grad:#?}"
        );
        let accepted: Vec<&str> = report
            .accepted
            .iter()
            .filter(|r| r.channel == ch)
            .map(|r| r.effect.as_str())
            .collect();
        assert_eq!(accepted.first(), Some(&"custom:trate"), "{accepted:?}");
        assert!(
            !accepted.contains(&"gyro.temperature_gradient_bias"),
            "{accepted:?}"
        );
    }
    // --apply custom:trate: the fitted model brings each gyro residual to the noise floor.
    let applied = an.applied.clone().unwrap().unwrap();
    let fitted = &applied.model.sensor.gyro.custom[0];
    assert!(fitted.enabled);
    let after = analyse(&applied.model, &h, &Options::default());
    for c in after
        .comparison
        .channels
        .iter()
        .filter(|c| c.channel.starts_with("gyro"))
    {
        assert!(
            c.residual_rms <= 1.1 * c.noise_floor_rms,
            "{}: {} vs floor {}",
            c.channel,
            c.residual_rms,
            c.noise_floor_rms
        );
    }
    // The model file written back carries the declared effect with its fitted coefficients.
    let text = applied.model_file(MODEL, "test").unwrap();
    let back = Scenario::from_toml(&text, "fitted").unwrap().plant;
    assert_eq!(back.sensor.gyro.custom, applied.model.sensor.gyro.custom);
    eprintln!(
        "fitted coef {:?} (true {K_DPH_PER_K_PER_S:?}); before {:?} after {:?}",
        fitted.coef, report.residual_rms_before, report.residual_rms_after
    );
}

#[test]
fn bad_declarations_name_the_line() {
    let cases = [
        (
            "regressor = \"dtemp_dt:block\"",
            "regressor = \"dtemp:block\"",
            "unknown signal",
        ),
        ("unit = \"K/s\"", "unit = \"K\"", "K/s"),
        (
            "coef = [0.0, 0.0, 0.0]",
            "coef = [0.0, 0.0, 1e308]",
            "expected a number in [-1e9, 1e9], got 1e308",
        ),
    ];
    for (from, to, says) in cases {
        let text = MODEL.replace(from, to);
        let line = text
            .lines()
            .position(|l| l.starts_with(to.split(' ').next().unwrap()))
            .unwrap()
            + 1;
        let e = Scenario::from_toml(&text, "bad.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains(&format!("line {line},")), "{to}: {e}");
        assert!(e.contains(says), "{to}: {e}");
        assert!(e.contains("sensor.gyro.custom[0]."), "{to}: {e}");
    }
    // A product that overflows over the signals' ranges (time up to 1e7 s) is refused.
    let text = MODEL
        .replace(
            "regressor = \"dtemp_dt:block\"",
            "regressor = \"time^8*time^8*time^8*time^8*time^8*time^8\"",
        )
        .replace("unit = \"K/s\"", "unit = \"s^48\"")
        .replace("coef = [0.0, 0.0, 0.0]", "coef = [0.0, 0.0, 1.0]");
    let e = Scenario::from_toml(&text, "bad.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("stays finite") && e.contains("line 16,"), "{e}");
    // Unknown keys in a declaration are the parser's errors, with their line.
    let text = MODEL.replace("kind = \"bias\"", "kind = \"bias\"\nslope = 1.0");
    let e = Scenario::from_toml(&text, "bad.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("slope") && e.contains("line"), "{e}");
}
