//! What a model must provide to be wrapped as a co-simulation FMU. The FMI glue
//! ([`crate::instance`], the `rins-fmi2`/`rins-fmi3` libraries) knows nothing else about it,
//! as in modelica/Reference-FMUs where `model.c` sits apart from `fmi2Functions.c`.

use crate::vars::{Value, VariableTable};

/// A fixed-step co-simulation model.
pub trait Model: Clone + Send + 'static {
    /// Model name and FMI model identifier (the shared library's name inside the FMU).
    const NAME: &'static str;

    /// The variable table (the same on every call).
    fn table() -> &'static VariableTable;

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

    /// Everything needed to resume, by value.
    fn save(&self) -> Vec<u8>;

    /// Resumes from [`Model::save`] output.
    fn restore(&mut self, bytes: &[u8]) -> Result<(), String>;
}
