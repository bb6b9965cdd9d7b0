//! The plant's stream as a recording: every output sample goes in, one row per bucket comes out.

use anyhow::Result;
use nalgebra::{Matrix3, Vector3};
use rerun::{RecordingStream, TextLog};
use rins_experiments::{NavRecord, Tracker};
use rins_plant::carrier::CarrierTruth;
use rins_plant::effects::accel::ACCEL_TERMS;
use rins_plant::effects::gyro::GYRO_TERMS;
use rins_plant::effects::{AccelTerm, GyroTerm};
use rins_plant::output_columns::column;
use rins_plant::table::position_label;
use rins_plant::thermal::node;
use rins_plant::units::{DPH, UG};
use rins_plant::{ImuSample, PlantConfig, Truth};

use crate::bucket::MinMaxMean;
use crate::carrier::CarrierColumns;
use crate::nav::NavSeries;
use crate::scene;
use crate::series::{Series, nanos};

const AXES: [&str; 3] = ["x", "y", "z"];

/// What the end of a bucket needs of its last sample (a whole [`Truth`] is ~700 bytes).
#[derive(Clone, Copy, Debug)]
struct Last {
    index: u64,
    t_s: f64,
    outer_rad: f64,
    inner_rad: f64,
    /// The carrier, when it moves.
    carrier: Option<CarrierTruth>,
}
/// The output columns ([`rins_plant::output_columns`]) shown as min/max/mean envelopes per axis.
const ENV_INCREMENTS: [&str; 2] = ["dtheta_rad", "dv_mps"];
const XYZ: [[u8; 3]; 3] = [[220, 50, 50], [50, 160, 50], [50, 90, 230]];
const ENVELOPE: [[u8; 3]; 3] = [[30, 30, 30], [150, 150, 150], [150, 150, 150]];
/// Channels of the min/max/mean block: Δθ xyz, Δv xyz, outer, inner.
const ENV_CHANNELS: usize = 8;
/// Samples per bucket over which temperatures and effect contributions are averaged.
pub const SLOW_SAMPLES: u64 = 64;
/// Temperature channels: the six nodes and the chamber.
const TEMPS: usize = node::COUNT + 1;

/// Entity root of the IMU output series.
pub const IMU: &str = "imu";

/// Options of a run recording.
#[derive(Clone, Copy, Debug)]
pub struct RunOptions {
    /// Output samples per logged row.
    pub bucket_samples: u64,
    /// Run the reference navigator (aligned to the truth) alongside and log its errors.
    pub navigate: bool,
}

/// Logs a plant run: the 3D table (on a moving carrier: the carrier's attitude, and its track
/// in a view of its own), the dwell label, Δθ/Δv, gimbal angles, temperatures and each
/// enabled effect's contribution, and (optionally) the reference navigator's errors.
///
/// Per-sample work is a few additions and comparisons; rows go out in column chunks.
pub struct RunRecorder {
    rec: RecordingStream,
    bucket: u64,
    in_bucket: u64,
    /// Samples between reads of the temperatures and effects, and the countdown to the next.
    slow_stride: u64,
    slow_countdown: u64,
    /// Reads in the current bucket.
    slow_n: u64,
    env: MinMaxMean<ENV_CHANNELS>,
    temps: [f64; TEMPS],
    gyro: [Vector3<f64>; GYRO_TERMS],
    accel: [Vector3<f64>; ACCEL_TERMS],
    gyro_on: Vec<GyroTerm>,
    accel_on: Vec<AccelTerm>,
    env_series: Vec<Series>,
    temp_series: Series,
    gyro_series: Vec<Series>,
    accel_series: Vec<Series>,
    label: &'static str,
    /// (moving, outer, inner) the label was computed for: recomputed only when these change.
    label_key: (bool, f64, f64),
    dwell_log: u64,
    last: Option<Last>,
    poses: scene::PoseColumns,
    /// A moving carrier's poses and track.
    carrier: Option<CarrierColumns>,
    tracker: Option<(Tracker, NavSeries)>,
    nav_at_last: bool,
    /// The last truth, kept only when navigating (the final record needs it).
    last_truth: Option<Truth>,
    dt_s: f64,
}

