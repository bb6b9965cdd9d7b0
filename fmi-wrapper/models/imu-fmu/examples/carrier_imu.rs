//! The carrier -> IMU system in process: the generic FMI state machines of RinsCarrier and
//! RinsImu connected as the co-simulation masters connect them (Jacobi: both step from t, then
//! the carrier's outputs become the IMU's inputs; the carrier's initial outputs reach the IMU
//! before it leaves initialization mode). Prints the wall time of the steps on stderr and,
//! with `--csv`, the IMU's `imu.dtheta_rad` after every step (`{:?}`, exact) on stdout.
//!
//! `cargo run --release -p rins-imu-fmu --example carrier_imu -- STEPS [--csv]`

use rins_carrier_fmu::RinsCarrier;
use rins_fmi::instance::Instance;
use rins_fmi::model::Model;
use rins_fmi::vars::Value;
use rins_imu_fmu::RinsImu;
use rins_imu_fmu::carrier_inputs::{INPUTS, SWITCH};

fn slot<M: Model>(name: &str) -> usize {
    M::table().slot(name).expect("variable exists")
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().collect();
    let steps: u64 = args
        .get(1)
        .and_then(|s| s.parse().ok())
        .ok_or("usage: carrier_imu STEPS [--csv]")?;
    let csv = args.iter().any(|a| a == "--csv");
    let e = |e: rins_fmi::instance::FmiError| e.message;
    let src: Vec<usize> = INPUTS.iter().map(|i| slot::<RinsCarrier>(i.name)).collect();
    let dst: Vec<usize> = INPUTS.iter().map(|i| slot::<RinsImu>(i.name)).collect();
    let out: Vec<usize> = (0..3)
        .map(|i| slot::<RinsImu>(&format!("imu.dtheta_rad[{i}]")))
        .collect();
    let mut car = Instance::<RinsCarrier>::new();
    let mut imu = Instance::<RinsImu>::new();
    car.setup(0.0).map_err(e)?;
    imu.setup(0.0).map_err(e)?;
    imu.set_slot(slot::<RinsImu>("run.seed"), Value::Integer(5))
        .map_err(e)?;
    imu.set_slot(slot::<RinsImu>(SWITCH), Value::Boolean(true))
        .map_err(e)?;
    car.enter_initialization().map_err(e)?;
    car.exit_initialization().map_err(e)?;
    imu.enter_initialization().map_err(e)?;
    let copy = |car: &Instance<RinsCarrier>, imu: &mut Instance<RinsImu>| {
        for (s, d) in src.iter().zip(&dst) {
            imu.set_slot(*d, car.get_slot(*s))?;
        }
        Ok(())
    };
    copy(&car, &mut imu).map_err(e)?;
    imu.exit_initialization().map_err(e)?;
    let mut text = String::new();
    let t0 = std::time::Instant::now();
    for k in 0..steps {
        let t = k as f64 * 0.01;
        car.do_step(t, 0.01).map_err(e)?;
        imu.do_step(t, 0.01).map_err(e)?;
        copy(&car, &mut imu).map_err(e)?;
        if csv {
            let v: Vec<String> = out
                .iter()
                .map(|s| match imu.get_slot(*s) {
                    Value::Real(x) => format!("{x:?}"),
                    v => format!("{v:?}"),
                })
                .collect();
            text.push_str(&v.join(","));
            text.push('\n');
        }
    }
    eprintln!("wall_s {}", t0.elapsed().as_secs_f64());
    print!("{text}");
    Ok(())
}
