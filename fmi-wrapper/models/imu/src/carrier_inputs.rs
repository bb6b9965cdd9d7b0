//! The IMU FMU's carrier inputs: a vessel model (the RinsCarrier FMU, or any other) drives
//! the carrier that holds the table. The names, units and FMI 3 arrays are those of the
//! RinsCarrier outputs, so they connect one to one. They act only when the parameter
//! `carrier.external_inputs` is true at the end of initialization; otherwise the FMU ignores
//! them and runs exactly as without them.
//!
//! Semantics (docs/fmu.md): the inputs set before `doStep(t, Δ)` are the carrier state at the
//! end of that step; the plant moves from the previous sample (the values at the end of
//! initialization for the first step) to this one as between two rows of a trajectory file
//! ([`rins_plant::carrier::external`]).

use rins_fmi::vars::{Causality, Kind, ScalarVar, Value};
use rins_plant::PlantConfig;
use rins_plant::carrier::external::CarrierSample;

/// Name of the switch parameter.
pub const SWITCH: &str = "carrier.external_inputs";

/// One carrier input: (FMI 2 name, FMI 3 array, unit, range, description).
pub type InputDecl = (
    &'static str,
    &'static str,
    &'static str,
    (f64, f64),
    &'static str,
);

/// The inputs in slot order.
pub const INPUTS: [InputDecl; 10] = [
    (
        "carrier.lat_deg",
        "carrier.lat_deg",
        "deg",
        (-89.0, 89.0),
        "geodetic latitude of the carrier reference point (WGS-84) at the end of the step",
    ),
    (
        "carrier.lon_deg",
        "carrier.lon_deg",
        "deg",
        (-360.0, 360.0),
        "longitude of the carrier reference point at the end of the step",
    ),
    (
        "carrier.height_m",
        "carrier.height_m",
        "m",
        (-1.0e4, 1.0e5),
        "ellipsoidal height of the carrier reference point at the end of the step",
    ),
    (
        "carrier.v_enu_mps[0]",
        "carrier.v_enu_mps",
        "m/s",
        (-300.0, 300.0),
        "ground velocity of the reference point, east, north, up, at the end of the step",
    ),
    (
        "carrier.v_enu_mps[1]",
        "carrier.v_enu_mps",
        "m/s",
        (-300.0, 300.0),
        "ground velocity of the reference point, east, north, up, at the end of the step",
    ),
    (
        "carrier.v_enu_mps[2]",
        "carrier.v_enu_mps",
        "m/s",
        (-300.0, 300.0),
        "ground velocity of the reference point, east, north, up, at the end of the step",
    ),
    (
        "carrier.q_cn[0]",
        "carrier.q_cn",
        "1",
        (-1.0, 1.0),
        "attitude quaternion q_c^n (w, x, y, z, norm 1): carrier axes (x starboard, y bow, z up) to east-north-up, at the end of the step",
    ),
    (
        "carrier.q_cn[1]",
        "carrier.q_cn",
        "1",
        (-1.0, 1.0),
        "attitude quaternion q_c^n (w, x, y, z, norm 1): carrier axes (x starboard, y bow, z up) to east-north-up, at the end of the step",
    ),
    (
        "carrier.q_cn[2]",
        "carrier.q_cn",
        "1",
        (-1.0, 1.0),
        "attitude quaternion q_c^n (w, x, y, z, norm 1): carrier axes (x starboard, y bow, z up) to east-north-up, at the end of the step",
    ),
    (
        "carrier.q_cn[3]",
        "carrier.q_cn",
        "1",
        (-1.0, 1.0),
        "attitude quaternion q_c^n (w, x, y, z, norm 1): carrier axes (x starboard, y bow, z up) to east-north-up, at the end of the step",
    ),
];

/// The switch parameter and the inputs, start values at rest at the default site with the
/// carrier axes on east-north-up.
pub(crate) fn vars(defaults: &PlantConfig) -> Vec<ScalarVar> {
    let site = &defaults.site;
    let start = [
        site.lat_deg,
        site.lon_deg,
        site.height_m,
        0.0,
        0.0,
        0.0,
        1.0,
        0.0,
        0.0,
        0.0,
    ];
    let mut v = vec![ScalarVar {
        name: SWITCH.into(),
        array: SWITCH.into(),
        kind: Kind::Boolean,
        causality: Causality::Parameter,
        unit: None,
        start: Value::Boolean(false),
        range: None,
        description: "drive the carrier from the carrier.* inputs (a vessel model) instead of the carrier.kind parameters".into(),
    }];
    for ((name, array, unit, range, description), x) in INPUTS.iter().zip(start) {
        v.push(ScalarVar {
            name: (*name).into(),
            array: (*array).into(),
            kind: Kind::Real,
            causality: Causality::Input,
            unit: (*unit != "1").then_some(*unit),
            start: Value::Real(x),
            range: Some(*range),
            description: (*description).into(),
        });
    }
    v
}

/// The sample the ten input values (in [`INPUTS`] order) describe.
pub(crate) fn sample(values: &[Value]) -> CarrierSample {
    let x: Vec<f64> = values
        .iter()
        .map(|v| if let Value::Real(x) = v { *x } else { f64::NAN })
        .collect();
    CarrierSample {
        lat_deg: x[0],
        lon_deg: x[1],
        height_m: x[2],
        v_enu_mps: [x[3], x[4], x[5]],
        q_cn: [x[6], x[7], x[8], x[9]],
    }
}
