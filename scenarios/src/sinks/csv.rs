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
use nalgebra::Vector3;
use rins_plant::effects::{AccelTerm, GyroTerm};
use rins_plant::thermal::node;
use rins_plant::units::{DPH, UG};
use rins_plant::{ImuSample, Truth};

use crate::file::OutputSpec;
use crate::runner::Sink;

/// Writes `imu.csv`.
pub struct CsvSink<W: Write> {
    out: W,
    opts: OutputSpec,
    gyro_terms: Vec<GyroTerm>,
    accel_terms: Vec<AccelTerm>,
    in_row: u64,
    dtheta: Vector3<f64>,
    dv: Vector3<f64>,
    dtheta_true: Vector3<f64>,
    dv_true: Vector3<f64>,
    gyro_sum: Vec<Vector3<f64>>,
    accel_sum: Vec<Vector3<f64>>,
    line: String,
    dt_s: f64,
    /// The mount between the truth's carrier attitude and the table, for q_b^n.
    mount: rins_plant::TruthMount,
    /// The carrier moves: write its truth columns.
    moving_carrier: bool,
    last: Option<(ImuSample, Truth)>,
    /// Run label written as a leading `run` column (measurement files with several runs).
    run: Option<String>,
}

const AXES: [&str; 3] = ["x", "y", "z"];

/// The carrier truth columns of a moving carrier, in the trajectory file's names and units
/// (docs/carrier.md): reference point (WGS-84), ground velocity ENU, attitude q_c^n.
pub const CARRIER_COLUMNS: [&str; 10] = [
    "lat_deg", "lon_deg", "height_m", "v_e_mps", "v_n_mps", "v_u_mps", "q_cn_w", "q_cn_x",
    "q_cn_y", "q_cn_z",
];

