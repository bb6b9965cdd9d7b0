//! # rins-fmi
//!
//! The rins plant as FMI 2.0 and FMI 3.0 co-simulation FMUs, without C: the variable table
//! ([`vars`]), the model interface the FMI glue is generic over ([`model`]), the rins plant behind
//! it ([`rins`]), the FMI state machine ([`instance`]), modelDescription.xml ([`xml`]), `.fmu`
//! packaging ([`package`], [`zip`]) and an FMI 2 importer for tests and `rins fmu run`
//! ([`importer`]). The exported C functions live in the `rins-fmi2` and `rins-fmi3` cdylibs.

pub mod ffi;
pub mod fmu;
pub mod importer;
pub mod instance;
pub mod model;
pub mod package;
pub mod rins;
pub mod vars;
pub mod xml;
pub mod zip;
