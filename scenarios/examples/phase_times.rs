//! Times the phases of `rins compare` / `rins diagnose` on a measurement file (the ≤ 10 s
//! target on the 37-run campaign): `phase_times MODEL DATA`.
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let t0 = std::time::Instant::now();
    let t1 = 0.0;
    let m = rins_scenarios::measurement::read(std::path::Path::new(&args[2])).unwrap();
    let t2 = t0.elapsed().as_secs_f64();
    let sc = rins_scenarios::file::Scenario::load(std::path::Path::new(&args[1])).unwrap();
    let h = rins_scenarios::diagnose::to_history(m, "data").unwrap();
    let t3 = t0.elapsed().as_secs_f64();
    let a = rins_verify::diagnosis::analyse(&sc.plant, &h, Default::default());
    let t4 = t0.elapsed().as_secs_f64();
    let r = a.compare_report("x", &a.zero_pred());
    let t5 = t0.elapsed().as_secs_f64();
    let (d, _, _) = rins_verify::diagnosis::diagnose(&sc.plant, &h, Default::default());
    let t6 = t0.elapsed().as_secs_f64();
    eprintln!(
        "read {t1:.2} parse {:.2} history {:.2} replay {:.2} report {:.2} diagnose {:.2} ({} cells, {} ranked)",
        t2 - t1,
        t3 - t2,
        t4 - t3,
        t5 - t4,
        t6 - t5,
        r.cells.len(),
        d.ranking.len()
    );
}
