//! The rins ship carrier as an FMI 3.0 shared library: all the FMI code is in `rins-fmi3`.

rins_fmi3::export_fmi3!(rins_carrier_fmu::RinsCarrier);
