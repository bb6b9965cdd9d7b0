//! The typed walk against the former CBOR path ([`super::cbor_reference`]): the same table
//! (paths, order, values to the bit, units, ranges) and the same results of setting every
//! parameter, of wrong kinds, unknown names and paths, for the built-in scenarios and for
//! configurations with lists, declared effects, a trajectory carrier and special floats.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::cbor_reference as old;
use crate::carrier::spec::{AfterEnd, CarrierKind, LegSpec, SpectrumKind};
use crate::effects::CustomSpec;
use crate::effects::custom::Axis;
use crate::params::{Param, ParamError, ParamValue, apply, enum_choices, flatten, set};
use crate::table::{GimbalAxis, RotationStep, SchemeKind};
use crate::{PlantConfig, presets};

/// A row with its floats as bits, so NaN, -0.0 and ±inf compare exactly.
fn bits(p: &Param) -> String {
    let v = match &p.value {
        ParamValue::Real(x) => format!("Real({:#x})", x.to_bits()),
        v => format!("{v:?}"),
    };
    let r = p
        .range
        .map(|(lo, hi)| format!("({:#x}, {:#x})", lo.to_bits(), hi.to_bits()));
    format!("{} = {v} [{}] {r:?}", p.path, p.unit)
}

fn table_bits(cfg: &PlantConfig) -> Vec<String> {
    old::flatten(cfg).iter().map(bits).collect()
}

/// Two configurations are the same: every field (Debug, which shows the text fields too) and
/// every number to the bit (through the reference table, so a NaN's payload counts).
fn assert_same(new: &PlantConfig, reference: &PlantConfig, what: &str) {
    // PartialEq first (cheap); it is false with a NaN anywhere, then Debug decides.
    if new != reference {
        assert_eq!(format!("{new:?}"), format!("{reference:?}"), "{what}");
    }
    assert_eq!(table_bits(new), table_bits(reference), "{what}");
}

/// A value the reference accepted but could not read back (a deserialisation error); the new
/// path names the value's own path and says why in its own words.
fn misfit(e: &ParamError) -> bool {
    match e {
        ParamError::Invalid { message, .. } => {
            !(message.starts_with("expected ") || message.starts_with("unknown variant "))
        }
        ParamError::Unknown(_) => false,
    }
}

/// The same outcome: equal configurations, or the same error (for a value that does not fit,
/// the same kind of error and, for one value, the same path).
fn assert_same_result(
    new: Result<PlantConfig, ParamError>,
    reference: Result<PlantConfig, ParamError>,
    what: &str,
) {
    match (new, reference) {
        (Ok(n), Ok(r)) => assert_same(&n, &r, what),
        (Err(n), Err(r)) if misfit(&r) => {
            let (ParamError::Invalid { path: np, message }, ParamError::Invalid { path: rp, .. }) =
                (&n, &r)
            else {
                panic!("{what}: new {n:?}, reference {r:?}");
            };
            assert!(
                message.starts_with("expected a whole number in [0, 4294967295]")
                    || message.starts_with("unknown variant "),
                "{what}: {n:?} (reference {r:?})"
            );
            // With one value the reference's "last path" is the value's path.
            if !what.contains("apply") {
                assert_eq!(np, rp, "{what}");
            }
        }
        (Err(n), Err(r)) => assert_eq!(n, r, "{what}"),
        (n, r) => panic!("{what}: new {n:?}, reference {r:?}"),
    }
}

/// `cfg` over a preset's sensors, as a scenario file's `preset = NAME` gives it.
fn with_preset(name: &str, f: impl FnOnce(&mut PlantConfig)) -> PlantConfig {
    let mut cfg = PlantConfig {
        sensor: presets::preset(name).expect("known preset"),
        ..PlantConfig::default()
    };
    cfg.site.lat_deg = 36.6;
    cfg.site.lon_deg = 123.6;
    cfg.scheme.rate_dps = 2.0;
    f(&mut cfg);
    cfg
}

