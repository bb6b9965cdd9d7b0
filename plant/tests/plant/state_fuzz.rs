//! Property test of the plant state deserialiser (issue 16): for random configurations of run
//! length, seed and gimbal command, a saved state restores bit-identically; truncated,
//! extended, bit-flipped, spliced and random byte strings never panic, and every refusal names
//! where (the byte count read against the count expected, the header, or the fingerprints).
//!
//! Fixed seeds (ChaCha8): a failure prints the seed and case number to replay.

use rand::{Rng, RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rins_plant::state::StateError;
use rins_plant::{GimbalCommand, Plant, PlantConfig};

const SEED: u64 = 0x5eed_0016;
/// Random plants whose state is saved, restored and mutated.
const PLANTS: usize = 80;
/// Mutations of each saved state.
const MUTATIONS_PER_PLANT: usize = 400;
/// Fully random byte strings (with and without the right header).
const RANDOM_STRINGS: usize = 20_000;

fn cfg(seed: u64) -> PlantConfig {
    let mut c = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        seed,
        ..PlantConfig::default()
    };
    c.thermal.chamber.profile = vec![[0.0, 20.0], [3000.0, 35.0]];
    c
}

fn out_bits(p: &mut Plant, n: usize) -> Vec<u64> {
    (0..n)
        .flat_map(|_| {
            let s = p.step();
            let mut v = vec![s.t_s];
            v.extend(s.dtheta_rad.iter().chain(s.dv_mps.iter()));
            v.push(p.truth().gimbal.angles.outer_rad);
            v.into_iter().map(f64::to_bits).collect::<Vec<_>>()
        })
        .collect()
}

/// A plant stepped a random number of ticks, with a gimbal command in flight half the time
/// (so the state's optional command section is covered).
fn random_plant(rng: &mut ChaCha8Rng) -> (PlantConfig, Plant) {
    let c = cfg(rng.random_range(0..1000));
    let mut p = Plant::new(&c).expect("valid configuration");
    for _ in 0..rng.random_range(0..400) {
        p.step();
    }
    if rng.random_bool(0.5) {
        p.command_gimbal(&GimbalCommand::MoveTo {
            outer_rad: rng.random_range(-3.0..3.0),
            inner_rad: rng.random_range(-3.0..3.0),
            rate_rps: rng.random_range(0.05..0.5),
        })
        .expect("valid command");
        for _ in 0..rng.random_range(0..50) {
            p.step();
        }
    }
    (c, p)
}

/// A refusal must say where: a length error gives both byte counts and the expected count lies
/// past the bytes given or before their end (trailing bytes); the others name the header or the
/// two fingerprints.
fn check_refusal(e: &StateError, len: usize, ctx: &str) {
    let text = e.to_string();
    match e {
        StateError::Length { got, expected } => {
            assert_eq!(*got, len, "{ctx}: {text}");
            assert_ne!(*expected, len, "{ctx}: {text}");
            assert!(text.contains(&got.to_string()) && text.contains(&expected.to_string()));
        }
        StateError::BadHeader => assert!(text.contains("header"), "{ctx}: {text}"),
        StateError::ConfigMismatch { saved, current } => {
            assert_ne!(saved, current, "{ctx}");
            assert!(text.contains("fingerprint"), "{ctx}: {text}");
        }
        StateError::Inconsistent(m) => assert!(text.contains("inconsistent"), "{ctx}: {m}"),
        StateError::Config(m) => panic!("{ctx}: the configuration was valid, yet {m}"),
    }
}

