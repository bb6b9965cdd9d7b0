//! The effects an analysis integrates: each a channel whose body-frame error the plant's own
//! models give at a table state.

use nalgebra::{Matrix3, Vector3};
use rins_plant::SensorSpec;
use rins_plant::effects::custom::{Declared, Signal};
use rins_plant::effects::{
    AccelModel, AccelSpec, AccelTerm, CustomModel, CustomSpec, GyroModel, GyroSpec, GyroTerm,
    TermContext,
};
use rins_plant::thermal::node;
use rins_plant::units::{DPH, UG};
use serde::Serialize;

use crate::basis;
use crate::cycle::TableState;

/// Uniform temperature the analysis holds every node at, °C: the reference of the plant's
/// temperature polynomials, so temperature-driven terms are off. How a scheme moves the
/// temperature field is a simulation question (`rins run`), not a per-cycle integral.
pub const REFERENCE_TEMP_C: f64 = 25.0;

/// Which instrument an error belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Sensor {
    /// Gyro: residual in rad (angle), mean rate in °/h.
    Gyro,
    /// Accelerometer: residual in m/s (velocity), mean in µg.
    Accel,
}

impl Sensor {
    /// SI per reporting unit of a mean error (rad/s per °/h, m/s² per µg).
    pub fn unit_si(self) -> f64 {
        match self {
            Sensor::Gyro => DPH,
            Sensor::Accel => UG,
        }
    }

    /// Name of the reporting unit.
    pub fn unit(self) -> &'static str {
        match self {
            Sensor::Gyro => "deg/h",
            Sensor::Accel => "ug",
        }
    }
}

/// Where an effect is defined.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Group {
    /// A catalogue term at the sensor spec's magnitude.
    Catalogue,
    /// A declared effect (`[[sensor.*.custom]]`).
    Declared,
    /// A basis function of the general b_i(u), 1 °/h per unit.
    General,
}

/// One analysed effect.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Channel {
    /// Key: `gyro.bias`, `accel.scale_factor`, `gyro.custom.NAME`, `general.bz_uz2`.
    pub key: String,
    /// Instrument.
    pub sensor: Sensor,
    /// Where it is defined.
    pub group: Group,
    /// What the figure assumes (the model of the effect).
    pub model: String,
}

#[derive(Clone, Debug)]
enum Source {
    Gyro(usize),
    /// A catalogue term of its own gyro model (one axis of a per-axis class).
    GyroOwn(Box<GyroModel>, usize),
    /// A catalogue term of its own accelerometer model.
    AccelOwn(Box<AccelModel>, usize),
    Accel(usize),
    Declared(Box<Declared>, Sensor),
}

/// A set of effects and the plant models that evaluate them.
#[derive(Clone, Debug)]
pub struct EffectSet {
    channels: Vec<Channel>,
    sources: Vec<Source>,
    gyro: GyroModel,
    accel: AccelModel,
    gravity_mps2: f64,
    /// Earth rate in the navigation frame (E, N, U), rad/s: zero unless
    /// [`EffectSet::with_earth_rate`].
    earth_rate_n: Vector3<f64>,
    /// Effects left out, with why.
    pub skipped: Vec<(String, String)>,
}

/// Why a declared effect cannot be analysed per cycle.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EffectError {
    /// The declared effect breaks a rule of the plant (the message names the field).
    #[error("{0}")]
    Invalid(String),
    /// It reads something that is not a function of the table's state within a cycle.
    #[error(
        "declared effect `{name}` reads {what}: not a function of the table's attitude and rate, so it has no per-cycle residual; simulate it (`rins run`)"
    )]
    NotPeriodic {
        /// The effect.
        name: String,
        /// What it reads.
        what: String,
    },
}

fn model_text(t: GyroTerm) -> &'static str {
    match t {
        GyroTerm::Bias => "constant (Eq. 3)",
        GyroTerm::ScaleFactor => "times the body rate (Eq. 3)",
        GyroTerm::ScaleFactorAsymmetry => "times |body rate|",
        GyroTerm::Misalignment => "cross-axis body rate (Eq. 3)",
        GyroTerm::GSensitivity => "linear in specific force",
        GyroTerm::PositionBias => {
            "plant's delta-beta: b_i = dbeta_i * w(u_z), u_z alone (Eq. 9); a scheme that keeps z horizontal makes it a constant, an artefact of the model"
        }
        GyroTerm::DitherBias => "dither load: k_i (u_i^2 - 1/3)",
        GyroTerm::NavFieldBias => "field fixed in the navigation frame",
        _ => "",
    }
}

