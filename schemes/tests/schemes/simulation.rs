//! The analysis against the plant and navigator: two days at 20 Hz, one effect on.

use rins_schemes::effects::EffectSet;
use rins_schemes::response::StaticResponse;
use rins_schemes::{AnalyseOptions, analyse_scheme, library, simulate};

/// The plant's δβ under the 16-position scheme and `mirror-64`, the general class's invariant
/// member declared as custom effects, and Table 3's sensors: the navigator's Schuler-averaged east error
/// after two days against the analysis, within 3 % (the linear model against the closed forms
/// of `rins verify ins` holds to that).
#[test]
fn analysed_east_error_matches_the_navigator() {
    let days = 2.0;
    let opt = AnalyseOptions {
        days,
        ..AnalyseOptions::default()
    };
    let resp = StaticResponse::new(opt.lat_rad, days);
    let mut dbeta = rins_plant::SensorSpec::default();
    dbeta.gyro.position_bias.enabled = true;
    dbeta.gyro.position_bias.dph = [0.005; 3];
    let mut invariant = rins_plant::SensorSpec::default();
    let mut table = [[0.0; 9]; 3];
    for axis in 0..3 {
        table[axis][axis] = 0.01;
    }
    invariant.gyro.custom = rins_schemes::basis::as_declared(&table);
    // Table 3's constant errors cancel per cycle; what they leave is the within-cycle
    // excursion (a misalignment's attitude error held between a move and its reverse), which the
    // time-resolved response keeps.
    let table3 = rins_plant::presets::paper_table3();
    for name in ["sixteen-position", "mirror-64"] {
        let s = library::built_in(name).unwrap();
        for sensor in [&dbeta, &invariant, &table3] {
            let base = EffectSet::empty(9.8).with_earth_rate(opt.lat_rad);
            let set = if sensor.gyro.custom.is_empty() {
                base.with_catalogue(sensor)
            } else {
                base.with_declared(&sensor.gyro.custom, false).unwrap()
            };
            let a = analyse_scheme(&s, &set, &opt, &resp).unwrap();
            let analysed: f64 = a.effects.iter().map(|e| e.after.east_m).sum();
            let sim = simulate::simulate(&s, sensor, days, 20.0).unwrap();
            assert!(
                (sim.east_m - analysed).abs() <= 0.03 * analysed.abs(),
                "{name}: analysed {analysed} m, simulated {} m",
                sim.east_m
            );
        }
    }
}

/// A static table with a constant drift on each gyro axis: the linear model's week against the
/// navigator's, to 5 % of the week's largest error (the model omits nothing the closed forms
/// keep; see `closed_forms::static_response_matches_the_closed_form_position`).
#[test]
fn static_drift_response_matches_the_navigator() {
    let s = rins_schemes::SchemeFile {
        name: "static".into(),
        reference: String::new(),
        description: String::new(),
        scheme: rins_plant::table::SchemeSpec {
            kind: rins_plant::table::SchemeKind::Static,
            ..Default::default()
        },
    };
    let lat = 36.6_f64.to_radians();
    for axis in 0..3 {
        let mut sensor = rins_plant::SensorSpec::default();
        sensor.gyro.bias.enabled = true;
        sensor.gyro.bias.dph[axis] = 0.01;
        let mut eps = nalgebra::Vector3::zeros();
        eps[axis] = 0.01 * rins_plant::units::DPH;
        let scale = (0..=168)
            .map(|h| {
                let (n, e) =
                    rins_verification::ins::gyro_bias_position(&eps, lat, h as f64 * 3600.0);
                n.hypot(e)
            })
            .fold(0.0, f64::max);
        let days = 7.0;
        let sim = simulate::simulate(&s, &sensor, days, 10.0).unwrap();
        let m = StaticResponse::new(lat, days).apply(&eps, &nalgebra::Vector3::zeros());
        assert!(
            (sim.north_m - m.north_m).abs() < 0.05 * scale
                && (sim.east_m - m.east_m).abs() < 0.05 * scale,
            "axis {axis}: navigator ({}, {}) model ({}, {}), scale {scale}",
            sim.north_m,
            sim.east_m,
            m.north_m,
            m.east_m
        );
    }
}
