//! The rins plant as a [`Model`]: every scenario parameter is a parameter (from the plant's own
//! parameter table, [`rins_plant::params`]), the chamber temperature and gimbal commands are
//! inputs, and the increments, table angles, temperatures, true attitude and each effect's
//! contribution are outputs.

use std::sync::OnceLock;

use nalgebra::Vector3;
use rins_plant::effects::{AccelTerm, GyroTerm};
use rins_plant::params::{self, ParamValue};
use rins_plant::thermal::{CHAMBER_MAX_C, CHAMBER_MIN_C, node};
use rins_plant::{GimbalCommand, Plant, PlantConfig};

use crate::model::Model;
use crate::vars::{Causality, Kind, ScalarVar, Value, VariableTable};

/// Inputs, in table order after the parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Input {
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

/// Outputs, in table order after the inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Output {
    Dtheta(usize),
    Dv(usize),
    SampleCount,
    TimeS,
    GimbalOuter,
    GimbalInner,
    GimbalOuterRate,
    GimbalInnerRate,
    GimbalMoving,
    Quaternion(usize),
    Node(usize),
    Chamber,
    DthetaTrue(usize),
    DvTrue(usize),
    Gyro(usize, usize),
    Accel(usize, usize),
    PositionWeight,
}

/// What a slot is.
#[derive(Clone, Debug, PartialEq)]
enum Role {
    Param(String),
    Input(Input),
    Output(Output),
}

struct Table {
    vars: VariableTable,
    roles: Vec<Role>,
    defaults: PlantConfig,
    /// Slot of each input, indexed by `Input as usize` (doStep reads them every step).
    input_slots: Vec<usize>,
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
    let array = params::key_of(&p.path);
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
    // FMI structured names write matrix elements as `a[i,j]`.
    ScalarVar {
        name: p.path.replace("][", ","),
        array,
        kind,
        causality: Causality::Parameter,
        unit,
        start,
        range,
        description: describe(&p.path),
    }
}

