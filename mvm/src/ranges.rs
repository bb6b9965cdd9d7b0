//! Physical ranges of the measured columns (docs/measurement-format.md, "Physical ranges"). A
//! value outside them is not something a navigation unit on a table measured: it is a unit
//! mistake, a corrupt file or a wrong column, and it is refused with the file, the data row,
//! the column, the value and the allowed range. Bounded values also keep every sum the
//! comparison takes over a file finite (10^9 rows of at most 2^53 stay below 10^25).

// Numbers in messages: the workspace's one rule (a 1e300 is not printed as 301 digits).
use rins_plant::message::num;

use crate::header::{Kind, Layout};
use crate::measurement::{Measurement, MeasurementError};

/// Largest angular rate an angular increment may show, °/s: a navigation-grade gyro's range is
/// a few hundred °/s and a rotating table turns at tens of °/s.
pub const MAX_RATE_DPS: f64 = 2000.0;
/// Largest specific force a velocity increment may show, g (a navigation accelerometer's range
/// is 20–50 g).
pub const MAX_ACCEL_G: f64 = 100.0;
/// Standard gravity, m/s², for [`MAX_ACCEL_G`] and the µg columns.
pub const STANDARD_GRAVITY_MPS2: f64 = 9.806_65;
/// Temperatures, °C: below −273.15 is impossible, and a navigation unit never sees beyond this.
pub const TEMP_RANGE_C: [f64; 2] = [-100.0, 200.0];
/// Largest |t_s|, s (317 years: Unix seconds fit; a timestamp read as raw ms, µs or ns does
/// not).
pub const MAX_TIME_S: f64 = 1e10;
/// Row interval within a segment, s: at most 1 MHz, at least one row a day.
pub const ROW_INTERVAL_S: [f64; 2] = [1e-6, 86_400.0];
/// Largest |gimbal angle|, degrees: unwrapped angles may grow with every turn (a week at 10 °/s
/// is 6·10^6°); beyond 10^8° an f64 no longer resolves 10^-7°.
pub const MAX_GIMBAL_DEG: f64 = 1e8;
/// Largest | |q| − 1 | of an attitude quaternion.
pub const QUATERNION_NORM_TOL: f64 = 1e-3;
/// Site latitude, degrees: the model's `[site]` range (the ENU frame is singular at the poles).
pub const LAT_RANGE_DEG: [f64; 2] = [-89.0, 89.0];
/// Site longitude, degrees, [−180, 360) as the model's `[site]`.
pub const LON_RANGE_DEG: [f64; 2] = [-180.0, 360.0];
/// Site height, m, the model's `[site]` range.
pub const HEIGHT_RANGE_M: [f64; 2] = [-1000.0, 20_000.0];
/// Largest sample counter (2^53: integers an f64 holds exactly).
pub const MAX_SAMPLE: f64 = 9_007_199_254_740_992.0;

/// How a documented numeric column is bounded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bound {
    /// `lo <= x <= hi` (`x < hi` when `open_hi`), in the column's unit.
    Range {
        /// Lower bound.
        lo: f64,
        /// Upper bound.
        hi: f64,
        /// Whether `hi` itself is excluded.
        open_hi: bool,
        /// Whether the value must be a whole number.
        integer: bool,
        /// The reason, for the message.
        why: &'static str,
    },
    /// `|x| <= rate × Δt` of the row: increments over a row.
    PerRow {
        /// Largest rate, in the column's unit per second.
        rate: f64,
        /// The rate as written in the message (`2000 °/s`).
        rate_text: &'static str,
    },
}

const fn range(lo: f64, hi: f64, why: &'static str) -> Bound {
    Bound::Range {
        lo,
        hi,
        open_hi: false,
        integer: false,
        why,
    }
}