impl RunRecorder {
    /// Declares the entities for `cfg`'s enabled effects and logs the static scene.
    pub fn new(
        rec: &RecordingStream,
        cfg: &PlantConfig,
        c_vn: &Matrix3<f64>,
        opts: RunOptions,
        tracker: Option<Tracker>,
    ) -> Result<Self> {
        let bucket = opts.bucket_samples.max(1);
        let dt_s = 1.0 / cfg.rate_hz;
        let span = format!("{} s", fmt_s(bucket as f64 * dt_s));
        let stride = (bucket / SLOW_SAMPLES).max(1);
        let slow = if stride == 1 {
            format!("mean over {span} bucket")
        } else {
            format!("mean over {span} bucket, one sample in {stride}")
        };
        let env_names = |unit: &str| -> Vec<String> {
            vec![
                format!("mean per sample over {span} bucket, {unit}"),
                format!("min in bucket, {unit}"),
                format!("max in bucket, {unit}"),
            ]
        };
        let mut env_series = Vec::new();
        // The increments' entity names and units are the output table's.
        for c in ENV_INCREMENTS.map(|k| column(k).expect("an output column")) {
            let (q, unit) = (c.key, c.unit);
            for a in AXES {
                env_series.push(Series::new(
                    rec,
                    format!("{IMU}/{q}/{a}"),
                    &env_names(unit),
                    &ENVELOPE,
                )?);
            }
        }
        env_series.push(Series::new(
            rec,
            "gimbal/outer_deg",
            &env_names("deg"),
            &ENVELOPE,
        )?);
        env_series.push(Series::new(
            rec,
            "gimbal/inner_deg",
            &env_names("deg"),
            &ENVELOPE,
        )?);
        let mut tnames: Vec<String> = node::NAMES
            .iter()
            .map(|n| format!("{n} ({slow}), °C"))
            .collect();
        tnames.push(format!("chamber ({slow}), °C"));
        let temp_series = Series::new(rec, "thermal/temps_c", &tnames, &[])?;
        let s = &cfg.sensor;
        let gyro_on: Vec<GyroTerm> = s.gyro.enabled_terms();
        let accel_on: Vec<AccelTerm> = s.accel.enabled_terms();
        let xyz = |unit: &str| -> Vec<String> {
            AXES.iter()
                .map(|a| format!("{a} ({slow}), {unit}"))
                .collect()
        };
        let gyro_series = gyro_on
            .iter()
            .map(|t| {
                Series::new(
                    rec,
                    format!("effects/gyro/{}_dph", t.key()),
                    &xyz("deg/h"),
                    &XYZ,
                )
            })
            .collect::<Result<_>>()?;
        let accel_series = accel_on
            .iter()
            .map(|t| {
                Series::new(
                    rec,
                    format!("effects/accel/{}_ug", t.key()),
                    &xyz("µg"),
                    &XYZ,
                )
            })
            .collect::<Result<_>>()?;
        let carrier = if cfg.carrier.is_static() {
            scene::log_static(rec, Some(c_vn))?;
            None
        } else {
            scene::log_static(rec, None)?;
            crate::carrier::log_static(rec)?;
            Some(CarrierColumns::new(&cfg.vehicle.c_vn()))
        };
        let tracker = match tracker {
            Some(t) if opts.navigate => Some((
                t,
                NavSeries::new(rec, "reference", "instantaneous at each record")?,
            )),
            _ => None,
        };
        Ok(Self {
            rec: rec.clone(),
            bucket,
            in_bucket: 0,
            slow_stride: stride,
            slow_countdown: 0,
            slow_n: 0,
            env: MinMaxMean::default(),
            temps: [0.0; TEMPS],
            gyro: [Vector3::zeros(); GYRO_TERMS],
            accel: [Vector3::zeros(); ACCEL_TERMS],
            gyro_on,
            accel_on,
            env_series,
            temp_series,
            gyro_series,
            accel_series,
            label: "",
            label_key: (false, f64::NAN, f64::NAN),
            dwell_log: 0,
            last: None,
            poses: scene::PoseColumns::default(),
            carrier,
            tracker,
            nav_at_last: false,
            last_truth: None,
            dt_s,
        })
    }