fn real(
    name: String,
    array: &str,
    causality: Causality,
    unit: Option<&'static str>,
    start: f64,
    range: Option<(f64, f64)>,
    description: &str,
) -> ScalarVar {
    ScalarVar {
        name,
        array: array.into(),
        kind: Kind::Real,
        causality,
        unit,
        start: Value::Real(start),
        range,
        description: description.into(),
    }
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
    let inp = Causality::Input;
    let mut push = |v: ScalarVar, r: Role| {
        scalars.push(v);
        roles.push(r);
    };
    let boolean = |name: &str, description: &str| ScalarVar {
        name: name.into(),
        array: name.into(),
        kind: Kind::Boolean,
        causality: inp,
        unit: None,
        start: Value::Boolean(false),
        range: None,
        description: description.into(),
    };
    push(
        boolean(
            "input.chamber_override",
            "use input.chamber_temp_c instead of the scenario's chamber temperature",
        ),
        Role::Input(Input::ChamberOverride),
    );
    let chamber0 = defaults.thermal.chamber.temp_c;
    push(
        real(
            "input.chamber_temp_c".into(),
            "input.chamber_temp_c",
            inp,
            Some("degC"),
            chamber0,
            Some((CHAMBER_MIN_C, CHAMBER_MAX_C)),
            "chamber (ambient) temperature when input.chamber_override",
        ),
        Role::Input(Input::ChamberTemp),
    );
    push(
        boolean(
            "input.gimbal_command",
            "drive the table to input.gimbal_outer_deg/inner_deg instead of the rotation scheme",
        ),
        Role::Input(Input::GimbalEnable),
    );
    let angle = Some((-3600.0, 3600.0));
    push(
        real(
            "input.gimbal_outer_deg".into(),
            "input.gimbal_outer_deg",
            inp,
            Some("deg"),
            0.0,
            angle,
            "commanded outer (azimuth) gimbal angle",
        ),
        Role::Input(Input::GimbalOuter),
    );
    push(
        real(
            "input.gimbal_inner_deg".into(),
            "input.gimbal_inner_deg",
            inp,
            Some("deg"),
            0.0,
            angle,
            "commanded inner gimbal angle",
        ),
        Role::Input(Input::GimbalInner),
    );
    push(
        real(
            "input.gimbal_rate_dps".into(),
            "input.gimbal_rate_dps",
            inp,
            Some("deg/s"),
            defaults.scheme.rate_dps,
            Some((1e-6, 100.0)),
            "cruise rate of commanded moves",
        ),
        Role::Input(Input::GimbalRate),
    );
    push(
        ScalarVar {
            name: "input.noise_seed".into(),
            array: "input.noise_seed".into(),
            kind: Kind::Integer,
            causality: inp,
            unit: None,
            start: Value::Integer(0),
            range: Some((0.0, i32::MAX as f64)),
            description: "a new non-zero value restarts every noise stream from this seed at the next step (Monte Carlo from a saved warm state)".into(),
        },
        Role::Input(Input::NoiseSeed),
    );

    let out = Causality::Output;
    let o = |name: String, array: &str, unit: &'static str, d: &str| {
        real(name, array, out, Some(unit), 0.0, None, d)
    };
    for i in 0..3 {
        push(
            o(
                format!("imu.dtheta_rad[{i}]"),
                "imu.dtheta_rad",
                "rad",
                "angular increment over the last communication step (body x, y, z)",
            ),
            Role::Output(Output::Dtheta(i)),
        );
    }
    for i in 0..3 {
        push(
            o(
                format!("imu.dv_mps[{i}]"),
                "imu.dv_mps",
                "m/s",
                "velocity increment over the last communication step (body x, y, z)",
            ),
            Role::Output(Output::Dv(i)),
        );
    }
    push(
        ScalarVar {
            name: "imu.sample_count".into(),
            array: "imu.sample_count".into(),
            kind: Kind::Integer,
            causality: out,
            unit: None,
            start: Value::Integer(0),
            range: None,
            description: "IMU output samples since initialisation (the integer tick)".into(),
        },
        Role::Output(Output::SampleCount),
    );
    push(
        o(
            "imu.time_s".into(),
            "imu.time_s",
            "s",
            "end of the last IMU sample interval (integer tick × internal step)",
        ),
        Role::Output(Output::TimeS),
    );
    push(
        o(
            "gimbal.outer_rad".into(),
            "gimbal.outer_rad",
            "rad",
            "outer (azimuth) gimbal angle",
        ),
        Role::Output(Output::GimbalOuter),
    );
    push(
        o(
            "gimbal.inner_rad".into(),
            "gimbal.inner_rad",
            "rad",
            "inner gimbal angle",
        ),
        Role::Output(Output::GimbalInner),
    );
    push(
        o(
            "gimbal.outer_rate_rps".into(),
            "gimbal.outer_rate_rps",
            "rad/s",
            "outer gimbal rate",
        ),
        Role::Output(Output::GimbalOuterRate),
    );
    push(
        o(
            "gimbal.inner_rate_rps".into(),
            "gimbal.inner_rate_rps",
            "rad/s",
            "inner gimbal rate",
        ),
        Role::Output(Output::GimbalInnerRate),
    );
    push(
        ScalarVar {
            name: "gimbal.moving".into(),
            array: "gimbal.moving".into(),
            kind: Kind::Boolean,
            causality: out,
            unit: None,
            start: Value::Boolean(false),
            range: None,
            description: "the table is moving (false while dwelling)".into(),
        },
        Role::Output(Output::GimbalMoving),
    );
    for i in 0..4 {
        push(
            real(
                format!("truth.q_bn[{i}]"),
                "truth.q_bn",
                out,
                None,
                if i == 0 { 1.0 } else { 0.0 },
                None,
                "true attitude quaternion body→ENU navigation frame (w, x, y, z)",
            ),
            Role::Output(Output::Quaternion(i)),
        );
    }
    for (n, name) in node::NAMES.iter().enumerate() {
        push(
            o(
                format!("thermal.{name}_c"),
                &format!("thermal.{name}_c"),
                "degC",
                "node temperature",
            ),
            Role::Output(Output::Node(n)),
        );
    }
    push(
        o(
            "thermal.chamber_c".into(),
            "thermal.chamber_c",
            "degC",
            "chamber temperature in use",
        ),
        Role::Output(Output::Chamber),
    );
    for i in 0..3 {
        push(
            o(
                format!("truth.dtheta_rad[{i}]"),
                "truth.dtheta_rad",
                "rad",
                "error-free angular increment over the last communication step",
            ),
            Role::Output(Output::DthetaTrue(i)),
        );
    }
    for i in 0..3 {
        push(
            o(
                format!("truth.dv_mps[{i}]"),
                "truth.dv_mps",
                "m/s",
                "error-free velocity increment over the last communication step",
            ),
            Role::Output(Output::DvTrue(i)),
        );
    }
    for (t, term) in GyroTerm::ALL.iter().enumerate() {
        let arr = format!("effect.gyro.{}_rad", term.key());
        for i in 0..3 {
            push(
                o(
                    format!("{arr}[{i}]"),
                    &arr,
                    "rad",
                    "this gyro term's angular increment error over the last IMU sample",
                ),
                Role::Output(Output::Gyro(t, i)),
            );
        }
    }
    for (t, term) in AccelTerm::ALL.iter().enumerate() {
        let arr = format!("effect.accel.{}_mps", term.key());
        for i in 0..3 {
            push(
                o(
                    format!("{arr}[{i}]"),
                    &arr,
                    "m/s",
                    "this accelerometer term's velocity increment error over the last IMU sample",
                ),
                Role::Output(Output::Accel(t, i)),
            );
        }
    }
    push(
        real(
            "effect.position_weight".into(),
            "effect.position_weight",
            out,
            None,
            0.0,
            None,
            "weight of the position-dependent bias (0 Z-up, 1 Z-down, Eq. 9)",
        ),
        Role::Output(Output::PositionWeight),
    );
    let mut input_slots = vec![usize::MAX; Input::COUNT];
    for (slot, r) in roles.iter().enumerate() {
        if let Role::Input(i) = r {
            input_slots[*i as usize] = slot;
        }
    }
    Table {
        vars: VariableTable::new(scalars),
        roles,
        defaults,
        input_slots,
    }
}

