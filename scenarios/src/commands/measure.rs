//! `rins measure`: simulate a measurement log from a scenario (test data with known effects).

use std::path::PathBuf;

use anyhow::Result;
use rins_plant::PlantConfig;

use super::args::{Overrides, load};

/// Arguments of `rins measure`.
#[derive(clap::Args, Debug)]
pub struct MeasureArgs {
    /// Scenario to simulate.
    pub scenario: PathBuf,
    /// Output file.
    #[arg(long)]
    pub out: PathBuf,
    /// `csv` (default) or `parquet` (docs/measurement-format.md, "Parquet").
    #[arg(long, default_value = "csv", value_parser = ["csv", "parquet"])]
    pub format: String,
    /// `--seed`, `--duration-s`, `--rate-hz`.
    #[command(flatten)]
    pub overrides: Overrides,
}

/// Writes one run, or one per `[campaign]` temperature (seeds counting up from the scenario's),
/// in the measurement format.
pub fn run(a: &MeasureArgs) -> Result<()> {
    let sc = load(&a.scenario, &a.overrides)?;
    let n = sc.samples();
    let runs: Vec<(String, PlantConfig, u64)> = match &sc.campaign {
        Some(c) => c
            .temperatures_c()
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let mut cfg = sc.plant.clone();
                cfg.thermal.chamber.temp_c = *t;
                cfg.thermal.chamber.profile.clear();
                cfg.seed = sc.plant.seed.wrapping_add(i as u64);
                (format!("run{:02}-{t:.2}C", i + 1), cfg, n)
            })
            .collect(),
        None => vec![(sc.meta.name.clone(), sc.plant.clone(), n)],
    };
    let t0 = std::time::Instant::now();
    if a.format == "parquet" {
        // Written as CSV first and read back through the strict reader, so the Parquet file
        // holds exactly the columns and numbers the CSV would.
        let tmp = a.out.with_extension("parquet-tmp.csv");
        crate::diagnose::write_measurements(&tmp, &runs)?;
        let m = rins_mvm::reader::read(&tmp);
        let _ = std::fs::remove_file(&tmp);
        rins_mvm::parquet::write(&a.out, &m?).map_err(anyhow::Error::msg)?;
    } else {
        crate::diagnose::write_measurements(&a.out, &runs)?;
    }
    eprintln!(
        "{}: {} runs x {} samples in {:.1} s -> {}",
        sc.meta.name,
        runs.len(),
        n,
        t0.elapsed().as_secs_f64(),
        a.out.display()
    );
    Ok(())
}
