//! The units the models use, with their expansion in SI base units: modelDescription's
//! UnitDefinitions, so a tool can convert between them (`deg/h` to `rad/s`).

/// A unit in SI base units: value in base units = factor × value + offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SiUnit {
    /// Factor to the base units.
    pub factor: f64,
    /// Offset to the base units (temperatures).
    pub offset: f64,
    /// Exponents of kg, m, s, A, K, mol, cd and rad.
    pub exponents: [i8; 8],
}

/// Units used by the variables, with their SI base-unit expansion where one exists
/// (factor, offset, exponents of kg m s A K mol cd rad).
const UNITS: &[(&str, f64, f64, [i8; 8])] = &[
    ("rad", 1.0, 0.0, [0, 0, 0, 0, 0, 0, 0, 1]),
    (
        "deg",
        std::f64::consts::PI / 180.0,
        0.0,
        [0, 0, 0, 0, 0, 0, 0, 1],
    ),
    (
        "arcsec",
        std::f64::consts::PI / 648_000.0,
        0.0,
        [0, 0, 0, 0, 0, 0, 0, 1],
    ),
    ("rad/s", 1.0, 0.0, [0, 0, -1, 0, 0, 0, 0, 1]),
    (
        "deg/s",
        std::f64::consts::PI / 180.0,
        0.0,
        [0, 0, -1, 0, 0, 0, 0, 1],
    ),
    (
        "deg/s2",
        std::f64::consts::PI / 180.0,
        0.0,
        [0, 0, -2, 0, 0, 0, 0, 1],
    ),
    (
        "deg/h",
        std::f64::consts::PI / 648_000.0,
        0.0,
        [0, 0, -1, 0, 0, 0, 0, 1],
    ),
    (
        "deg/h/K",
        std::f64::consts::PI / 648_000.0,
        0.0,
        [0, 0, -1, 0, -1, 0, 0, 1],
    ),
    (
        "deg/h/K2",
        std::f64::consts::PI / 648_000.0,
        0.0,
        [0, 0, -1, 0, -2, 0, 0, 1],
    ),
    (
        "deg/h/K3",
        std::f64::consts::PI / 648_000.0,
        0.0,
        [0, 0, -1, 0, -3, 0, 0, 1],
    ),
    ("m", 1.0, 0.0, [0, 1, 0, 0, 0, 0, 0, 0]),
    ("m/s", 1.0, 0.0, [0, 1, -1, 0, 0, 0, 0, 0]),
    ("ug", 9.806_65e-6, 0.0, [0, 1, -2, 0, 0, 0, 0, 0]),
    ("ug/K", 9.806_65e-6, 0.0, [0, 1, -2, 0, -1, 0, 0, 0]),
    ("ug/K2", 9.806_65e-6, 0.0, [0, 1, -2, 0, -2, 0, 0, 0]),
    ("ug/K3", 9.806_65e-6, 0.0, [0, 1, -2, 0, -3, 0, 0, 0]),
    ("s", 1.0, 0.0, [0, 0, 1, 0, 0, 0, 0, 0]),
    ("Hz", 1.0, 0.0, [0, 0, -1, 0, 0, 0, 0, 0]),
    ("degC", 1.0, 273.15, [0, 0, 0, 0, 1, 0, 0, 0]),
    ("W", 1.0, 0.0, [1, 2, -3, 0, 0, 0, 0, 0]),
    ("W/K", 1.0, 0.0, [1, 2, -3, 0, -1, 0, 0, 0]),
    ("J/K", 1.0, 0.0, [1, 2, -2, 0, -1, 0, 0, 0]),
    ("ppm", 1e-6, 0.0, [0, 0, 0, 0, 0, 0, 0, 0]),
];

/// The SI expansion of the unit called `name`, if it has one here.
pub fn si_unit(name: &str) -> Option<SiUnit> {
    UNITS
        .iter()
        .find(|(n, ..)| *n == name)
        .map(|&(_, factor, offset, exponents)| SiUnit {
            factor,
            offset,
            exponents,
        })
}
