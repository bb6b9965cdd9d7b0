//! The output columns: every quantity a sink writes of a sample and its truth, once, as a row
//! (name, unit, description, group, how a decimated row combines it, how to read it). The CSV
//! sink and the Python package's arrays iterate over these rows; the sinks whose format fixes
//! the layout (the FMU's value references, the transport's `#[repr(C)]` records, the Rerun
//! series) check theirs against them in their tests, so a quantity added here and not there
//! fails a test. Columns and units as the user sees them: docs/scenario-format.md#output-columns.
//!
//! The groups stay apart: the measured outputs are what the unit reports; the truth (and the
//! per-term errors and the carrier's truth) is for error measures only.

use nalgebra::Vector3;

use crate::effects::{AccelTerm, GyroTerm};
use crate::output::{ImuSample, Truth};
use crate::table::position_label;
use crate::thermal::node;
use crate::true_attitude::TruthMount;
use crate::units::{DPH, UG};

/// Which kind of output a column is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    /// What the unit reports: the increments, the encoders, the temperature sensors (and the
    /// sample's number and time).
    Measured,
    /// The test set-up beside the measured outputs: the table's station and the chamber.
    Setup,
    /// The truth: error-free increments and the true attitude, for error measures only.
    Truth,
    /// Each enabled error term's contribution (truth too, written on its own switch).
    Effects,
    /// A moving carrier's truth, in the trajectory file's names and units (docs/carrier.md).
    CarrierTruth,
}

/// How the samples of one decimated row combine into the row's value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OverRow {
    /// Summed (increments: the column's sum over the file is its sum over every sample).
    Sum,
    /// The row's last sample (states: angles, temperatures, attitude).
    Last,
    /// Summed, then divided by the row's span and by `unit_si` (the output unit in SI, e.g.
    /// [`DPH`]): the mean rate of an increment error over the row.
    MeanRate {
        /// One output unit in SI units.
        unit_si: f64,
    },
}

/// The CSV names of a column's elements.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Names {
    /// One element, this name.
    One(&'static str),
    /// One element per body axis: `{prefix}_{x|y|z}_{suffix}` (a term's key after the prefix).
    Axes {
        /// Before the axis.
        prefix: &'static str,
        /// After the axis (the unit).
        suffix: &'static str,
    },
    /// One element per thermal node ([`node::NAMES`]): `{prefix}_{node}_{suffix}`.
    Nodes {
        /// Before the node's name.
        prefix: &'static str,
        /// After it (the unit).
        suffix: &'static str,
    },
    /// These names, one per element.
    List(&'static [&'static str]),
}

/// Reads the values of one element group of a column.
pub type ReadReals = fn(&Reading<'_>, &mut [f64]);

/// How a column's value is read from a sample and its truth.
#[derive(Clone, Copy, Debug)]
pub enum Read {
    /// The sample's number ([`ImuSample::index`]), an integer.
    Index,
    /// The table's station label ([`position_label`]) of the truth's gimbal, a string.
    Position,
    /// Real values, one per element.
    Reals(ReadReals),
    /// Per enabled gyro term, its increment error ([`Truth::gyro_terms_rad`]), rad.
    GyroTerm,
    /// Per enabled accelerometer term, its increment error ([`Truth::accel_terms_mps`]), m/s.
    AccelTerm,
}

/// What a column reads: one sample, its truth, and the mount that composes the true attitude.
pub struct Reading<'a> {
    /// The sample.
    pub sample: &'a ImuSample,
    /// The truth over it.
    pub truth: &'a Truth,
    /// The mount between the truth's carrier attitude and the table (for q_b^n).
    pub mount: &'a TruthMount,
}

/// One output quantity.
#[derive(Clone, Copy, Debug)]
pub struct Column {
    /// The quantity's name: the Python package's dict key (for a term column, the key of the
    /// dict of its terms).
    pub key: &'static str,
    /// The CSV names of its elements.
    pub names: Names,
    /// Unit of the values as written (`""`: none).
    pub unit: &'static str,
    /// What it is.
    pub description: &'static str,
    /// Measured, set-up, truth, effects or carrier truth.
    pub group: Group,
    /// How a decimated row combines its samples.
    pub over_row: OverRow,
    /// How it is read.
    pub read: Read,
    /// Written to the CSV too (false: the arrays only; the CSV gives the table through the
    /// encoders and q_bn).
    pub in_csv: bool,
}