    /// Takes one output sample and the plant's truth over it.
    #[inline]
    pub fn sample(&mut self, s: &ImuSample, tr: &Truth) -> Result<()> {
        let g = &tr.gimbal;
        let (d, v) = (&s.dtheta_rad, &s.dv_mps);
        self.env.push(&[
            d.x,
            d.y,
            d.z,
            v.x,
            v.y,
            v.z,
            // The series show what the unit reports (encoders, temperature sensors); the 3D
            // scene and the dwell label show the true table.
            s.encoder.outer_rad.to_degrees(),
            s.encoder.inner_rad.to_degrees(),
        ]);
        // Temperatures and effect contributions are averaged over evenly spaced samples of the
        // bucket (every sample when the bucket has at most SLOW_SAMPLES): reading the ~60
        // values of the truth every sample would cost a third of the plant's own time, and these
        // series vary slowly (temperatures; effects within a dwell) or are noise whose bucket
        // mean is what the plot shows anyway.
        if self.slow_countdown == 0 {
            self.slow_countdown = self.slow_stride;
            self.slow_n += 1;
            for (acc, t) in self
                .temps
                .iter_mut()
                .zip(s.temps_c.iter().chain([&tr.temps.chamber_c]))
            {
                *acc += t;
            }
            for (a, e) in self.gyro.iter_mut().zip(&tr.gyro_terms_rad) {
                *a += e;
            }
            for (a, e) in self.accel.iter_mut().zip(&tr.accel_terms_mps) {
                *a += e;
            }
        }
        self.slow_countdown -= 1;
        self.in_bucket += 1;
        let (outer, inner) = (g.angles.outer_rad, g.angles.inner_rad);
        self.last = Some(Last {
            index: s.index,
            t_s: s.t_s,
            outer_rad: outer,
            inner_rad: inner,
            carrier: self.carrier.as_ref().map(|_| tr.carrier),
        });
        // The label changes only when the table starts or stops moving; dwells hold the angles.
        let key = (g.moving, outer, inner);
        if key.0 != self.label_key.0
            || (!key.0 && (key.1 != self.label_key.1 || key.2 != self.label_key.2))
        {
            self.label_key = key;
            let label = position_label(outer, inner, g.moving);
            if label != self.label {
                self.dwell_changed(s, tr, label)?;
            }
        }
        if let Some((t, series)) = &mut self.tracker {
            self.last_truth = Some(*tr);
            let r = t.push(s, || *tr);
            self.nav_at_last = r.is_some();
            if let Some(r) = r {
                series.push(&self.rec, s.index, &r)?;
            }
        }
        if self.in_bucket >= self.bucket {
            self.write_row()?;
        }
        Ok(())
    }

    /// A new dwell (or the start of a move): the label, the pose and a log line, at this sample.
    fn dwell_changed(&mut self, s: &ImuSample, tr: &Truth, label: &'static str) -> Result<()> {
        self.label = label;
        self.dwell_log += 1;
        self.set_time(s);
        let text = scene::dwell_label(label, tr.gimbal.angles.inner_rad);
        scene::log_imu_label(&self.rec, &text)?;
        scene::log_gimbal(
            &self.rec,
            tr.gimbal.angles.outer_rad,
            tr.gimbal.angles.inner_rad,
        )?;
        self.rec.log(
            "status/position",
            &TextLog::new(format!(
                "{text} at t = {:.2} s (outer {:.1}°, inner {:.1}°)",
                s.t_s,
                tr.gimbal.angles.outer_rad.to_degrees(),
                tr.gimbal.angles.inner_rad.to_degrees()
            )),
        )?;
        Ok(())
    }

    fn set_time(&self, s: &ImuSample) {
        self.rec
            .set_time_sequence(crate::series::STEP, s.index as i64);
        self.rec.set_time(
            crate::series::SIM_TIME,
            std::time::Duration::from_nanos(nanos(s.t_s).max(0) as u64),
        );
    }

