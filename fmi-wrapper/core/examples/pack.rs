//! Packs the FMUs from built libraries: `cargo run -p rins-fmi --example pack -- LIB_DIR OUT_DIR`
//! (the `rins fmu build` command does the same).
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (lib_dir, out) = (
        std::path::Path::new(&args[1]),
        std::path::Path::new(&args[2]),
    );
    for v in [rins_fmi::xml::FmiVersion::V2, rins_fmi::xml::FmiVersion::V3] {
        let lib = lib_dir.join(rins_fmi::package::library_file(v));
        if lib.exists() {
            println!(
                "{}",
                rins_fmi::package::build_fmu(v, &lib, out)
                    .unwrap()
                    .display()
            );
        }
    }
}
