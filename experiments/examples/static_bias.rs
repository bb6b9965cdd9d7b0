//! Development aid: static, non-rotating navigation with one gyro bias against the closed form.
use rins_experiments::{NavRunConfig, run};
use rins_plant::{Plant, PlantConfig, table::SchemeKind, units::DPH};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let axis: usize = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(1);
    let hours: f64 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(24.0);
    let mut cfg = PlantConfig::default();
    cfg.scheme.kind = SchemeKind::Static;
    cfg.thermal.enabled = false;
    if axis < 3 {
        cfg.sensor.gyro.bias.enabled = true;
        cfg.sensor.gyro.bias.dph[axis] = 0.01;
    }
    let mut p = Plant::new(&cfg).unwrap();
    let t0 = std::time::Instant::now();
    let r = run(
        &mut p,
        hours * 3600.0,
        &NavRunConfig {
            record_every_s: 3600.0,
            ..Default::default()
        },
    )
    .unwrap();
    eprintln!("wall {:.2} s", t0.elapsed().as_secs_f64());
    let w = rins_plant::earth::OMEGA_IE_RPS;
    let l = 36.6f64.to_radians();
    let mut e = [0.0; 3];
    if axis < 3 {
        e[axis] = 0.01 * DPH;
    }
    let (rm, rn) = rins_plant::earth::radii_of_curvature(l);
    for rec in r.records.iter() {
        let t = rec.t_s;
        let dl = -(e[0] / w) * (w * t).sin()
            - ((l.sin() * e[1] - l.cos() * e[2]) / w) * (1.0 - (w * t).cos());
        let dlam = (e[1] * l.cos() + e[2] * l.sin()) * t
            - (l.tan() * e[0] / w) * (1.0 - (w * t).cos())
            + l.tan() * (l.sin() * e[1] - l.cos() * e[2]) * (w * t).sin() / w;
        println!(
            "{:6.1} h  north {:10.1} m (cf {:10.1})  east {:10.1} m (cf {:10.1})  phiU {:+.3e}",
            t / 3600.0,
            rec.north_m,
            dl * rm,
            rec.east_m,
            dlam * rn * l.cos(),
            rec.att_err_rad[2]
        );
    }
}