/// One mutation of `good`; returns the bytes and a short description for failure messages.
fn mutate(rng: &mut ChaCha8Rng, good: &[u8]) -> (Vec<u8>, String) {
    let mut b = good.to_vec();
    let what = match rng.random_range(0..6) {
        0 => {
            let n = rng.random_range(0..b.len());
            b.truncate(n);
            format!("truncated to {n}")
        }
        1 => {
            let n = rng.random_range(1..64);
            b.extend((0..n).map(|_| rng.random::<u8>()));
            format!("{n} bytes appended")
        }
        2 => {
            let k = rng.random_range(0..b.len());
            b[k] ^= 1 << rng.random_range(0..8);
            format!("bit flipped at {k}")
        }
        3 => {
            // An 8-byte field overwritten with an extreme value (NaN, inf, huge counts).
            let k = 16 + 8 * rng.random_range(0..(b.len() - 16) / 8);
            let v: u64 = match rng.random_range(0..6) {
                0 => f64::NAN.to_bits(),
                1 => f64::INFINITY.to_bits(),
                2 => f64::NEG_INFINITY.to_bits(),
                3 => 1e300f64.to_bits(),
                4 => u64::MAX,
                _ => rng.random(),
            };
            b[k..k + 8].copy_from_slice(&v.to_le_bytes());
            format!("field at {k} set to {v:#x}")
        }
        4 => {
            let (i, j) = (rng.random_range(0..b.len()), rng.random_range(0..b.len()));
            let (i, j) = (i.min(j), i.max(j));
            b.drain(i..j);
            format!("bytes {i}..{j} removed")
        }
        _ => {
            let k = rng.random_range(0..b.len());
            let n = rng.random_range(1..32);
            let junk: Vec<u8> = (0..n).map(|_| rng.random()).collect();
            b.splice(k..k, junk);
            format!("{n} bytes inserted at {k}")
        }
    };
    (b, what)
}

#[test]
fn saved_states_round_trip_and_mutated_states_are_refused_with_where_or_run() {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let (mut accepted, mut refused) = (0usize, 0usize);
    for case in 0..PLANTS {
        let ctx = format!("seed {SEED:#x}, plant case {case}");
        let (c, mut p) = random_plant(&mut rng);
        let good = p.serialize_state();
        // The exact round trip: the restored plant continues bit for bit.
        let mut restored = Plant::from_serialized_state(&c, &good).expect(&ctx);
        assert_eq!(restored.serialize_state(), good, "{ctx}");
        assert_eq!(out_bits(&mut restored, 50), out_bits(&mut p, 50), "{ctx}");
        for m in 0..MUTATIONS_PER_PLANT {
            let (bytes, what) = mutate(&mut rng, &good);
            let ctx = format!("{ctx}, mutation {m} ({what})");
            match Plant::from_serialized_state(&c, &bytes) {
                Ok(mut q) => {
                    accepted += 1;
                    // An accepted state is a plant: it steps without panicking.
                    out_bits(&mut q, 3);
                }
                Err(e) => {
                    refused += 1;
                    check_refusal(&e, bytes.len(), &ctx);
                }
            }
        }
    }
    // Both branches are exercised: flips inside float fields are accepted, cuts are refused.
    assert!(accepted > 0 && refused > 0, "{accepted} {refused}");
}

#[test]
fn random_byte_strings_are_refused_and_name_where() {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED ^ 1);
    let c = cfg(1);
    let good = Plant::new(&c).unwrap().serialize_state();
    for case in 0..RANDOM_STRINGS {
        let ctx = format!("seed {:#x}, case {case}", SEED ^ 1);
        let n = rng.random_range(0..2 * good.len());
        let mut b = vec![0u8; n];
        rng.fill_bytes(&mut b);
        // Half keep the right header and fingerprint, so the body reader is what refuses.
        if case % 2 == 1 && n >= 16 {
            b[..16].copy_from_slice(&good[..16]);
        }
        match Plant::from_serialized_state(&c, &b) {
            Ok(mut q) if n == good.len() => {
                out_bits(&mut q, 3);
            }
            Ok(_) => panic!("{ctx}: {n} bytes accepted, a state has {}", good.len()),
            Err(e) => check_refusal(&e, n, &ctx),
        }
    }
}
