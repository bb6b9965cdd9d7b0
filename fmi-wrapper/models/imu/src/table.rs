//! The variable table of the IMU FMU: every fixed-shape scenario parameter (from the plant's
//! own parameter table, [`rins_plant::params`]), the inputs, then the rows of the output table
//! ([`crate::outputs`]).

use std::sync::OnceLock;

use rins_fmi::vars::{Causality, Kind, ScalarVar, Value, VariableTable};
use rins_plant::PlantConfig;
use rins_plant::params::{self, ParamValue};
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

impl Input {
    const COUNT: usize = 7;
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
    pub defaults: PlantConfig,
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

fn describe(path: &str) -> String {
    let key = params::key_of(path);
    match path.rsplit('.').next().unwrap_or("") {
        "enabled" => format!("switch: {} on/off", key.trim_end_matches(".enabled")),
        _ => format!("scenario key {key}"),
    }
}

fn param_var(p: &params::Param) -> ScalarVar {
    // FMI structured names write matrix elements as `a[i,j]`; the FMI 3 variable is the name
    // without its trailing index (`carrier.ship.legs[0].heading_deg` is a scalar of its own).
    let name = p.path.replace("][", ",");
    let array = rins_fmi::vars::array_name(&name).to_string();
    let unit = (p.unit != "1").then_some(p.unit);
    let (kind, start, range) = match &p.value {
        ParamValue::Real(x) => (Kind::Real, Value::Real(*x), p.range),
        ParamValue::Integer(u) => {
            // FMI 2 Integer is 32-bit signed: the seed range is what both FMI versions carry.
            let (lo, hi) = p.range.unwrap_or((0.0, f64::INFINITY));
            (
                Kind::Integer,
                Value::Integer(*u),
                Some((lo, hi.min(i32::MAX as f64))),
            )
        }
        ParamValue::Bool(b) => (Kind::Boolean, Value::Boolean(*b), None),
        ParamValue::Enum(name) => {
            let items = params::enum_choices(&p.path)
                .expect("every enumeration has choices (tested in rins-plant)");
            let type_name = match array.as_str() {
                "scheme.kind" => "SchemeKind",
                "scheme.axis" => "GimbalAxis",
                "carrier.kind" => "CarrierKind",
                "carrier.ship.sea.spectrum" => "WaveSpectrum",
                _ => "PositionBiasTransition",
            };
            let idx = items
                .iter()
                .position(|c| c == name)
                .expect("start value is a valid item");
            (
                Kind::Enumeration { type_name, items },
                Value::Enumeration(idx),
                None,
            )
        }
    };
    ScalarVar {
        name,
        array,
        kind,
        causality: Causality::Parameter,
        unit,
        start,
        range,
        description: describe(&p.path),
    }
}

fn input_vars(defaults: &PlantConfig) -> [(ScalarVar, Input); Input::COUNT] {
    let real = |name: &str, unit, start, range, description: &str| ScalarVar {
        name: name.into(),
        array: name.into(),
        kind: Kind::Real,
        causality: Causality::Input,
        unit: Some(unit),
        start: Value::Real(start),
        range: Some(range),
        description: description.into(),
    };
    let boolean = |name: &str, description: &str| ScalarVar {
        kind: Kind::Boolean,
        unit: None,
        start: Value::Boolean(false),
        range: None,
        ..real(name, "", 0.0, (0.0, 0.0), description)
    };
    let angle = (-3600.0, 3600.0);
    [
        (
            boolean(
                "input.chamber_override",
                "use input.chamber_temp_c instead of the scenario's chamber temperature",
            ),
            Input::ChamberOverride,
        ),
        (
            real(
                "input.chamber_temp_c",
                "degC",
                defaults.thermal.chamber.temp_c,
                (CHAMBER_MIN_C, CHAMBER_MAX_C),
                "chamber (ambient) temperature when input.chamber_override",
            ),
            Input::ChamberTemp,
        ),
        (
            boolean(
                "input.gimbal_command",
                "drive the table to input.gimbal_outer_deg/inner_deg instead of the rotation scheme",
            ),
            Input::GimbalEnable,
        ),
        (
            real(
                "input.gimbal_outer_deg",
                "deg",
                0.0,
                angle,
                "commanded outer (azimuth) gimbal angle",
            ),
            Input::GimbalOuter,
        ),
        (
            real(
                "input.gimbal_inner_deg",
                "deg",
                0.0,
                angle,
                "commanded inner gimbal angle",
            ),
            Input::GimbalInner,
        ),
        (
            real(
                "input.gimbal_rate_dps",
                "deg/s",
                defaults.scheme.rate_dps,
                (1e-6, 100.0),
                "cruise rate of commanded moves",
            ),
            Input::GimbalRate,
        ),
        (
            ScalarVar {
                kind: Kind::Integer,
                unit: None,
                start: Value::Integer(0),
                ..real(
                    "input.noise_seed",
                    "",
                    0.0,
                    (0.0, i32::MAX as f64),
                    "a new non-zero value restarts every noise stream from this seed at the next step (Monte Carlo from a saved warm state)",
                )
            },
            Input::NoiseSeed,
        ),
    ]
}

fn build_table() -> Table {
    let defaults = rins_plant::presets::paper_16pos_config();
    let mut scalars = Vec::new();
    let mut roles = Vec::new();
    for p in params::flatten(&defaults)
        .into_iter()
        .filter(|p| is_fixed_shape(&p.path))
    {
        scalars.push(param_var(&p));
        roles.push(Role::Param(p.path));
    }
    let mut input_slots = vec![usize::MAX; Input::COUNT];
    for (v, i) in input_vars(&defaults) {
        input_slots[i as usize] = scalars.len();
        scalars.push(v);
        roles.push(Role::Input(i));
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
    for (i, v) in crate::carrier_inputs::vars(&defaults)
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
        defaults,
        input_slots,
        carrier_switch,
    }
}

/// The knowns an output's value in initialization mode depends on. Outputs of the last
/// sample (increments, readings, effect terms) are 0 until the first step: none. The plant's
/// state at the start depends on the start attitude (vehicle and table: `vehicle.*`,
/// `scheme.*`); the thermal nodes also on the thermal network and the chamber temperature,
/// the chamber inputs included (tests/… `initial_dependencies_cover_every_known_that_changes_an_initial_output`
/// checks this list against perturbed parameters).
fn initial_dependencies(vars: &VariableTable, roles: &[Role], slot: usize) -> Vec<usize> {
    let Role::Output(k, _) = roles[slot] else {
        return Vec::new();
    };
    let name = outputs()[k].decl.name.as_str();
    let attitude = |p: &str| p.starts_with("vehicle.") || p.starts_with("scheme.");
    // With external carrier inputs the start attitude is theirs.
    let carrier = |r: &Role| matches!(r, Role::CarrierSwitch | Role::Carrier(_));
    let depends: Box<dyn Fn(&Role) -> bool> = if name.starts_with("thermal.") {
        Box::new(move |r| match r {
            Role::Param(p) => attitude(p) || p.starts_with("thermal."),
            Role::Input(i) => matches!(i, Input::ChamberOverride | Input::ChamberTemp),
            Role::Output(..) | Role::Declared(_) => false,
            Role::CarrierSwitch | Role::Carrier(_) => true,
        })
    } else if name.starts_with("gimbal.")
        || name == "truth.q_bn"
        || name == "effect.position_weight"
    {
        Box::new(move |r| matches!(r, Role::Param(p) if attitude(p)) || carrier(r))
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

/// The parameter value `v` of slot `s` in the plant's parameter form.
pub(crate) fn to_param(s: &ScalarVar, v: Value) -> ParamValue {
    match (s.kind, v) {
        (_, Value::Real(x)) => ParamValue::Real(x),
        (_, Value::Integer(u)) => ParamValue::Integer(u),
        (_, Value::Boolean(b)) => ParamValue::Bool(b),
        (Kind::Enumeration { items, .. }, Value::Enumeration(i)) => {
            ParamValue::Enum(items[i].to_string())
        }
        (_, Value::Enumeration(i)) => ParamValue::Integer(i as u64),
    }
}