/// The built-in scenarios (scenarios/scenario/files/*.toml), written out key by key over the defaults.
fn builtin() -> Vec<(&'static str, PlantConfig)> {
    let calibration = |kind| {
        with_preset("paper-table3", |c| {
            c.scheme.kind = kind;
            c.scheme.lead_dwell_s = 300.0;
            c.scheme.dwell_s = 600.0;
        })
    };
    let table3_week = with_preset("paper-table3", |c| {
        c.scheme.accel_dps2 = 20.0;
        c.scheme.dwell_s = 180.0;
        c.thermal.enabled = true;
        c.thermal.chamber.temp_c = 25.0;
    });
    let mut ship = table3_week.clone();
    ship.carrier.kind = CarrierKind::Ship;
    ship.carrier.azimuth_isolation = false;
    let s = &mut ship.carrier.ship;
    (s.lat_deg, s.lon_deg, s.height_m) = (36.6, 123.6, 0.0);
    (s.turn_rate_dps, s.accel_mps2) = (1.0, 0.05);
    s.legs = [
        (45.0, 12.0),
        (135.0, 14.0),
        (225.0, 10.0),
        (315.0, 15.0),
        (0.0, 11.0),
        (90.0, 13.0),
        (180.0, 12.0),
        (270.0, 14.0),
        (60.0, 10.0),
        (150.0, 15.0),
        (240.0, 12.0),
        (330.0, 13.0),
        (20.0, 11.0),
        (200.0, 12.0),
    ]
    .map(|(heading_deg, speed_kn)| LegSpec {
        heading_deg,
        speed_kn,
        duration_s: 43_200.0,
    })
    .to_vec();
    s.sea.spectrum = SpectrumKind::Jonswap;
    (s.sea.sea_state, s.sea.hs_m, s.sea.tp_s) = (0, 2.5, 9.2);
    s.sea.heading_to_waves_deg = 135.0;
    let quiet_nav_grade = |c: &mut PlantConfig| {
        c.sensor.gyro.angle_random_walk.dpsh = [0.0005; 3];
        c.sensor.gyro.bias_instability.sigma_dph = [0.0005; 3];
    };
    vec![
        (
            "calibration-z-down",
            calibration(SchemeKind::ZDownCalibration),
        ),
        ("calibration-z-up", calibration(SchemeKind::ZUpCalibration)),
        (
            "campaign-37",
            with_preset("nav-grade-full", |c| {
                c.scheme.kind = SchemeKind::ZUpCalibration;
                c.scheme.lead_dwell_s = 300.0;
                c.scheme.dwell_s = 705.0;
                quiet_nav_grade(c);
            }),
        ),
        (
            "paper-16pos-short",
            with_preset("paper-table3", |c| c.scheme.dwell_s = 180.0),
        ),
        ("paper-16pos-week", table3_week),
        (
            "paper-static-week",
            with_preset("nav-grade-full", |c| {
                c.scheme.dwell_s = 180.0;
                quiet_nav_grade(c);
                c.thermal.enabled = true;
                c.thermal.chamber.profile = (0..=28)
                    .map(|i: u32| {
                        [
                            f64::from(i) * 21_600.0,
                            [25.0, 30.0, 25.0, 20.0][i as usize % 4],
                        ]
                    })
                    .collect();
            }),
        ),
        ("ship-16pos-week", ship),
    ]
}

fn custom(name: &str, axes: Vec<Axis>, coef: [f64; 3], scale: bool) -> CustomSpec {
    CustomSpec {
        name: name.into(),
        enabled: !scale,
        kind: if scale {
            crate::effects::CustomKind::ScaleFactor
        } else {
            crate::effects::CustomKind::Bias
        },
        regressor: "temp:block^2".into(),
        unit: "K^2".into(),
        axes,
        coef,
    }
}

