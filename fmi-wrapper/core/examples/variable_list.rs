//! Prints the FMU variable list as Markdown (FMI 3 names, arrays grouped), as in docs/fmu.md.
fn main() {
    print!(
        "{}",
        rins_fmi::package::variable_list(rins_fmi::xml::FmiVersion::V3)
    );
}
