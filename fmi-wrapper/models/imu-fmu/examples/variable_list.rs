//! Prints the FMU variable list as Markdown (FMI 3 names, arrays grouped), as in docs/fmu.md.
use rins_fmi::model::Model;

fn main() {
    print!(
        "{}",
        rins_fmi::package::variable_list(
            rins_imu_fmu::RinsImu::table(),
            rins_fmi::standard::FmiVersion::V3
        )
    );
}
