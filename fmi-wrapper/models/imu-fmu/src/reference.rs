//! Reference results shipped beside each FMU, as modelica/Reference-FMUs ship theirs:
//! `<Model>_ref.opt` (the experiment), `<Model>_in.csv` (the inputs) and `<Model>_ref.csv`
//! (the outputs at every communication point, the initial ones first). They come from the
//! generic FMI state machine over this model in-process ([`Instance`]), the code the shared
//! libraries export, so a master that simulates the FMU with these inputs must reproduce
//! them bit for bit (tests/python/test_fmu.py does it with FMPy).

use std::fmt::Write;

use rins_fmi::instance::Instance;
use rins_fmi::vars::Value;

use crate::RinsImu;
use crate::table::table;

/// Stop time of the reference experiment, s (two minutes of thermal updates and the first
/// part of the first dwell).
pub const STOP_TIME_S: f64 = 20.0;
/// Communication step, s (one IMU sample).
pub const STEP_S: f64 = 0.01;
/// When the chamber input switches to [`CHAMBER_STEP_C`]: a communication point (masters such
/// as FMPy step to input events, so a switch between points would ask for a half step).
pub const CHAMBER_SWITCH_S: f64 = 10.0;
/// The chamber temperature after the switch, °C (25 °C before: the default).
pub const CHAMBER_STEP_C: f64 = 40.0;

/// Outputs written to `_ref.csv` (FMI 2 names; the FMI 3 FMU names array elements the same way
/// in the CSV, as FMPy writes them).
pub const OUTPUTS: [&str; 11] = [
    "imu.dtheta_rad[0]",
    "imu.dtheta_rad[1]",
    "imu.dtheta_rad[2]",
    "imu.dv_mps[0]",
    "imu.dv_mps[1]",
    "imu.dv_mps[2]",
    "imu.time_s",
    "gimbal.outer_rad",
    "thermal.chamber_c",
    "thermal.housing_c",
    "thermal.gyro_z_c",
];

/// The three files: (`_ref.opt`, `_in.csv`, `_ref.csv`).
pub fn reference_results() -> Result<(String, String, String), String> {
    let opt = format!(
        "StartTime,    0.0\nStopTime,     {STOP_TIME_S:?}\nStepSize,     {STEP_S:?}\nRelTol,       1e-4\nOutputInterval, {STEP_S:?}\n"
    );
    let input = format!(
        "\"time\",\"input.chamber_override\",\"input.chamber_temp_c\"\n0.0,0,25.0\n{s:?},0,25.0\n{s:?},1,{c:?}\n{STOP_TIME_S:?},1,{c:?}\n",
        s = CHAMBER_SWITCH_S,
        c = CHAMBER_STEP_C
    );
    let t = table();
    let slot = |n: &str| t.vars.slot(n).ok_or(format!("no variable {n}"));
    let outputs: Vec<usize> = OUTPUTS.iter().map(|n| slot(n)).collect::<Result<_, _>>()?;
    let (over, temp) = (
        slot("input.chamber_override")?,
        slot("input.chamber_temp_c")?,
    );
    let mut inst = Instance::<RinsImu>::new();
    let e = |e: rins_fmi::instance::FmiError| e.message;
    inst.setup(0.0).map_err(e)?;
    inst.enter_initialization().map_err(e)?;
    inst.exit_initialization().map_err(e)?;
    let mut csv = String::from("\"time\"");
    for n in OUTPUTS {
        let _ = write!(csv, ",\"{n}\"");
    }
    csv.push('\n');
    let row = |csv: &mut String, inst: &Instance<RinsImu>, t_s: f64| {
        let _ = write!(csv, "{t_s:?}");
        for s in &outputs {
            let _ = match inst.get_slot(*s) {
                Value::Real(x) => write!(csv, ",{x:?}"),
                Value::Integer(u) => write!(csv, ",{u}"),
                Value::Boolean(b) => write!(csv, ",{}", b as u8),
                Value::Enumeration(i) => write!(csv, ",{}", i + 1),
            };
        }
        csv.push('\n');
    };
    row(&mut csv, &inst, 0.0);
    let steps = (STOP_TIME_S / STEP_S).round() as u64;
    for k in 0..steps {
        let t_s = k as f64 * STEP_S;
        // At the switch the master sets the new value before the step from it (the CSV's
        // second row at that time); the tolerance covers masters that accumulate time.
        if t_s >= CHAMBER_SWITCH_S - 1e-9 && inst.get_slot(over) == Value::Boolean(false) {
            inst.set_slot(over, Value::Boolean(true)).map_err(e)?;
            inst.set_slot(temp, Value::Real(CHAMBER_STEP_C))
                .map_err(e)?;
        }
        inst.do_step(t_s, STEP_S).map_err(e)?;
        row(&mut csv, &inst, (k + 1) as f64 * STEP_S);
    }
    Ok((opt, input, csv))
}
