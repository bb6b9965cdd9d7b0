//! The per-seed table of a sweep, one row per point × seed × navigator, as CSV and as Parquet:
//! the point's index and swept values, the seed, the navigator and the end figures a run returns
//! (`lat_nm`, `lon_nm`, `horizontal_nm`, `trms_nm`, `up_att_mean_deg`). The CSV writes every
//! number with Rust's shortest round-trip form, so it reads back bit for bit.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use rins_mvm::measurement::{LabelColumn, Measurement};

use super::outputs::PER_SEED;
use super::result::{NAVIGATORS, SweepReport, value_text};

/// The value of an end figure by its [`PER_SEED`] name.
fn figure(f: &rins_verification::paper::EndFigures, name: &str) -> f64 {
    match name {
        "lat_nm" => f.lat_nm,
        "lon_nm" => f.lon_nm,
        "horizontal_nm" => f.horizontal_nm,
        "trms_nm" => f.trms_nm,
        _ => f.up_att_mean_deg,
    }
}

/// Rows of the table (point × seed × navigator).
pub fn rows(r: &SweepReport) -> usize {
    r.points.len() * r.seeds.len() * NAVIGATORS.len()
}

/// The CSV text: a header, then one row per point × seed × navigator.
pub fn csv(r: &SweepReport) -> String {
    let mut s = String::from("point");
    for p in &r.parameters {
        let _ = write!(s, ",{}", p.key);
    }
    s.push_str(",seed,navigator");
    for f in PER_SEED {
        let _ = write!(s, ",{f}");
    }
    s.push('\n');
    for (k, point) in r.points.iter().enumerate() {
        for seed in &point.per_seed {
            for (n, nav) in NAVIGATORS.iter().enumerate() {
                let _ = write!(s, "{k}");
                for v in &point.values {
                    let _ = write!(s, ",{}", value_text(v));
                }
                let _ = write!(s, ",{},{nav}", seed.seed);
                for f in PER_SEED {
                    let _ = write!(s, ",{}", figure(seed.figures(n), f));
                }
                s.push('\n');
            }
        }
    }
    s
}

/// Writes the CSV to `path`.
pub fn write_csv(r: &SweepReport, path: &Path) -> Result<()> {
    std::fs::write(path, csv(r)).with_context(|| format!("cannot write {}", path.display()))
}

/// The same table as Parquet (Snappy pages, through the measurement writer of rins-mvm): the
/// numeric columns as DOUBLE (`point`, `seed`, numeric swept keys, the figures), the navigator
/// and swept names or switches as UTF-8 strings. Columns are in name order, text columns first.
pub fn write_parquet(r: &SweepReport, path: &Path) -> Result<()> {
    let mut m = Measurement {
        rows: rows(r),
        ..Measurement::default()
    };
    let mut numeric: Vec<(String, Vec<f64>)> = vec![("point".into(), Vec::new())];
    let mut text: Vec<(String, LabelColumn)> = vec![("navigator".into(), LabelColumn::default())];
    // A swept key is a number column when every value is a number.
    let is_number: Vec<bool> = r
        .parameters
        .iter()
        .map(|p| p.values.iter().all(serde_json::Value::is_number))
        .collect();
    for (p, &num) in r.parameters.iter().zip(&is_number) {
        if num {
            numeric.push((p.key.clone(), Vec::new()));
        } else {
            text.push((p.key.clone(), LabelColumn::default()));
        }
    }
    numeric.push(("seed".into(), Vec::new()));
    for f in PER_SEED {
        numeric.push((f.into(), Vec::new()));
    }
    let push_label = |c: &mut LabelColumn, s: &str| {
        let k = c.names.iter().position(|n| n == s).unwrap_or_else(|| {
            c.names.push(s.to_string());
            c.names.len() - 1
        });
        c.index.push(k as u32);
    };
    for (k, point) in r.points.iter().enumerate() {
        for seed in &point.per_seed {
            for (n, nav) in NAVIGATORS.iter().enumerate() {
                let (mut ni, mut ti) = (0, 0);
                numeric[ni].1.push(k as f64);
                ni += 1;
                push_label(&mut text[ti].1, nav);
                ti += 1;
                for (v, &num) in point.values.iter().zip(&is_number) {
                    if num {
                        numeric[ni].1.push(v.as_f64().unwrap_or(f64::NAN));
                        ni += 1;
                    } else {
                        push_label(&mut text[ti].1, &value_text(v));
                        ti += 1;
                    }
                }
                // Seeds above 2^53 lose digits as DOUBLE; the CSV keeps them whole.
                numeric[ni].1.push(seed.seed as f64);
                ni += 1;
                for f in PER_SEED {
                    numeric[ni].1.push(figure(seed.figures(n), f));
                    ni += 1;
                }
            }
        }
    }
    m.columns = numeric.into_iter().collect();
    m.labels = text.into_iter().collect();
    rins_mvm::parquet::write(path, &m).map_err(anyhow::Error::msg)
}
