//! Unit tests of the parameter mapping and the output table.

use super::*;
use crate::outputs::Record;
use rins_plant::Truth;
use rins_plant::params;

#[test]
fn every_fixed_shape_scenario_key_is_a_parameter_and_round_trips() {
    let cfg = rins_plant::presets::paper_16pos_config();
    let t = table();
    let n_params = t
        .roles
        .iter()
        .filter(|r| matches!(r, Role::Param(_)))
        .count();
    assert_eq!(
        n_params,
        params::flatten(&cfg).len(),
        "the paper config has no list parameters"
    );
    // Setting every parameter to its start value reproduces the configuration.
    let m = RinsImu::new();
    assert_eq!(m.config().unwrap(), cfg);
    // Changing one parameter changes exactly that key.
    let mut m = RinsImu::new();
    let slot = t.vars.slot("sensor.gyro.bias.dph[2]").unwrap();
    m.set(slot, Value::Real(0.02)).unwrap();
    assert_eq!(m.config().unwrap().sensor.gyro.bias.dph, [0.01, 0.01, 0.02]);
    let kind = t.vars.slot("scheme.kind").unwrap();
    m.set(kind, Value::Enumeration(1)).unwrap();
    assert_eq!(
        m.config().unwrap().scheme.kind,
        rins_plant::table::SchemeKind::EightPosition
    );
}

#[test]
fn docs_fmu_md_lists_the_current_variables() {
    let doc = include_str!("../../../../docs/fmu.md");
    let list = rins_fmi::package::variable_list(RinsImu::table(), FmiVersion::V3);
    assert!(
        doc.contains(&list),
        "docs/fmu.md is out of date: regenerate with `cargo run -p rins-imu-fmu --example variable_list`"
    );
}

/// The record the old `Record::template` gave, kept as the reference: a plant built and
/// stepped once for its first sample and truth.
fn stepped_template(cfg: &PlantConfig) -> Record {
    let mut p = Plant::new(cfg).unwrap();
    let sample = p.step();
    Record {
        sample,
        truth: p.truth(),
    }
}

/// Stores into `rec` every output row of `plant` after its step gave `sample` (what an importer
/// does with the outputs of one communication step of one sample).
fn store_rows(rec: &mut Record, plant: &Plant, sample: &ImuSample) {
    let view = View {
        plant,
        truth: plant.truth(),
        sample: Some(sample),
        true_sums: None,
    };
    for o in outputs() {
        if let Some(store) = &o.store {
            for i in 0..o.decl.count() {
                store(rec, i, (o.read)(&view, i));
            }
        }
    }
}

/// The template is built without running a plant, yet the records the output rows rebuild from
/// it are those they rebuilt from the old one (a plant stepped once), every field bit for bit
/// (Debug text, which tells -0.0 from 0.0), on the static carrier and on a ship at sea. The one
/// field no row stores that differs is a ship's carrier: the old template held the carrier after
/// the first step, the new one holds it before (an unstepped plant's); no output carries it,
/// and `rins fmu run` refuses moving carriers.
#[test]
fn the_template_rebuilds_the_records_of_the_stepped_plant_template() {
    use rins_plant::carrier::{CarrierKind, SpectrumKind};
    let still = rins_plant::presets::paper_16pos_config();
    let mut ship = still.clone();
    ship.carrier.kind = CarrierKind::Ship;
    ship.carrier.ship.sea.spectrum = SpectrumKind::PiersonMoskowitz;
    ship.carrier.ship.sea.sea_state = 5;
    for (name, cfg) in [("static", still), ("ship", ship)] {
        let mut old = stepped_template(&cfg);
        let mut new = Record::template(&cfg).unwrap();
        let mut plant = Plant::new(&cfg).unwrap();
        let start = plant.truth().carrier;
        assert_eq!(
            new.truth.carrier, start,
            "{name}: the carrier before the first step"
        );
        for k in 0..300 {
            let s = plant.step();
            store_rows(&mut old, &plant, &s);
            store_rows(&mut new, &plant, &s);
            // The stepped plant's own sample and truth, with the carrier before the first step
            // (the static carrier's never changes).
            let truth = plant.truth();
            assert_eq!(truth.carrier != start, name == "ship", "{name}: step {k}");
            let own = Record {
                sample: s,
                truth: Truth {
                    carrier: start,
                    ..truth
                },
            };
            assert_eq!(format!("{own:?}"), format!("{new:?}"), "{name}: step {k}");
            // The old template's record: the same but for a ship's carrier, which it held after
            // the first step.
            assert_eq!(
                old.truth.carrier != start,
                name == "ship",
                "{name}: step {k}"
            );
            let old_ref = Record {
                truth: Truth {
                    carrier: start,
                    ..old.truth
                },
                ..old
            };
            assert_eq!(
                format!("{old_ref:?}"),
                format!("{new:?}"),
                "{name}: step {k}"
            );
        }
    }
}

