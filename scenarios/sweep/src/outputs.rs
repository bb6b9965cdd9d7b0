//! The end figures a sweep can tabulate and draw, by name: those `rins paper table4` reports per
//! seed ([`EndFigures`]) and the magnitudes of the signed ones (the paper prints magnitudes).

use rins_verification::paper::EndFigures;

/// One end figure of a navigation run.
#[derive(Clone, Copy, Debug)]
pub struct Output {
    /// Name in the sweep file, the JSON and the figure file (`lon_nm`).
    pub name: &'static str,
    /// What it is, for titles and headings.
    pub what: &'static str,
    /// Unit as a reader writes it.
    pub unit: &'static str,
    /// Its value for one run.
    pub get: fn(&EndFigures) -> f64,
}

/// Every output a sweep file may name, in the order the docs list them.
pub const OUTPUTS: [Output; 7] = [
    Output {
        name: "lat_nm",
        what: "latitude error at the end (signed, north positive)",
        unit: "nmi",
        get: |e| e.lat_nm,
    },
    Output {
        name: "lon_nm",
        what: "longitude error at the end (signed, east positive)",
        unit: "nmi",
        get: |e| e.lon_nm,
    },
    Output {
        name: "abs_lat_nm",
        what: "|latitude error| at the end",
        unit: "nmi",
        get: |e| e.lat_nm.abs(),
    },
    Output {
        name: "abs_lon_nm",
        what: "|longitude error| at the end",
        unit: "nmi",
        get: |e| e.lon_nm.abs(),
    },
    Output {
        name: "horizontal_nm",
        what: "horizontal error at the end",
        unit: "nmi",
        get: |e| e.horizontal_nm,
    },
    Output {
        name: "trms_nm",
        what: "tRMS of the horizontal error at the end (Eq. 20)",
        unit: "nmi",
        get: |e| e.trms_nm,
    },
    Output {
        name: "up_att_mean_deg",
        what: "mean |up-axis attitude error| over the run",
        unit: "deg",
        get: |e| e.up_att_mean_deg,
    },
];

/// The output called `name`.
pub fn output(name: &str) -> Option<&'static Output> {
    OUTPUTS.iter().find(|o| o.name == name)
}

/// The names accepted, for error messages.
pub fn names() -> Vec<&'static str> {
    OUTPUTS.iter().map(|o| o.name).collect()
}

/// The per-seed columns of the CSV and Parquet tables: the figures a run returns (the
/// magnitudes follow from the signed errors).
pub const PER_SEED: [&str; 5] = [
    "lat_nm",
    "lon_nm",
    "horizontal_nm",
    "trms_nm",
    "up_att_mean_deg",
];
