//! What a trial measures: the runs (a chamber profile and a table sequence each), the row
//! rate, the mount, and the unit's thermal constants.

use rins_plant::PlantConfig;
use serde::{Deserialize, Serialize};

/// One leg of a chamber profile. The profile starts at the first leg's temperature (a
/// [`ChamberLeg::Hold`]) and holds its last temperature after its last leg.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum ChamberLeg {
    /// Hold `temp_c` for `dur_s` seconds (a hold at another temperature than the current one
    /// jumps to it at once).
    Hold {
        /// Chamber temperature, °C.
        temp_c: f64,
        /// Duration, s.
        dur_s: f64,
    },
    /// Ramp linearly from the current temperature to `to_c` at `rate_k_per_min` (a step is a
    /// fast ramp, e.g. 10 K/min).
    Ramp {
        /// End temperature, °C.
        to_c: f64,
        /// Ramp rate, K/min, > 0.
        rate_k_per_min: f64,
    },
}

/// A gimbal of the dual-axis table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Gimbal {
    /// The outer (azimuth) gimbal, about z before the inner rotation.
    Outer,
    /// The inner gimbal, about body x.
    Inner,
}

/// One leg of a table sequence. Every run starts at outer = inner = 0 (Z-up); the table keeps
/// its last position after its last leg.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum TableLeg {
    /// Stand still for `dur_s` seconds.
    Dwell {
        /// Duration, s.
        dur_s: f64,
    },
    /// Turn one gimbal by `delta_deg` at the constant rate `rate_dps` (starting and stopping
    /// instantly); the other gimbal stands still.
    Move {
        /// The gimbal that turns.
        gimbal: Gimbal,
        /// Signed angle, degrees.
        delta_deg: f64,
        /// Rate, °/s, > 0.
        rate_dps: f64,
    },
}

/// A run design: one chamber profile and one table sequence over `duration_s`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunDesign {
    /// Chamber profile.
    pub chamber: Vec<ChamberLeg>,
    /// Table sequence.
    pub table: Vec<TableLeg>,
    /// Length of the run, s (the rows cover (0, duration_s]).
    pub duration_s: f64,
}

/// The unit's thermal constants: the housing follows the chamber as a first-order lag; each
/// gyro block and the accelerometer node follow the housing plus a self-heating offset, each as
/// a first-order lag of its own (docs of [`crate::thermal`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct UnitThermal {
    /// Housing time constant τ_h, s.
    pub tau_housing_s: f64,
    /// Gyro block self-heating offsets s_i over the housing, K.
    pub block_offset_k: [f64; 3],
    /// Gyro block time constants τ_b,i, s.
    pub tau_block_s: [f64; 3],
    /// Accelerometer node self-heating offset s_a, K.
    pub accel_offset_k: f64,
    /// Accelerometer node time constant τ_a, s.
    pub tau_accel_s: f64,
}

impl UnitThermal {
    /// Fixed mid-range constants for the named designs.
    pub fn typical() -> Self {
        Self {
            tau_housing_s: 1500.0,
            block_offset_k: [2.5, 2.0, 3.0],
            tau_block_s: [400.0, 500.0, 600.0],
            accel_offset_k: 1.5,
            tau_accel_s: 300.0,
        }
    }
}

/// A whole trial design: the runs, sampled at `rate_hz`, with the vehicle mount's roll.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Design {
    /// Runs, named "run1", "run2", … in the history.
    pub runs: Vec<RunDesign>,
    /// Row rate, Hz.
    pub rate_hz: f64,
    /// Vehicle mount roll, degrees (about the vehicle y axis; 30° lets body x see gravity). It
    /// overrides the model's `[vehicle] roll_deg` ([`Design::model_for`]).
    pub mount_roll_deg: f64,
    /// The unit's thermal constants.
    pub thermal: UnitThermal,
    /// Short description.
    pub name: String,
}

/// Gap between the end of one run and the first row of the next, s.
pub const RUN_GAP_S: f64 = 100.0;

impl Design {
    /// `model` as the diagnosis must see it on this design: the mount roll and the row rate
    /// of the design (everything else as given). Generate and diagnose with this model.
    pub fn model_for(&self, model: &PlantConfig) -> PlantConfig {
        let mut m = model.clone();
        m.vehicle.roll_deg = self.mount_roll_deg;
        m.rate_hz = self.rate_hz;
        m
    }

