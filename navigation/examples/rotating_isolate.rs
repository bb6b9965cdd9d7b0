//! Development aid: 16-position rotation, noise off, one error group at a time.
use rins_nav::{NavRunConfig, run};
use rins_plant::{Plant, PlantConfig, effects::GyroTerm};

fn go(label: &str, cfg: &PlantConfig, comp: bool, hours: f64) {
    let mut p = Plant::new(cfg).unwrap();
    let nav = NavRunConfig { compensation: comp.then_some(cfg.sensor.gyro.position_bias), record_every_s: 600.0, ..Default::default() };
    let r = run(&mut p, hours * 3600.0, &nav).unwrap();
    let e = r.end();
    println!("{label:<34} north {:9.1} m east {:9.1} m  phi [{:+.2e} {:+.2e} {:+.2e}]", e.north_m, e.east_m, e.att_err_rad[0], e.att_err_rad[1], e.att_err_rad[2]);
}

fn main() {
    let hours = 24.0;
    let mut base = PlantConfig::default();
    base.thermal.enabled = false;
    go("ideal, rotating", &base, false, hours);
    let mut t3 = base.clone();
    t3.sensor = rins_plant::presets::paper_table3();
    t3.sensor.gyro.angle_random_walk.enabled = false;
    let mut no_db = t3.clone();
    no_db.sensor.gyro.position_bias.enabled = false;
    go("table3 without dbeta", &no_db, false, hours);
    for t in [GyroTerm::Bias, GyroTerm::ScaleFactor, GyroTerm::Misalignment] {
        let mut c = base.clone();
        c.sensor.gyro = t3.sensor.gyro.only(&[t]);
        go(&format!("gyro {t:?} only"), &c, false, hours);
    }
    let mut a = base.clone();
    a.sensor.accel = t3.sensor.accel.clone();
    go("accel table3 only", &a, false, hours);
    let mut d = base.clone();
    d.sensor.gyro = t3.sensor.gyro.only(&[GyroTerm::PositionBias]);
    go("dbeta only, uncompensated", &d, false, hours);
    go("dbeta only, compensated", &d, true, hours);
}
