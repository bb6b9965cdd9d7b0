//! Reference results shipped beside each carrier FMU, as modelica/Reference-FMUs ship theirs:
//! `<Model>_ref.opt` (the experiment) and `<Model>_ref.csv` (the outputs at every
//! communication point, the initial ones first; the FMU has no inputs, so no `_in.csv`). They
//! come from the generic FMI state machine over this model in-process, the code the shared
//! libraries export, so a master must reproduce them bit for bit.

use std::fmt::Write;

use rins_fmi::instance::Instance;
use rins_fmi::vars::Value;

use crate::RinsCarrier;
use crate::table::{outputs, table};

/// Stop time of the reference experiment, s (two wave periods of a sea state 5).
pub const STOP_TIME_S: f64 = 20.0;
/// Communication step, s (one tick at the default 100 Hz).
pub const STEP_S: f64 = 0.01;

/// The two files: (`_ref.opt`, `_ref.csv`), every output in the CSV.
pub fn reference_results() -> Result<(String, String), String> {
    let opt = format!(
        "StartTime,    0.0\nStopTime,     {STOP_TIME_S:?}\nStepSize,     {STEP_S:?}\nRelTol,       1e-4\nOutputInterval, {STEP_S:?}\n"
    );
    let names: Vec<String> = outputs()
        .iter()
        .flat_map(|o| (0..o.decl.count()).map(|i| o.decl.element_name(i)))
        .collect();
    let t = table();
    let slots: Vec<usize> = names
        .iter()
        .map(|n| t.vars.slot(n).ok_or(format!("no variable {n}")))
        .collect::<Result<_, _>>()?;
    let mut inst = Instance::<RinsCarrier>::new();
    let e = |e: rins_fmi::instance::FmiError| e.message;
    inst.setup(0.0).map_err(e)?;
    inst.enter_initialization().map_err(e)?;
    inst.exit_initialization().map_err(e)?;
    let mut csv = String::from("\"time\"");
    for n in &names {
        let _ = write!(csv, ",\"{n}\"");
    }
    csv.push('\n');
    let row = |csv: &mut String, inst: &Instance<RinsCarrier>, t_s: f64| {
        let _ = write!(csv, "{t_s:?}");
        for s in &slots {
            if let Value::Real(x) = inst.get_slot(*s) {
                let _ = write!(csv, ",{x:?}");
            }
        }
        csv.push('\n');
    };
    row(&mut csv, &inst, 0.0);
    let steps = (STOP_TIME_S / STEP_S).round() as u64;
    for k in 0..steps {
        inst.do_step(k as f64 * STEP_S, STEP_S).map_err(e)?;
        row(&mut csv, &inst, (k + 1) as f64 * STEP_S);
    }
    Ok((opt, csv))
}