impl EffectSet {
    /// Nothing yet, with gravity `gravity_mps2`.
    pub fn empty(gravity_mps2: f64) -> Self {
        Self {
            channels: Vec::new(),
            sources: Vec::new(),
            gyro: GyroModel::new(&GyroSpec::default()),
            accel: AccelModel::new(&AccelSpec::default()),
            gravity_mps2,
            earth_rate_n: Vector3::zeros(),
            skipped: Vec::new(),
        }
    }

    /// Adds the Earth rate at latitude `lat_rad` to the body rate every effect sees: a scale
    /// factor or misalignment on it is C·S·Cᵀ·ω_ie, rectified in part by any scheme (as the
    /// accelerometer scale factor is on gravity). Eq. 8 and Eq. 11 are stated without it.
    pub fn with_earth_rate(mut self, lat_rad: f64) -> Self {
        let w = rins_plant::earth::OMEGA_IE_RPS;
        self.earth_rate_n = Vector3::new(0.0, w * lat_rad.cos(), w * lat_rad.sin());
        self
    }

    /// The channels, in evaluation order.
    pub fn channels(&self) -> &[Channel] {
        &self.channels
    }

    /// Adds every deterministic catalogue term switched on in `sensor` (at its magnitudes).
    /// Temperature-driven terms are listed in [`EffectSet::skipped`]: at a uniform constant
    /// temperature they are off.
    pub fn with_catalogue(mut self, sensor: &SensorSpec) -> Self {
        let mut g = sensor.gyro.clone();
        g.custom.clear();
        let mut a = sensor.accel.clone();
        a.custom.clear();
        for (k, t) in GyroTerm::ALL.into_iter().enumerate() {
            if !GyroTerm::DETERMINISTIC.contains(&t) || !g.is_enabled(t) {
                continue;
            }
            if matches!(
                t,
                GyroTerm::TemperatureBias | GyroTerm::TemperatureGradientBias
            ) {
                self.skipped.push((
                    format!("gyro.{}", t.key()),
                    "driven by the temperature field; the analysis holds a uniform reference temperature (simulate it)".into(),
                ));
                continue;
            }
            self.channels.push(Channel {
                key: format!("gyro.{}", t.key()),
                sensor: Sensor::Gyro,
                group: Group::Catalogue,
                model: model_text(t).into(),
            });
            self.sources.push(Source::Gyro(k));
        }
        for (k, t) in AccelTerm::ALL.into_iter().enumerate() {
            if !AccelTerm::DETERMINISTIC.contains(&t) || !a.is_enabled(t) {
                continue;
            }
            if t == AccelTerm::TemperatureBias {
                self.skipped.push((
                    format!("accel.{}", t.key()),
                    "driven by the temperature field; the analysis holds a uniform reference temperature (simulate it)".into(),
                ));
                continue;
            }
            self.channels.push(Channel {
                key: format!("accel.{}", t.key()),
                sensor: Sensor::Accel,
                group: Group::Catalogue,
                model: match t {
                    AccelTerm::Bias => "constant (Eq. 4)",
                    AccelTerm::ScaleFactor => "times the specific force (Eq. 4)",
                    _ => "cross-axis specific force (Eq. 4)",
                }
                .into(),
            });
            self.sources.push(Source::Accel(k));
        }
        self.gyro = GyroModel::new(&g);
        self.accel = AccelModel::new(&a);
        self
    }

