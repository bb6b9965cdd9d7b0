//! Serialised plant state resumes bit-identically; wrong states are refused.

use rins_plant::state::StateError;
use rins_plant::{Plant, PlantConfig};

fn cfg() -> PlantConfig {
    let mut c = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        substeps: 2,
        seed: 9,
        ..PlantConfig::default()
    };
    c.thermal.chamber.profile = vec![[0.0, 20.0], [3000.0, 35.0]];
    c
}

fn outputs(p: &mut Plant, n: usize) -> Vec<u64> {
    (0..n)
        .flat_map(|_| {
            let s = p.step();
            let t = p.truth();
            let mut v: Vec<f64> = vec![s.t_s];
            v.extend(s.dtheta_rad.iter().chain(s.dv_mps.iter()));
            v.extend(t.gyro_terms_rad.iter().flat_map(|x| x.iter().copied()));
            v.extend(t.temps.nodes_c);
            v.push(t.gimbal.angles.outer_rad);
            v.into_iter().map(f64::to_bits).collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn resumes_bit_identically_mid_move_and_mid_dwell() {
    let c = cfg();
    // 4500 samples = 45 s: inside the first move; 40_000 = 400 s: inside a dwell, after thermal steps.
    for split in [4500usize, 40_000] {
        let mut a = Plant::new(&c).unwrap();
        outputs(&mut a, split);
        let bytes = a.serialize_state();
        let expected = outputs(&mut a, 30_000);
        let mut b = Plant::from_serialized_state(&c, &bytes).unwrap();
        assert_eq!(b.samples_done(), split as u64);
        assert_eq!(outputs(&mut b, 30_000), expected, "split at {split}");
    }
}

#[test]
fn wrong_states_are_refused() {
    let c = cfg();
    let mut a = Plant::new(&c).unwrap();
    a.step();
    let bytes = a.serialize_state();
    let mut other = c.clone();
    other.seed = 10;
    assert!(matches!(
        Plant::from_serialized_state(&other, &bytes),
        Err(StateError::ConfigMismatch { .. })
    ));
    assert!(matches!(
        Plant::from_serialized_state(&c, &bytes[..bytes.len() - 3]),
        Err(StateError::Length { .. })
    ));
    assert_eq!(
        Plant::from_serialized_state(&c, b"not a state at all").unwrap_err(),
        StateError::BadHeader
    );
    let mut longer = bytes.clone();
    longer.push(0);
    assert!(matches!(
        Plant::from_serialized_state(&c, &longer),
        Err(StateError::Length { .. })
    ));
}
