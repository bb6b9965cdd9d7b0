//! A new FMU model needs nothing outside its own table and `Model` impl: a one-axis rate gyro
//! whose parameters are three keys of the plant's parameter table (through this crate), with
//! one input row and one output row. The generic layer writes its modelDescription.xml and
//! `.fmu`, and runs it through the generic instance (state machine, range checks,
//! enumeration codes, saved state) with no line of FMI code of its own.

use std::sync::OnceLock;

use rins_fmi::instance::Instance;
use rins_fmi::model::{Model, ModelInfo};
use rins_fmi::standard::FmiVersion;
use rins_fmi::state::{StateReader, StateWriter};
use rins_fmi::vars::{Causality, Kind, OutputDecl, Value, VariableTable};
use rins_fmi_plant::{InputRow, PlantParams};

/// The scenario keys the model exposes: the gyro biases (an FMI 3 array is whole; the model
/// reads the z element), the rate and one enumeration.
const PARAMETERS: [&str; 3] = ["sensor.gyro.bias.dph", "run.rate_hz", "scheme.axis"];

/// The one input.
const RATE: InputRow = InputRow {
    name: "input.rate_dps",
    kind: Kind::Real,
    causality: Causality::Input,
    unit: Some("deg/s"),
    start: |_| Value::Real(0.0),
    range: Some((-500.0, 500.0)),
    description: "true rate about the axis",
};

struct Table {
    vars: VariableTable,
    params: PlantParams,
    rate: usize,
    angle: usize,
}

fn table() -> &'static Table {
    static T: OnceLock<Table> = OnceLock::new();
    T.get_or_init(|| {
        let mut scalars = Vec::new();
        let params = PlantParams::push_vars(
            rins_plant::presets::paper_16pos_config(),
            |p| PARAMETERS.contains(&rins_plant::params::key_of(p).as_str()),
            &mut scalars,
        );
        let rate = scalars.len();
        scalars.push(RATE.var(&params.defaults));
        let angle = scalars.len();
        scalars.extend(
            OutputDecl {
                name: "angle_deg".into(),
                len: None,
                kind: Kind::Real,
                unit: Some("deg"),
                start: vec![Value::Real(0.0)],
                description: "measured angle: true rate plus bias, integrated".into(),
            }
            .scalars(),
        );
        Table {
            vars: VariableTable::with_enum_codes(scalars),
            params,
            rate,
            angle,
        }
    })
}

/// The model: values by slot, and once initialised the bias, rate and angle.
#[derive(Clone, Debug)]
struct OneAxis {
    values: Vec<Value>,
    /// (bias °/h, internal rate Hz) from the parameters.
    running: Option<(f64, f64)>,
    angle_deg: f64,
}

impl Model for OneAxis {
    const INFO: ModelInfo = ModelInfo {
        fmi2_id: "OneAxis",
        fmi3_id: "OneAxis3",
        description: "one-axis rate gyro (test model)",
        stop_time_s: 10.0,
        step_size_s: 0.1,
    };
    fn table() -> &'static VariableTable {
        &table().vars
    }
    fn new() -> Self {
        Self {
            values: table().vars.scalars.iter().map(|s| s.start).collect(),
            running: None,
            angle_deg: 0.0,
        }
    }
    fn set(&mut self, slot: usize, v: Value) -> Result<(), String> {
        self.values[slot] = v;
        Ok(())
    }
    fn get(&self, slot: usize) -> Value {
        if slot == table().angle {
            Value::Real(self.angle_deg)
        } else {
            self.values[slot]
        }
    }
    fn initialize(&mut self) -> Result<(), String> {
        let t = table();
        let cfg = t.params.config(&t.vars.scalars, &self.values)?;
        self.running = Some((cfg.sensor.gyro.bias.dph[2], cfg.rate_hz));
        Ok(())
    }
    fn internal_rate_hz(&self) -> f64 {
        self.running.map_or(100.0, |(_, hz)| hz)
    }
    fn advance(&mut self, n: u64) -> Result<(), String> {
        let (bias_dph, hz) = self.running.ok_or("not initialised")?;
        let Value::Real(rate_dps) = self.values[table().rate] else {
            return Err("input.rate_dps is not a number".into());
        };
        for _ in 0..n {
            self.angle_deg += (rate_dps + bias_dph / 3600.0) / hz;
        }
        Ok(())
    }
    fn save(&self, w: &mut StateWriter) {
        w.values(&self.values);
        let (bias, hz) = self.running.unwrap_or((f64::NAN, f64::NAN));
        w.u64(self.running.is_some() as u64);
        w.f64(bias);
        w.f64(hz);
        w.f64(self.angle_deg);
    }
    fn restore(&mut self, r: &mut StateReader<'_>) -> Result<(), String> {
        self.values = r.values(&table().vars)?;
        let running = r.u64()? != 0;
        let (bias, hz) = (r.f64()?, r.f64()?);
        self.running = running.then_some((bias, hz));
        self.angle_deg = r.f64()?;
        Ok(())
    }
}