    /// Adds declared effects of the gyros (`accel = false`) or accelerometers, checked as the
    /// plant checks them; refuses those with memory or reading time, which have no per-cycle
    /// residual.
    pub fn with_declared(mut self, specs: &[CustomSpec], accel: bool) -> Result<Self, EffectError> {
        let prefix = if accel { "accel" } else { "gyro" };
        for s in specs.iter().filter(|s| s.enabled) {
            let model = CustomModel::new(std::slice::from_ref(s), accel).map_err(|errs| {
                EffectError::Invalid(
                    errs.iter()
                        .map(|e| format!("sensor.{prefix}.custom `{}`: {e}", s.name))
                        .collect::<Vec<_>>()
                        .join("\n"),
                )
            })?;
            if model.has_memory() {
                return Err(EffectError::NotPeriodic {
                    name: s.name.clone(),
                    what: "a lag or decay (memory)".into(),
                });
            }
            for e in model.effects() {
                for sig in e.signals() {
                    let what = match sig {
                        Signal::Time => Some("`time`"),
                        Signal::TempRate(_) => Some("a temperature rate"),
                        _ => None,
                    };
                    if let Some(what) = what {
                        return Err(EffectError::NotPeriodic {
                            name: s.name.clone(),
                            what: what.into(),
                        });
                    }
                }
            }
            let (gs, as_) = if accel {
                (
                    GyroSpec::default(),
                    AccelSpec {
                        custom: vec![s.clone()],
                        ..AccelSpec::default()
                    },
                )
            } else {
                (
                    GyroSpec {
                        custom: vec![s.clone()],
                        ..GyroSpec::default()
                    },
                    AccelSpec::default(),
                )
            };
            let d = Declared::new(&gs, &as_, &[REFERENCE_TEMP_C; node::COUNT]);
            let sensor = if accel { Sensor::Accel } else { Sensor::Gyro };
            self.channels.push(Channel {
                key: format!("{prefix}.custom.{}", s.name),
                sensor,
                group: Group::Declared,
                model: format!("declared: {} ({:?})", s.regressor, s.kind).to_lowercase(),
            });
            self.sources.push(Source::Declared(Box::new(d), sensor));
        }
        Ok(self)
    }

    /// Adds the plant's δβ (Eq. 9) one axis at a time, 1 °/h each (`gyro.position_bias.x`, …),
    /// with `shape`'s transition: the class the design searches under the plant's model.
    pub fn with_delta_beta_axes(
        mut self,
        shape: &rins_plant::effects::gyro::PositionBiasSpec,
    ) -> Self {
        let k = GyroTerm::ALL
            .iter()
            .position(|t| *t == GyroTerm::PositionBias)
            .expect("catalogue term");
        for axis in 0..3 {
            let mut g = GyroSpec::default();
            g.position_bias = *shape;
            g.position_bias.enabled = true;
            g.position_bias.dph = [0.0; 3];
            g.position_bias.dph[axis] = 1.0;
            g.position_bias.dph_per_k = [0.0; 3];
            g.position_bias.dph_per_k2 = [0.0; 3];
            g.position_bias.dph_per_k3 = [0.0; 3];
            self.channels.push(Channel {
                key: format!("gyro.position_bias.{}", ["x", "y", "z"][axis]),
                sensor: Sensor::Gyro,
                group: Group::Catalogue,
                model: model_text(GyroTerm::PositionBias).into(),
            });
            self.sources
                .push(Source::GyroOwn(Box::new(GyroModel::new(&g)), k));
        }
        self
    }

    /// Adds the constant errors of Eq. 3 and Eq. 4 one axis (or axis pair) at a time at
    /// `sensor`'s magnitudes (`const.gyro.bias.x`, `const.accel.misalignment.yz`, …): what
    /// every scheme must cancel over a cycle.
    pub fn with_constant_axes(mut self, sensor: &SensorSpec) -> Self {
        const PAIRS: [&str; 6] = ["xy", "xz", "yx", "yz", "zx", "zy"];
        for (term, k, n) in [
            (GyroTerm::Bias, 0usize, 3usize),
            (GyroTerm::ScaleFactor, 1, 3),
            (GyroTerm::Misalignment, 3, 6),
        ] {
            for j in 0..n {
                let mut g = GyroSpec::default();
                g.set_enabled(term, true);
                match term {
                    GyroTerm::Bias => g.bias.dph[j] = sensor.gyro.bias.dph[j],
                    GyroTerm::ScaleFactor => {
                        g.scale_factor.ppm[j] = sensor.gyro.scale_factor.ppm[j]
                    }
                    _ => g.misalignment.arcsec[j] = sensor.gyro.misalignment.arcsec[j],
                }
                let axis = if n == 3 { ["x", "y", "z"][j] } else { PAIRS[j] };
                self.channels.push(Channel {
                    key: format!("const.gyro.{}.{axis}", term.key()),
                    sensor: Sensor::Gyro,
                    group: Group::Catalogue,
                    model: model_text(term).into(),
                });
                self.sources
                    .push(Source::GyroOwn(Box::new(GyroModel::new(&g)), k));
            }
        }
        for (term, k, n) in [
            (AccelTerm::Bias, 0usize, 3usize),
            (AccelTerm::ScaleFactor, 1, 3),
            (AccelTerm::Misalignment, 2, 6),
        ] {
            for j in 0..n {
                let mut a = AccelSpec::default();
                match term {
                    AccelTerm::Bias => {
                        a.bias.enabled = true;
                        a.bias.ug[j] = sensor.accel.bias.ug[j];
                    }
                    AccelTerm::ScaleFactor => {
                        a.scale_factor.enabled = true;
                        a.scale_factor.ppm[j] = sensor.accel.scale_factor.ppm[j];
                    }
                    _ => {
                        a.misalignment.enabled = true;
                        a.misalignment.arcsec[j] = sensor.accel.misalignment.arcsec[j];
                    }
                }
                let axis = if n == 3 { ["x", "y", "z"][j] } else { PAIRS[j] };
                self.channels.push(Channel {
                    key: format!("const.accel.{}.{axis}", term.key()),
                    sensor: Sensor::Accel,
                    group: Group::Catalogue,
                    model: "constant error (Eq. 4)".into(),
                });
                self.sources
                    .push(Source::AccelOwn(Box::new(AccelModel::new(&a)), k));
            }
        }
        self
    }

