//! Tests of the parameter table (plant/src/params.rs).

use super::*;

mod against_cbor;
mod cbor_reference;

#[test]
fn non_finite_and_large_whole_values_keep_their_identity() {
    // NaN is reported as NaN (JSON made it null and the check said "inf").
    let mut cfg = PlantConfig::default();
    cfg.site.lat_deg = f64::NAN;
    let errs = cfg.validate().unwrap_err();
    let e = errs.iter().find(|e| e.path == "site.lat_deg").unwrap();
    assert_eq!(e.got, "NaN", "{e}");
    // inf (a documented value of scheme.accel_dps2) survives a set of another parameter.
    let mut cfg = PlantConfig::default();
    cfg.scheme.accel_dps2 = f64::INFINITY;
    cfg.seed = u64::MAX;
    let c2 = set(&cfg, "sensor.gyro.bias.dph[0]", ParamValue::Real(0.5)).unwrap();
    assert_eq!(c2.scheme.accel_dps2, f64::INFINITY);
    assert_eq!(c2.seed, u64::MAX);
    assert!(c2.validate().is_ok());
    let p = flatten(&c2);
    let get = |k: &str| p.iter().find(|x| x.path == k).unwrap().value.clone();
    assert_eq!(get("scheme.accel_dps2"), ParamValue::Real(f64::INFINITY));
    assert_eq!(get("run.seed"), ParamValue::Integer(u64::MAX));
    // Whole-number fields take whole reals only.
    assert_eq!(
        set(&cfg, "run.seed", ParamValue::Real(7.0)).unwrap().seed,
        7
    );
    assert!(set(&cfg, "run.seed", ParamValue::Real(7.5)).is_err());
}

#[test]
fn every_number_has_a_unit_and_a_range() {
    let mut cfg = PlantConfig {
        sensor: crate::presets::nav_grade_full(),
        ..PlantConfig::default()
    };
    cfg.thermal.chamber.profile = vec![[0.0, 20.0], [10.0, 30.0]];
    let params = flatten(&cfg);
    assert!(params.len() > 150, "{}", params.len());
    for p in &params {
        if matches!(p.value, ParamValue::Real(_) | ParamValue::Integer(_)) {
            assert!(p.range.is_some(), "{} has no range in RANGES", p.path);
            let dimensionless = [
                "run.",
                "amplitude_change",
                "board_to_block_dir_body",
                "sea.sea_state",
                "sea.seed",
                "sea.gamma",
                "sea.components",
                "sea.band",
                ".gain",
                ".damping",
            ]
            .iter()
            .any(|k| p.path.contains(k));
            if !dimensionless {
                assert_ne!(p.unit, "1", "{} has no unit", p.path);
            }
        }
    }
}

#[test]
fn set_then_flatten_round_trips_and_errors_name_the_key() {
    let cfg = PlantConfig::default();
    let c2 = set(&cfg, "sensor.gyro.bias.dph[2]", ParamValue::Real(0.02)).unwrap();
    assert_eq!(c2.sensor.gyro.bias.dph, [0.0, 0.0, 0.02]);
    let c3 = set(&c2, "run.seed", ParamValue::Integer(42)).unwrap();
    assert_eq!(c3.seed, 42);
    let c4 = set(
        &c3,
        "scheme.kind",
        ParamValue::Enum("eight-position".into()),
    )
    .unwrap();
    assert_eq!(c4.scheme.kind, crate::table::SchemeKind::EightPosition);
    let p = flatten(&c4)
        .into_iter()
        .find(|p| p.path == "sensor.gyro.bias.dph[2]")
        .unwrap();
    assert_eq!((p.value, p.unit), (ParamValue::Real(0.02), "deg/h"));
    assert!(matches!(
        set(&cfg, "sensor.gyro.bias.dph[7]", ParamValue::Real(1.0)),
        Err(ParamError::Unknown(_))
    ));
    assert!(matches!(
        set(&cfg, "sensor.gyro.bias.enabled", ParamValue::Real(1.0)),
        Err(ParamError::Invalid { .. })
    ));
    let e = set(&cfg, "scheme.kind", ParamValue::Enum("spiral".into())).unwrap_err();
    assert!(e.to_string().contains("scheme.kind"), "{e}");
}

#[test]
fn declared_effects_expose_switch_and_coefficients_only() {
    let mut cfg = PlantConfig::default();
    cfg.sensor.gyro.custom = vec![crate::effects::CustomSpec {
        name: "trate".into(),
        enabled: true,
        kind: crate::effects::CustomKind::Bias,
        regressor: "dtemp_dt:block".into(),
        unit: "K/s".into(),
        axes: vec![crate::effects::custom::Axis::Z],
        coef: [0.0, 0.0, 5.0],
    }];
    let p: Vec<Param> = flatten(&cfg)
        .into_iter()
        .filter(|p| p.path.contains("custom"))
        .collect();
    let paths: Vec<&str> = p.iter().map(|p| p.path.as_str()).collect();
    assert_eq!(
        paths,
        [
            "sensor.gyro.custom[0].enabled",
            "sensor.gyro.custom[0].coef[0]",
            "sensor.gyro.custom[0].coef[1]",
            "sensor.gyro.custom[0].coef[2]"
        ]
    );
    assert_eq!(p[3].range, Some((-1e9, 1e9)));
    let c2 = set(&cfg, "sensor.gyro.custom[0].coef[2]", ParamValue::Real(7.5)).unwrap();
    assert_eq!(c2.sensor.gyro.custom[0].coef, [0.0, 0.0, 7.5]);
    assert_eq!(c2.sensor.gyro.custom[0].regressor, "dtemp_dt:block");
}

#[test]
fn every_enumeration_lists_exactly_the_names_serde_accepts() {
    let cfg = PlantConfig::default();
    let enums: Vec<Param> = flatten(&cfg)
        .into_iter()
        .filter(|p| matches!(p.value, ParamValue::Enum(_)))
        .collect();
    assert_eq!(enums.len(), ENUMS.len(), "{enums:?}");
    for p in enums {
        let choices = enum_choices(&p.path).unwrap_or_else(|| panic!("{} has no choices", p.path));
        for c in choices {
            let c2 = set(&cfg, &p.path, ParamValue::Enum(c.to_string())).unwrap();
            let back = flatten(&c2).into_iter().find(|q| q.path == p.path).unwrap();
            assert_eq!(back.value, ParamValue::Enum(c.to_string()));
        }
    }
}