/// A configuration out of range is refused by the template as by the plant, naming the key.
#[test]
fn the_template_refuses_an_out_of_range_configuration_as_the_plant_does() {
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.rate_hz = -1.0;
    let e = Record::template(&cfg).unwrap_err();
    let plant = Plant::new(&cfg)
        .err()
        .unwrap()
        .iter()
        .map(|x| x.to_string())
        .collect::<Vec<_>>()
        .join("; ");
    assert_eq!(e, plant);
    assert!(e.contains("rate_hz"), "{e}");
}

/// Reading every output row and storing it back rebuilds exactly the sample and truth the
/// in-process plant gives (what `rins fmu run` relies on), including over a move.
#[test]
fn the_output_table_rebuilds_the_in_process_sample_and_truth() {
    use rins_fmi::instance::Instance;
    let cfg = rins_plant::presets::paper_16pos_config();
    let mut plant = Plant::new(&cfg).unwrap();
    let mut inst = Instance::<RinsImu>::new();
    inst.enter_initialization().unwrap();
    inst.exit_initialization().unwrap();
    let mut rec = Record::template(&cfg).unwrap();
    let t = table();
    let mut moving = 0;
    // The first dwell is 180 s: cover it and the first move.
    for k in 0..20_000u64 {
        let s = plant.step();
        inst.do_step(k as f64 * 0.01, 0.01).unwrap();
        for (slot, role) in t.roles.iter().enumerate() {
            if let Role::Output(o, i) = role
                && let Some(store) = &outputs()[*o].store
            {
                store(&mut rec, *i, inst.get_slot(slot));
            }
        }
        assert_eq!(rec.sample, s, "sample {k}");
        assert_eq!(rec.truth, plant.truth(), "truth {k}");
        moving += rec.truth.gimbal.moving as u32;
    }
    assert!(
        moving > 100,
        "the run covers a move ({moving} moving samples)"
    );
}

/// A saved state restores the last sample's outputs before any further step.
#[test]
fn a_restored_state_reports_the_same_outputs() {
    use rins_fmi::instance::Instance;
    let mut inst = Instance::<RinsImu>::new();
    inst.enter_initialization().unwrap();
    inst.exit_initialization().unwrap();
    inst.do_step(0.0, 0.05).unwrap();
    let back = Instance::<RinsImu>::deserialize(&inst.serialize()).unwrap();
    for slot in 0..t_len() {
        assert_eq!(back.get_slot(slot), inst.get_slot(slot), "slot {slot}");
    }
    assert!(
        matches!(inst.get_slot(table().vars.slot("imu.dv_mps[2]").unwrap()), Value::Real(x) if x > 0.04)
    );
}

fn t_len() -> usize {
    table().vars.scalars.len()
}

