//! Arguments several commands share: the scenario overrides, `--rerun`, and the checks of
//! numeric flags. Every numeric flag takes negative numbers (`allow_negative_numbers`), so a
//! value like `-5` reaches the range check, which names the flag and the expected range,
//! instead of clap's "use `-- -5`" tip.

use std::path::Path;

use anyhow::Result;
use rins_plant::message::Num;

use rins_scenario::file::{Override, Scenario};

/// `--seed`, `--duration-s`, `--rate-hz`: override the scenario file's values.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct Overrides {
    /// Override `run.seed`.
    #[arg(long, value_parser = seed, allow_negative_numbers = true)]
    pub seed: Option<u64>,
    /// Override `scenario.duration_s`.
    #[arg(long, allow_negative_numbers = true)]
    pub duration_s: Option<f64>,
    /// Override `run.rate_hz`.
    #[arg(long, allow_negative_numbers = true)]
    pub rate_hz: Option<f64>,
}

/// Parses `--seed`: any whole number in 0..=2^64-1 (a negative one is refused with the range).
fn seed(s: &str) -> Result<u64, String> {
    s.parse()
        .map_err(|_| format!("expected a whole number in [0, {}]", u64::MAX))
}

/// Loads a scenario with the command-line overrides laid over its text, so the file and the
/// flags are validated once, together; a value out of range is reported with the flag that set
/// it. `--seed` is set afterwards: every u64 is a valid seed, and TOML integers stop at 2^63.
pub fn load(path: &Path, o: &Overrides) -> Result<Scenario> {
    let mut given = Vec::new();
    if let Some(d) = o.duration_s {
        given.push(Override {
            flag: "--duration-s",
            path: "scenario.duration_s",
            value: toml::Value::Float(d),
        });
    }
    if let Some(r) = o.rate_hz {
        given.push(Override {
            flag: "--rate-hz",
            path: "run.rate_hz",
            value: toml::Value::Float(r),
        });
    }
    let mut sc = Scenario::load_with(path, &given)?;
    if let Some(s) = o.seed {
        sc.plant.seed = s;
    }
    Ok(sc)
}

/// Checks a positive, finite number given to `flag`.
pub fn positive(flag: &str, v: f64) -> Result<f64> {
    if !(v > 0.0 && v.is_finite()) {
        anyhow::bail!("{flag}: expected a finite number > 0, got {}", Num(v));
    }
    Ok(v)
}

/// Checks a whole number given to `flag` against `min..=max` (`what` says what it counts). The
/// flag is parsed signed so that a negative value reaches this check.
pub fn whole(flag: &str, v: i64, min: usize, max: usize, what: &str) -> Result<usize> {
    match usize::try_from(v) {
        Ok(n) if (min..=max).contains(&n) => Ok(n),
        _ if max == usize::MAX => {
            anyhow::bail!("{flag}: expected at least {min} {what}, got {v}")
        }
        _ => anyhow::bail!("{flag}: expected {what} in {min}..={max}, got {v}"),
    }
}

/// `--rerun` and its bucket length, shared by the commands that can record.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct RerunArgs {
    /// Record to Rerun: save:PATH.rrd, spawn (viewer on PATH), or connect[:URL|:HOST:PORT].
    /// Needs a build with `--features rerun`. docs/visualization.md.
    #[arg(long, value_name = "DEST")]
    pub rerun: Option<String>,
    /// Length of a Rerun bucket, s: each series gets one row (mean, and min/max for the IMU
    /// output and gimbal angles) per bucket. Default: the run split into 20,000 buckets.
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub rerun_bucket_s: Option<f64>,
}

impl RerunArgs {
    /// The destination, checked, or None when no recording was asked for.
    #[cfg(feature = "rerun")]
    pub fn target(&self) -> Result<Option<rins_rerun_sink::Target>> {
        if let Some(b) = self.rerun_bucket_s
            && !(b > 0.0 && b.is_finite())
        {
            anyhow::bail!(
                "--rerun-bucket-s: expected a finite number of seconds > 0, got {}",
                Num(b)
            );
        }
        Ok(self.rerun.as_deref().map(str::parse).transpose()?)
    }

    /// Refuses `--rerun` in a build without the feature.
    #[cfg(not(feature = "rerun"))]
    pub fn target(&self) -> Result<Option<std::convert::Infallible>> {
        if self.rerun.is_some() || self.rerun_bucket_s.is_some() {
            anyhow::bail!(
                "--rerun: this rins was built without Rerun support; rebuild with `cargo build --release --features rerun` (or `cargo install --path scenarios --features rerun`)"
            );
        }
        Ok(None)
    }

    /// The destination as given, for messages.
    pub fn dest(&self) -> &str {
        self.rerun.as_deref().unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_numbers_outside_the_range_name_flag_and_range() {
        assert_eq!(whole("--runs", 3, 1, usize::MAX, "seed").unwrap(), 3);
        let e = whole("--runs", -2, 1, usize::MAX, "seed").unwrap_err();
        assert_eq!(e.to_string(), "--runs: expected at least 1 seed, got -2");
        let e = whole("--batch", 65, 1, 64, "records per message").unwrap_err();
        assert_eq!(
            e.to_string(),
            "--batch: expected records per message in 1..=64, got 65"
        );
        assert!(seed("-5").unwrap_err().contains("18446744073709551615"));
    }
}