/// Every built-in scenario, the presets and defaults, and configurations with every list,
/// declared effects, a trajectory carrier and special values.
fn configs() -> Vec<(String, PlantConfig)> {
    let mut out: Vec<(String, PlantConfig)> = builtin()
        .into_iter()
        .map(|(n, c)| (n.to_string(), c))
        .collect();
    out.push(("default".into(), PlantConfig::default()));
    out.push(("paper_16pos_config".into(), presets::paper_16pos_config()));
    for name in presets::PRESET_NAMES {
        out.push((format!("preset {name}"), with_preset(name, |_| {})));
    }
    // Steps, declared effects, a chamber profile, special floats and whole numbers at their ends.
    let mut c = with_preset("nav-grade-full", |_| {});
    c.scheme.kind = SchemeKind::Steps;
    c.scheme.repeat = true;
    c.scheme.steps = vec![
        RotationStep {
            axis: GimbalAxis::Inner,
            angle_deg: 180.0,
            rate_dps: 9.0,
            dwell_s: 300.0,
        },
        RotationStep {
            axis: GimbalAxis::Outer,
            angle_deg: -90.0,
            rate_dps: 4.5,
            dwell_s: 0.0,
        },
    ];
    c.scheme.accel_dps2 = f64::INFINITY;
    c.sensor.gyro.custom = vec![
        custom("trate", vec![Axis::Z], [0.0, 0.0, 5.0], false),
        custom("sq", vec![Axis::X, Axis::Y], [1e-3, -2e-3, 0.0], true),
    ];
    c.sensor.accel.custom = vec![custom("a", vec![], [0.0; 3], false)];
    c.thermal.chamber.profile = vec![[0.0, 20.0], [10.0, f64::NAN], [f64::INFINITY, -0.0]];
    c.site.height_m = f64::NEG_INFINITY;
    c.vehicle.roll_deg = -0.0;
    c.vehicle.pitch_deg = f64::from_bits(0x7ff8_0000_0000_beef);
    c.sensor.gyro.bias.dph = [f64::MIN_POSITIVE / 4.0, f64::MAX, -f64::MAX];
    c.seed = u64::MAX;
    c.substeps = u32::MAX;
    out.push(("steps, declared effects, specials".into(), c));
    // A ship without legs or waves, with its sea at its whole-number ends.
    let mut c = PlantConfig::default();
    c.carrier.kind = CarrierKind::Ship;
    c.carrier.ship.legs.clear();
    c.carrier.ship.sea.sea_state = 6;
    c.carrier.ship.sea.components = u32::MAX;
    c.carrier.lever_arm_m = [1.5, -2.0, 30.0];
    c.seed = 1 << 53 | 1;
    out.push(("ship without legs".into(), c));
    // A trajectory carrier (its file and end rule are data, no parameters).
    let mut c = presets::paper_16pos_config();
    c.carrier.kind = CarrierKind::Trajectory;
    c.carrier.trajectory.file = "track.csv".into();
    c.carrier.trajectory.after_end = AfterEnd::Hold;
    c.carrier.azimuth_isolation = true;
    out.push(("trajectory".into(), c));
    out
}

#[test]
fn the_table_is_the_reference_table_to_the_bit() {
    for (name, cfg) in configs() {
        let new: Vec<String> = flatten(&cfg).iter().map(bits).collect();
        assert_eq!(new, table_bits(&cfg), "{name}");
        // And the reference reads back what it wrote (the comparison below relies on it).
        assert_same(&old::apply(&cfg, []).unwrap(), &cfg, &name);
    }
}

