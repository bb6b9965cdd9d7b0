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
use rins_fmi_plant::InputRow;
use rins_plant::PlantConfig;
use rins_plant::carrier::external::CarrierSample;

/// Name of the switch parameter.
pub const SWITCH: &str = "carrier.external_inputs";

/// The switch: a parameter, fixed at the end of initialisation.
const SWITCH_ROW: InputRow = InputRow {
    name: SWITCH,
    kind: Kind::Boolean,
    causality: Causality::Parameter,
    unit: None,
    start: |_| Value::Boolean(false),
    range: None,
    description: "drive the carrier from the carrier.* inputs (a vessel model) instead of the carrier.kind parameters",
};

/// The inputs in slot order, start values at rest at the default site with the carrier axes on
/// east-north-up.
pub const INPUTS: [InputRow; 10] = [
    InputRow {
        name: "carrier.lat_deg",
        kind: Kind::Real,
        causality: Causality::Input,
        unit: Some("deg"),
        start: |d| Value::Real(d.site.lat_deg),
        range: Some((-89.0, 89.0)),
        description: "geodetic latitude of the carrier reference point (WGS-84) at the end of the step",
    },
    InputRow {
        name: "carrier.lon_deg",
        kind: Kind::Real,
        causality: Causality::Input,
        unit: Some("deg"),
        start: |d| Value::Real(d.site.lon_deg),
        range: Some((-360.0, 360.0)),
        description: "longitude of the carrier reference point at the end of the step",
    },
    InputRow {
        name: "carrier.height_m",
        kind: Kind::Real,
        causality: Causality::Input,
        unit: Some("m"),
        start: |d| Value::Real(d.site.height_m),
        range: Some((-1.0e4, 1.0e5)),
        description: "ellipsoidal height of the carrier reference point at the end of the step",
    },
    InputRow {
        name: "carrier.v_enu_mps[0]",
        kind: Kind::Real,
        causality: Causality::Input,
        unit: Some("m/s"),
        start: |_| Value::Real(0.0),
        range: Some((-300.0, 300.0)),
        description: "ground velocity of the reference point, east, north, up, at the end of the step",
    },
    InputRow {
        name: "carrier.v_enu_mps[1]",
        kind: Kind::Real,
        causality: Causality::Input,
        unit: Some("m/s"),
        start: |_| Value::Real(0.0),
        range: Some((-300.0, 300.0)),
        description: "ground velocity of the reference point, east, north, up, at the end of the step",
    },
    InputRow {
        name: "carrier.v_enu_mps[2]",
        kind: Kind::Real,
        causality: Causality::Input,
        unit: Some("m/s"),
        start: |_| Value::Real(0.0),
        range: Some((-300.0, 300.0)),
        description: "ground velocity of the reference point, east, north, up, at the end of the step",
    },
    InputRow {
        name: "carrier.q_cn[0]",
        kind: Kind::Real,
        causality: Causality::Input,
        unit: None,
        start: |_| Value::Real(1.0),
        range: Some((-1.0, 1.0)),
        description: "attitude quaternion q_c^n (w, x, y, z, norm 1): carrier axes (x starboard, y bow, z up) to east-north-up, at the end of the step",
    },
    InputRow {
        name: "carrier.q_cn[1]",
        kind: Kind::Real,
        causality: Causality::Input,
        unit: None,
        start: |_| Value::Real(0.0),
        range: Some((-1.0, 1.0)),
        description: "attitude quaternion q_c^n (w, x, y, z, norm 1): carrier axes (x starboard, y bow, z up) to east-north-up, at the end of the step",
    },
    InputRow {
        name: "carrier.q_cn[2]",
        kind: Kind::Real,
        causality: Causality::Input,
        unit: None,
        start: |_| Value::Real(0.0),
        range: Some((-1.0, 1.0)),
        description: "attitude quaternion q_c^n (w, x, y, z, norm 1): carrier axes (x starboard, y bow, z up) to east-north-up, at the end of the step",
    },
    InputRow {
        name: "carrier.q_cn[3]",
        kind: Kind::Real,
        causality: Causality::Input,
        unit: None,
        start: |_| Value::Real(0.0),
        range: Some((-1.0, 1.0)),
        description: "attitude quaternion q_c^n (w, x, y, z, norm 1): carrier axes (x starboard, y bow, z up) to east-north-up, at the end of the step",
    },
];

/// The switch parameter and the inputs.
pub(crate) fn vars(defaults: &PlantConfig) -> Vec<ScalarVar> {
    std::iter::once(&SWITCH_ROW)
        .chain(&INPUTS)
        .map(|row| row.var(defaults))
        .collect()
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
