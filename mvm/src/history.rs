//! A measured history in SI units: what the model is replayed on, built from a parsed
//! measurement file.

use std::ops::Range;

use rins_plant::PlantConfig;
use rins_plant::carrier::CarrierKind;

use crate::measurement::{Measurement, MeasurementError};

/// IMU attitude over the history.
#[derive(Clone, Debug, PartialEq)]
pub enum Attitude {
    /// Gimbal angles at the end of each row, rad (C_b^n = C_v^n R_z(outer) R_x(inner)).
    Gimbal {
        /// Outer (azimuth) angle.
        outer_rad: Vec<f64>,
        /// Inner angle.
        inner_rad: Vec<f64>,
    },
    /// Body-to-ENU quaternion (w, x, y, z) at the end of each row.
    Quaternion(Vec<[f64; 4]>),
}

/// Measured rows (row k covers (t_{k-1}, t_k]), one vector per quantity and axis (the columns
/// of the file, moved rather than copied).
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// End time of each row, s.
    pub t_s: Vec<f64>,
    /// Angular increments per axis, rad.
    pub dtheta_rad: [Vec<f64>; 3],
    /// Velocity increments per axis, m/s.
    pub dv_mps: [Vec<f64>; 3],
    /// Attitude at the end of each row.
    pub attitude: Attitude,
    /// Gyro block temperatures per axis, °C (the one measured temperature on every axis when
    /// the file has no per-gyro columns).
    pub gyro_temp_c: [Vec<f64>; 3],
    /// Housing temperature, °C, when measured: the gradient across gyro block i is
    /// `gyro_temp_c[i] − housing_temp_c`.
    pub housing_temp_c: Option<Vec<f64>>,
    /// Accelerometer temperature, °C.
    pub accel_temp_c: Vec<f64>,
    /// Run index of each row (into `run_names`).
    pub run: Vec<u32>,
    /// Run names.
    pub run_names: Vec<String>,
    /// Row ranges of the segments (rows of one run and segment label, time increasing).
    pub segments: Vec<Range<usize>>,
    /// Where the data came from (file name), for messages.
    pub source: String,
}

impl History {
    /// Number of rows.
    pub fn len(&self) -> usize {
        self.t_s.len()
    }

    /// Whether there are no rows.
    pub fn is_empty(&self) -> bool {
        self.t_s.is_empty()
    }
}

/// The measured rows in SI, with the temperatures mapped to the model's inputs: per-gyro
/// columns `temp_gyro_{x,y,z}_c` when present (else the first temperature column on every
/// axis), the gradient as gyro − `temp_housing_c` when a housing temperature is present, and
/// `temp_accel_c` (else the first gyro column) for the accelerometers. The columns are moved
/// out of the measurement, not copied. `source` names the data in messages and reports.
pub fn to_history(m: Measurement, source: &str) -> Result<History, MeasurementError> {
    chunk_to_history(m, source, &mut Vec::new())
}

