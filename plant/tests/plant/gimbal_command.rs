//! Table commands from the navigation side: the table goes where it is told, the kinematics stay
//! consistent (the integrated gyro output equals the commanded rotation), and a saved state
//! replays a commanded run bit for bit.

use approx::assert_relative_eq;
use rins_plant::table::scheme::ResolvedStep;
use rins_plant::table::{GimbalAxis, SchemeKind, SchemeSpec};
use rins_plant::{GimbalCommand, Plant, PlantConfig};

fn static_ideal() -> PlantConfig {
    let mut cfg = PlantConfig {
        scheme: SchemeSpec {
            kind: SchemeKind::Static,
            ..SchemeSpec::default()
        },
        ..PlantConfig::default()
    };
    cfg.earth.rotation = false;
    cfg
}

#[test]
fn move_to_reaches_the_target_and_the_gyros_see_exactly_that_rotation() {
    let mut p = Plant::new(&static_ideal()).unwrap();
    for _ in 0..100 {
        p.step();
    }
    let target = 90f64.to_radians();
    p.command_gimbal(&GimbalCommand::MoveTo {
        outer_rad: target,
        inner_rad: 0.0,
        rate_rps: 10f64.to_radians(),
    })
    .unwrap();
    let mut sum_z = 0.0;
    // 9 s cruise + 0.5 s of acceleration at 20 °/s²; run 12 s.
    for _ in 0..1200 {
        sum_z += p.step().dtheta_rad.z;
    }
    let g = p.truth().gimbal;
    assert_eq!(g.angles.outer_rad, target);
    assert_eq!(g.angles.inner_rad, 0.0);
    assert!(!g.moving);
    // Earth rate is off and the table turns about body z (inner at 0): Δθz sums to the angle.
    assert_relative_eq!(sum_z, target, epsilon = 1e-12);
}

#[test]
fn commands_are_validated_with_the_reason() {
    let mut p = Plant::new(&static_ideal()).unwrap();
    let e = p
        .command_gimbal(&GimbalCommand::MoveTo {
            outer_rad: f64::NAN,
            inner_rad: 0.0,
            rate_rps: 0.1,
        })
        .unwrap_err();
    assert!(e.contains("finite"), "{e}");
    let e = p
        .command_gimbal(&GimbalCommand::MoveTo {
            outer_rad: 1.0,
            inner_rad: 0.0,
            rate_rps: 0.0,
        })
        .unwrap_err();
    assert!(e.contains("rate"), "{e}");
    let bad = ResolvedStep {
        axis: GimbalAxis::Inner,
        angle_rad: 1.0,
        rate_rps: 0.1,
        dwell_s: -1.0,
    };
    let e = p
        .command_gimbal(&GimbalCommand::Steps {
            steps: vec![bad],
            repeat: false,
        })
        .unwrap_err();
    assert!(e.contains("step 0"), "{e}");
}

#[test]
fn a_commanded_run_resumes_bit_identically_from_a_saved_state() {
    let cfg = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    };
    let mut a = Plant::new(&cfg).unwrap();
    for _ in 0..500 {
        a.step();
    }
    let steps = vec![
        ResolvedStep {
            axis: GimbalAxis::Inner,
            angle_rad: std::f64::consts::PI,
            rate_rps: 0.2,
            dwell_s: 3.0,
        },
        ResolvedStep {
            axis: GimbalAxis::Outer,
            angle_rad: -1.0,
            rate_rps: 0.1,
            dwell_s: 2.0,
        },
    ];
    a.command_gimbal(&GimbalCommand::Steps {
        steps,
        repeat: true,
    })
    .unwrap();
    for _ in 0..1234 {
        a.step();
    }
    let saved = a.serialize_state();
    let mut b = Plant::from_serialized_state(&cfg, &saved).unwrap();
    for _ in 0..5000 {
        let (x, y) = (a.step(), b.step());
        assert_eq!(x, y);
        assert_eq!(a.truth(), b.truth());
    }
}

#[test]
fn reseeding_gives_new_noise_from_the_same_state_and_survives_save_restore() {
    let cfg = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    };
    let mut warm = Plant::new(&cfg).unwrap();
    for _ in 0..300 {
        warm.step();
    }
    let (mut a, mut b, mut c) = (warm.clone(), warm.clone(), warm.clone());
    a.reseed_noise(11);
    b.reseed_noise(12);
    c.reseed_noise(11);
    let (sa, sb, sc) = (a.step(), b.step(), c.step());
    assert_ne!(
        sa.dtheta_rad, sb.dtheta_rad,
        "different seeds, different noise"
    );
    assert_eq!(sa, sc, "same seed, same noise");
    // A reseeded plant restores from its state with the new seed.
    let restored = Plant::from_serialized_state(&cfg, &a.serialize_state()).unwrap();
    assert_eq!(restored.noise_seed(), 11);
    let (mut a2, mut r2) = (a.clone(), restored);
    for _ in 0..1000 {
        assert_eq!(a2.step(), r2.step());
    }
}
