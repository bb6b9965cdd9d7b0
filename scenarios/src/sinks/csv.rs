//! CSV output of the IMU stream. Columns and units: docs/scenario-format.md#output-columns.
//!
//! With decimation N, each row covers N output samples: increments are summed (so the sum of a
//! column over the file equals the sum over every sample), attitude and temperatures are taken
//! at the end of the row, effect contributions are the mean rate over the row. Numbers are
//! written in Rust's shortest round-trip form: reading them back gives the same bits.
//!
//! A moving carrier (`[carrier] kind = "ship"` or `"trajectory"`) adds its truth at the end of
//! each row, under the trajectory file's own column names (docs/carrier.md), so a run's carrier
//! columns with `t_s` form a trajectory file; the static carrier adds nothing (its output is
//! unchanged byte for byte).

use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use anyhow::{Context, Result};
use rins_plant::effects::{AccelTerm, GyroTerm};
use rins_plant::output_columns::{self, Entry, Group, OverRow, Read, Reading};
use rins_plant::{ImuSample, Truth};

use crate::runner::Sink;
use rins_scenario::file::OutputSpec;

/// Writes `imu.csv`.
pub struct CsvSink<W: Write> {
    out: W,
    opts: OutputSpec,
    /// The columns written, in order ([`rins_plant::output_columns`]).
    entries: Vec<Entry>,
    /// Where each entry's values start in `sums` and `values`.
    offsets: Vec<usize>,
    in_row: u64,
    /// The row's sums of the summed columns (increments, term errors), per element.
    sums: Vec<f64>,
    /// One sample's values (scratch).
    values: Vec<f64>,
    line: String,
    dt_s: f64,
    /// The mount between the truth's carrier attitude and the table, for q_b^n.
    mount: rins_plant::TruthMount,
    last: Option<(ImuSample, Truth)>,
    /// Run label written as a leading `run` column (measurement files with several runs).
    run: Option<String>,
}

/// The carrier truth columns of a moving carrier, in the trajectory file's names and units
/// (docs/carrier.md): reference point (WGS-84), ground velocity ENU, attitude q_c^n.
pub const CARRIER_COLUMNS: [&str; 10] = output_columns::CARRIER_NAMES;

/// The columns of a run with `opts`, the enabled terms and a moving carrier or not, in order.
fn entries(
    opts: &OutputSpec,
    gyro_terms: &[GyroTerm],
    accel_terms: &[AccelTerm],
    moving_carrier: bool,
) -> Vec<Entry> {
    let mut groups = vec![Group::Measured, Group::Setup];
    if opts.truth {
        groups.push(Group::Truth);
    }
    if opts.effects {
        groups.push(Group::Effects);
    }
    // A moving carrier's truth is written whatever the options: with `t_s` it forms a
    // trajectory file; the static carrier adds nothing.
    if moving_carrier {
        groups.push(Group::CarrierTruth);
    }
    output_columns::entries(&groups, gyro_terms, accel_terms, true)
}

/// Column names for the given options and enabled terms (the carrier truth columns of a moving
/// carrier are added by the sink, [`CARRIER_COLUMNS`]).
pub fn header(
    opts: &OutputSpec,
    gyro_terms: &[GyroTerm],
    accel_terms: &[AccelTerm],
) -> Vec<String> {
    entries(opts, gyro_terms, accel_terms, false)
        .iter()
        .flat_map(Entry::names)
        .collect()
}

pub use rins_plant::table::position_label;

impl CsvSink<BufWriter<File>> {
    /// Creates `path` for the scenario's enabled terms.
    pub fn create(
        path: &Path,
        opts: OutputSpec,
        plant_cfg: &rins_plant::PlantConfig,
    ) -> Result<Self> {
        let f = File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
        CsvSink::new(BufWriter::with_capacity(1 << 20, f), opts, plant_cfg)
    }
}

impl<W: Write> CsvSink<W> {
    /// Wraps a writer and writes the header.
    pub fn new(out: W, opts: OutputSpec, plant_cfg: &rins_plant::PlantConfig) -> Result<Self> {
        Self::for_run(out, opts, plant_cfg, None, true)
    }

