//! Tests of the trial generator, each against an independent reference: RK4 integration of the
//! thermal network, closed forms of the kinematics and of the effects' row integrals, the
//! linearity and projections of the oracle, and the diagnosis's own CSV reader.

mod csv;
mod diagnosis;
mod draw;
mod effects;
mod generate;
mod increments;
mod oracle;
mod thermal;

use rins_mvm_trials::{ChamberLeg, Design, Gimbal, RunDesign, TableLeg, UnitThermal};
use rins_plant::PlantConfig;

/// The benchmark's base model: gyro bias, scale factor and ARW, accelerometer bias, scale
/// factor and VRW.
pub fn base_model() -> PlantConfig {
    let mut m = PlantConfig::default();
    let g = &mut m.sensor.gyro;
    g.bias.enabled = true;
    g.bias.dph = [0.01, -0.02, 0.015];
    g.scale_factor.enabled = true;
    g.scale_factor.ppm = [3.0, -2.0, 5.0];
    g.angle_random_walk.enabled = true;
    g.angle_random_walk.dpsh = [0.003; 3];
    let a = &mut m.sensor.accel;
    a.bias.enabled = true;
    a.bias.ug = [50.0, -30.0, 20.0];
    a.scale_factor.enabled = true;
    a.scale_factor.ppm = [50.0, 40.0, -30.0];
    a.velocity_random_walk.enabled = true;
    a.velocity_random_walk.ug_per_sqrthz = [10.0; 3];
    m
}

/// [`base_model`] without white noise: what the increments are, noise-free.
pub fn quiet_model() -> PlantConfig {
    let mut m = base_model();
    m.sensor.gyro.angle_random_walk.enabled = false;
    m.sensor.accel.velocity_random_walk.enabled = false;
    m
}

/// A one-run design with `table` and `chamber` over `duration_s`.
pub fn one_run(
    table: Vec<TableLeg>,
    chamber: Vec<ChamberLeg>,
    duration_s: f64,
    roll: f64,
) -> Design {
    Design {
        runs: vec![RunDesign {
            chamber,
            table,
            duration_s,
        }],
        rate_hz: 10.0,
        mount_roll_deg: roll,
        thermal: UnitThermal::typical(),
        name: "test".into(),
    }
}

/// A move of `gimbal` by `delta_deg` at `rate_dps`.
pub fn mv(gimbal: Gimbal, delta_deg: f64, rate_dps: f64) -> TableLeg {
    TableLeg::Move {
        gimbal,
        delta_deg,
        rate_dps,
    }
}

/// A hold at `temp_c` for `dur_s`.
pub fn hold(temp_c: f64, dur_s: f64) -> ChamberLeg {
    ChamberLeg::Hold { temp_c, dur_s }
}