/// The bound of a documented numeric column (`None` for a name that is not one).
pub fn bound(name: &str) -> Option<Bound> {
    let family = |p: &str, s: &str| name.starts_with(p) && name.ends_with(s);
    let rate_rad = MAX_RATE_DPS.to_radians();
    let accel_mps2 = MAX_ACCEL_G * STANDARD_GRAVITY_MPS2;
    Some(match name {
        "t_s" => range(
            -MAX_TIME_S,
            MAX_TIME_S,
            "seconds (a timestamp in ms, µs or ns needs a column map unit or a Parquet timestamp type)",
        ),
        "outer_deg" | "inner_deg" => range(
            -MAX_GIMBAL_DEG,
            MAX_GIMBAL_DEG,
            "gimbal angle in degrees (beyond 1e8° an f64 no longer resolves the angle)",
        ),
        "q_bn_w" | "q_bn_x" | "q_bn_y" | "q_bn_z" => range(
            -1.0 - QUATERNION_NORM_TOL,
            1.0 + QUATERNION_NORM_TOL,
            "a component of a unit quaternion",
        ),
        "lat_deg" => range(
            LAT_RANGE_DEG[0],
            LAT_RANGE_DEG[1],
            "latitude of the site, the model's [site] range (the ENU frame is singular at the poles)",
        ),
        "lon_deg" => Bound::Range {
            lo: LON_RANGE_DEG[0],
            hi: LON_RANGE_DEG[1],
            open_hi: true,
            integer: false,
            why: "longitude of the site, the model's [site] range",
        },
        "height_m" => range(
            HEIGHT_RANGE_M[0],
            HEIGHT_RANGE_M[1],
            "ellipsoidal height of the site, the model's [site] range",
        ),
        "sample" => Bound::Range {
            lo: 0.0,
            hi: MAX_SAMPLE,
            open_hi: false,
            integer: true,
            why: "a sample counter (a whole number an f64 holds exactly)",
        },
        _ if family("temp_", "_c") => range(
            TEMP_RANGE_C[0],
            TEMP_RANGE_C[1],
            "a temperature in °C (below -273.15 is impossible; a navigation unit never sees beyond this range)",
        ),
        _ if family("dtheta_", "_rad") => Bound::PerRow {
            rate: rate_rad,
            rate_text: "2000 °/s",
        },
        _ if family("dv_", "_mps") => Bound::PerRow {
            rate: accel_mps2,
            rate_text: "100 g",
        },
        _ if family("gyro_", "_dph") => range(
            -MAX_RATE_DPS * 3600.0,
            MAX_RATE_DPS * 3600.0,
            "a gyro rate contribution in °/h (2000 °/s)",
        ),
        _ if family("accel_", "_ug") => range(
            -MAX_ACCEL_G * 1e6,
            MAX_ACCEL_G * 1e6,
            "an accelerometer contribution in µg (100 g)",
        ),
        _ => return None,
    })
}

/// Source name of documented column `name` (for errors: the column as the file calls it),
/// with the documented name when a column map renamed it.
pub(crate) fn source_of(layout: &Layout, name: &str) -> (String, String) {
    for (i, h) in layout.header.iter().enumerate() {
        if h == name && layout.kind[i] == Kind::Num {
            let raw = layout.raw[i].clone();
            let note = if raw == name {
                String::new()
            } else {
                format!(" (read as {name})")
            };
            return (raw, note);
        }
    }
    (name.to_string(), String::new())
}

/// The first bad row of a column (0-based) and its message.
type Bad = Option<(usize, String)>;

fn first_bad_value(v: &[f64], b: Bound) -> Bad {
    let Bound::Range {
        lo,
        hi,
        open_hi,
        integer,
        why,
    } = b
    else {
        return None;
    };
    let k = v.iter().position(|&x| {
        !(x >= lo && (x < hi || (!open_hi && x == hi))) || (integer && x.fract() != 0.0)
    })?;
    let close = if open_hi { ')' } else { ']' };
    let what = if integer { "a whole number in" } else { "in" };
    Some((
        k,
        format!(
            "{} is outside the physical range: expected {what} [{}, {}{close}, {why}",
            num(v[k]),
            num(lo),
            num(hi)
        ),
    ))
}