/// A different valid value for a known: the next enumeration item, the switch flipped, a
/// number moved inside its range (`None` when the range allows no other value).
fn perturbed(s: &rins_fmi::vars::ScalarVar) -> Option<Value> {
    use rins_fmi::vars::Kind;
    let (lo, hi) = s.range.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
    match (s.kind, s.start) {
        (Kind::Enumeration { items, .. }, Value::Enumeration(i)) => {
            Some(Value::Enumeration((i + 1) % items.len()))
        }
        (_, Value::Boolean(b)) => Some(Value::Boolean(!b)),
        (_, Value::Integer(u)) => {
            let v = if (u + 1) as f64 <= hi {
                u + 1
            } else {
                u.checked_sub(1)?
            };
            (v as f64 >= lo).then_some(Value::Integer(v))
        }
        (_, Value::Real(x)) => {
            let step = (x.abs() * 0.1).max(0.05);
            [x + step, x - step, (x + hi) / 2.0, (x + lo) / 2.0]
                .into_iter()
                .find(|y| y.is_finite() && *y >= lo && *y <= hi && *y != x)
                .map(Value::Real)
        }
        _ => None,
    }
}

/// The InitialUnknowns dependencies are true: every parameter or input whose change moves an
/// output's value in initialization mode is listed for that output (each known perturbed in
/// turn from the defaults), and the chamber inputs do move the thermal outputs.
#[test]
fn initial_dependencies_cover_every_known_that_changes_an_initial_output() {
    use rins_fmi::instance::Instance;
    let t = table();
    let outputs: Vec<usize> = (0..t.roles.len())
        .filter(|s| matches!(t.roles[*s], Role::Output(..)))
        .collect();
    let initial = |set: &dyn Fn(&mut Instance<RinsImu>) -> bool| {
        let mut inst = Instance::<RinsImu>::new();
        // A perturbation the configuration refuses (e.g. 0.05 for the whole
        // `carrier.ship.sea.sea_state`, or `carrier.azimuth_isolation` on the static carrier)
        // describes no plant: exiting initialization says why.
        if !set(&mut inst)
            || inst
                .model()
                .config()
                .map_or(true, |c| c.validate().is_err())
        {
            return None;
        }
        inst.enter_initialization().unwrap();
        Some(
            outputs
                .iter()
                .map(|s| inst.get_slot(*s))
                .collect::<Vec<_>>(),
        )
    };
    let base = initial(&|_| true).unwrap();
    let mut checked = 0;
    for known in 0..t.vars.scalars.len() {
        let s = &t.vars.scalars[known];
        if s.causality == rins_fmi::vars::Causality::Output {
            continue;
        }
        let Some(v) = perturbed(s) else { continue };
        // The chamber temperature only acts with the override on.
        let Some(out) = initial(&|i| {
            if s.name == "input.chamber_temp_c" {
                i.set(
                    t.vars.slot("input.chamber_override").unwrap() as u32,
                    Value::Boolean(true),
                )
                .unwrap();
            }
            i.set_slot(known, v).is_ok()
        }) else {
            continue;
        };
        checked += 1;
        for (k, slot) in outputs.iter().enumerate() {
            if out[k] != base[k] {
                assert!(
                    t.vars.initial_dependencies[*slot].contains(&known),
                    "{} changes {} in initialization mode but is not listed",
                    s.name,
                    t.vars.scalars[*slot].name
                );
            }
        }
    }
    assert!(checked > 100, "{checked} knowns perturbed");
    let housing = t.vars.slot("thermal.housing_c").unwrap();
    let chamber = t.vars.slot("input.chamber_temp_c").unwrap();
    assert!(t.vars.initial_dependencies[housing].contains(&chamber));
    assert!(t.vars.initial_dependencies[t.vars.slot("imu.dtheta_rad[0]").unwrap()].is_empty());
}

/// The parameter sets shipped in fmi-wrapper/examples/system/ are those of the presets now.
#[test]
fn shipped_parameter_sets_are_current() {
    for preset in ["paper-table3", "nav-grade-full"] {
        let path = format!(
            "{}/../../examples/system/{preset}.ssv",
            env!("CARGO_MANIFEST_DIR")
        );
        let shipped = std::fs::read_to_string(&path).unwrap_or_default();
        assert_eq!(
            shipped,
            crate::ssv::sensor_parameter_set(preset).unwrap(),
            "{path} is out of date: regenerate with `cargo run -p rins-imu-fmu --example parameter_sets`"
        );
    }
}

