//! What a model must provide to be exported as a co-simulation FMU. The FMI glue
//! ([`crate::instance`], the `rins-fmi2`/`rins-fmi3` libraries) knows nothing else about it,
//! as in modelica/Reference-FMUs where `model.c` sits apart from `fmi2Functions.c`.

use crate::state::{StateReader, StateWriter};
use crate::vars::{Value, VariableTable};

/// Identity and defaults of a model's FMUs: everything modelDescription.xml says besides the
/// variables.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelInfo {
    /// Model identifier of the FMI 2 FMU: its binary and `.fmu` file name.
    pub fmi2_id: &'static str,
    /// Model identifier of the FMI 3 FMU.
    pub fmi3_id: &'static str,
    /// One-line description.
    pub description: &'static str,
    /// Default experiment: stop time, s.
    pub stop_time_s: f64,
    /// Default experiment: communication step, s.
    pub step_size_s: f64,
}

/// A fixed-step co-simulation model.
pub trait Model: Clone + Send + 'static {
    /// Identifiers and default experiment.
    const INFO: ModelInfo;

    /// The variable table: parameters, inputs and outputs (the same on every call).
    fn table() -> &'static VariableTable;

    /// Markdown placed in the FMU's `documentation/index.md` before the variable list.
    fn documentation() -> String {
        String::new()
    }

    /// A model with every variable at its start value.
    fn new() -> Self;

    /// Stores a parameter or input value (already type- and range-checked by the glue).
    fn set(&mut self, slot: usize, v: Value) -> Result<(), String>;

    /// Current value of any slot.
    fn get(&self, slot: usize) -> Value;

    /// Ends initialisation: builds the simulation from the parameters, or says what is wrong.
    fn initialize(&mut self) -> Result<(), String>;

    /// Internal steps per second: communication steps must be whole multiples of its inverse.
    fn internal_rate_hz(&self) -> f64;

    /// Advances `n` internal steps (inputs as last set).
    fn advance(&mut self, n: u64) -> Result<(), String>;

    /// A doStep after initialisation was refused (or [`Model::advance`] failed): outputs that
    /// are sums over the last communication step (increments) should read NaN until the next
    /// step is taken, so a master that ignores the status does not take the last step's
    /// increments twice. Outputs that are states at the FMU's time stay valid. Default: none.
    fn step_refused(&mut self) {}

    /// Writes everything needed to resume, by value.
    fn save(&self, w: &mut StateWriter);

    /// Resumes from what [`Model::save`] wrote.
    fn restore(&mut self, r: &mut StateReader<'_>) -> Result<(), String>;
}