/// Checks every value against its column's fixed range (not the per-row increment bounds);
/// reports the earliest bad row (ties: header order).
pub(crate) fn check_values(
    m: &Measurement,
    layout: &Layout,
    row0: usize,
) -> Result<(), MeasurementError> {
    use rayon::prelude::*;
    let bad: Vec<(usize, String, String)> = m
        .columns
        .par_iter()
        .filter_map(|(name, v)| {
            let (k, msg) = first_bad_value(v, bound(name)?)?;
            Some((k, name.clone(), msg))
        })
        .collect();
    report(bad, layout, row0)
}

/// Checks the row intervals and the increments against [`MAX_RATE_DPS`] and [`MAX_ACCEL_G`]
/// times each row's interval, and the quaternion norm. `dt_s[k]` is row k's interval (the
/// segment's median for its first row).
pub(crate) fn check_rows(
    m: &Measurement,
    layout: &Layout,
    dt_s: &[f64],
    row0: usize,
) -> Result<(), MeasurementError> {
    use rayon::prelude::*;
    let mut bad: Vec<(usize, String, String)> = Vec::new();
    if let Some(k) = dt_s
        .iter()
        .position(|d| !(*d >= ROW_INTERVAL_S[0] && *d <= ROW_INTERVAL_S[1]))
    {
        bad.push((
            k,
            "t_s".into(),
            format!(
                "row interval {} s outside [{}, {}] s (1 MHz to one row a day)",
                num(dt_s[k]),
                num(ROW_INTERVAL_S[0]),
                num(ROW_INTERVAL_S[1])
            ),
        ));
    }
    bad.par_extend(m.columns.par_iter().filter_map(|(name, v)| {
        let Some(Bound::PerRow { rate, rate_text }) = bound(name) else {
            return None;
        };
        let k = v
            .iter()
            .zip(dt_s)
            .position(|(x, d)| !(x.abs() <= rate * d))?;
        let unit = name.rsplit('_').next().unwrap_or("");
        Some((
            k,
            name.clone(),
            format!(
                "{} {unit} over a row of {} s is outside the physical range: |x| <= {rate_text} x the row interval = {} {unit}",
                num(v[k]),
                num(dt_s[k]),
                num(rate * dt_s[k])
            ),
        ))
    }));
    if let (Some(w), Some(x), Some(y), Some(z)) = (
        m.col("q_bn_w"),
        m.col("q_bn_x"),
        m.col("q_bn_y"),
        m.col("q_bn_z"),
    ) {
        let norm = |k: usize| (w[k] * w[k] + x[k] * x[k] + y[k] * y[k] + z[k] * z[k]).sqrt();
        if let Some(k) = (0..w.len()).find(|&k| !((norm(k) - 1.0).abs() <= QUATERNION_NORM_TOL)) {
            bad.push((
                k,
                "q_bn_w".into(),
                format!(
                    "quaternion (q_bn_w, q_bn_x, q_bn_y, q_bn_z) = ({}, {}, {}, {}) has norm {}: expected within {} of 1",
                    num(w[k]),
                    num(x[k]),
                    num(y[k]),
                    num(z[k]),
                    num(norm(k)),
                    num(QUATERNION_NORM_TOL)
                ),
            ));
        }
    }
    report(bad, layout, row0)
}

/// The error for the earliest bad row (ties: the column first in the header); the rows of `m`
/// follow `row0` rows of the file.
fn report(
    mut bad: Vec<(usize, String, String)>,
    layout: &Layout,
    row0: usize,
) -> Result<(), MeasurementError> {
    let order = |name: &str| layout.header.iter().position(|h| h == name);
    bad.sort_by_key(|(k, name, _)| (*k, order(name)));
    match bad.into_iter().next() {
        None => Ok(()),
        Some((k, name, msg)) => {
            let (raw, note) = source_of(layout, &name);
            Err(layout.err(row0 + k + 1, &raw, format!("{msg}{note}")))
        }
    }
}