fn table() -> &'static Table {
    // Built once from constants: the same table on every call, no mutable global state.
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(build_table)
}

/// The plant as an FMU model.
#[derive(Clone, Debug)]
pub struct RinsModel {
    /// Parameter and input values by slot (outputs are read from the plant).
    values: Vec<Value>,
    plant: Option<Plant>,
    /// Sums over the last communication step.
    dtheta_rad: Vector3<f64>,
    dv_mps: Vector3<f64>,
    dtheta_true_rad: Vector3<f64>,
    dv_true_mps: Vector3<f64>,
    /// Last gimbal command sent to the plant (outer, inner, rate in degrees).
    applied_command: Option<[f64; 3]>,
    /// Last noise seed applied through `input.noise_seed` (0: none).
    applied_noise_seed: u64,
    /// IMU samples in the last communication step (the true increments are summed when > 1).
    steps_in_last: u64,
    /// An input changed since the last step: apply the inputs before stepping (skipping this
    /// when nothing changed keeps doStep within a few ns of the in-process plant).
    inputs_dirty: bool,
}

impl RinsModel {
    fn input(&self, which: Input) -> Value {
        self.values[table().input_slots[which as usize]]
    }

    /// The plant configuration the parameters describe.
    pub fn config(&self) -> Result<PlantConfig, String> {
        let t = table();
        let pairs = t
            .roles
            .iter()
            .zip(&t.vars.scalars)
            .zip(&self.values)
            .filter_map(|((r, s), v)| match r {
                Role::Param(path) if *v != s.start => Some((path.as_str(), to_param(s, *v))),
                _ => None,
            });
        params::apply(&t.defaults, pairs).map_err(|e| e.to_string())
    }

    /// The running plant (after initialisation).
    pub fn plant(&self) -> Option<&Plant> {
        self.plant.as_ref()
    }

    fn apply_inputs(&mut self) -> Result<(), String> {
        let on = |v: Value| matches!(v, Value::Boolean(true));
        let real = |v: Value| if let Value::Real(x) = v { x } else { f64::NAN };
        let chamber =
            on(self.input(Input::ChamberOverride)).then(|| real(self.input(Input::ChamberTemp)));
        let command = on(self.input(Input::GimbalEnable)).then(|| {
            [
                real(self.input(Input::GimbalOuter)),
                real(self.input(Input::GimbalInner)),
                real(self.input(Input::GimbalRate)),
            ]
        });
        let noise_seed = if let Value::Integer(u) = self.input(Input::NoiseSeed) {
            u
        } else {
            0
        };
        let plant = self.plant.as_mut().ok_or("the plant is not initialised")?;
        plant.set_chamber_temp_c(chamber);
        if noise_seed != 0 && noise_seed != self.applied_noise_seed {
            plant.reseed_noise(noise_seed);
            self.applied_noise_seed = noise_seed;
        }
        if let Some(c) = command
            && self.applied_command != Some(c)
        {
            plant.command_gimbal(&GimbalCommand::MoveTo {
                outer_rad: c[0].to_radians(),
                inner_rad: c[1].to_radians(),
                rate_rps: c[2].to_radians(),
            })?;
            self.applied_command = Some(c);
        }
        self.inputs_dirty = false;
        Ok(())
    }

