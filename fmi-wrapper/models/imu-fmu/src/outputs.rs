//! The output table: every output of the IMU FMU declared once, as a row (name, length, unit,
//! description, how to read it from the plant, and where an importer puts it back). The
//! modelDescription, the variable list in docs/fmu.md and `rins fmu run` (which rebuilds the
//! [`ImuSample`] and [`Truth`] the sinks take) all use these rows: an output name is typed once,
//! here. A new measured output of [`ImuSample`] is one [`sample_real`] row.

use std::sync::{Arc, OnceLock};

use nalgebra::Vector3;
use rins_fmi::vars::{Kind, OutputDecl, Value};
use rins_plant::carrier::run::CarrierRun;
use rins_plant::carrier::{Carrier, CarrierState, CarrierTruth};
use rins_plant::earth::Site;
use rins_plant::effects::{AccelTerm, GyroTerm};
use rins_plant::thermal::node;
use rins_plant::{ConfigError, ImuSample, Plant, PlantConfig, Truth};

/// What a row reads: the plant after the last communication step.
pub struct View<'a> {
    /// The running plant.
    pub plant: &'a Plant,
    /// Its truth at the end of the step.
    pub truth: Truth,
    /// The last IMU sample, its increments summed over the communication step (`None` before
    /// the first step).
    pub sample: Option<&'a ImuSample>,
    /// True increments summed over the communication step when it held more than one sample
    /// (with one, the truth's own are the step's).
    pub true_sums: Option<(&'a Vector3<f64>, &'a Vector3<f64>)>,
}

impl View<'_> {
    /// Error-free angular increment over the communication step, rad.
    pub fn dtheta_true_rad(&self) -> &Vector3<f64> {
        self.true_sums.map_or(&self.truth.dtheta_true_rad, |s| s.0)
    }

    /// Error-free velocity increment over the communication step, m/s.
    pub fn dv_true_mps(&self) -> &Vector3<f64> {
        self.true_sums.map_or(&self.truth.dv_true_mps, |s| s.1)
    }
}

/// What an importer rebuilds from the outputs of one communication step: what the sinks take.
#[derive(Clone, Debug)]
pub struct Record {
    /// The IMU sample.
    pub sample: ImuSample,
    /// The truth.
    pub truth: Truth,
}

impl Record {
    /// A record of the right shape for `cfg`, to be overwritten by the outputs each step; built
    /// from the configuration alone (nothing runs). Every field a row stores starts at its
    /// default ([`ImuSample::default`], [`Truth::default`]) and is stored by the first step's
    /// outputs. The fields no row stores keep what the configuration fixes: the carrier at the
    /// start (the static carrier's site and `[vehicle]` attitude, which every step's truth
    /// holds; a moving carrier's state before its first tick), the table's step index (0: the
    /// first step is in the lead dwell or the first segment) and the declared effects' sums
    /// (zero: no output carries them).
    ///
    /// Errors: `cfg` out of range, or its trajectory file unreadable, worded as [`Plant::new`]
    /// words them.
    pub fn template(cfg: &PlantConfig) -> Result<Self, String> {
        cfg.validate().map_err(|e| {
            e.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join("; ")
        })?;
        Ok(Self {
            sample: ImuSample::default(),
            truth: Truth {
                carrier: start_carrier(cfg)?,
                ..Truth::default()
            },
        })
    }
}

