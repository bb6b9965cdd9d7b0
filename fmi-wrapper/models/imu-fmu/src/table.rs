//! The variable table of the IMU FMU: every fixed-shape scenario parameter (from the plant's
//! own parameter table, [`rins_plant::params`]), the inputs, then the rows of the output table
//! ([`crate::outputs`]).

use std::sync::OnceLock;

use rins_fmi::vars::{Causality, Kind, Value, VariableTable};
use rins_fmi_plant::{InputRow, PlantParams};
use rins_plant::thermal::{CHAMBER_MAX_C, CHAMBER_MIN_C};

use crate::outputs::outputs;

/// Inputs, in table order after the parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Input {
    ChamberOverride,
    ChamberTemp,
    GimbalEnable,
    GimbalOuter,
    GimbalInner,
    GimbalRate,
    NoiseSeed,
}

/// What a slot is.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Role {
    /// A scenario parameter, by key path.
    Param(String),
    /// An input.
    Input(Input),
    /// Element `.1` of output row `.0`.
    Output(usize, usize),
    /// The `carrier.external_inputs` switch ([`crate::carrier_inputs`]).
    CarrierSwitch,
    /// Carrier input `.0` of [`crate::carrier_inputs::INPUTS`].
    Carrier(usize),
    /// A field of a declared-effect slot ([`crate::declared`]).
    Declared(crate::declared::SlotVar),
}

pub(crate) struct Table {
    pub vars: VariableTable,
    pub roles: Vec<Role>,
    /// The scenario parameters (the first slots) and the configuration they describe.
    pub params: PlantParams,
    /// Slot of each input, indexed by `Input as usize` (doStep reads them every step).
    pub input_slots: Vec<usize>,
    /// Slot of the carrier switch; the carrier inputs follow it.
    pub carrier_switch: usize,
}

/// Parameters that are lists of any length cannot be fixed FMU variables: the chamber profile
/// is replaced by the `input.chamber_temp_c` input, explicit steps by gimbal commands.
fn is_fixed_shape(path: &str) -> bool {
    !(path.starts_with("scheme.steps") || path.starts_with("thermal.chamber.profile"))
}

/// The inputs, one row each, in table order after the parameters.
const INPUTS: [(InputRow, Input); 7] = [
    (
        InputRow {
            name: "input.chamber_override",
            kind: Kind::Boolean,
            causality: Causality::Input,
            unit: None,
            start: |_| Value::Boolean(false),
            range: None,
            description: "use input.chamber_temp_c instead of the scenario's chamber temperature",
        },
        Input::ChamberOverride,
    ),
    (
        InputRow {
            name: "input.chamber_temp_c",
            kind: Kind::Real,
            causality: Causality::Input,
            unit: Some("degC"),
            start: |d| Value::Real(d.thermal.chamber.temp_c),
            range: Some((CHAMBER_MIN_C, CHAMBER_MAX_C)),
            description: "chamber (ambient) temperature when input.chamber_override",
        },
        Input::ChamberTemp,
    ),
    (
        InputRow {
            name: "input.gimbal_command",
            kind: Kind::Boolean,
            causality: Causality::Input,
            unit: None,
            start: |_| Value::Boolean(false),
            range: None,
            description: "drive the table to input.gimbal_outer_deg/inner_deg instead of the rotation scheme",
        },
        Input::GimbalEnable,
    ),
    (
        InputRow {
            name: "input.gimbal_outer_deg",
            kind: Kind::Real,
            causality: Causality::Input,
            unit: Some("deg"),
            start: |_| Value::Real(0.0),
            range: Some(GIMBAL_ANGLE_DEG),
            description: "commanded outer (azimuth) gimbal angle",
        },
        Input::GimbalOuter,
    ),
    (
        InputRow {
            name: "input.gimbal_inner_deg",
            kind: Kind::Real,
            causality: Causality::Input,
            unit: Some("deg"),
            start: |_| Value::Real(0.0),
            range: Some(GIMBAL_ANGLE_DEG),
            description: "commanded inner gimbal angle",
        },
        Input::GimbalInner,
    ),
    (
        InputRow {
            name: "input.gimbal_rate_dps",
            kind: Kind::Real,
            causality: Causality::Input,
            unit: Some("deg/s"),
            start: |d| Value::Real(d.scheme.rate_dps),
            range: Some((1e-6, 100.0)),
            description: "cruise rate of commanded moves",
        },
        Input::GimbalRate,
    ),
    (
        InputRow {
            name: "input.noise_seed",
            kind: Kind::Integer,
            causality: Causality::Input,
            unit: None,
            start: |_| Value::Integer(0),
            range: Some((0.0, i32::MAX as f64)),
            description: "a new non-zero value restarts every noise stream from this seed at the next step (Monte Carlo from a saved warm state)",
        },
        Input::NoiseSeed,
    ),
];