    /// The case of chamber steps with four azimuths: runs with chamber steps 10→45 °C,
    /// 45→10 °C, 15→50→20 °C (at 10 K/min) and a steady 30 °C, each with two cycles of 300 s
    /// dwells at four azimuths Z-up, a 120 s dwell tilted 90°, the four azimuths Z-down, and a
    /// turn back to Z-up; every move 90° (the turn back 180°) at 2 °/s. 10 Hz, level mount.
    pub fn chamber_steps_four_azimuths() -> Self {
        let cycle = four_azimuth_cycle(300.0, Some(120.0), 2.0);
        let table: Vec<TableLeg> = cycle.iter().chain(&cycle).copied().collect();
        let duration_s = table_length_s(&table);
        let hold = |temp_c, dur_s| ChamberLeg::Hold { temp_c, dur_s };
        let step = |to_c| ChamberLeg::Ramp {
            to_c,
            rate_k_per_min: 10.0,
        };
        let chambers = [
            vec![hold(10.0, 1200.0), step(45.0)],
            vec![hold(45.0, 1200.0), step(10.0)],
            vec![
                hold(15.0, 900.0),
                step(50.0),
                hold(50.0, 2400.0),
                step(20.0),
            ],
            vec![hold(30.0, duration_s)],
        ];
        Self {
            runs: chambers
                .into_iter()
                .map(|chamber| RunDesign {
                    chamber,
                    table: table.clone(),
                    duration_s,
                })
                .collect(),
            rate_hz: 10.0,
            mount_roll_deg: 0.0,
            thermal: UnitThermal::typical(),
            name: "chamber steps 10→45, 45→10, 15→50→20 °C and 30 °C; 300 s dwells at 4 azimuths Z-up/Z-down, tilted 120 s; 90° moves at 2 °/s".into(),
        }
    }

    /// A design for effects fixed in the navigation frame: four runs at steady 20, 25, 30 and
    /// 25 °C, each with 600 s dwells at four azimuths Z-up and then Z-down, 90° moves (the flip
    /// 180°) at 10 °/s. 10 Hz, the mount rolled 30°: on a level mount body y never turns (the
    /// outer axis is ±z at Z-up and Z-down), so its scale factor reads only the Earth rate's
    /// north component and is the same column as the field's north part.
    pub fn field_four_azimuths() -> Self {
        let table = four_azimuth_cycle(600.0, None, 10.0);
        let duration_s = table_length_s(&table);
        Self {
            runs: [20.0, 25.0, 30.0, 25.0]
                .into_iter()
                .map(|temp_c| RunDesign {
                    chamber: vec![ChamberLeg::Hold {
                        temp_c,
                        dur_s: duration_s,
                    }],
                    table: table.clone(),
                    duration_s,
                })
                .collect(),
            rate_hz: 10.0,
            mount_roll_deg: 30.0,
            thermal: UnitThermal::typical(),
            name: "4 soaks 20/25/30/25 °C; 600 s dwells at 4 azimuths Z-up and Z-down; moves at 10 °/s; mount rolled 30°".into(),
        }
    }
}

/// One cycle: dwells at outer 0, 90, 180, 270° Z-up, optionally a tilted dwell (inner 90°),
/// dwells at 270, 180, 90, 0° Z-down and, when tilted, the turn back to Z-up.
fn four_azimuth_cycle(dwell_s: f64, tilt_s: Option<f64>, rate_dps: f64) -> Vec<TableLeg> {
    let dwell = TableLeg::Dwell { dur_s: dwell_s };
    let mv = |gimbal, delta_deg| TableLeg::Move {
        gimbal,
        delta_deg,
        rate_dps,
    };
    let mut legs = vec![dwell];
    for _ in 0..3 {
        legs.extend([mv(Gimbal::Outer, 90.0), dwell]);
    }
    match tilt_s {
        Some(t) => legs.extend([
            mv(Gimbal::Inner, 90.0),
            TableLeg::Dwell { dur_s: t },
            mv(Gimbal::Inner, 90.0),
        ]),
        None => legs.push(mv(Gimbal::Inner, 180.0)),
    }
    legs.push(dwell);
    for _ in 0..3 {
        legs.extend([mv(Gimbal::Outer, -90.0), dwell]);
    }
    if tilt_s.is_some() {
        legs.push(mv(Gimbal::Inner, -180.0));
    }
    legs
}

/// Total length of a table sequence, s.
pub fn table_length_s(table: &[TableLeg]) -> f64 {
    table
        .iter()
        .map(|l| match *l {
            TableLeg::Dwell { dur_s } => dur_s,
            TableLeg::Move {
                delta_deg,
                rate_dps,
                ..
            } => delta_deg.abs() / rate_dps,
        })
        .sum()
}