/// Column names for the given options and enabled terms (the carrier truth columns of a moving
/// carrier are added by the sink, [`CARRIER_COLUMNS`]).
pub fn header(
    opts: &OutputSpec,
    gyro_terms: &[GyroTerm],
    accel_terms: &[AccelTerm],
) -> Vec<String> {
    let mut h: Vec<String> = vec!["sample".into(), "t_s".into()];
    h.extend(AXES.iter().map(|a| format!("dtheta_{a}_rad")));
    h.extend(AXES.iter().map(|a| format!("dv_{a}_mps")));
    h.extend(["outer_deg", "inner_deg", "position"].map(String::from));
    h.extend(node::NAMES.iter().map(|n| format!("temp_{n}_c")));
    h.push("temp_chamber_c".into());
    if opts.truth {
        h.extend(AXES.iter().map(|a| format!("dtheta_true_{a}_rad")));
        h.extend(AXES.iter().map(|a| format!("dv_true_{a}_mps")));
        h.extend(["q_bn_w", "q_bn_x", "q_bn_y", "q_bn_z"].map(String::from));
    }
    if opts.effects {
        for t in gyro_terms {
            h.extend(AXES.iter().map(|a| format!("gyro_{}_{a}_dph", t.key())));
        }
        for t in accel_terms {
            h.extend(AXES.iter().map(|a| format!("accel_{}_{a}_ug", t.key())));
        }
    }
    h
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
        let moving_carrier = !plant_cfg.carrier.is_static();
        if write_header {
            let mut h = header(&opts, &gyro_terms, &accel_terms);
            if run.is_some() {
                h.insert(0, "run".into());
            }
            if moving_carrier {
                h.extend(CARRIER_COLUMNS.map(String::from));
            }
            writeln!(out, "{}", h.join(","))?;
        }
        Ok(Self {
            out,
            opts,
            gyro_sum: vec![Vector3::zeros(); gyro_terms.len()],
            accel_sum: vec![Vector3::zeros(); accel_terms.len()],
            gyro_terms,
            accel_terms,
            in_row: 0,
            dtheta: Vector3::zeros(),
            dv: Vector3::zeros(),
            dtheta_true: Vector3::zeros(),
            dv_true: Vector3::zeros(),
            line: String::with_capacity(1024),
            dt_s: 1.0 / plant_cfg.rate_hz,
            mount: rins_plant::TruthMount::of_config(plant_cfg),
            moving_carrier,
            last: None,
            run: run.map(str::to_string),
        })
    }

    /// The underlying writer.
    pub fn into_inner(self) -> W {
        self.out
    }

    fn write_row(&mut self) -> Result<()> {
        let Some((s, tr)) = self.last else {
            return Ok(());
        };
        let span_s = self.in_row as f64 * self.dt_s;
        let l = &mut self.line;
        l.clear();
        let g = &tr.gimbal;
        let label = position_label(g.angles.outer_rad, g.angles.inner_rad, g.moving);
        if let Some(r) = &self.run {
            write!(l, "{r},")?;
        }
        write!(l, "{},{}", s.index, s.t_s)?;
        for v in [&self.dtheta, &self.dv] {
            write!(l, ",{},{},{}", v.x, v.y, v.z)?;
        }
        // Angles and temperatures as the unit reports them (encoders, temperature sensors); the
        // position label and the chamber temperature describe the test set-up.
        write!(
            l,
            ",{},{},{}",
            s.encoder.outer_rad.to_degrees(),
            s.encoder.inner_rad.to_degrees(),
            label
        )?;
        for t in s.temps_c {
            write!(l, ",{t}")?;
        }
        write!(l, ",{}", tr.temps.chamber_c)?;
        if self.opts.truth {
            for v in [&self.dtheta_true, &self.dv_true] {
                write!(l, ",{},{},{}", v.x, v.y, v.z)?;
            }
            // q_b^n = q_c^n·q_v^c·q_z(outer)·q_x(inner) in closed form, the plant's own
            // composition (docs/carrier.md, Frames).
            let q = self.mount.q_bn_of(&tr);
            write!(l, ",{},{},{},{}", q.w, q.i, q.j, q.k)?;
        }
        if self.opts.effects {
            for v in &self.gyro_sum {
                let r = v / (span_s * DPH);
                write!(l, ",{},{},{}", r.x, r.y, r.z)?;
            }
            for v in &self.accel_sum {
                let r = v / (span_s * UG);
                write!(l, ",{},{},{}", r.x, r.y, r.z)?;
            }
        }
        if self.moving_carrier {
            let c = &tr.carrier;
            let q = c.q_cn.quaternion();
            write!(
                l,
                ",{},{},{},{},{},{},{},{},{},{}",
                c.lat_rad.to_degrees(),
                c.lon_rad.to_degrees(),
                c.height_m,
                c.v_n.x,
                c.v_n.y,
                c.v_n.z,
                q.w,
                q.i,
                q.j,
                q.k
            )?;
        }
        l.push('\n');
        self.out.write_all(l.as_bytes())?;
        self.in_row = 0;
        self.dtheta = Vector3::zeros();
        self.dv = Vector3::zeros();
        self.dtheta_true = Vector3::zeros();
        self.dv_true = Vector3::zeros();
        self.gyro_sum.iter_mut().for_each(|v| *v = Vector3::zeros());
        self.accel_sum
            .iter_mut()
            .for_each(|v| *v = Vector3::zeros());
        Ok(())
    }
}

impl<W: Write> Sink for CsvSink<W> {
    fn sample(&mut self, s: &ImuSample, tr: &Truth) -> Result<()> {
        self.dtheta += s.dtheta_rad;
        self.dv += s.dv_mps;
        if self.opts.truth {
            self.dtheta_true += tr.dtheta_true_rad;
            self.dv_true += tr.dv_true_mps;
        }
        if self.opts.effects {
            for (acc, t) in self.gyro_sum.iter_mut().zip(&self.gyro_terms) {
                *acc += tr.gyro_terms_rad[*t as usize];
            }
            for (acc, t) in self.accel_sum.iter_mut().zip(&self.accel_terms) {
                *acc += tr.accel_terms_mps[*t as usize];
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