/// Values to set a parameter of current value `v` to: a changed one, the ends of its range and
/// special values (numbers), the other state (switches), every name and an unknown one
/// (enumerations), and one of each wrong kind.
fn trial_values(path: &str, v: &ParamValue) -> Vec<ParamValue> {
    use ParamValue::*;
    let mut out = vec![Bool(true), Real(0.25), Integer(3), Enum("bogus".into())];
    match v {
        Real(x) => out.extend([
            Real(if x.is_finite() && *x + 1.0 != *x {
                *x + 1.0
            } else {
                0.5
            }),
            Real(f64::NAN),
            Real(f64::from_bits(0xfff8_0000_0000_1234)),
            Real(f64::NEG_INFINITY),
            Real(-0.0),
            Real(2.0),
            Real(-3.0),
            Real(1e10),
            Real(18_446_744_073_709_551_616.0),
            Integer(u64::MAX),
            Integer(1 << 53 | 1),
            Integer(5_000_000_000),
        ]),
        Integer(u) => out.extend([
            Integer(u.wrapping_add(1)),
            Integer(u64::MAX),
            Integer(u64::from(u32::MAX) + 1),
            Real(7.0),
            Real(7.5),
            Real(-1.0),
            Real(-0.0),
            Real(f64::NAN),
            Real(f64::INFINITY),
            Real(18_446_744_073_709_551_616.0),
            Real(4_294_967_296.0),
        ]),
        Bool(b) => out.push(Bool(!b)),
        Enum(_) => {
            // A step's axis is an enumeration of the table without a list in ENUMS.
            let choices = enum_choices(path).unwrap_or(&["outer", "inner", "static"]);
            out.extend(choices.iter().map(|c| Enum(c.to_string())));
            out.push(Enum(String::new()));
            out.push(Enum("Sixteen-Position".into()));
        }
    }
    out
}

#[test]
fn setting_every_parameter_gives_the_reference_configuration() {
    let mut n = 0;
    for (name, cfg) in configs() {
        for p in old::flatten(&cfg) {
            for v in trial_values(&p.path, &p.value) {
                let what = format!("{name}: set {} = {v:?}", p.path);
                assert_same_result(
                    set(&cfg, &p.path, v.clone()),
                    old::set(&cfg, &p.path, v),
                    &what,
                );
                n += 1;
            }
        }
    }
    assert!(n > 20_000, "{n}");
}

