//! Static figures of a plant run (`rins run --figures`): what the Rerun recording shows, for a
//! reader without the viewer. Each line is the mean per bucket of at most [`POINTS`] buckets.

use std::path::{Path, PathBuf};

use anyhow::Result;
use nalgebra::Vector3;
use rins_plant::effects::{AccelTerm, GyroTerm};
use rins_plant::thermal::node;
use rins_plant::units::{DPH, UG};
use rins_plant::{ImuSample, PlantConfig, Truth};

use crate::runner::Sink;
use rins_report::figures::plot::{Kind, Line, PALETTE, Panel, write_figure};

/// Buckets per figure line.
pub const POINTS: u64 = 2000;

/// One bucket's means.
#[derive(Clone, Debug, Default)]
struct Row {
    t_s: f64,
    rate_dph: Vector3<f64>,
    accel_mps2: Vector3<f64>,
    outer_deg: f64,
    inner_deg: f64,
    temps_c: Vec<f64>,
    gyro_dph: Vec<Vector3<f64>>,
    accel_ug: Vec<Vector3<f64>>,
}

/// Collects a run into bucket means and draws it.
pub struct RunFigures {
    bucket: u64,
    n: u64,
    dt_s: f64,
    dtheta: Vector3<f64>,
    dv: Vector3<f64>,
    temps: [f64; node::COUNT + 1],
    gyro_on: Vec<GyroTerm>,
    accel_on: Vec<AccelTerm>,
    gyro: Vec<Vector3<f64>>,
    accel: Vec<Vector3<f64>>,
    last: Option<Truth>,
    last_t: f64,
    rows: Vec<Row>,
}

impl RunFigures {
    /// For a run of `samples` output samples of `cfg`.
    pub fn new(cfg: &PlantConfig, samples: u64) -> Self {
        let s = &cfg.sensor;
        let gyro_on: Vec<GyroTerm> = s.gyro.enabled_terms();
        let accel_on: Vec<AccelTerm> = s.accel.enabled_terms();
        Self {
            bucket: samples.div_ceil(POINTS).max(1),
            n: 0,
            dt_s: 1.0 / cfg.rate_hz,
            dtheta: Vector3::zeros(),
            dv: Vector3::zeros(),
            temps: [0.0; node::COUNT + 1],
            gyro: vec![Vector3::zeros(); gyro_on.len()],
            accel: vec![Vector3::zeros(); accel_on.len()],
            gyro_on,
            accel_on,
            last: None,
            last_t: 0.0,
            rows: Vec::new(),
        }
    }

    fn close_bucket(&mut self) {
        let Some(tr) = self.last else { return };
        let span = self.n as f64 * self.dt_s;
        let k = self.n as f64;
        self.rows.push(Row {
            t_s: self.last_t,
            rate_dph: self.dtheta / (span * DPH),
            accel_mps2: self.dv / span,
            outer_deg: tr.gimbal.angles.outer_rad.to_degrees(),
            inner_deg: tr.gimbal.angles.inner_rad.to_degrees(),
            temps_c: self.temps.iter().map(|t| t / k).collect(),
            gyro_dph: self.gyro.iter().map(|v| v / (span * DPH)).collect(),
            accel_ug: self.accel.iter().map(|v| v / (span * UG)).collect(),
        });
        self.n = 0;
        self.dtheta = Vector3::zeros();
        self.dv = Vector3::zeros();
        self.temps = [0.0; node::COUNT + 1];
        self.gyro
            .iter_mut()
            .chain(self.accel.iter_mut())
            .for_each(|v| *v = Vector3::zeros());
    }

