//! Unit tests of the parameter mapping and the output table.

use super::*;
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
        assert_eq!(rec.truth, *plant.truth(), "truth {k}");
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