fn v3(out: &mut [f64], v: &Vector3<f64>) {
    out.copy_from_slice(v.as_slice());
}

const fn col(
    key: &'static str,
    names: Names,
    unit: &'static str,
    description: &'static str,
    group: Group,
    over_row: OverRow,
    read: Read,
) -> Column {
    Column {
        key,
        names,
        unit,
        description,
        group,
        over_row,
        read,
        in_csv: true,
    }
}

/// The carrier truth columns of a moving carrier, in the trajectory file's names and units
/// (docs/carrier.md): reference point (WGS-84), ground velocity ENU, attitude q_c^n.
pub const CARRIER_NAMES: [&str; 10] = [
    "lat_deg", "lon_deg", "height_m", "v_e_mps", "v_n_mps", "v_u_mps", "q_cn_w", "q_cn_x",
    "q_cn_y", "q_cn_z",
];

use Group::*;
use OverRow::*;

/// Every output column, in the order the sinks write them.
pub static COLUMNS: &[Column] = &[
    col(
        "sample",
        Names::One("sample"),
        "",
        "output sample number",
        Measured,
        Last,
        Read::Index,
    ),
    col(
        "t_s",
        Names::One("t_s"),
        "s",
        "end of the sample interval",
        Measured,
        Last,
        Read::Reals(|r, o| o[0] = r.sample.t_s),
    ),
    col(
        "dtheta_rad",
        Names::Axes {
            prefix: "dtheta",
            suffix: "rad",
        },
        "rad",
        "angular increment (body x, y, z)",
        Measured,
        Sum,
        Read::Reals(|r, o| v3(o, &r.sample.dtheta_rad)),
    ),
    col(
        "dv_mps",
        Names::Axes {
            prefix: "dv",
            suffix: "mps",
        },
        "m/s",
        "velocity increment (body x, y, z)",
        Measured,
        Sum,
        Read::Reals(|r, o| v3(o, &r.sample.dv_mps)),
    ),
    col(
        "outer_deg",
        Names::One("outer_deg"),
        "deg",
        "outer (azimuth) gimbal encoder reading at the end of the interval",
        Measured,
        Last,
        Read::Reals(|r, o| o[0] = r.sample.encoder.outer_rad.to_degrees()),
    ),
    col(
        "inner_deg",
        Names::One("inner_deg"),
        "deg",
        "inner gimbal encoder reading at the end of the interval",
        Measured,
        Last,
        Read::Reals(|r, o| o[0] = r.sample.encoder.inner_rad.to_degrees()),
    ),
    col(
        "position",
        Names::One("position"),
        "",
        "the table's station (A…D, z-up, z-down, moving) from its true angles",
        Setup,
        Last,
        Read::Position,
    ),
    col(
        "temps_c",
        Names::Nodes {
            prefix: "temp",
            suffix: "c",
        },
        "degC",
        "temperature-sensor readings (held between thermal updates)",
        Measured,
        Last,
        Read::Reals(|r, o| o.copy_from_slice(&r.sample.temps_c)),
    ),
    col(
        "temp_chamber_c",
        Names::One("temp_chamber_c"),
        "degC",
        "chamber temperature in use",
        Setup,
        Last,
        Read::Reals(|r, o| o[0] = r.truth.temps.chamber_c),
    ),
    col(
        "dtheta_true_rad",
        Names::Axes {
            prefix: "dtheta_true",
            suffix: "rad",
        },
        "rad",
        "error-free angular increment",
        Truth,
        Sum,
        Read::Reals(|r, o| v3(o, &r.truth.dtheta_true_rad)),
    ),
    col(
        "dv_true_mps",
        Names::Axes {
            prefix: "dv_true",
            suffix: "mps",
        },
        "m/s",
        "error-free velocity increment",
        Truth,
        Sum,
        Read::Reals(|r, o| v3(o, &r.truth.dv_true_mps)),
    ),
    col(
        "q_bn",
        Names::List(&["q_bn_w", "q_bn_x", "q_bn_y", "q_bn_z"]),
        "",
        "true attitude quaternion body→ENU navigation frame (w, x, y, z)",
        Truth,
        Last,
        // q_b^n = q_c^n·q_v^c·q_z(outer)·q_x(inner) in closed form, the plant's own
        // composition (docs/carrier.md, Frames).
        Read::Reals(|r, o| {
            let q = r.mount.q_bn_of(r.truth);
            o.copy_from_slice(&[q.w, q.i, q.j, q.k]);
        }),
    ),
    Column {
        in_csv: false,
        ..col(
            "gimbal_outer_rad",
            Names::One("gimbal_outer_rad"),
            "rad",
            "true outer gimbal angle",
            Truth,
            Last,
            Read::Reals(|r, o| o[0] = r.truth.gimbal.angles.outer_rad),
        )
    },
    Column {
        in_csv: false,
        ..col(
            "gimbal_inner_rad",
            Names::One("gimbal_inner_rad"),
            "rad",
            "true inner gimbal angle",
            Truth,
            Last,
            Read::Reals(|r, o| o[0] = r.truth.gimbal.angles.inner_rad),
        )
    },
    col(
        "gyro_effects_dph",
        Names::Axes {
            prefix: "gyro",
            suffix: "dph",
        },
        "deg/h",
        "each enabled gyro term's mean rate error",
        Effects,
        MeanRate { unit_si: DPH },
        Read::GyroTerm,
    ),
    col(
        "accel_effects_ug",
        Names::Axes {
            prefix: "accel",
            suffix: "ug",
        },
        "ug",
        "each enabled accelerometer term's mean acceleration error",
        Effects,
        MeanRate { unit_si: UG },
        Read::AccelTerm,
    ),
    col(
        "carrier",
        Names::List(&CARRIER_NAMES),
        "deg, deg, m, m/s (ENU), 1 (q_c^n)",
        "the carrier's reference point, ground velocity and attitude",
        CarrierTruth,
        Last,
        Read::Reals(|r, o| {
            let c = &r.truth.carrier;
            let q = c.q_cn.quaternion();
            o.copy_from_slice(&[
                c.lat_rad.to_degrees(),
                c.lon_rad.to_degrees(),
                c.height_m,
                c.v_n.x,
                c.v_n.y,
                c.v_n.z,
                q.w,
                q.i,
                q.j,
                q.k,
            ]);
        }),
    ),
];

