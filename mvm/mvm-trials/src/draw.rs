//! Randomised designs: the variety of chamber profiles, dwells, azimuths, tilts and move rates
//! a method must cope with (diagnosis-benchmark.md, "Draw the design").
//!
//! Ranges: 3–8 runs; 5 or 10 Hz; mount roll 0° or 30°; runs of 45–120 min; the chamber a soak
//! at 10–45 °C, a step (ramp at 5–10 K/min) between two temperatures in 10–45 °C at least
//! 10 K apart, or a ramp at 0.3–2 K/min up or down by 10–35 K (less when the ramp would take
//! more than 60 % of the run) between holds; the table cycling through dwells of 2–15 min
//! (a base length per run, each dwell within ±20 % of it) at the n azimuths (n = 4–8, outer
//! steps of 360°/n; the dwells are shortened so that one cycle fits into the run, and fewer
//! azimuths, at least 2, are visited only when 2 min dwells at all n do not fit) Z-up, optionally a dwell tilted by ±45° or ±90° on the inner gimbal,
//! the same azimuths Z-down in reverse order, and the 180° turn back, moves at 2–20 °/s. The
//! first cycle always fits into the run, so every run dwells at two azimuths or more at both
//! Z-up and Z-down. The unit's thermal constants: τ_h 900–2400 s, self-heating offsets 1–4 K,
//! τ_b and τ_a 200–800 s.

use rand::Rng;
use rand::seq::IndexedRandom;
use rand_chacha::ChaCha8Rng;

use crate::design::{ChamberLeg, Design, Gimbal, RunDesign, TableLeg, UnitThermal};

/// A randomised design (ranges in the module documentation).
pub fn draw_design(rng: &mut ChaCha8Rng) -> Design {
    let n_runs = rng.random_range(3..=8);
    let rate_hz = if rng.random_bool(0.5) { 5.0 } else { 10.0 };
    let mount_roll_deg = if rng.random_bool(0.5) { 0.0 } else { 30.0 };
    let thermal = UnitThermal {
        tau_housing_s: rng.random_range(900.0..=2400.0),
        block_offset_k: [(); 3].map(|_| rng.random_range(1.0..=4.0)),
        tau_block_s: [(); 3].map(|_| rng.random_range(200.0..=800.0)),
        accel_offset_k: rng.random_range(1.0..=4.0),
        tau_accel_s: rng.random_range(200.0..=800.0),
    };
    let mut runs = Vec::new();
    let mut parts = Vec::new();
    for _ in 0..n_runs {
        let duration_s = (rng.random_range(45.0..=120.0) * 60.0f64).round();
        let (chamber, c) = draw_chamber(rng, duration_s);
        let (table, t) = draw_table(rng, duration_s);
        parts.push(format!("{:.0} min, {c}, {t}", duration_s / 60.0));
        runs.push(RunDesign {
            chamber,
            table,
            duration_s,
        });
    }
    Design {
        runs,
        rate_hz,
        mount_roll_deg,
        thermal,
        name: format!(
            "{n_runs} runs, {rate_hz} Hz, roll {mount_roll_deg}°: {}",
            parts.join("; ")
        ),
    }
}

/// Rounded to 0.1.
fn tenth(x: f64) -> f64 {
    (x * 10.0).round() / 10.0
}

/// A chamber profile over `duration_s`, with its description.
fn draw_chamber(rng: &mut ChaCha8Rng, duration_s: f64) -> (Vec<ChamberLeg>, String) {
    let temp = |rng: &mut ChaCha8Rng, lo: f64, hi: f64| tenth(rng.random_range(lo..=hi));
    match rng.random_range(0..3) {
        0 => {
            let t = temp(rng, 10.0, 45.0);
            (
                vec![ChamberLeg::Hold {
                    temp_c: t,
                    dur_s: duration_s,
                }],
                format!("soak {t} °C"),
            )
        }
        1 => {
            let (a, b) = loop {
                let (a, b) = (temp(rng, 10.0, 45.0), temp(rng, 10.0, 45.0));
                if (a - b).abs() >= 10.0 {
                    break (a, b);
                }
            };
            let at = (duration_s * rng.random_range(0.1..=0.5)).round();
            let rate = tenth(rng.random_range(5.0..=10.0));
            (
                vec![
                    ChamberLeg::Hold {
                        temp_c: a,
                        dur_s: at,
                    },
                    ChamberLeg::Ramp {
                        to_c: b,
                        rate_k_per_min: rate,
                    },
                ],
                format!("step {a}→{b} °C at {at} s, {rate} K/min"),
            )
        }
        _ => {
            let rate = tenth(rng.random_range(0.3..=2.0)).max(0.3);
            let up = rng.random_bool(0.5);
            let hold = (duration_s * rng.random_range(0.05..=0.25)).round();
            let most = rate * 0.6 * duration_s / 60.0;
            let span = tenth(rng.random_range(10.0..=35.0f64).min(most));
            let a = if up {
                tenth(rng.random_range(10.0..=45.0 - span))
            } else {
                tenth(rng.random_range(10.0 + span..=45.0))
            };
            let b = tenth(if up { a + span } else { a - span }).clamp(10.0, 45.0);
            (
                vec![
                    ChamberLeg::Hold {
                        temp_c: a,
                        dur_s: hold,
                    },
                    ChamberLeg::Ramp {
                        to_c: b,
                        rate_k_per_min: rate,
                    },
                ],
                format!("ramp {a}→{b} °C at {rate} K/min after {hold} s"),
            )
        }
    }
}

