//! The rins ship carrier as an FMI 2.0 shared library: all the FMI code is in `rins-fmi2`.

rins_fmi2::export_fmi2!(rins_carrier_fmu::RinsCarrier);