/// The column of `key`.
pub fn column(key: &str) -> Option<&'static Column> {
    COLUMNS.iter().find(|c| c.key == key)
}

const AXES: [&str; 3] = ["x", "y", "z"];

/// One column as a run writes it: for a term column, one of its enabled terms.
#[derive(Clone, Copy, Debug)]
pub struct Entry {
    /// The column.
    pub column: &'static Column,
    /// For a term column: the term's index in [`Truth::gyro_terms_rad`] or
    /// [`Truth::accel_terms_mps`] and its key.
    pub term: Option<(usize, &'static str)>,
}

impl Entry {
    /// Values per sample.
    pub fn width(&self) -> usize {
        match self.column.names {
            Names::One(_) => 1,
            Names::Axes { .. } => 3,
            Names::Nodes { .. } => node::COUNT,
            Names::List(l) => l.len(),
        }
    }

    /// The CSV names of its elements.
    pub fn names(&self) -> Vec<String> {
        let stem = |p: &str| match self.term {
            Some((_, key)) => format!("{p}_{key}"),
            None => p.to_string(),
        };
        match self.column.names {
            Names::One(n) => vec![n.to_string()],
            Names::Axes { prefix, suffix } => {
                let p = stem(prefix);
                AXES.iter().map(|a| format!("{p}_{a}_{suffix}")).collect()
            }
            Names::Nodes { prefix, suffix } => {
                let p = stem(prefix);
                node::NAMES
                    .iter()
                    .map(|n| format!("{p}_{n}_{suffix}"))
                    .collect()
            }
            Names::List(l) => l.iter().map(|n| n.to_string()).collect(),
        }
    }

    /// Reads the real values of one sample into `out` (`width` of them), before the row's
    /// combination ([`OverRow`]). The index and the position are not reals: `out` is left as
    /// it is for them ([`Read::Index`], [`Read::Position`]).
    #[inline]
    pub fn read(&self, r: &Reading<'_>, out: &mut [f64]) {
        match self.column.read {
            Read::Reals(f) => f(r, out),
            Read::GyroTerm => v3(out, &r.truth.gyro_terms_rad[self.term_index()]),
            Read::AccelTerm => v3(out, &r.truth.accel_terms_mps[self.term_index()]),
            Read::Index | Read::Position => {}
        }
    }