/// The FMU outputs of each output column of the plant's table ([`rins_plant::output_columns`])
/// and the factor from the FMU's unit to the column's; `None`: the FMU does not output it.
/// The FMU's names and value references stay as they are (a master's connections rely on
/// them), so a column added to the table has its outputs named here, or the reason it has none.
fn fmu_outputs_of(key: &str) -> Option<(Vec<String>, f64)> {
    let one = |n: &str| Some((vec![n.to_string()], 1.0));
    let deg = |n: &str| Some((vec![n.to_string()], 1f64.to_degrees()));
    match key {
        "t_s" => one("imu.time_s"),
        "dtheta_rad" => one("imu.dtheta_rad"),
        "dv_mps" => one("imu.dv_mps"),
        "outer_deg" => deg("imu.encoder_outer_rad"),
        "inner_deg" => deg("imu.encoder_inner_rad"),
        "temps_c" => Some((
            rins_plant::thermal::node::NAMES
                .iter()
                .map(|n| format!("imu.temp_{n}_c"))
                .collect(),
            1.0,
        )),
        "temp_chamber_c" => one("thermal.chamber_c"),
        "dtheta_true_rad" => one("truth.dtheta_rad"),
        "dv_true_mps" => one("truth.dv_mps"),
        "q_bn" => one("truth.q_bn"),
        "gimbal_outer_rad" => one("gimbal.outer_rad"),
        "gimbal_inner_rad" => one("gimbal.inner_rad"),
        // The sample's number is `imu.sample_count`, an Integer (the count, index + 1): checked
        // beside. The station label is a string the FMU leaves to the master (its gimbal.*
        // outputs carry the angles and `gimbal.moving`); the term columns are one output per
        // term (`effect.gyro.*`, `effect.accel.*`, checked beside); `rins fmu run` refuses a
        // moving carrier, whose truth no output carries.
        "sample" | "position" | "gyro_effects_dph" | "accel_effects_ug" | "carrier" => None,
        k => panic!(
            "the output column {k} has no FMU output: add its row at the end of outputs.rs's \
             table (the value references of the others stay) and name it here"
        ),
    }
}

/// Every output column of the plant's table is an FMU output reading the same values (in the
/// FMU's units), and every term column's enabled terms are outputs too: a quantity added to
/// the table and not to the FMU fails here.
#[test]
fn every_output_column_of_the_table_is_an_fmu_output() {
    use rins_plant::output_columns::{Reading, every_entry_read};
    let cfg = rins_plant::presets::paper_16pos_config();
    let mut plant = Plant::new(&cfg).unwrap();
    let mut s = plant.step();
    for _ in 0..300 {
        s = plant.step();
    }
    let truth = plant.truth();
    let mount = plant.truth_mount();
    let r = Reading {
        sample: &s,
        truth: &truth,
        mount: &mount,
    };
    let view = View {
        plant: &plant,
        truth,
        sample: Some(&s),
        true_sums: None,
    };
    let read = |name: &str| -> Vec<f64> {
        let o = outputs()
            .iter()
            .find(|o| o.decl.name == name)
            .unwrap_or_else(|| panic!("no FMU output {name}"));
        (0..o.decl.count())
            .map(|i| match (o.read)(&view, i) {
                Value::Real(x) => x,
                v => panic!("{name}: {v:?}"),
            })
            .collect()
    };
    for (e, want) in every_entry_read(&r) {
        let (names, factor) = match (e.column.key, e.term) {
            ("gyro_effects_dph", Some((_, key))) => (vec![format!("effect.gyro.{key}_rad")], 1.0),
            ("accel_effects_ug", Some((_, key))) => (vec![format!("effect.accel.{key}_mps")], 1.0),
            ("sample", _) => {
                let o = outputs()
                    .iter()
                    .find(|o| o.decl.name == "imu.sample_count")
                    .unwrap();
                assert_eq!((o.read)(&view, 0), Value::Integer(s.index + 1));
                continue;
            }
            (key, _) => match fmu_outputs_of(key) {
                Some(x) => x,
                None => continue,
            },
        };
        let got: Vec<f64> = names
            .iter()
            .flat_map(|n| read(n))
            .map(|x| x * factor)
            .collect();
        assert_eq!(got, want, "column {} ({names:?})", e.column.key);
    }
}