/// Paths that are no parameter of the table: unknown, containers, lists, other spellings,
/// and the structural text the table leaves out (settable by name in both).
#[test]
fn other_paths_give_the_reference_result() {
    use ParamValue::*;
    let paths = [
        "",
        "nope",
        "run",
        "run.",
        "run.seed",
        "seed",
        "rate_hz",
        "substeps",
        "run.seed[0]",
        "run.seed.x",
        "run.site.lat_deg",
        "run[0].seed",
        "site",
        "site.",
        "site..lat_deg",
        ".site.lat_deg",
        "site[0].lat_deg",
        "site.lat_deg[0]",
        "sensor",
        "sensor.gyro",
        "sensor.gyro.bias",
        "sensor.gyro.bias.dph",
        "sensor.gyro.bias.dph[3]",
        "sensor.gyro.bias.dph[2]",
        "sensor.gyro.bias.dph[02]",
        "sensor.gyro.bias.dph[+2]",
        "sensor.gyro.bias.dph[2",
        "sensor.gyro.bias.dph[[2]",
        "sensor.gyro.bias.dph[2]]",
        "sensor.gyro.bias.dph[2][0]",
        "sensor.gyro.bias.dph[-1]",
        "sensor.gyro.bias.dph[x]",
        "sensor.gyro.bias.dph[]",
        "sensor.gyro.bias.dph]2[",
        "sensor.gyro.bias.dph[99999999999999999999999]",
        "sensor.gyro.g_sensitivity.dph_per_g[1]",
        "sensor.gyro.g_sensitivity.dph_per_g[1][2]",
        "sensor.gyro.custom",
        "sensor.gyro.custom[0]",
        "sensor.gyro.custom[0].name",
        "sensor.gyro.custom[0].kind",
        "sensor.gyro.custom[0].regressor",
        "sensor.gyro.custom[0].unit",
        "sensor.gyro.custom[0].axes",
        "sensor.gyro.custom[0].axes[0]",
        "sensor.gyro.custom[1].axes[1]",
        "sensor.gyro.custom[2].coef[0]",
        "sensor.accel.custom",
        "sensor.accel.custom[0].axes",
        "sensor.accel.custom[0].axes[0]",
        "scheme.steps",
        "scheme.steps[0]",
        "scheme.steps[0].axis",
        "scheme.steps[1].axis",
        "scheme.steps[2].axis",
        "thermal.chamber.profile",
        "thermal.chamber.profile[1]",
        "thermal.chamber.profile[1][1]",
        "thermal.chamber.profile[9][1]",
        "carrier.ship.legs",
        "carrier.ship.legs[0].speed_kn",
        "carrier.ship.sea.sea_state",
        "carrier.ship.sea.components",
        "carrier.trajectory",
        "carrier.trajectory.file",
        "carrier.trajectory.after_end",
        "carrier.trajectory.nope",
    ];
    let values = [
        Real(1.0),
        Real(-1.0),
        Real(1.5),
        Real(5e9),
        Integer(2),
        Integer(u64::MAX),
        Bool(false),
        Enum("x".into()),
        Enum("y".into()),
        Enum("hold".into()),
        Enum("inner".into()),
        Enum("scale-factor".into()),
        Enum("diagonal".into()),
        Enum("ship".into()),
    ];
    for (name, cfg) in configs() {
        for path in paths {
            for v in &values {
                let what = format!("{name}: set {path:?} = {v:?}");
                assert_same_result(
                    set(&cfg, path, v.clone()),
                    old::set(&cfg, path, v.clone()),
                    &what,
                );
            }
        }
    }
}

/// Many values at once: the whole table (as an FMU sets it), and random batches with repeated
/// paths, wrong kinds, unknown paths and values that do not fit, in random order.
#[test]
fn applying_many_values_gives_the_reference_result() {
    let mut rng = ChaCha8Rng::seed_from_u64(27);
    for (name, cfg) in configs() {
        let table = old::flatten(&cfg);
        let all: Vec<(&str, ParamValue)> = table
            .iter()
            .map(|p| (p.path.as_str(), p.value.clone()))
            .collect();
        assert_same_result(
            apply(&cfg, all.clone()),
            old::apply(&cfg, all),
            &format!("{name}: apply the whole table"),
        );
        let mut oks = 0;
        for round in 0..400 {
            let len = rng.random_range(1..12);
            let mut batch: Vec<(String, ParamValue)> = Vec::new();
            for _ in 0..len {
                let p = &table[rng.random_range(0..table.len())];
                let vs = trial_values(&p.path, &p.value);
                // Mostly values of the right kind, so that many batches succeed.
                let v = if rng.random_bool(0.9) {
                    vs[4 + rng.random_range(0..vs.len() - 4)].clone()
                } else {
                    vs[rng.random_range(0..4)].clone()
                };
                let path = match rng.random_range(0..40) {
                    0 => "sensor.gyro.bias.dph[3]".to_string(),
                    1 => "sensor.gyro".to_string(),
                    2 => p.path.replace("run.", ""),
                    _ => p.path.clone(),
                };
                batch.push((path, v));
                if rng.random_bool(0.2) {
                    // The same path again, with another value.
                    let v = vs[4 + rng.random_range(0..vs.len() - 4)].clone();
                    batch.push((p.path.clone(), v));
                }
            }
            let pairs = || batch.iter().map(|(p, v)| (p.as_str(), v.clone()));
            let new = apply(&cfg, pairs());
            oks += usize::from(new.is_ok());
            assert_same_result(
                new,
                old::apply(&cfg, pairs()),
                &format!("{name}: apply round {round}: {batch:?}"),
            );
            // The same batch in the table's order (repeated paths kept in their order), as an
            // FMU gives its values: met as the walk passes.
            let at = |path: &str| {
                let path = if path.starts_with("run.")
                    || !["rate_hz", "substeps", "seed"].contains(&path)
                {
                    path.to_string()
                } else {
                    format!("run.{path}")
                };
                table
                    .iter()
                    .position(|p| p.path == path)
                    .unwrap_or(usize::MAX)
            };
            batch.sort_by_key(|(p, _)| at(p));
            let pairs = || batch.iter().map(|(p, v)| (p.as_str(), v.clone()));
            let new = apply(&cfg, pairs());
            oks += usize::from(new.is_ok());
            assert_same_result(
                new,
                old::apply(&cfg, pairs()),
                &format!("{name}: apply round {round} in order: {batch:?}"),
            );
        }
        assert!(oks > 80, "{name}: only {oks} batches succeeded");
    }
}