fn slot(name: &str) -> usize {
    table()
        .vars
        .slot(name)
        .unwrap_or_else(|| panic!("{name} is no variable"))
}

fn angle(inst: &Instance<OneAxis>) -> f64 {
    match inst.get_slot(table().angle) {
        Value::Real(x) => x,
        v => panic!("angle_deg: {v:?}"),
    }
}

#[test]
fn its_model_description_and_fmu_come_from_the_table_alone() {
    for (version, id) in [(FmiVersion::V2, "OneAxis"), (FmiVersion::V3, "OneAxis3")] {
        let (xml, token) = rins_fmi::fmu::description::<OneAxis>(version);
        for needle in [
            format!("modelIdentifier=\"{id}\""),
            "name=\"sensor.gyro.bias.dph[2]\"".into(),
            "name=\"run.rate_hz\"".into(),
            "name=\"input.rate_dps\"".into(),
            "name=\"angle_deg\"".into(),
            // The enumeration under its own type name, with its Integer code.
            "name=\"GimbalAxis\"".into(),
            "name=\"scheme.axis_code\"".into(),
            token.clone(),
        ] {
            assert!(
                xml.contains(&needle),
                "{version:?}: {needle} missing:\n{xml}"
            );
        }
        // Nothing of the other models leaks in.
        assert!(
            !xml.contains("SchemeKind") && !xml.contains("carrier."),
            "{xml}"
        );

        // Packed beside a stand-in binary, modelDescription.xml is the description above.
        let dir = std::env::temp_dir().join(format!(
            "rins-fmi-plant-one-axis-{}-{id}",
            std::process::id()
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let lib = dir.join("libone_axis.so");
        std::fs::write(&lib, b"not a library: packaging only copies it").unwrap();
        let fmu = rins_fmi::package::build_fmu::<OneAxis>(version, &lib, &dir).unwrap();
        let entries = rins_fmi::zip::read(&std::fs::read(&fmu).unwrap()).unwrap();
        let md = entries
            .iter()
            .find(|(n, _)| n == "modelDescription.xml")
            .expect("modelDescription.xml in the .fmu");
        assert_eq!(md.1, xml.as_bytes());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
fn it_runs_through_the_generic_instance_as_the_closed_form_says() {
    let mut inst = Instance::<OneAxis>::new();
    inst.enter_initialization().unwrap();
    // 3.6 °/h = 0.001 °/s; 50 Hz instead of the plant's 100.
    inst.set_slot(slot("sensor.gyro.bias.dph[2]"), Value::Real(3.6))
        .unwrap();
    inst.set_slot(slot("run.rate_hz"), Value::Real(50.0))
        .unwrap();
    inst.set_slot(slot("input.rate_dps"), Value::Real(0.5))
        .unwrap();
    // A parameter out of its range (the plant's own, ±100 °/h) is refused, naming it.
    let e = inst
        .set_slot(slot("sensor.gyro.bias.dph[2]"), Value::Real(1000.0))
        .unwrap_err();
    assert!(
        e.message.contains("sensor.gyro.bias.dph[2]") && e.message.contains("[-100, 100]"),
        "{}",
        e.message
    );
    // The refused set must not count: start again from the good values.
    let mut inst = Instance::<OneAxis>::new();
    inst.enter_initialization().unwrap();
    for (name, v) in [
        ("sensor.gyro.bias.dph[2]", Value::Real(3.6)),
        ("run.rate_hz", Value::Real(50.0)),
        ("input.rate_dps", Value::Real(0.5)),
        // The enumeration's Integer code sets the enumeration.
        ("scheme.axis_code", Value::Integer(2)),
    ] {
        inst.set_slot(slot(name), v).unwrap();
    }
    assert_eq!(inst.get_slot(slot("scheme.axis")), Value::Enumeration(1));
    inst.exit_initialization().unwrap();
    // A communication step that is not a whole number of 1/50 s steps is refused.
    assert!(inst.do_step(0.0, 0.01).is_err());
    let mut t = 0.0;
    for _ in 0..10 {
        inst.do_step(t, 0.1).unwrap();
        t += 0.1;
    }
    // 1 s at 0.5 °/s plus 0.001 °/s of bias (50 additions of 0.01002 °: rounding only).
    assert!((angle(&inst) - 0.501).abs() < 1e-12, "{}", angle(&inst));
    let saved = inst.serialize();
    inst.set_slot(slot("input.rate_dps"), Value::Real(-0.25))
        .unwrap();
    for _ in 0..10 {
        inst.do_step(t, 0.1).unwrap();
        t += 0.1;
    }
    assert!(
        (angle(&inst) - (0.501 - 0.249)).abs() < 1e-12,
        "{}",
        angle(&inst)
    );
    // The saved state resumes where it was, with the input it had.
    let mut back = Instance::<OneAxis>::deserialize(&saved).unwrap();
    back.do_step(1.0, 1.0).unwrap();
    assert!((angle(&back) - 1.002).abs() < 1e-12, "{}", angle(&back));
}
