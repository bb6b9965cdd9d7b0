//! # rins-imu-fmu
//!
//! The rins plant as a [`rins_fmi::model::Model`], named `RinsImu` (FMI 2) / `RinsImu3` (FMI 3):
//! every fixed-shape scenario parameter is a parameter (from the plant's own parameter table),
//! the chamber temperature, gimbal commands and a noise reseed are inputs ([`table`]), and the
//! outputs are the rows of the output table ([`outputs`]). The FMI code is generic and lives in
//! `rins-fmi`, `rins-fmi2` and `rins-fmi3`; the shared libraries are the one-line crates
//! `rins-imu-fmi2` and `rins-imu-fmi3` beside this one.

use std::sync::OnceLock;

use nalgebra::Vector3;
use rins_fmi::model::{Model, ModelInfo};
use rins_fmi::standard::FmiVersion;
use rins_fmi::state::{StateReader, StateWriter};
use rins_fmi::vars::{Value, VariableTable};
use rins_plant::carrier::CarrierKind;
use rins_plant::carrier::external::CarrierSample;
use rins_plant::{GimbalCommand, ImuSample, Plant, PlantConfig};

pub mod carrier_inputs;
pub mod declared;
pub mod outputs;
pub mod reference;
pub mod slots;
pub mod ssv;
mod table;

use outputs::{View, outputs};
use table::{Input, Role, table};