    /// A sink whose rows start with a `run` label column (one file holding several runs, as the
    /// measurement format allows); `write_header` is false when appending a further run.
    pub fn for_run(
        mut out: W,
        opts: OutputSpec,
        plant_cfg: &rins_plant::PlantConfig,
        run: Option<&str>,
        write_header: bool,
    ) -> Result<Self> {
        let s = &plant_cfg.sensor;
        let gyro_terms: Vec<GyroTerm> = s.gyro.enabled_terms();
        let accel_terms: Vec<AccelTerm> = s.accel.enabled_terms();
        let entries = entries(
            &opts,
            &gyro_terms,
            &accel_terms,
            !plant_cfg.carrier.is_static(),
        );
        if write_header {
            let mut h: Vec<String> = entries.iter().flat_map(Entry::names).collect();
            if run.is_some() {
                h.insert(0, "run".into());
            }
            writeln!(out, "{}", h.join(","))?;
        }
        let offsets: Vec<usize> = entries
            .iter()
            .scan(0, |at, e| {
                let o = *at;
                *at += e.width();
                Some(o)
            })
            .collect();
        let width = entries.iter().map(Entry::width).sum();
        Ok(Self {
            out,
            opts,
            entries,
            offsets,
            in_row: 0,
            sums: vec![0.0; width],
            values: vec![0.0; width],
            line: String::with_capacity(1024),
            dt_s: 1.0 / plant_cfg.rate_hz,
            mount: rins_plant::TruthMount::of_config(plant_cfg),
            last: None,
            run: run.map(str::to_string),
        })
    }

    /// The underlying writer.
    pub fn into_inner(self) -> W {
        self.out
    }

    fn write_row(&mut self) -> Result<()> {
        let Some((s, tr)) = &self.last else {
            return Ok(());
        };
        let span_s = self.in_row as f64 * self.dt_s;
        let r = Reading {
            sample: s,
            truth: tr,
            mount: &self.mount,
        };
        let l = &mut self.line;
        l.clear();
        if let Some(run) = &self.run {
            write!(l, "{run},")?;
        }
        for (k, (e, &at)) in self.entries.iter().zip(&self.offsets).enumerate() {
            let sep = if k == 0 { "" } else { "," };
            let w = e.width();
            match e.column.read {
                Read::Index => write!(l, "{sep}{}", s.index)?,
                Read::Position => write!(l, "{sep}{}", output_columns::position_of(&r))?,
                _ => {
                    let v = &mut self.values[at..at + w];
                    match e.column.over_row {
                        // Attitude, angles and temperatures at the end of the row.
                        OverRow::Last => e.read(&r, v),
                        OverRow::Sum => v.copy_from_slice(&self.sums[at..at + w]),
                        OverRow::MeanRate { unit_si } => {
                            for (x, sum) in v.iter_mut().zip(&self.sums[at..at + w]) {
                                *x = sum / (span_s * unit_si);
                            }
                        }
                    }
                    for (i, x) in v.iter().enumerate() {
                        let sep = if i == 0 { sep } else { "," };
                        write!(l, "{sep}{x}")?;
                    }
                }
            }
        }
        l.push('\n');
        self.out.write_all(l.as_bytes())?;
        self.in_row = 0;
        self.sums.iter_mut().for_each(|x| *x = 0.0);
        Ok(())
    }
}

impl<W: Write> Sink for CsvSink<W> {
    fn sample(&mut self, s: &ImuSample, tr: &Truth) -> Result<()> {
        let r = Reading {
            sample: s,
            truth: tr,
            mount: &self.mount,
        };
        // Increments and term errors are summed over the row, element by element.
        for (e, &at) in self.entries.iter().zip(&self.offsets) {
            if e.column.over_row != OverRow::Last {
                let w = e.width();
                let v = &mut self.values[at..at + w];
                e.read(&r, v);
                for (acc, x) in self.sums[at..at + w].iter_mut().zip(v.iter()) {
                    *acc += x;
                }
            }
        }
        self.in_row += 1;
        self.last = Some((*s, *tr));
        if self.in_row >= self.opts.decimation {
            self.write_row()?;
        }
        Ok(())
    }

    fn finish(&mut self) -> Result<()> {
        // A final partial row is written too (its span is shorter): no sample is dropped.
        if self.in_row > 0 {
            self.write_row()?;
        }
        self.out.flush()?;
        Ok(())
    }
}
