//! Times the phases of `rins compare` / `rins diagnose` on a measurement file (the ≤ 10 s
//! target on the 37-run campaign): `phase_times MODEL DATA`.
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let t0 = std::time::Instant::now();
    let t1 = 0.0;
    let m = rins_mvm::reader::read(std::path::Path::new(&args[2])).unwrap();
    let t2 = t0.elapsed().as_secs_f64();
    let sc = rins_scenario::file::Scenario::load(std::path::Path::new(&args[1])).unwrap();
    let h = rins_mvm::to_history(m, "data").unwrap();
    let t3 = t0.elapsed().as_secs_f64();
    let a = rins_mvm::analyse(&sc.plant, &h, &Default::default());
    let t4 = t0.elapsed().as_secs_f64();
    let opts = rins_mvm::Options {
        diagnose: true,
        ..Default::default()
    };
    let d = rins_mvm::analyse(&sc.plant, &h, &opts);
    let t5 = t0.elapsed().as_secs_f64();
    eprintln!(
        "read {t1:.2} parse {:.2} history {:.2} compare (replay and report) {:.2} diagnose (replay, reports, selection) {:.2} ({} cells, {} ranked)",
        t2 - t1,
        t3 - t2,
        t4 - t3,
        t5 - t4,
        a.comparison.cells.len(),
        d.diagnosis.as_ref().map_or(0, |d| d.report.ranking.len())
    );
}