/// File name of the shared library cargo builds for `version` (the crates `rins-imu-fmi2` /
/// `rins-imu-fmi3`).
pub fn library_file(version: FmiVersion) -> &'static str {
    match version {
        FmiVersion::V2 => "librins_imu_fmi2.so",
        FmiVersion::V3 => "librins_imu_fmi3.so",
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

/// The plant as an FMU model.
#[derive(Clone, Debug)]
pub struct RinsImu {
    /// Parameter and input values by slot (outputs are read from the plant).
    values: Vec<Value>,
    plant: Option<Plant>,
    /// The last IMU sample, its increments summed over the last communication step.
    sample: Option<ImuSample>,
    /// True increments summed over the last communication step (used when it held more than
    /// one sample; with one, the plant's truth is read directly).
    dtheta_true_rad: Vector3<f64>,
    dv_true_mps: Vector3<f64>,
    /// IMU samples in the last communication step.
    steps_in_last: u64,
    /// Last gimbal command sent to the plant (outer, inner, rate in degrees).
    applied_command: Option<[f64; 3]>,
    /// Last noise seed applied through `input.noise_seed` (0: none).
    applied_noise_seed: u64,
    /// An input changed since the last step: apply the inputs before stepping (skipping this
    /// when nothing changed keeps doStep within a few ns of the in-process plant).
    inputs_dirty: bool,
    /// The chamber input the plant started from (`input.chamber_override` set before the end
    /// of initialisation): part of the configuration, so a restored state rebuilds it.
    start_chamber_c: Option<f64>,
    /// Before the end of initialisation: the plant the current parameters and inputs would
    /// start, built on the first read in initialization mode, so outputs read there are the
    /// initial values (the thermal steady state, the table's start angles), not zeros.
    preview: OnceLock<Option<Box<Plant>>>,
    /// With `carrier.external_inputs`: the carrier sample the plant is at (the inputs at the
    /// end of the last step, or of initialisation), the start of the next step's segment.
    carrier_at: Option<CarrierSample>,
    /// The last doStep was refused: the increments (outputs marked
    /// [`outputs::Output::per_step`]) read NaN until a step is taken.
    step_refused: bool,
}

impl RinsImu {
    fn input(&self, which: Input) -> Value {
        self.values[table().input_slots[which as usize]]
    }

    /// The chamber temperature the inputs ask for (`None`: the parameter's).
    fn chamber_input_c(&self) -> Option<f64> {
        match (
            self.input(Input::ChamberOverride),
            self.input(Input::ChamberTemp),
        ) {
            (Value::Boolean(true), Value::Real(x)) => Some(x),
            _ => None,
        }
    }

    /// The configuration the plant starts from: the parameters, with the chamber input set
    /// before the end of initialisation as the initial chamber temperature (so the thermal
    /// network starts in its steady state at that temperature).
    fn start_config(&self, chamber_c: Option<f64>) -> Result<PlantConfig, String> {
        let mut cfg = self.config()?;
        if let Some(c) = chamber_c {
            cfg.thermal.chamber.temp_c = c;
        }
        Ok(cfg)
    }

    fn build_plant(cfg: &PlantConfig, carrier: Option<&CarrierSample>) -> Result<Plant, String> {
        if carrier.is_some() {
            check_external_carrier(cfg)?;
        }
        let mut p = Plant::new(cfg).map_err(|errs| {
            errs.iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("; ")
        })?;
        if let Some(c) = carrier {
            p.attach_external_carrier(c)?;
        }
        Ok(p)
    }

    /// The carrier sample of the carrier inputs when `carrier.external_inputs` is on.
    fn carrier_input(&self) -> Option<CarrierSample> {
        let t = table();
        let on = self.values[t.carrier_switch] == Value::Boolean(true);
        let first = t.carrier_switch + 1;
        on.then(|| {
            carrier_inputs::sample(&self.values[first..first + carrier_inputs::INPUTS.len()])
        })
    }

    /// The plant configuration the parameters describe.
    pub fn config(&self) -> Result<PlantConfig, String> {
        let t = table();
        let mut cfg = t.params.config(&t.vars.scalars, &self.values)?;
        // Declared effects from the slots (none enabled: the configuration is unchanged).
        let slots = declared::read(
            t.roles
                .iter()
                .zip(&self.values)
                .filter_map(|(r, v)| match r {
                    Role::Declared(d) => Some((d, *v)),
                    _ => None,
                }),
        );
        declared::apply(&mut cfg, &slots)?;
        Ok(cfg)
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

    fn view<'a>(&'a self, plant: &'a Plant) -> View<'a> {
        View {
            plant,
            truth: plant.truth(),
            sample: self.sample.as_ref(),
            true_sums: (self.steps_in_last > 1)
                .then_some((&self.dtheta_true_rad, &self.dv_true_mps)),
        }
    }
}

/// With `carrier.external_inputs` the carrier inputs are the whole carrier: a carrier of the
/// FMU's own (`carrier.kind` ship or trajectory) cannot be honoured beside them, so it is an
/// error naming both parameters rather than a ship silently replaced by the inputs.
fn check_external_carrier(cfg: &PlantConfig) -> Result<(), String> {
    let kind = match cfg.carrier.kind {
        CarrierKind::Static => return Ok(()),
        CarrierKind::Ship => "ship",
        CarrierKind::Trajectory => "trajectory",
    };
    let code = rins_plant::params::enum_choices("carrier.kind")
        .and_then(|items| items.iter().position(|x| *x == kind))
        .map_or(0, |i| i + 1);
    Err(format!(
        "carrier.kind = {kind} (carrier.kind_code = {code}) with {} = true: the carrier inputs are the whole carrier, so the FMU cannot also run a {kind} of its own; set carrier.kind = static (carrier.kind_code = 1) to drive the carrier from the inputs, or {} = false to run the {kind}",
        carrier_inputs::SWITCH,
        carrier_inputs::SWITCH
    ))
}

impl Model for RinsImu {
    const INFO: ModelInfo = ModelInfo {
        fmi2_id: "RinsImu",
        fmi3_id: "RinsImu3",
        description: "Dual-axis rotating RLG IMU (Seo et al., Sensors 2022, 22, 8355): 16-position table, Earth, thermal network and every gyro/accelerometer error term",
        // The paper's headline experiment: one week at 100 Hz.
        stop_time_s: 604_800.0,
        step_size_s: 0.01,
    };

    fn table() -> &'static VariableTable {
        &table().vars
    }

    fn documentation() -> String {
        let mut s = String::from(
            "Default experiment: the paper's headline scenario (one week, 100 Hz, 16-position scheme, Table 3 sensors).\n\nScenario keys that are lists cannot be fixed FMU parameters:\n\n",
        );
        for (k, instead) in NOT_PARAMETERS {
            s.push_str(&format!("- `{k}`: use {instead}\n"));
        }
        s
    }

    fn new() -> Self {
        Self {
            values: table().vars.scalars.iter().map(|s| s.start).collect(),
            plant: None,
            sample: None,
            dtheta_true_rad: Vector3::zeros(),
            dv_true_mps: Vector3::zeros(),
            steps_in_last: 1,
            applied_command: None,
            applied_noise_seed: 0,
            inputs_dirty: true,
            start_chamber_c: None,
            preview: OnceLock::new(),
            carrier_at: None,
            step_refused: false,
        }
    }

    fn set(&mut self, slot: usize, v: Value) -> Result<(), String> {
        self.values[slot] = v;
        self.inputs_dirty |= matches!(table().roles[slot], Role::Input(_));
        if self.plant.is_none() {
            self.preview = OnceLock::new();
        }
        Ok(())
    }

    fn get(&self, slot: usize) -> Value {
        match (&table().roles[slot], &self.plant) {
            // After a refused step, also when the plant was never built (initialization
            // failed and a master stepped on regardless): per-step sums read NaN, not the
            // initial zeros a master ignoring the status would take as a real step.
            (Role::Output(k, _), _) if self.step_refused && outputs()[*k].per_step => {
                Value::Real(f64::NAN)
            }
            (Role::Output(k, i), Some(p)) => (outputs()[*k].read)(&self.view(p), *i),
            (Role::Output(k, i), None) => {
                // Initialization mode: the initial values of the plant the parameters and
                // inputs describe (start values if they do not describe one: exiting
                // initialization mode then says why).
                let preview = self.preview.get_or_init(|| {
                    self.start_config(self.chamber_input_c())
                        .and_then(|c| Self::build_plant(&c, self.carrier_input().as_ref()))
                        .ok()
                        .map(Box::new)
                });
                match preview {
                    Some(p) => (outputs()[*k].read)(&self.view(p), *i),
                    None => self.values[slot],
                }
            }
            _ => self.values[slot],
        }
    }

    fn initialize(&mut self) -> Result<(), String> {
        let chamber = self.chamber_input_c();
        let carrier = self.carrier_input();
        let plant = Self::build_plant(&self.start_config(chamber)?, carrier.as_ref())?;
        self.start_chamber_c = chamber;
        self.carrier_at = carrier;
        self.plant = Some(plant);
        self.preview = OnceLock::new();
        self.apply_inputs()
    }

    fn internal_rate_hz(&self) -> f64 {
        self.plant.as_ref().map_or(100.0, |p| p.config().rate_hz)
    }

    fn advance(&mut self, n: u64) -> Result<(), String> {
        if self.inputs_dirty {
            self.apply_inputs()?;
        }
        // The carrier inputs are the carrier at the end of this step (`carrier.external_inputs`
        // is fixed after initialisation, so it is on exactly when `carrier_at` is set).
        let end = self.carrier_at.and(self.carrier_input());
        let plant = self.plant.as_mut().ok_or("the plant is not initialised")?;
        if let (Some(start), Some(end)) = (self.carrier_at, end) {
            // A refused sample leaves the plant as it was.
            plant.drive_carrier(&start, &end, n)?;
            self.carrier_at = Some(end);
        }
        let mut s = plant.step();
        self.steps_in_last = n;
        if n > 1 {
            // Sums over the communication step; with one sample the truth is read directly.
            let (mut dth, mut dv) = (s.dtheta_rad, s.dv_mps);
            let mut dth_true = plant.truth().dtheta_true_rad;
            let mut dv_true = plant.truth().dv_true_mps;
            for _ in 1..n {
                s = plant.step();
                dth += s.dtheta_rad;
                dv += s.dv_mps;
                dth_true += plant.truth().dtheta_true_rad;
                dv_true += plant.truth().dv_true_mps;
            }
            (s.dtheta_rad, s.dv_mps) = (dth, dv);
            (self.dtheta_true_rad, self.dv_true_mps) = (dth_true, dv_true);
        }
        self.sample = Some(s);
        self.step_refused = false;
        Ok(())
    }

    fn step_refused(&mut self) {
        self.step_refused = true;
    }

    fn save(&self, w: &mut StateWriter) {
        w.values(&self.values);
        // The last sample, by the fields the outputs carry (rebuilt on restore).
        w.u64(self.sample.is_some() as u64);
        if let Some(s) = &self.sample {
            for o in outputs() {
                if let Some(f) = &o.sample_field {
                    (0..o.decl.count()).for_each(|i| w.f64((f.get)(s, i)));
                }
            }
        }
        for x in self.dtheta_true_rad.iter().chain(&self.dv_true_mps) {
            w.f64(*x);
        }
        w.u64(self.steps_in_last);
        w.u64(self.applied_command.is_some() as u64);
        self.applied_command
            .unwrap_or_default()
            .iter()
            .for_each(|x| w.f64(*x));
        w.u64(self.applied_noise_seed);
        w.u64(self.start_chamber_c.is_some() as u64);
        w.f64(self.start_chamber_c.unwrap_or_default());
        // The external carrier sample the plant is at (rebuilt on restore: the plant's codec
        // knows only the carriers its configuration describes).
        w.u64(self.carrier_at.is_some() as u64);
        let c = self.carrier_at.unwrap_or(CarrierSample {
            lat_deg: 0.0,
            lon_deg: 0.0,
            height_m: 0.0,
            v_enu_mps: [0.0; 3],
            q_cn: [0.0; 4],
        });
        for x in [c.lat_deg, c.lon_deg, c.height_m]
            .iter()
            .chain(&c.v_enu_mps)
            .chain(&c.q_cn)
        {
            w.f64(*x);
        }
        w.u64(self.step_refused as u64);
        // The plant in its own codec (it checks the configuration fingerprint on restore).
        w.bytes(
            &self
                .plant
                .as_ref()
                .map_or(Vec::new(), Plant::serialize_state),
        );
    }

    fn restore(&mut self, r: &mut StateReader<'_>) -> Result<(), String> {
        // A corrupted state must not put a value of the wrong kind, out of range or past an
        // enumeration's items into a slot (that indexed out of bounds; tests/fmi_property.rs).
        self.values = r.values(&table().vars)?;
        let mut fields = Vec::new();
        if r.u64()? != 0 {
            for o in outputs().iter().filter(|o| o.sample_field.is_some()) {
                for i in 0..o.decl.count() {
                    fields.push((o, i, r.f64()?));
                }
            }
        }
        let mut sums = [0.0; 6];
        for x in sums.iter_mut() {
            *x = r.f64()?;
        }
        self.dtheta_true_rad = Vector3::new(sums[0], sums[1], sums[2]);
        self.dv_true_mps = Vector3::new(sums[3], sums[4], sums[5]);
        self.steps_in_last = r.u64()?;
        let has_cmd = r.u64()? != 0;
        let cmd = [r.f64()?, r.f64()?, r.f64()?];
        self.applied_command = has_cmd.then_some(cmd);
        self.applied_noise_seed = r.u64()?;
        let has_start_chamber = r.u64()? != 0;
        let start_chamber_c = r.f64()?;
        self.start_chamber_c = has_start_chamber.then_some(start_chamber_c);
        self.preview = OnceLock::new();
        self.inputs_dirty = true;
        let has_carrier = r.u64()? != 0;
        let mut x = [0.0; 10];
        for v in x.iter_mut() {
            *v = r.f64()?;
        }
        self.carrier_at = has_carrier.then(|| carrier_inputs::sample(&x.map(Value::Real)));
        self.step_refused = r.u64()? != 0;
        let plant = r.bytes()?;
        if plant.is_empty() {
            (self.plant, self.sample) = (None, None);
            return Ok(());
        }
        let cfg = self.start_config(self.start_chamber_c)?;
        let mut plant = Plant::from_serialized_state(&cfg, plant).map_err(|e| e.to_string())?;
        if let Some(c) = &self.carrier_at {
            plant.attach_external_carrier(c)?;
        }
        self.plant = Some(plant);
        self.sample = if fields.is_empty() {
            None
        } else {
            // A sample of the right shape, then every field the outputs carry (the model reads
            // its last sample by these fields only).
            let mut s = ImuSample::default();
            for (o, i, x) in fields {
                let f = o.sample_field.as_ref().expect("filtered on sample fields");
                (f.set)(&mut s, i, x);
            }
            Some(s)
        };
        Ok(())
    }
}

#[cfg(test)]
mod tests;
