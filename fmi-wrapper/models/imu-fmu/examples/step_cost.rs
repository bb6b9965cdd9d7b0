//! Runs N 10 ms steps of the paper's plant either in process or through the FMI 2.0 binary's C
//! ABI, for instruction counting: `valgrind --tool=callgrind target/release/examples/step_cost
//! plant|fmu N` at two N; the difference over ΔN is the cost of one step, free of timing noise.
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    match args.get(1).map(String::as_str) {
        Some("plant") => {
            let mut p = rins_plant::Plant::new(&rins_plant::presets::paper_16pos_config()).unwrap();
            let mut acc = 0.0;
            for _ in 0..n {
                acc += p.step().dtheta_rad.z;
            }
            println!("{acc}");
        }
        Some("fmu") => {
            let exe = std::env::current_exe().unwrap();
            let so =
                exe.parent()
                    .and_then(|d| d.parent())
                    .unwrap()
                    .join(rins_imu_fmu::library_file(
                        rins_fmi::standard::FmiVersion::V2,
                    ));
            let (guid, _, vars) = rins_fmi_import::parse_model_description(
                &rins_fmi::fmu::description::<rins_imu_fmu::RinsImu>(
                    rins_fmi::standard::FmiVersion::V2,
                )
                .0,
            )
            .unwrap();
            let lib = rins_fmi_import::Fmu2::load(&so, guid, vars).unwrap();
            let inst = lib.instantiate("cost", false).unwrap();
            inst.setup_experiment(0.0, None).unwrap();
            inst.enter_initialization_mode().unwrap();
            inst.exit_initialization_mode().unwrap();
            let vr = [lib.vr("imu.dtheta_rad[2]").unwrap()];
            let mut acc = 0.0;
            let mut out = [0.0];
            for k in 0..n {
                inst.do_step(k as f64 * 0.01, 0.01).unwrap();
                inst.get_real(&vr, &mut out).unwrap();
                acc += out[0];
            }
            println!("{acc}");
        }
        _ => eprintln!("usage: step_cost plant|fmu N"),
    }
}