    fn output(&self, o: Output) -> Value {
        let Some(p) = &self.plant else {
            return match o {
                Output::SampleCount => Value::Integer(0),
                Output::GimbalMoving => Value::Boolean(false),
                Output::Quaternion(0) => Value::Real(1.0),
                _ => Value::Real(0.0),
            };
        };
        let tr = p.truth();
        let g = &tr.gimbal;
        Value::Real(match o {
            Output::Dtheta(i) => self.dtheta_rad[i],
            Output::Dv(i) => self.dv_mps[i],
            Output::SampleCount => return Value::Integer(p.samples_done()),
            Output::GimbalMoving => return Value::Boolean(g.moving),
            Output::TimeS => p.time_s(),
            Output::GimbalOuter => g.angles.outer_rad,
            Output::GimbalInner => g.angles.inner_rad,
            Output::GimbalOuterRate => g.outer_rate_rps,
            Output::GimbalInnerRate => g.inner_rate_rps,
            Output::Quaternion(i) => {
                let q = p.attitude_q_bn();
                [q.w, q.i, q.j, q.k][i]
            }
            Output::Node(n) => tr.temps.nodes_c[n],
            Output::Chamber => tr.temps.chamber_c,
            Output::DthetaTrue(i) => {
                if self.steps_in_last > 1 {
                    self.dtheta_true_rad[i]
                } else {
                    tr.dtheta_true_rad[i]
                }
            }
            Output::DvTrue(i) => {
                if self.steps_in_last > 1 {
                    self.dv_true_mps[i]
                } else {
                    tr.dv_true_mps[i]
                }
            }
            Output::Gyro(t, i) => tr.gyro_terms_rad[t][i],
            Output::Accel(t, i) => tr.accel_terms_mps[t][i],
            Output::PositionWeight => tr.position_weight,
        })
    }
}

