//! What the FMI standard fixes for every model, shared by every layer of this crate: which
//! version a description or C API is for, and the log categories the FMUs declare. It imports
//! nothing from the crate, so the variable table, the instance, the C glue and the
//! modelDescription writer can all use it without importing one another.

/// Which standard.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FmiVersion {
    /// FMI 2.0 co-simulation.
    V2,
    /// FMI 3.0 co-simulation.
    V3,
}

/// Log categories the FMUs declare (name, description): in modelDescription.xml, and the
/// only names setDebugLogging accepts.
pub const LOG_CATEGORIES: [(&str, &str); 3] = [
    (
        "logStatusError",
        "Calls that fail, with the reason (always reported)",
    ),
    (
        "logStatusWarning",
        "Calls that succeed with a remark (always reported)",
    ),
    (
        "logEvents",
        "Instantiation, mode changes (initialization, step mode, terminate, reset) and every doStep with its start time and size (only with loggingOn)",
    ),
];
