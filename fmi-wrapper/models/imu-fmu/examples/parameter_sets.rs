//! Writes the SSP parameter sets of the sensor presets into fmi-wrapper/examples/system/.
fn main() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/system");
    for preset in ["paper-table3", "nav-grade-full"] {
        let path = format!("{dir}/{preset}.ssv");
        let text = rins_imu_fmu::ssv::sensor_parameter_set(preset).expect("a known preset");
        std::fs::write(&path, text).expect("writable examples folder");
        println!("{path}");
    }
}
