//! The oracle z: linear in the coefficients, zero for a nuisance column, and what
//! `scale_to_z` aims at.

use rins_mvm_trials::oracle::{Nuisance, oracle_z_per_channel_with};
use rins_mvm_trials::{Design, HiddenEffect, oracle_z, oracle_z_per_channel, scale_to_z};

use super::base_model;

#[test]
fn doubling_the_coefficient_doubles_z() {
    let model = base_model();
    let design = Design::field_four_azimuths();
    let field = HiddenEffect::NavFieldBias {
        dph: [0.004, 0.0, -0.003],
        inclination_deg: 55.0,
        declination_deg: -8.0,
    };
    let z1 = oracle_z(&model, &design, &field);
    let z2 = oracle_z(&model, &design, &field.scaled(2.0));
    assert!(z1 > 1.0, "{z1}");
    assert!((z2 - 2.0 * z1).abs() < 1e-12 * z1, "{z1} {z2}");
    // Two channels, z their root sum of squares.
    let per = oracle_z_per_channel(&model, &design, &field);
    assert_eq!(per.len(), 2);
    let rss = per.iter().map(|c| c.1 * c.1).sum::<f64>().sqrt();
    assert!((rss - z1).abs() < 1e-12 * z1);

    let design = Design::chamber_steps_four_azimuths();
    let sf = HiddenEffect::ScaleFactorTempLinear {
        ppm_per_k: [0.0, 0.0, 0.8],
        ppm: [0.0, 0.0, 3.0],
    };
    let z1 = oracle_z(&model, &design, &sf);
    let z2 = oracle_z(&model, &design, &sf.scaled(2.0));
    assert!(z1 > 0.0 && (z2 - 2.0 * z1).abs() < 1e-9 * z1, "{z1} {z2}");
}

#[test]
fn a_nuisance_column_has_no_z_against_the_full_set() {
    let model = base_model();
    let design = Design::field_four_azimuths();
    for effect in [
        HiddenEffect::GyroBias {
            dph: [0.0, 0.01, 0.0],
        },
        HiddenEffect::GyroScaleFactor {
            ppm: [0.0, 0.0, 2.0],
        },
        HiddenEffect::GyroMisalignment {
            axis: 0,
            from: 2,
            arcsec: 3.0,
        },
        HiddenEffect::AccelBias {
            ug: [20.0, 0.0, 0.0],
        },
        HiddenEffect::AccelScaleFactor {
            ppm: [0.0, 0.0, 30.0],
        },
    ] {
        let all = oracle_z_per_channel_with(&model, &design, &effect, Nuisance::All);
        let own = oracle_z_per_channel_with(&model, &design, &effect, Nuisance::ExcludeOwn);
        let z_all = all[0].1;
        let z_own = own[0].1;
        // Against its own column nothing is left (to the rounding of the projection, relative
        // to what it achieves without it).
        assert!(z_all < 1e-8 * z_own, "{effect:?}: {z_all} vs {z_own}");
        assert!(z_own > 0.0);
    }
}

#[test]
fn scale_to_z_hits_the_target() {
    let model = base_model();
    let design = Design::chamber_steps_four_azimuths();
    for effect in [
        HiddenEffect::LaggedTempBias {
            dph_per_k: [1e-3, 0.0, 0.0],
            tau_s: 1800.0,
        },
        HiddenEffect::PostMoveTransient {
            dph: [0.0, 0.01, 0.0],
            tau_s: 120.0,
        },
        HiddenEffect::GyroBias {
            dph: [0.0, 0.0, 0.001],
        },
    ] {
        let scaled = scale_to_z(&model, &design, &effect, 12.0).expect("visible");
        let z = oracle_z(&model, &design, &scaled);
        assert!((z - 12.0).abs() < 1e-9, "{effect:?}: {z}");
    }
    // An x-axis g-sensitivity to f_x: body x never sees gravity with a level mount and inner
    // turns about x, so the effect is invisible.
    let gx = HiddenEffect::GyroGSensitivity {
        axis: 0,
        from: 0,
        dph_per_g: 0.01,
    };
    assert!(scale_to_z(&model, &design, &gx, 10.0).is_none());
}
