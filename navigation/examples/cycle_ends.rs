//! Development aid: attitude error at each 16-position cycle end, one gyro error on.
use rins_nav::{NavRunConfig, run};
use rins_plant::{Plant, PlantConfig, effects::GyroTerm};
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map(String::as_str).unwrap_or("mis");
    let mut c = PlantConfig::default();
    c.thermal.enabled = false;
    c.scheme.accel_dps2 = f64::INFINITY;
    let t3 = rins_plant::presets::paper_table3();
    let term = if which == "sf" { GyroTerm::ScaleFactor } else { GyroTerm::Misalignment };
    c.sensor.gyro = t3.gyro.only(&[term]);
    let mut p = Plant::new(&c).unwrap();
    let cycle = p.schedule().cycle_s();
    let r = run(&mut p, 6.0 * cycle, &NavRunConfig { record_every_s: cycle / 16.0, ..Default::default() }).unwrap();
    for rec in r.records.iter() {
        println!("{:8.0} s phi [{:+.3e} {:+.3e} {:+.3e}] v [{:+.2e} {:+.2e}]", rec.t_s, rec.att_err_rad[0], rec.att_err_rad[1], rec.att_err_rad[2], rec.vel_err_mps[0], rec.vel_err_mps[1]);
    }
}