/// A table sequence over `duration_s`, with its description.
fn draw_table(rng: &mut ChaCha8Rng, duration_s: f64) -> (Vec<TableLeg>, String) {
    let n_az: u32 = rng.random_range(4..=8);
    let step = 360.0 / n_az as f64;
    let rate = tenth(rng.random_range(2.0..=20.0)).max(2.0);
    let tilt: Option<f64> = rng
        .random_bool(0.5)
        .then(|| *[45.0, 90.0, -45.0, -90.0].choose(rng).expect("not empty"));
    let mut base = rng.random_range(120.0..=900.0f64);
    // Moves of one cycle over m azimuths: the steps out and back, the turn to Z-down and back.
    let moves_s = |m: u32| (2.0 * (m - 1) as f64 * step + 360.0) / rate;
    let dwells = |m: u32| (2 * m + u32::from(tilt.is_some())) as f64;
    // The first cycle fits into the run even with every dwell 20 % over the base: shorten the
    // dwells, and visit fewer azimuths only when even 2 min dwells at all n would not fit (the
    // ranges never need it: 17 dwells of 2 min and 8 azimuths at 2 °/s fit into 45 min).
    let fit = |m: u32| (duration_s - moves_s(m)) / (dwells(m) * 1.2);
    let mut m = n_az;
    while m > 2 && 1.2 * fit(m) < 120.0 {
        m -= 1;
    }
    base = base.min(fit(m));
    let mut seq = Sequence {
        legs: Vec::new(),
        t: 0.0,
        end: duration_s,
    };
    let mv = |gimbal, delta_deg| TableLeg::Move {
        gimbal,
        delta_deg,
        rate_dps: rate,
    };
    let dwell = |rng: &mut ChaCha8Rng| TableLeg::Dwell {
        dur_s: (base * rng.random_range(0.8..=1.2))
            .clamp(120.0, 900.0)
            .round(),
    };
    let down = match tilt {
        Some(x) if x < 0.0 => -180.0,
        _ => 180.0,
    };
    while !seq.full() {
        seq.push(dwell(rng));
        for _ in 1..m {
            seq.push(mv(Gimbal::Outer, step));
            seq.push(dwell(rng));
        }
        match tilt {
            Some(x) => {
                seq.push(mv(Gimbal::Inner, x));
                seq.push(dwell(rng));
                seq.push(mv(Gimbal::Inner, down - x));
            }
            None => seq.push(mv(Gimbal::Inner, down)),
        }
        seq.push(dwell(rng));
        for _ in 1..m {
            seq.push(mv(Gimbal::Outer, -step));
            seq.push(dwell(rng));
        }
        seq.push(mv(Gimbal::Inner, -down));
    }
    let legs = seq.legs;
    let tilt_text = tilt.map_or(String::new(), |x| format!(", tilt {x}°"));
    (
        legs,
        format!(
            "{m} of {n_az} azimuths, dwells ~{:.0} s{tilt_text}, {rate} °/s",
            base
        ),
    )
}

/// A table sequence being filled up to its run's length.
struct Sequence {
    legs: Vec<TableLeg>,
    /// Length so far, s.
    t: f64,
    /// The run's length, s.
    end: f64,
}

impl Sequence {
    /// Whether the run is covered.
    fn full(&self) -> bool {
        self.t >= self.end
    }

    /// Appends `leg`; the leg that would reach the run's end is replaced by a dwell to it (a
    /// move is never cut), and nothing is appended after.
    fn push(&mut self, leg: TableLeg) {
        if self.full() {
            return;
        }
        let len = crate::design::table_length_s(&[leg]);
        if self.t + len >= self.end {
            self.legs.push(TableLeg::Dwell {
                dur_s: self.end - self.t,
            });
            self.t = self.end;
        } else {
            self.legs.push(leg);
            self.t += len;
        }
    }
}
