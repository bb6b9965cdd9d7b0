//! Packs the FMUs from built libraries: `cargo run -p rins-imu-fmu --example pack -- LIB_DIR
//! OUT_DIR` (the `rins fmu build` command does the same).
use rins_fmi::standard::FmiVersion;
use rins_imu_fmu::{RinsImu, library_file};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (lib_dir, out) = (
        std::path::Path::new(&args[1]),
        std::path::Path::new(&args[2]),
    );
    for v in [FmiVersion::V2, FmiVersion::V3] {
        let lib = lib_dir.join(library_file(v));
        if lib.exists() {
            let fmu = rins_fmi::package::build_fmu::<RinsImu>(v, &lib, out).unwrap();
            println!("{}", fmu.display());
        }
    }
}