/// Every enumeration of the walk takes each of its names and no other, and an enumeration of
/// [`crate::params::ENUMS`] has exactly that list (its order is the FMU's numbering).
#[test]
fn every_enumeration_of_the_walk_takes_its_names() {
    use crate::params::fields::{ParamFields, Slot};
    let mut seen = std::collections::BTreeSet::new();
    for (name, mut cfg) in configs() {
        cfg.visit_fields(&mut String::new(), &mut |path, slot| {
            let Slot::Enum(c) = slot else {
                return;
            };
            let start = c.name();
            let names = c.names();
            assert!(names.contains(&start), "{name}: {path} = {start}");
            if let Some(listed) = enum_choices(path) {
                assert_eq!(names, listed, "{name}: {path}");
            }
            for n in names {
                assert!(c.set_name(n), "{name}: {path} = {n}");
                assert_eq!(c.name(), *n, "{name}: {path}");
            }
            assert!(!c.set_name("bogus"), "{name}: {path}");
            assert!(c.set_name(start));
            seen.insert(crate::params::key_of(path));
        });
    }
    // Every enumeration type is met somewhere in the configurations above.
    assert_eq!(
        seen.into_iter().collect::<Vec<_>>(),
        [
            "carrier.kind",
            "carrier.ship.sea.realisation",
            "carrier.ship.sea.spectrum",
            "carrier.trajectory.after_end",
            "scheme.axis",
            "scheme.kind",
            "scheme.steps.axis",
            "sensor.accel.custom.kind",
            "sensor.gyro.custom.axes",
            "sensor.gyro.custom.kind",
            "sensor.gyro.position_bias.transition",
        ]
    );
}

/// Where the two paths name a different path: a value that does not fit, given with others.
/// The reference named the last path of the batch; the typed path names the value's own.
#[test]
fn a_value_that_does_not_fit_is_named_by_its_own_path() {
    let cfg = PlantConfig::default();
    let batch = [
        ("run.substeps", ParamValue::Integer(u64::from(u32::MAX) + 1)),
        ("site.lat_deg", ParamValue::Real(10.0)),
    ];
    let e = apply(&cfg, batch.clone()).unwrap_err();
    assert!(
        matches!(&e, ParamError::Invalid { path, message }
            if path == "run.substeps" && message.contains("4294967296")),
        "{e:?}"
    );
    let r = old::apply(&cfg, batch).unwrap_err();
    assert!(
        matches!(&r, ParamError::Invalid { path, .. } if path == "site.lat_deg"),
        "{r:?}"
    );
    // A later value of the same path that fits replaces it, in both.
    let batch = [
        ("run.substeps", ParamValue::Integer(u64::from(u32::MAX) + 1)),
        ("run.substeps", ParamValue::Real(4.0)),
    ];
    assert_eq!(apply(&cfg, batch.clone()).unwrap().substeps, 4);
    assert_eq!(old::apply(&cfg, batch).unwrap().substeps, 4);
}
