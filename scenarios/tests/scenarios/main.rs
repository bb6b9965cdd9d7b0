//! The integration tests of rins-scenarios in one test binary (one link instead of one per file):
//! one module per former test file. The command-line tests run the built `rins`
//! (`CARGO_BIN_EXE_rins`); `transport` (`rins serve`/`rins nav` over iceoryx2) is compiled only
//! with the `transport` feature, whose library edge it needs.

mod carrier_csv;
mod carrier_section;
mod cli;
mod declared;
mod diagnose;
mod discover;
mod discover_cli;
mod figure_rules;
mod figures;
mod fmu_run;
mod measurement;
mod measurement_cli;
mod preset_path;
mod scenario_errors;
mod scenario_files;
mod scenario_fuzz;
mod schemes_cli;
mod sea;
mod sweep;
#[cfg(feature = "transport")]
mod transport;