    fn term_index(&self) -> usize {
        self.term.expect("a term column's entry names its term").0
    }
}

/// The station label of `r`'s truth ([`Read::Position`]).
pub fn position_of(r: &Reading<'_>) -> &'static str {
    let g = &r.truth.gimbal;
    position_label(g.angles.outer_rad, g.angles.inner_rad, g.moving)
}

/// The entries of a run: the columns of `groups`, in table order, the term columns once per
/// enabled term (`gyro_terms`, `accel_terms`); with `csv`, only the columns the CSV writes.
pub fn entries(
    groups: &[Group],
    gyro_terms: &[GyroTerm],
    accel_terms: &[AccelTerm],
    csv: bool,
) -> Vec<Entry> {
    let mut out = Vec::new();
    for c in COLUMNS {
        if !groups.contains(&c.group) || (csv && !c.in_csv) {
            continue;
        }
        match c.read {
            Read::GyroTerm => out.extend(gyro_terms.iter().map(|t| Entry {
                column: c,
                term: Some((*t as usize, t.key())),
            })),
            Read::AccelTerm => out.extend(accel_terms.iter().map(|t| Entry {
                column: c,
                term: Some((*t as usize, t.key())),
            })),
            _ => out.push(Entry {
                column: c,
                term: None,
            }),
        }
    }
    out
}

/// Every group, in the order the CSV writes them.
pub const GROUPS: [Group; 5] = [
    Group::Measured,
    Group::Setup,
    Group::Truth,
    Group::Effects,
    Group::CarrierTruth,
];

/// Every entry a run can write (every group, every catalogue term), each with its values in
/// `r` ([`Entry::read`]; zeros for the index and the position): what a sink whose layout is
/// fixed (the FMU's outputs, the wire's records) checks itself against, so a column added to
/// the table reaches its test.
pub fn every_entry_read(r: &Reading<'_>) -> Vec<(Entry, Vec<f64>)> {
    entries(&GROUPS, &GyroTerm::ALL, &AccelTerm::ALL, false)
        .into_iter()
        .map(|e| {
            let mut values = vec![0.0; e.width()];
            e.read(r, &mut values);
            (e, values)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Keys are unique (they name the Python arrays and the sinks' checks), and every group's
    /// columns come together in the order the CSV writes them.
    #[test]
    fn keys_are_unique_and_groups_are_in_csv_order() {
        for (i, c) in COLUMNS.iter().enumerate() {
            assert!(
                COLUMNS[..i].iter().all(|d| d.key != c.key),
                "key {} twice",
                c.key
            );
        }
        let rank = |g| GROUPS.iter().position(|x| *x == g).unwrap();
        // Measured and set-up columns interleave (the CSV's first block); then each group.
        let block = |g| rank(g).max(1);
        assert!(
            COLUMNS
                .windows(2)
                .all(|w| block(w[0].group) <= block(w[1].group))
        );
    }

    /// Every column the CSV writes is in docs/scenario-format.md's list of output columns
    /// (by name, or by the stem and unit of its per-axis, per-node or per-term pattern), and a
    /// term column's names put the term's key after the stem.
    #[test]
    fn every_csv_column_is_documented() {
        let doc = include_str!("../../docs/scenario-format.md");
        let doc = &doc[doc.find("## Output columns").expect("the section")..];
        for e in entries(&GROUPS, &[GyroTerm::Bias], &[AccelTerm::Bias], true) {
            let documented = match e.column.names {
                Names::One(n) => doc.contains(&format!("`{n}`")),
                Names::List(l) => l.iter().all(|n| doc.contains(&format!("`{n}`"))),
                Names::Axes { prefix, suffix } | Names::Nodes { prefix, suffix } => {
                    doc.contains(&format!("`{prefix}_")) && doc.contains(&format!("_{suffix}`"))
                }
            };
            assert!(
                documented,
                "column {} is not in docs/scenario-format.md",
                e.column.key
            );
        }
        let t = entries(&[Effects], &[GyroTerm::Bias], &[], true);
        assert_eq!(t[0].names()[2], "gyro_bias_z_dph");
    }
}