/// The carrier's truth at the start of a run of `cfg`, from the configuration alone. The static
/// carrier's is the site at rest in the `[vehicle]` attitude, what the plant's truth holds at
/// every step. No output carries a moving carrier's truth (`rins fmu run` refuses one), so
/// its record keeps the carrier's state before the first tick, as an unstepped plant's truth.
fn start_carrier(cfg: &PlantConfig) -> Result<CarrierTruth, String> {
    // The plant's tick: a ship's waves and a trajectory's sampling are built on it.
    let tick_s = 1.0 / (cfg.rate_hz * cfg.substeps as f64);
    let carrier = Carrier::new(&cfg.carrier, cfg.seed, tick_s).map_err(|e| {
        ConfigError {
            path: "carrier.trajectory.file".into(),
            expected: "a readable, valid trajectory file (docs/carrier.md)".into(),
            got: e,
        }
        .to_string()
    })?;
    Ok(match carrier {
        None => {
            let site = Site::new(&cfg.site, &cfg.earth);
            CarrierState::at_rest(
                site.lat_rad,
                site.lon_rad,
                site.height_m,
                cfg.vehicle.c_vn(),
            )
            .truth()
        }
        Some(c) => CarrierRun::new(c, cfg).state().truth(),
    })
}

/// How a row reads element `i`.
pub type Read = Box<dyn Fn(&View<'_>, usize) -> Value + Send + Sync>;
/// How a row stores element `i` into a [`Record`] (`None`: the sinks do not take it).
pub type Store = Option<Box<dyn Fn(&mut Record, usize, Value) + Send + Sync>>;

/// Reads element `i` of a sample field.
pub type FieldGet = Arc<dyn Fn(&ImuSample, usize) -> f64 + Send + Sync>;
/// Sets element `i` of a sample field.
pub type FieldSet = Arc<dyn Fn(&mut ImuSample, usize, f64) + Send + Sync>;

/// A field of [`ImuSample`] an output carries: the model keeps the last sample by these (its
/// FMU state saves them), so a new sample field needs no code besides its row.
#[derive(Clone)]
pub struct SampleField {
    /// Element `i` of the field.
    pub get: FieldGet,
    /// Sets element `i`.
    pub set: FieldSet,
}

/// One output variable.
pub struct Output {
    /// Name, type, unit, length, start and description.
    pub decl: OutputDecl,
    /// How to read it.
    pub read: Read,
    /// Where an importer puts it back.
    pub store: Store,
    /// The sample field it is, if it is one.
    pub sample_field: Option<SampleField>,
    /// A sum over the last communication step (an increment): reads NaN after a refused
    /// doStep until the next step is taken ([`increment`]).
    pub per_step: bool,
}

/// `o` marked as an increment over the last step ([`Output::per_step`]).
pub fn increment(mut o: Output) -> Output {
    o.per_step = true;
    o
}

fn real(x: Value) -> f64 {
    if let Value::Real(x) = x { x } else { f64::NAN }
}

fn decl(name: &str, len: Option<usize>, kind: Kind, unit: &'static str, d: &str) -> OutputDecl {
    let start = match kind {
        Kind::Integer => Value::Integer(0),
        Kind::Boolean => Value::Boolean(false),
        _ => Value::Real(0.0),
    };
    OutputDecl {
        name: name.into(),
        len,
        kind,
        unit: (!unit.is_empty()).then_some(unit),
        start: vec![start],
        description: d.into(),
    }
}

/// A Real output read from the plant's view (`len` elements, or a scalar for `None`).
pub fn plant_real(
    name: &str,
    len: Option<usize>,
    unit: &'static str,
    description: &str,
    read: impl Fn(&View<'_>, usize) -> f64 + Send + Sync + 'static,
    store: impl Fn(&mut Record, usize, f64) + Send + Sync + 'static,
) -> Output {
    Output {
        decl: decl(name, len, Kind::Real, unit, description),
        read: Box::new(move |v, i| Value::Real(read(v, i))),
        store: Some(Box::new(move |r, i, x| store(r, i, real(x)))),
        sample_field: None,
        per_step: false,
    }
}

/// A Real output read from the last IMU sample (0 before the first step).
pub fn sample_real(
    name: &str,
    len: Option<usize>,
    unit: &'static str,
    description: &str,
    read: impl Fn(&ImuSample, usize) -> f64 + Clone + Send + Sync + 'static,
    store: impl Fn(&mut ImuSample, usize, f64) + Clone + Send + Sync + 'static,
) -> Output {
    let field = SampleField {
        get: Arc::new(read.clone()),
        set: Arc::new(store.clone()),
    };
    Output {
        decl: decl(name, len, Kind::Real, unit, description),
        // Its own copy of the reader: one dynamic call per read on the doStep path.
        read: Box::new(move |v, i| {
            Value::Real(match v.sample {
                Some(s) => read(s, i),
                // Before the first step (initialization mode included) the unit's readings of
                // its initial state: a master initialising a controller from them reads the
                // start temperatures and angles, not zeros.
                None => read(&v.plant.start_sample(), i),
            })
        }),
        store: Some(Box::new(move |r, i, x| store(&mut r.sample, i, real(x)))),
        sample_field: Some(field),
        per_step: false,
    }
}

fn build() -> Vec<Output> {
    let mut rows = vec![
        increment(sample_real(
            "imu.dtheta_rad",
            Some(3),
            "rad",
            "angular increment over the last communication step (body x, y, z)",
            |s, i| s.dtheta_rad[i],
            |s, i, x| s.dtheta_rad[i] = x,
        )),
        increment(sample_real(
            "imu.dv_mps",
            Some(3),
            "m/s",
            "velocity increment over the last communication step (body x, y, z)",
            |s, i| s.dv_mps[i],
            |s, i, x| s.dv_mps[i] = x,
        )),
        Output {
            decl: decl(
                "imu.sample_count",
                None,
                Kind::Integer,
                "",
                "IMU output samples since initialisation (the integer tick)",
            ),
            read: Box::new(|v, _| Value::Integer(v.plant.samples_done())),
            // Sample k is the (k+1)-th: its index is the count less one.
            store: Some(Box::new(|r, _, x| {
                if let Value::Integer(n) = x {
                    r.sample.index = n.saturating_sub(1);
                }
            })),
            sample_field: None,
            per_step: false,
        },
        plant_real(
            "imu.time_s",
            None,
            "s",
            "end of the last IMU sample interval (integer tick × internal step)",
            |v, _| v.plant.time_s(),
            |r, _, x| r.sample.t_s = x,
        ),
        plant_real(
            "gimbal.outer_rad",
            None,
            "rad",
            "true outer (azimuth) gimbal angle",
            |v, _| v.truth.gimbal.angles.outer_rad,
            |r, _, x| r.truth.gimbal.angles.outer_rad = x,
        ),
        plant_real(
            "gimbal.inner_rad",
            None,
            "rad",
            "true inner gimbal angle",
            |v, _| v.truth.gimbal.angles.inner_rad,
            |r, _, x| r.truth.gimbal.angles.inner_rad = x,
        ),
        plant_real(
            "gimbal.outer_rate_rps",
            None,
            "rad/s",
            "outer gimbal rate",
            |v, _| v.truth.gimbal.outer_rate_rps,
            |r, _, x| r.truth.gimbal.outer_rate_rps = x,
        ),
        plant_real(
            "gimbal.inner_rate_rps",
            None,
            "rad/s",
            "inner gimbal rate",
            |v, _| v.truth.gimbal.inner_rate_rps,
            |r, _, x| r.truth.gimbal.inner_rate_rps = x,
        ),
        Output {
            decl: decl(
                "gimbal.moving",
                None,
                Kind::Boolean,
                "",
                "the table is moving (false while dwelling)",
            ),
            read: Box::new(|v, _| Value::Boolean(v.truth.gimbal.moving)),
            store: Some(Box::new(|r, _, x| {
                r.truth.gimbal.moving = x == Value::Boolean(true)
            })),
            sample_field: None,
            per_step: false,
        },
        Output {
            decl: OutputDecl {
                start: [1.0, 0.0, 0.0, 0.0].map(Value::Real).to_vec(),
                ..decl(
                    "truth.q_bn",
                    Some(4),
                    Kind::Real,
                    "",
                    "true attitude quaternion body→ENU navigation frame (w, x, y, z)",
                )
            },
            read: Box::new(|v, i| {
                let q = v.plant.attitude_q_bn();
                Value::Real([q.w, q.i, q.j, q.k][i])
            }),
            // The sinks derive the attitude from the gimbal angles themselves.
            store: None,
            sample_field: None,
            per_step: false,
        },
    ];
    // What the unit reports beside the increments: encoder angles and temperature-sensor
    // readings (sensor.encoder / sensor.temperature effects); the gimbal.* and thermal.* rows
    // are the truth.
    rows.extend([
        sample_real(
            "imu.encoder_outer_rad",
            None,
            "rad",
            "outer gimbal encoder reading at the end of the last sample",
            |s, _| s.encoder.outer_rad,
            |s, _, x| s.encoder.outer_rad = x,
        ),
        sample_real(
            "imu.encoder_inner_rad",
            None,
            "rad",
            "inner gimbal encoder reading at the end of the last sample",
            |s, _| s.encoder.inner_rad,
            |s, _, x| s.encoder.inner_rad = x,
        ),
    ]);
    for (n, name) in node::NAMES.iter().enumerate() {
        rows.push(sample_real(
            &format!("imu.temp_{name}_c"),
            None,
            "degC",
            "temperature-sensor reading (held between thermal updates)",
            move |s, _| s.temps_c[n],
            move |s, _, x| s.temps_c[n] = x,
        ));
    }
    for (n, name) in node::NAMES.iter().enumerate() {
        rows.push(plant_real(
            &format!("thermal.{name}_c"),
            None,
            "degC",
            "true node temperature",
            move |v, _| v.truth.temps.nodes_c[n],
            move |r, _, x| r.truth.temps.nodes_c[n] = x,
        ));
    }
    rows.extend([
        plant_real(
            "thermal.chamber_c",
            None,
            "degC",
            "chamber temperature in use",
            |v, _| v.truth.temps.chamber_c,
            |r, _, x| r.truth.temps.chamber_c = x,
        ),
        increment(plant_real(
            "truth.dtheta_rad",
            Some(3),
            "rad",
            "error-free angular increment over the last communication step",
            |v, i| v.dtheta_true_rad()[i],
            |r, i, x| r.truth.dtheta_true_rad[i] = x,
        )),
        increment(plant_real(
            "truth.dv_mps",
            Some(3),
            "m/s",
            "error-free velocity increment over the last communication step",
            |v, i| v.dv_true_mps()[i],
            |r, i, x| r.truth.dv_true_mps[i] = x,
        )),
    ]);
    for (t, term) in GyroTerm::ALL.iter().enumerate() {
        rows.push(increment(plant_real(
            &format!("effect.gyro.{}_rad", term.key()),
            Some(3),
            "rad",
            "this gyro term's angular increment error over the last IMU sample",
            move |v, i| v.truth.gyro_terms_rad[t][i],
            move |r, i, x| r.truth.gyro_terms_rad[t][i] = x,
        )));
    }
    for (t, term) in AccelTerm::ALL.iter().enumerate() {
        rows.push(increment(plant_real(
            &format!("effect.accel.{}_mps", term.key()),
            Some(3),
            "m/s",
            "this accelerometer term's velocity increment error over the last IMU sample",
            move |v, i| v.truth.accel_terms_mps[t][i],
            move |r, i, x| r.truth.accel_terms_mps[t][i] = x,
        )));
    }
    rows.push(plant_real(
        "effect.position_weight",
        None,
        "",
        "weight of the position-dependent bias (0 Z-up, 1 Z-down, Eq. 9)",
        |v, _| v.truth.position_weight,
        |r, _, x| r.truth.position_weight = x,
    ));
    rows
}

/// The output table, in value-reference order (built once).
pub fn outputs() -> &'static [Output] {
    static ROWS: OnceLock<Vec<Output>> = OnceLock::new();
    ROWS.get_or_init(build)
}
