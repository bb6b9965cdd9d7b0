//! `rins bench-diagnosis`: the randomised benchmark of `rins diagnose --iterate`
//! (docs/model-vs-measurements.md, "How often is it right"): trials drawn from an effect class,
//! a run design, a magnitude and noise, written by the independent generator
//! (`rins-mvm-trials`), diagnosed, and scored; the rates per class with their intervals.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use anyhow::{Context, Result, bail};
use rins_mvm_trials::bench::{markdown, plan, run as run_trials, with_paired_controls};
use rins_mvm_trials::classes::Class;

/// Arguments of `rins bench-diagnosis`.
#[derive(clap::Args, Debug)]
pub struct BenchDiagnosisArgs {
    /// Trials (cycling through the classes), 1 to 100000.
    #[arg(long, default_value_t = 200, allow_negative_numbers = true)]
    pub trials: i64,
    /// Seed of the benchmark (each trial's own seed is drawn from it and its index).
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    pub seed: u64,
    /// Classes to draw from, comma-separated (default: every class, controls included).
    #[arg(long, value_delimiter = ',')]
    pub classes: Vec<String>,
    /// Skip the paired controls: by default every trial that hides something is run again on
    /// the same design, model and noise with nothing hidden (indices after the trials'), so the
    /// false-claim rate is measured on as many controls as there are effect trials.
    #[arg(long)]
    pub no_paired_controls: bool,
    /// Only these trial indices of the plan (replay a failing trial alone).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub only: Vec<usize>,
    /// Print the whole report (every trial and the rates) as JSON.
    #[arg(long)]
    pub json: bool,
    /// Write `benchmark.json`, `benchmark.md` and, for each trial that was not right, its log
    /// (`trial-N.csv`) and model (`trial-N-model.toml`) for `rins diagnose --iterate`.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Runs the benchmark.
pub fn run(a: &BenchDiagnosisArgs) -> Result<()> {
    if !(1..=100_000).contains(&a.trials) {
        bail!(
            "--trials must be a whole number from 1 to 100000, got {}",
            a.trials
        );
    }
    let classes: Vec<Class> = if a.classes.is_empty() {
        Class::all()
    } else {
        a.classes
            .iter()
            .map(|c| {
                Class::parse(c).with_context(|| {
                    let names: Vec<&str> = Class::all().iter().map(|c| c.name()).collect();
                    format!(
                        "--classes: unknown class {c:?}; the classes are {}",
                        names.join(", ")
                    )
                })
            })
            .collect::<Result<_>>()?
    };
    let mut specs = plan(a.trials as usize, a.seed, &classes);
    if !a.no_paired_controls {
        specs = with_paired_controls(specs);
    }
    if !a.only.is_empty() {
        if let Some(bad) = a.only.iter().find(|i| **i >= specs.len()) {
            bail!("--only {bad}: the plan has trials 0 to {}", specs.len() - 1);
        }
        specs.retain(|s| a.only.contains(&s.index));
    }
    let bar = crate::progress::bar(specs.len() as u64, "trials");
    let done = AtomicUsize::new(0);
    let report = run_trials(&specs, a.seed, &|o| {
        done.fetch_add(1, Ordering::Relaxed);
        bar.inc(1);
        if !o.score.correct {
            bar.suspend(|| {
                eprintln!(
                    "trial {} ({}{}): missing {:?}, extra {:?}; {}",
                    o.spec.index,
                    o.spec.class.name(),
                    if o.spec.paired_control {
                        ", paired control"
                    } else {
                        ""
                    },
                    o.score.missing,
                    o.score.extra,
                    o.stop
                )
            });
        }
    });
    bar.finish_and_clear();
    if let Some(dir) = &a.out {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        std::fs::write(
            dir.join("benchmark.json"),
            serde_json::to_string_pretty(&report)?,
        )?;
        std::fs::write(dir.join("benchmark.md"), markdown(&report))?;
        for o in report.outcomes.iter().filter(|o| !o.score.correct) {
            let t = rins_mvm_trials::bench::draw_trial(o.spec);
            let h = rins_mvm_trials::generate(&t.model, &t.design, &t.hidden, t.noise_seed);
            rins_mvm_trials::write_csv(&h, dir.join(format!("trial-{}.csv", o.spec.index)))?;
            rins_mvm_trials::write_model(
                &t.model,
                &format!("trial-{}", o.spec.index),
                dir.join(format!("trial-{}-model.toml", o.spec.index)),
            )?;
        }
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", markdown(&report));
        println!(
            "{} trials in {:.0} s on {} threads (seed {})",
            report.outcomes.len(),
            report.wall_s,
            rayon::current_num_threads(),
            a.seed
        );
    }
    Ok(())
}
