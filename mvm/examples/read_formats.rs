//! Reads one measurement log as CSV and as Parquet and prints both times (the Parquet copy is
//! written next to the CSV if missing). Usage: `cargo run --release -p rins-mvm --example
//! read_formats -- DATA.csv [REPEATS]`; docs/measurement-format.md quotes its figures for the
//! 37-run campaign (`rins measure builtin:campaign-37`).

use std::path::PathBuf;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let csv = PathBuf::from(
        args.next()
            .ok_or("usage: read_formats DATA.csv [REPEATS]")?,
    );
    let repeats: usize = args.next().map_or(Ok(3), |s| s.parse())?;
    let pq = csv.with_extension("parquet");
    if !pq.exists() {
        let t = Instant::now();
        let m = rins_mvm::reader::read(&csv)?;
        rins_mvm::parquet::write(&pq, &m)?;
        eprintln!(
            "wrote {} in {:.1} s",
            pq.display(),
            t.elapsed().as_secs_f64()
        );
    }
    for (name, path) in [("csv", &csv), ("parquet", &pq)] {
        let size = std::fs::metadata(path)?.len() as f64 / 1e6;
        let mut best = f64::INFINITY;
        let mut rows = 0;
        for _ in 0..repeats {
            let t = Instant::now();
            let m = rins_mvm::reader::read(path)?;
            best = best.min(t.elapsed().as_secs_f64());
            rows = m.rows;
        }
        println!("{name:<8} {size:>8.0} MB  {rows} rows  best of {repeats}: {best:.2} s");
    }
    Ok(())
}
