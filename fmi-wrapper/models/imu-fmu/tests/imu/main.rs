//! The integration tests of rins-imu-fmu in one test binary (one link instead of one per file):
//! one module per former test file; `common` is the built libraries' path and the FMI 3 function
//! table the FMI tests share. The FMI libraries are found beside this binary's folder
//! (`cargo build --release -p rins-imu-fmi2 -p rins-imu-fmi3` first).

mod common;

mod c_api;
mod carrier_inputs;
mod declared_slots;
mod fmi3_property;
mod fmi_property;
mod fmi_rss;
mod initial_outputs;
mod master_fixes;
