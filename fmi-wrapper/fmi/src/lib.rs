//! # rins-fmi
//!
//! A generic FMI 2.0 / 3.0 co-simulation layer, without C: what the standard fixes for every
//! model ([`standard`]: the version, the log categories; it imports nothing else of the crate),
//! the model interface it is generic over ([`model`]), the variable table ([`vars`]), the FMI state machine ([`instance`]), the FMU
//! state codec ([`state`]), the registry of live instance handles ([`live`]), modelDescription.xml ([`xml`], [`fmu`]), `.fmu` packaging
//! ([`package`], [`zip`]: stored and deflated archives through the `zip` crate) and the C-ABI
//! helpers both FMI versions share ([`ffi`]). It knows no
//! model: the exported C functions are in `rins-fmi2` / `rins-fmi3`, generic too, and each model
//! is exported by a one-line cdylib crate (`rins_fmi2::export_fmi2!(Model)`).

pub mod ffi;
pub mod fmu;
pub mod instance;
pub mod live;
pub mod model;
pub mod package;
pub mod standard;
pub mod state;
pub mod vars;
pub mod xml;
pub mod zip;
