//! Identities of the physics that hold for every scheme.

use rins_plant::units::DPH;
use rins_schemes::effects::EffectSet;
use rins_schemes::response::StaticResponse;
use rins_schemes::{AnalyseOptions, analyse_scheme, library};

/// b_i(u) = k·u_i on every axis (isotropic g-sensitivity) is k along up in the navigation
/// frame whatever the attitude: every scheme leaves exactly k·T per cycle on the up axis.
#[test]
fn the_isotropic_part_survives_every_scheme_unchanged() {
    let set = EffectSet::empty(9.8).with_general();
    let opt = AnalyseOptions::default();
    let resp = StaticResponse::new(opt.lat_rad, opt.days);
    for s in library::all_built_in() {
        let a = analyse_scheme(&s, &set, &opt, &resp).unwrap();
        let mut sum = [0.0; 3];
        for key in ["general.bx_ux", "general.by_uy", "general.bz_uz"] {
            let e = a.effect(key).unwrap();
            for i in 0..3 {
                sum[i] += e.per_cycle[i];
            }
        }
        let expected = a.cycle_s * DPH;
        assert!(
            sum[0].abs() < 1e-12 * expected && sum[1].abs() < 1e-12 * expected,
            "{}: {sum:?}",
            s.name
        );
        assert!(
            ((sum[2] - expected) / expected).abs() < 1e-12,
            "{}: {sum:?}",
            s.name
        );
    }
}

/// Where both methods exist they agree to 1e-12 of the modulated error for every effect.
#[test]
fn quadrature_and_exact_integration_agree() {
    let mut sensor = rins_plant::presets::nav_grade_full();
    sensor.gyro.nav_field_bias.enabled = true;
    sensor.gyro.nav_field_bias.dph_enu =
        [[0.001, 0.0, 0.0005], [0.0, 0.001, 0.0], [0.0, 0.0, 0.001]];
    let set = EffectSet::empty(9.8).with_catalogue(&sensor).with_general();
    let opt = AnalyseOptions::default();
    let resp = StaticResponse::new(opt.lat_rad, opt.days);
    for mut s in library::all_built_in() {
        s.scheme.accel_dps2 = f64::INFINITY;
        let a = analyse_scheme(&s, &set, &opt, &resp).unwrap();
        assert!(a.constant_rate);
        for e in &a.effects {
            let ex = e
                .per_cycle_exact
                .unwrap_or_else(|| panic!("{}: {} has no exact integral", s.name, e.effect));
            let d = (0..3)
                .map(|i| (e.per_cycle[i] - ex[i]).abs())
                .fold(0.0, f64::max);
            assert!(
                d <= 1e-12 * e.modulated,
                "{} {}: {d:e} of {:e}",
                s.name,
                e.effect,
                e.modulated
            );
        }
    }
}