/// [`to_history`] of one chunk of a file read in chunks: its runs are looked up in (and new
/// ones added to) `run_names`, the runs of the chunks before it, so `run` indexes the whole
/// file's list; the history's `run_names` is a copy of it.
pub(crate) fn chunk_to_history(
    mut m: Measurement,
    source: &str,
    run_names: &mut Vec<String>,
) -> Result<History, MeasurementError> {
    let n = m.rows;
    // The reader has checked the columns; a missing one here means a hand-built measurement.
    let missing = |c: &str| MeasurementError {
        source_name: source.into(),
        row: 0,
        column: c.into(),
        message: "column missing".into(),
    };
    fn take(
        m: &mut Measurement,
        c: &str,
        missing: &dyn Fn(&str) -> MeasurementError,
    ) -> Result<Vec<f64>, MeasurementError> {
        m.columns.remove(c).ok_or_else(|| missing(c))
    }
    let has_gimbal = m.columns.contains_key("outer_deg") && m.columns.contains_key("inner_deg");
    let per_axis = ["temp_gyro_x_c", "temp_gyro_y_c", "temp_gyro_z_c"]
        .iter()
        .all(|c| m.columns.contains_key(*c));
    let first_temp = m
        .temperature_columns()
        .first()
        .map(|s| s.to_string())
        .ok_or_else(|| missing("temp_*_c"))?;
    let common_temp = if per_axis {
        None
    } else {
        m.columns.get(&first_temp).cloned()
    };
    let housing = if per_axis {
        m.columns.remove("temp_housing_c")
    } else {
        None
    };
    let accel = m.columns.remove("temp_accel_c");
    let segs = std::mem::take(&mut m.segments);
    let mut take = |c: &str| take(&mut m, c, &missing);
    let t_s = take("t_s")?;
    let dtheta_rad = [
        take("dtheta_x_rad")?,
        take("dtheta_y_rad")?,
        take("dtheta_z_rad")?,
    ];
    let dv_mps = [take("dv_x_mps")?, take("dv_y_mps")?, take("dv_z_mps")?];
    let attitude = if has_gimbal {
        let mut o = take("outer_deg")?;
        let mut i = take("inner_deg")?;
        o.iter_mut()
            .chain(i.iter_mut())
            .for_each(|d| *d = d.to_radians());
        Attitude::Gimbal {
            outer_rad: o,
            inner_rad: i,
        }
    } else {
        let q: Vec<Vec<f64>> = ["q_bn_w", "q_bn_x", "q_bn_y", "q_bn_z"]
            .iter()
            .map(|c| take(c))
            .collect::<Result<_, _>>()?;
        Attitude::Quaternion(
            (0..n)
                .map(|k| [q[0][k], q[1][k], q[2][k], q[3][k]])
                .collect(),
        )
    };
    let gyro_temp_c: [Vec<f64>; 3] = match common_temp {
        None => [
            take("temp_gyro_x_c")?,
            take("temp_gyro_y_c")?,
            take("temp_gyro_z_c")?,
        ],
        Some(t) => [t.clone(), t.clone(), t],
    };
    let housing_temp_c = housing;
    let accel_temp_c = accel.unwrap_or_else(|| gyro_temp_c[0].clone());
    let mut run = vec![0u32; n];
    let mut segments = Vec::new();
    for (r, _, a, b) in &segs {
        let idx = run_names.iter().position(|x| x == r).unwrap_or_else(|| {
            run_names.push(r.clone());
            run_names.len() - 1
        });
        run[*a..*b].iter_mut().for_each(|x| *x = idx as u32);
        segments.push(*a..*b);
    }
    Ok(History {
        t_s,
        dtheta_rad,
        dv_mps,
        attitude,
        gyro_temp_c,
        housing_temp_c,
        accel_temp_c,
        run,
        run_names: run_names.clone(),
        segments,
        source: source.into(),
    })
}

/// Whether the replay can represent `model`, or why not. The replay puts the table on a static
/// carrier: fixed at the site, with the `[vehicle]` mount, turning only with the Earth. A
/// moving carrier (`[carrier] kind = "ship"` or `"trajectory"`; an external vessel model drives
/// the plant through a trajectory too) adds its rotation, transport rate and lever-arm
/// accelerations to every row, which the replay would leave in the residuals (a ship's 0.1–1
/// °/s of roll shows as a residual of thousands of °/h). The commands call this before
/// replaying and refuse the model with the message.
pub fn check_model(model: &PlantConfig) -> Result<(), String> {
    let what = match model.carrier.kind {
        CarrierKind::Static => return Ok(()),
        CarrierKind::Ship => "a ship ([carrier] kind = \"ship\")",
        CarrierKind::Trajectory => "a trajectory file ([carrier] kind = \"trajectory\")",
    };
    Err(format!(
        "the model's carrier moves: {what}. The replay represents a static carrier only (the table fixed at the site with the [vehicle] mount), so the carrier's rotation, transport rate and lever-arm accelerations would stay in every residual and the comparison would mean nothing. Compare data recorded at rest with the model on a static carrier (remove [carrier] or set kind = \"static\", with the test's [site] and [vehicle] mount); a run on a moving carrier is checked by simulating it (`rins run`), not by replay"
    ))
}

/// The model with the site the data give (lat/lon/height columns, first row), if any; returns
/// a note. The reader has checked the columns against the model's `[site]` ranges
/// ([`crate::ranges`]), so the site is one the model accepts.
pub fn with_data_site(model: &PlantConfig, m: &Measurement) -> (PlantConfig, Option<String>) {
    let get = |c: &str| m.col(c).and_then(|v| v.first().copied());
    let site = get("lat_deg").zip(get("lon_deg"));
    with_site(model, site.map(|(lat, lon)| (lat, lon, get("height_m"))))
}

/// [`with_data_site`] from the first row's (lat_deg, lon_deg, height_m), when the data have
/// them (a [`crate::row_cache::RowCache`] keeps them).
pub fn with_site(
    model: &PlantConfig,
    first: Option<(f64, f64, Option<f64>)>,
) -> (PlantConfig, Option<String>) {
    let mut cfg = model.clone();
    let mut note = None;
    if let Some((lat, lon, height)) = first {
        cfg.site.lat_deg = lat;
        cfg.site.lon_deg = lon;
        if let Some(h) = height {
            cfg.site.height_m = h;
        }
        if cfg.site != model.site {
            note = Some(format!("site from the data: {lat} deg, {lon} deg"));
        }
    }
    (cfg, note)
}