fn to_param(s: &ScalarVar, v: Value) -> ParamValue {
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

impl Model for RinsModel {
    const NAME: &'static str = "RinsImu";

    fn table() -> &'static VariableTable {
        &table().vars
    }

    fn new() -> Self {
        Self {
            values: table().vars.scalars.iter().map(|s| s.start).collect(),
            plant: None,
            dtheta_rad: Vector3::zeros(),
            dv_mps: Vector3::zeros(),
            dtheta_true_rad: Vector3::zeros(),
            dv_true_mps: Vector3::zeros(),
            applied_command: None,
            applied_noise_seed: 0,
            inputs_dirty: true,
            steps_in_last: 1,
        }
    }

    fn set(&mut self, slot: usize, v: Value) -> Result<(), String> {
        self.values[slot] = v;
        self.inputs_dirty |= matches!(table().roles[slot], Role::Input(_));
        Ok(())
    }

    fn get(&self, slot: usize) -> Value {
        match &table().roles[slot] {
            Role::Output(o) => self.output(*o),
            _ => self.values[slot],
        }
    }

    fn initialize(&mut self) -> Result<(), String> {
        let cfg = self.config()?;
        let plant = Plant::new(&cfg).map_err(|errs| {
            errs.iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("; ")
        })?;
        self.plant = Some(plant);
        self.apply_inputs()
    }

    fn internal_rate_hz(&self) -> f64 {
        self.plant.as_ref().map_or(100.0, |p| p.config().rate_hz)
    }

    fn advance(&mut self, n: u64) -> Result<(), String> {
        if self.inputs_dirty {
            self.apply_inputs()?;
        }
        let plant = self.plant.as_mut().ok_or("the plant is not initialised")?;
        let s = plant.step();
        (self.dtheta_rad, self.dv_mps) = (s.dtheta_rad, s.dv_mps);
        self.steps_in_last = n;
        if n > 1 {
            // Sums over the communication step; with one sample the truth is read directly.
            let mut dth_true = plant.truth().dtheta_true_rad;
            let mut dv_true = plant.truth().dv_true_mps;
            for _ in 1..n {
                let s = plant.step();
                self.dtheta_rad += s.dtheta_rad;
                self.dv_mps += s.dv_mps;
                dth_true += plant.truth().dtheta_true_rad;
                dv_true += plant.truth().dv_true_mps;
            }
            (self.dtheta_true_rad, self.dv_true_mps) = (dth_true, dv_true);
        }
        Ok(())
    }

    fn save(&self) -> Vec<u8> {
        let mut w = Vec::new();
        let u64w = |w: &mut Vec<u8>, x: u64| w.extend_from_slice(&x.to_le_bytes());
        u64w(&mut w, self.values.len() as u64);
        for v in &self.values {
            let (tag, bits) = match *v {
                Value::Real(x) => (0, x.to_bits()),
                Value::Integer(u) => (1, u),
                Value::Boolean(b) => (2, b as u64),
                Value::Enumeration(i) => (3, i as u64),
            };
            u64w(&mut w, tag);
            u64w(&mut w, bits);
        }
        for x in self
            .dtheta_rad
            .iter()
            .chain(&self.dv_mps)
            .chain(&self.dtheta_true_rad)
            .chain(&self.dv_true_mps)
        {
            u64w(&mut w, x.to_bits());
        }
        u64w(&mut w, self.applied_command.is_some() as u64);
        for x in self.applied_command.unwrap_or_default() {
            u64w(&mut w, x.to_bits());
        }
        u64w(&mut w, self.applied_noise_seed);
        u64w(&mut w, self.steps_in_last);
        if let Some(p) = &self.plant {
            w.extend(p.serialize_state());
        }
        w
    }

    fn restore(&mut self, bytes: &[u8]) -> Result<(), String> {
        let mut pos = 0;
        let mut next = || -> Result<u64, String> {
            let b = bytes.get(pos..pos + 8).ok_or("truncated state")?;
            pos += 8;
            Ok(u64::from_le_bytes(b.try_into().expect("8 bytes")))
        };
        let n = next()? as usize;
        if n != table().vars.scalars.len() {
            return Err(format!(
                "state has {n} variables, this FMU has {}",
                table().vars.scalars.len()
            ));
        }
        let mut values = Vec::with_capacity(n);
        for _ in 0..n {
            let (tag, bits) = (next()?, next()?);
            values.push(match tag {
                0 => Value::Real(f64::from_bits(bits)),
                1 => Value::Integer(bits),
                2 => Value::Boolean(bits != 0),
                _ => Value::Enumeration(bits as usize),
            });
        }
        let mut sums = [0.0; 12];
        for s in sums.iter_mut() {
            *s = f64::from_bits(next()?);
        }
        let has_cmd = next()? != 0;
        let cmd = [
            f64::from_bits(next()?),
            f64::from_bits(next()?),
            f64::from_bits(next()?),
        ];
        let applied_noise_seed = next()?;
        let steps_in_last = next()?;
        self.values = values;
        self.dtheta_rad = Vector3::new(sums[0], sums[1], sums[2]);
        self.dv_mps = Vector3::new(sums[3], sums[4], sums[5]);
        self.dtheta_true_rad = Vector3::new(sums[6], sums[7], sums[8]);
        self.dv_true_mps = Vector3::new(sums[9], sums[10], sums[11]);
        self.applied_command = has_cmd.then_some(cmd);
        self.applied_noise_seed = applied_noise_seed;
        self.steps_in_last = steps_in_last;
        self.inputs_dirty = true;
        let rest = &bytes[pos..];
        self.plant = if rest.is_empty() {
            None
        } else {
            let cfg = self.config()?;
            Some(Plant::from_serialized_state(&cfg, rest).map_err(|e| e.to_string())?)
        };
        Ok(())
    }
}

/// Every scenario key the FMU cannot carry as a parameter, with what to use instead.
pub const NOT_PARAMETERS: [(&str, &str); 2] = [
    (
        "scheme.steps",
        "gimbal commands (input.gimbal_command, input.gimbal_outer_deg/inner_deg)",
    ),
    (
        "thermal.chamber.profile",
        "the input input.chamber_temp_c with input.chamber_override = true",
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_fixed_shape_scenario_key_is_a_parameter_and_round_trips() {
        let cfg = rins_plant::presets::paper_16pos_config();
        let t = table();
        let n_params = t
            .roles
            .iter()
            .filter(|r| matches!(r, Role::Param(_)))
            .count();
        assert_eq!(
            n_params,
            params::flatten(&cfg).len(),
            "the paper config has no list parameters"
        );
        // Setting every parameter to its start value reproduces the configuration.
        let m = RinsModel::new();
        assert_eq!(m.config().unwrap(), cfg);
        // Changing one parameter changes exactly that key.
        let mut m = RinsModel::new();
        let slot = t.vars.slot("sensor.gyro.bias.dph[2]").unwrap();
        m.set(slot, Value::Real(0.02)).unwrap();
        assert_eq!(m.config().unwrap().sensor.gyro.bias.dph, [0.01, 0.01, 0.02]);
        let kind = t.vars.slot("scheme.kind").unwrap();
        m.set(kind, Value::Enumeration(1)).unwrap();
        assert_eq!(
            m.config().unwrap().scheme.kind,
            rins_plant::table::SchemeKind::EightPosition
        );
    }
}