    fn write_row(&mut self) -> Result<()> {
        let Some(last) = self.last else {
            return Ok(());
        };
        let n = self.in_bucket;
        let (step, t_ns) = (last.index, nanos(last.t_s));
        for (i, series) in self.env_series.iter_mut().enumerate() {
            series.push(&self.rec, step, t_ns, &self.env.take(i, n))?;
        }
        let m = self.slow_n.max(1) as f64;
        let temps: Vec<f64> = self.temps.iter().map(|t| t / m).collect();
        self.temp_series.push(&self.rec, step, t_ns, &temps)?;
        self.temps = [0.0; TEMPS];
        let span_s = m * self.dt_s;
        for (series, t) in self.gyro_series.iter_mut().zip(&self.gyro_on) {
            let r = self.gyro[*t as usize] / (span_s * DPH);
            series.push(&self.rec, step, t_ns, &[r.x, r.y, r.z])?;
        }
        for (series, t) in self.accel_series.iter_mut().zip(&self.accel_on) {
            let r = self.accel[*t as usize] / (span_s * UG);
            series.push(&self.rec, step, t_ns, &[r.x, r.y, r.z])?;
        }
        self.gyro = [Vector3::zeros(); GYRO_TERMS];
        self.accel = [Vector3::zeros(); ACCEL_TERMS];
        // The pose at the end of each bucket, so the 3D view follows the moves too.
        self.poses
            .push(&self.rec, step, t_ns, last.outer_rad, last.inner_rad)?;
        if let (Some(c), Some(truth)) = (&mut self.carrier, &last.carrier) {
            c.push(&self.rec, step, t_ns, truth)?;
        }
        self.in_bucket = 0;
        self.slow_n = 0;
        self.slow_countdown = 0;
        Ok(())
    }

    /// Writes the last partial bucket (no sample is dropped) and sends every buffered row.
    pub fn finish(&mut self) -> Result<()> {
        if self.in_bucket > 0 {
            self.write_row()?;
        }
        if let Some((t, series)) = &mut self.tracker {
            // The end of the run gets a record unless the last sample produced one.
            if let Some((last, tr)) = self
                .last
                .zip(self.last_truth.as_ref())
                .filter(|_| !self.nav_at_last)
            {
                let r: NavRecord = t.record(tr);
                series.push(&self.rec, last.index, &r)?;
            }
            series.flush(&self.rec)?;
        }
        self.poses.flush(&self.rec)?;
        if let Some(c) = &mut self.carrier {
            c.flush(&self.rec)?;
        }
        for s in self
            .env_series
            .iter_mut()
            .chain([&mut self.temp_series])
            .chain(self.gyro_series.iter_mut())
            .chain(self.accel_series.iter_mut())
        {
            s.flush(&self.rec)?;
        }
        Ok(())
    }

    /// Rows per series so far.
    pub fn rows(&self) -> u64 {
        self.temp_series.rows()
    }

    /// Dwell changes logged so far.
    pub fn dwell_changes(&self) -> u64 {
        self.dwell_log
    }

    /// Whether the carrier moves (its attitude and track are logged; the blueprint's
    /// [`crate::Layout::track`]).
    pub fn moving_carrier(&self) -> bool {
        self.carrier.is_some()
    }

    /// Whether navigation errors are logged.
    pub fn navigates(&self) -> bool {
        self.tracker.is_some()
    }

    /// The entity paths of the effect series (for the blueprint and the docs).
    pub fn effect_paths(&self) -> Vec<String> {
        self.gyro_series
            .iter()
            .chain(&self.accel_series)
            .map(|s| s.path().to_string())
            .collect()
    }
}

/// Seconds without trailing zeros.
fn fmt_s(s: f64) -> String {
    let t = format!("{s:.3}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use rins_plant::output_columns::{COLUMNS, Group};

    /// Where the recording shows each measured and set-up column of the output table: a
    /// quantity added to the table fails here until the recording shows it (or says why not).
    #[test]
    fn the_recording_shows_every_measured_column_of_the_table() {
        for c in COLUMNS
            .iter()
            .filter(|c| matches!(c.group, Group::Measured | Group::Setup))
        {
            let shown = match c.key {
                // The timeline and the dwell label.
                "sample" | "t_s" | "position" => "timeline / text log",
                k if super::ENV_INCREMENTS.contains(&k) => "imu/<key>/<axis> envelopes",
                "outer_deg" | "inner_deg" => "gimbal/<key> envelopes",
                "temps_c" | "temp_chamber_c" => "thermal/temps_c",
                k => panic!("the output column {k} is not in the recording: add its series"),
            };
            assert!(!shown.is_empty());
        }
    }
}