    /// Adds the 27 basis functions of the general b_i(u) ([`basis`]), 1 °/h per unit each.
    pub fn with_general(mut self) -> Self {
        for s in basis::all_unit() {
            let d = Declared::new(
                &GyroSpec {
                    custom: vec![s.clone()],
                    ..GyroSpec::default()
                },
                &AccelSpec::default(),
                &[REFERENCE_TEMP_C; node::COUNT],
            );
            self.channels.push(Channel {
                key: format!("general.{}", s.name),
                sensor: Sensor::Gyro,
                group: Group::General,
                model: format!(
                    "general b(u): b_{} = {} (1 deg/h per unit)",
                    &s.name[1..2],
                    s.regressor
                ),
            });
            self.sources
                .push(Source::Declared(Box::new(d), Sensor::Gyro));
        }
        self
    }

    /// C_b^n·δ for every channel at the table state `st`: rad/s (gyros) or m/s² (accelerometers)
    /// in the navigation frame (E, N, U), written to `out` (one entry per channel). The body
    /// rate is the table's plus the Earth rate when [`EffectSet::with_earth_rate`] set one.
    pub fn eval(&mut self, st: &TableState, out: &mut [Vector3<f64>]) {
        let c: Matrix3<f64> = st.c_bn();
        let ct = c.transpose();
        let omega = st.body_rate_rps() + ct * self.earth_rate_n;
        let f_b = ct * Vector3::new(0.0, 0.0, self.gravity_mps2);
        let ctx = TermContext {
            dt_s: 1.0,
            dtheta_rad: omega,
            dv_mps: f_b,
            f_b_mps2: f_b,
            up_b: ct.column(2).into_owned(),
            north_b: ct.column(1).into_owned(),
            east_b: ct.column(0).into_owned(),
            gyro_temp_c: Vector3::repeat(REFERENCE_TEMP_C),
            gyro_gradient_k: Vector3::zeros(),
            accel_temp_c: REFERENCE_TEMP_C,
        };
        let need_gyro = self.sources.iter().any(|s| matches!(s, Source::Gyro(_)));
        let need_accel = self.sources.iter().any(|s| matches!(s, Source::Accel(_)));
        let mut gt = [Vector3::zeros(); rins_plant::effects::gyro::GYRO_TERMS];
        let mut at = [Vector3::zeros(); rins_plant::effects::accel::ACCEL_TERMS];
        if need_gyro {
            self.gyro.increment_error(&ctx, &mut gt);
        }
        if need_accel {
            self.accel.increment_error(&ctx, &mut at);
        }
        for (o, s) in out.iter_mut().zip(self.sources.iter_mut()) {
            let body = match s {
                Source::Gyro(k) => gt[*k],
                Source::Accel(k) => at[*k],
                Source::GyroOwn(m, k) => {
                    let mut t = [Vector3::zeros(); rins_plant::effects::gyro::GYRO_TERMS];
                    m.increment_error(&ctx, &mut t);
                    t[*k]
                }
                Source::AccelOwn(m, k) => {
                    let mut t = [Vector3::zeros(); rins_plant::effects::accel::ACCEL_TERMS];
                    m.increment_error(&ctx, &mut t);
                    t[*k]
                }
                Source::Declared(d, sensor) => {
                    let (g, a) = d.increments(
                        &ctx.up_b,
                        &[ctx.north_b, ctx.east_b],
                        &omega,
                        &f_b,
                        1.0,
                        st.angles,
                        0.0,
                        st.since,
                    );
                    if *sensor == Sensor::Gyro { g } else { a }
                }
            };
            *o = c * body;
        }
    }
}
