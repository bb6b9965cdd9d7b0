//! The generated log: deterministic in its seed, its structure as documented, the base
//! model's terms by value.

use rins_mvm::Attitude;
use rins_mvm_trials::{Design, HiddenEffect, check_model, generate};

use super::base_model;

fn small() -> Design {
    let mut d = Design::field_four_azimuths();
    d.runs.truncate(2);
    for r in &mut d.runs {
        r.duration_s = 1500.0;
    }
    d
}

#[test]
fn same_seed_same_bits_other_seed_other_noise() {
    let model = base_model();
    let design = small();
    let hidden = [HiddenEffect::GyroDitherBias {
        dph: [0.0, 0.0, 0.01],
    }];
    let a = generate(&model, &design, &hidden, 7);
    let b = generate(&model, &design, &hidden, 7);
    assert_eq!(a, b);
    let c = generate(&model, &design, &hidden, 8);
    assert_ne!(a.dtheta_rad, c.dtheta_rad);
    assert_ne!(a.dv_mps, c.dv_mps);
    // Only the noise differs: everything else is the same.
    assert_eq!(a.t_s, c.t_s);
    assert_eq!(a.gyro_temp_c, c.gyro_temp_c);
    assert_eq!(a.attitude, c.attitude);
    // The difference is the noise: its spread is the ARW over a row (0.003 °/√h, 0.1 s).
    let n = a.len() as f64;
    let var: f64 = (0..a.len())
        .map(|k| (a.dtheta_rad[2][k] - c.dtheta_rad[2][k]).powi(2))
        .sum::<f64>()
        / n;
    let sigma = 0.003 * std::f64::consts::PI / 180.0 / 60.0 * 0.1f64.sqrt();
    let ratio = (var / 2.0).sqrt() / sigma;
    assert!((ratio - 1.0).abs() < 0.03, "{ratio}");
}

#[test]
fn history_has_one_segment_per_run_with_readings() {
    let model = base_model();
    let design = small();
    let h = generate(&model, &design, &[], 1);
    assert_eq!(h.run_names, ["run1", "run2"]);
    assert_eq!(h.segments, [0..15000, 15000..30000]);
    assert_eq!(h.t_s[0], 0.1);
    assert!((h.t_s[15000] - (1500.0 + 100.0 + 0.1)).abs() < 1e-9);
    for seg in &h.segments {
        assert!(h.t_s[seg.clone()].windows(2).all(|w| w[1] > w[0]));
    }
    // Readings on the 1/16 K grid; the blocks above the housing by their self-heating.
    let housing = h.housing_temp_c.as_ref().expect("housing");
    for k in [0, 7000, 29999] {
        for t in [h.gyro_temp_c[0][k], housing[k], h.accel_temp_c[k]] {
            assert_eq!((t * 16.0).fract(), 0.0);
        }
        assert!((h.gyro_temp_c[2][k] - housing[k] - 3.0).abs() <= 1.0 / 32.0);
    }
    let Attitude::Gimbal {
        outer_rad,
        inner_rad,
    } = &h.attitude
    else {
        panic!("gimbal angles")
    };
    assert_eq!((outer_rad[0], inner_rad[0]), (0.0, 0.0));
    // Outer 90° after the first dwell and move (600 s + 9 s).
    assert!((outer_rad[6200] - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
}

#[test]
fn model_terms_other_than_the_base_ones_are_refused() {
    assert!(check_model(&base_model()).is_ok());
    let mut m = base_model();
    m.sensor = rins_plant::presets::paper_table3();
    let e = check_model(&m).expect_err("misalignment and position bias are on");
    assert!(
        e.contains("gyro.misalignment") && e.contains("gyro.position_bias"),
        "{e}"
    );
}