/// Range of the commanded gimbal angles, degrees (ten turns either way).
const GIMBAL_ANGLE_DEG: (f64, f64) = (-3600.0, 3600.0);

fn build_table() -> Table {
    let mut scalars = Vec::new();
    let params = PlantParams::push_vars(
        rins_plant::presets::paper_16pos_config(),
        is_fixed_shape,
        &mut scalars,
    );
    let mut roles: Vec<Role> = params.iter().map(|(_, p)| Role::Param(p.into())).collect();
    let mut input_slots = vec![usize::MAX; INPUTS.len()];
    for (row, i) in &INPUTS {
        input_slots[*i as usize] = scalars.len();
        scalars.push(row.var(&params.defaults));
        roles.push(Role::Input(*i));
    }
    for (k, o) in outputs().iter().enumerate() {
        for (e, v) in o.decl.scalars().enumerate() {
            scalars.push(v);
            roles.push(Role::Output(k, e));
        }
    }
    // The carrier switch and inputs after the outputs, so the value references of everything
    // before them are those of the FMU without them.
    let carrier_switch = scalars.len();
    for (i, v) in crate::carrier_inputs::vars(&params.defaults)
        .into_iter()
        .enumerate()
    {
        scalars.push(v);
        roles.push(if i == 0 {
            Role::CarrierSwitch
        } else {
            Role::Carrier(i - 1)
        });
    }
    // The declared-effect slots (parameters) after them, for the same reason.
    for (v, r) in crate::declared::vars() {
        scalars.push(v);
        roles.push(Role::Declared(r));
    }
    // The Integer codes of the enumerations come last (the instance routes them).
    let mut vars = VariableTable::with_enum_codes(scalars);
    for slot in 0..roles.len() {
        vars.initial_dependencies[slot] = initial_dependencies(&vars, &roles, slot);
    }
    Table {
        vars,
        roles,
        params,
        input_slots,
        carrier_switch,
    }
}

/// The knowns an output's value in initialization mode depends on. The increments and effect
/// terms of the last sample are 0 until the first step: none. The plant's state at the start
/// depends on the start attitude (vehicle and table: `vehicle.*`, `scheme.*`); the thermal
/// nodes also on the thermal network and the chamber temperature, the chamber inputs
/// included; the readings of the initial state on what the true values depend on and on
/// their sensors (`sensor.temperature.*` and the seed of their noise, `sensor.encoder.*`).
/// (tests/… `initial_dependencies_cover_every_known_that_changes_an_initial_output` checks
/// this list against perturbed parameters.)
fn initial_dependencies(vars: &VariableTable, roles: &[Role], slot: usize) -> Vec<usize> {
    let Role::Output(k, _) = roles[slot] else {
        return Vec::new();
    };
    let name = outputs()[k].decl.name.as_str();
    let attitude = |p: &str| p.starts_with("vehicle.") || p.starts_with("scheme.");
    // With external carrier inputs the start attitude is theirs.
    let carrier = |r: &Role| matches!(r, Role::CarrierSwitch | Role::Carrier(_));
    let thermal = |p: &str| attitude(p) || p.starts_with("thermal.");
    let temp_sensors = |p: &str| p.starts_with("sensor.temperature.") || p == "run.seed";
    let temperatures = move |r: &Role, sensors: bool| match r {
        Role::Param(p) => thermal(p) || (sensors && temp_sensors(p)),
        Role::Input(i) => matches!(i, Input::ChamberOverride | Input::ChamberTemp),
        Role::Output(..) | Role::Declared(_) => false,
        Role::CarrierSwitch | Role::Carrier(_) => true,
    };
    let depends: Box<dyn Fn(&Role) -> bool> = if name.starts_with("thermal.") {
        Box::new(move |r| temperatures(r, false))
    } else if name.starts_with("imu.temp_") {
        Box::new(move |r| temperatures(r, true))
    } else if name.starts_with("gimbal.")
        || name == "truth.q_bn"
        || name == "effect.position_weight"
    {
        Box::new(move |r| matches!(r, Role::Param(p) if attitude(p)) || carrier(r))
    } else if name.starts_with("imu.encoder_") {
        Box::new(move |r| {
            matches!(r, Role::Param(p) if attitude(p) || p.starts_with("sensor.encoder."))
                || carrier(r)
        })
    } else {
        return Vec::new();
    };
    let mut deps: Vec<usize> = (0..roles.len()).filter(|i| depends(&roles[*i])).collect();
    // An enumeration's Integer code is a known too.
    for (code, e) in &vars.enum_codes {
        if deps.contains(e) {
            deps.push(*code);
        }
    }
    deps
}

/// The table (built once from constants: the same on every call, no mutable global state).
pub(crate) fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(build_table)
}