    /// Draws `run_imu`, `run_table_thermal` and `run_effects` (SVG and PNG) into `dir`.
    pub fn write(mut self, dir: &Path, name: &str) -> Result<Vec<PathBuf>> {
        if self.n > 0 {
            self.close_bucket();
        }
        let rows = &self.rows;
        let hours = rows.last().is_some_and(|r| r.t_s > 3.0 * 3600.0);
        let (x_label, xs) = if hours {
            ("time (h)", 1.0 / 3600.0)
        } else {
            ("time (s)", 1.0)
        };
        let pts = |f: &dyn Fn(&Row) -> f64| -> Vec<(f64, f64)> {
            rows.iter().map(|r| (r.t_s * xs, f(r))).collect()
        };
        let line = |label: &'static str, i: usize, f: &dyn Fn(&Row) -> f64| {
            Line::new(label, pts(f), PALETTE[i % PALETTE.len()], Kind::Solid)
        };
        let mut files = Vec::new();
        let axes = ["x", "y", "z"];
        let mut imu = Vec::new();
        for (i, a) in axes.iter().enumerate() {
            imu.push(Panel::new(
                format!("gyro {a}: mean rate per bucket (Earth rate + table rate + errors)"),
                "rate (deg/h)",
                vec![line("", i, &|r| r.rate_dph[i])],
            ));
        }
        for (i, a) in axes.iter().enumerate() {
            imu.push(Panel::new(
                format!("accelerometer {a}: mean specific force per bucket"),
                "specific force (m/s^2)",
                vec![line("", i, &|r| r.accel_mps2[i])],
            ));
        }
        files.extend(write_figure(
            &dir.join("run_imu.svg"),
            &format!("{name}: IMU output"),
            x_label,
            &imu,
        )?);
        let mut temps: Vec<Line> = node::NAMES
            .iter()
            .enumerate()
            .map(|(k, n)| line(n, k, &move |r: &Row| r.temps_c[k]))
            .collect();
        temps.push(line("chamber", node::COUNT, &|r| r.temps_c[node::COUNT]));
        let table = vec![
            Panel::new(
                "gimbal angles at the end of each bucket",
                "angle (deg)",
                vec![
                    line("outer", 0, &|r| r.outer_deg),
                    line("inner", 1, &|r| r.inner_deg),
                ],
            ),
            Panel::new("temperatures (bucket mean)", "temperature (deg C)", temps),
        ];
        files.extend(write_figure(
            &dir.join("run_table_thermal.svg"),
            &format!("{name}: table and temperatures"),
            x_label,
            &table,
        )?);
        let mut effects = Vec::new();
        for (i, a) in axes.iter().enumerate() {
            let lines = self
                .gyro_on
                .iter()
                .enumerate()
                .map(|(k, t)| line(t.key(), k, &move |r: &Row| r.gyro_dph[k][i]))
                .collect();
            effects.push(Panel::new(
                format!("gyro {a}: contribution of each enabled effect"),
                "contribution (deg/h)",
                lines,
            ));
        }
        for (i, a) in axes.iter().enumerate() {
            let lines = self
                .accel_on
                .iter()
                .enumerate()
                .map(|(k, t)| line(t.key(), k, &move |r: &Row| r.accel_ug[k][i]))
                .collect();
            effects.push(Panel::new(
                format!("accelerometer {a}: contribution of each enabled effect"),
                "contribution (ug)",
                lines,
            ));
        }
        files.extend(write_figure(
            &dir.join("run_effects.svg"),
            &format!("{name}: sensor error contributions (bucket mean)"),
            x_label,
            &effects,
        )?);
        Ok(files)
    }

    /// The bucket means so far: (time s, mean gyro rate deg/h) — for tests.
    pub fn rates_dph(&self) -> Vec<(f64, [f64; 3])> {
        self.rows
            .iter()
            .map(|r| (r.t_s, r.rate_dph.into()))
            .collect()
    }
}

impl Sink for RunFigures {
    fn sample(&mut self, s: &ImuSample, tr: &Truth) -> Result<()> {
        self.dtheta += s.dtheta_rad;
        self.dv += s.dv_mps;
        for (acc, t) in self
            .temps
            .iter_mut()
            .zip(tr.temps.nodes_c.iter().chain([&tr.temps.chamber_c]))
        {
            *acc += t;
        }
        for (acc, t) in self.gyro.iter_mut().zip(&self.gyro_on) {
            *acc += tr.gyro_terms_rad[*t as usize];
        }
        for (acc, t) in self.accel.iter_mut().zip(&self.accel_on) {
            *acc += tr.accel_terms_mps[*t as usize];
        }
        self.n += 1;
        self.last = Some(*tr);
        self.last_t = s.t_s;
        if self.n >= self.bucket {
            self.close_bucket();
        }
        Ok(())
    }
}
