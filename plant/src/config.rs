//! The plant's complete parameter set, with range validation that names the offending field.

use serde::{Deserialize, Serialize};

use crate::carrier::{CarrierKind, CarrierSpec};
use crate::earth::{EarthSpec, SiteSpec};
use crate::effects::encoder::EncoderSpec;
use crate::effects::temp_sensor::TempSensorSpec;
use crate::effects::{AccelSpec, GyroSpec};
use crate::message::{self, Num};
use crate::params::ParamValue;
use crate::table::{SchemeKind, SchemeSpec};
use crate::thermal::{CHAMBER_MAX_C, CHAMBER_MIN_C, ThermalSpec};

/// Static vehicle attitude: C_v^n = R_z(azimuth)·R_x(pitch)·R_y(roll), ENU, azimuth counter-clockwise
/// from east. Zero gives the paper's level mount where position A is C_b^n = I (Eq. 5).
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct VehicleSpec {
    /// Rotation about up, degrees.
    pub azimuth_deg: f64,
    /// Rotation about the vehicle x axis, degrees, in [-89, 89].
    pub pitch_deg: f64,
    /// Rotation about the vehicle y axis, degrees, in [-180, 180].
    pub roll_deg: f64,
}

impl VehicleSpec {
    /// The mount rotation C_v^n.
    pub fn c_vn(&self) -> nalgebra::Matrix3<f64> {
        use crate::table::gimbal::{rot_x, rot_y, rot_z};
        use crate::units::DEG;
        rot_z(self.azimuth_deg * DEG) * rot_x(self.pitch_deg * DEG) * rot_y(self.roll_deg * DEG)
    }
}

/// Gyro and accelerometer error terms.
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensorSpec {
    /// Gyro terms (Eq. 3, 9 and the RLG effects).
    pub gyro: GyroSpec,
    /// Accelerometer terms (Eq. 4).
    pub accel: AccelSpec,
    /// Gimbal angle encoders.
    pub encoder: EncoderSpec,
    /// Temperature sensors.
    pub temperature: TempSensorSpec,
}

/// Everything the plant needs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlantConfig {
    /// IMU output rate, Hz, in [1, 10000].
    pub rate_hz: f64,
    /// Internal integration steps per output interval, in [1, 1000].
    pub substeps: u32,
    /// Seed of every random stream.
    pub seed: u64,
    /// Geodetic site.
    pub site: SiteSpec,
    /// Vehicle mount attitude.
    pub vehicle: VehicleSpec,
    /// Earth switches.
    pub earth: EarthSpec,
    /// Rotation scheme.
    pub scheme: SchemeSpec,
    /// Sensor errors.
    pub sensor: SensorSpec,
    /// Thermal network.
    pub thermal: ThermalSpec,
    /// The carrier (static by default).
    pub carrier: CarrierSpec,
}

impl Default for PlantConfig {
    fn default() -> Self {
        Self {
            rate_hz: 100.0,
            substeps: 1,
            seed: 1,
            site: SiteSpec::default(),
            vehicle: VehicleSpec::default(),
            earth: EarthSpec::default(),
            scheme: SchemeSpec::default(),
            sensor: SensorSpec::default(),
            thermal: ThermalSpec::default(),
            carrier: CarrierSpec::default(),
        }
    }
}

/// A parameter outside its valid range. `path` uses the scenario-file key path.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{path}: expected {expected}, got {got}")]
pub struct ConfigError {
    /// Dotted key path, e.g. `sensor.gyro.bias.dph`.
    pub path: String,
    /// The valid range or form.
    pub expected: String,
    /// The offending value.
    pub got: String,
}

struct Checker {
    errors: Vec<ConfigError>,
}

impl Checker {
    /// Range check; an infinite bound admits infinity (`scheme.accel_dps2 = inf`), NaN never passes.
    fn range(&mut self, path: &str, v: f64, lo: f64, hi: f64) {
        let ok = !v.is_nan()
            && v >= lo
            && v <= hi
            && (v.is_finite() || (v > 0.0 && hi.is_infinite()) || (v < 0.0 && lo.is_infinite()));
        if !ok {
            self.errors.push(ConfigError {
                path: path.into(),
                expected: message::expected_in(v, lo, hi),
                got: message::num(v),
            });
        }
    }
    /// Range check of a whole number, echoed exactly (as a real, 2^63 - 1 would read
    /// 9.223372036854776e18).
    fn range_whole(&mut self, path: &str, u: u64, lo: f64, hi: f64) {
        if !(u as f64 >= lo && u as f64 <= hi) {
            self.errors.push(ConfigError {
                path: path.into(),
                expected: format!("a whole number in {}", message::range(lo, hi)),
                got: u.to_string(),
            });
        }
    }
    fn fail(&mut self, path: &str, expected: &str, got: String) {
        self.errors.push(ConfigError {
            path: path.into(),
            expected: expected.into(),
            got,
        });
    }
}

impl PlantConfig {
    /// Output interval, s.
    pub fn dt_s(&self) -> f64 {
        1.0 / self.rate_hz
    }

    /// This configuration run with seed `seed` (a member of a Monte Carlo case).
    pub fn with_seed(&self, seed: u64) -> PlantConfig {
        PlantConfig {
            seed,
            ..self.clone()
        }
    }

    /// This configuration with its stochastic terms off: gyro angle random walk, bias
    /// instability and rate random walk (Eq. 3's ε_g), accelerometer velocity random walk
    /// (Eq. 4's ε_a). Every deterministic error, the quantisation and the temperature sensors
    /// stay as they are: the paper's noise-free pair (Table 4). These are exactly the terms a
    /// member of a [`crate::SeedBatch`] may switch off and still share the seeds' physics.
    pub fn noise_free(&self) -> PlantConfig {
        use crate::effects::GyroTerm;
        let mut c = self.clone();
        for t in [
            GyroTerm::AngleRandomWalk,
            GyroTerm::BiasInstability,
            GyroTerm::RateRandomWalk,
        ] {
            c.sensor.gyro.set_enabled(t, false);
        }
        c.sensor.accel.velocity_random_walk.enabled = false;
        c
    }

    /// Checks every parameter against its range in [`crate::params::RANGES`] plus the structural
    /// rules (scheme steps, thermal step, chamber profile); returns all violations.
    pub fn validate(&self) -> Result<(), Vec<ConfigError>> {
        let mut c = Checker { errors: Vec::new() };
        for p in crate::params::flatten(self) {
            match (p.value, p.range) {
                (ParamValue::Real(v), Some((lo, hi))) => c.range(&p.path, v, lo, hi),
                (ParamValue::Integer(u), Some((lo, hi))) => c.range_whole(&p.path, u, lo, hi),
                _ => {}
            }
        }
        self.validate_scheme(&mut c);
        self.validate_thermal(&mut c);
        // Declared effects: unknown signals, unit mismatches, unbounded contributions.
        for (specs, accel) in [
            (&self.sensor.gyro.custom, false),
            (&self.sensor.accel.custom, true),
        ] {
            if let Err(e) = crate::effects::CustomModel::new(specs, accel) {
                c.errors.extend(e);
            }
        }
        // `custom:NAME` names one effect in the diagnosis: names are unique across sensors.
        for (k, a) in self.sensor.accel.custom.iter().enumerate() {
            if self.sensor.gyro.custom.iter().any(|g| g.name == a.name) {
                c.fail(
                    &format!("sensor.accel.custom[{k}].name"),
                    "a name not used by a declared gyro effect",
                    format!("{:?}", a.name),
                );
            }
        }
        self.validate_carrier(&mut c);
        if c.errors.is_empty() {
            Ok(())
        } else {
            Err(c.errors)
        }
    }

    fn validate_scheme(&self, c: &mut Checker) {
        let s = &self.scheme;
        if s.kind == SchemeKind::Steps && s.steps.is_empty() {
            c.fail(
                "scheme.steps",
                "at least one step when kind = \"steps\"",
                "an empty list".into(),
            );
        }
        if s.kind != SchemeKind::Steps && !s.steps.is_empty() {
            c.fail(
                "scheme.steps",
                "no steps unless kind = \"steps\"",
                format!("{} steps", s.steps.len()),
            );
        }
        for (i, st) in s.steps.iter().enumerate() {
            if st.angle_deg == 0.0 {
                c.fail(
                    &format!("scheme.steps[{i}].angle_deg"),
                    "a non-zero angle in [-3600, 3600]",
                    message::num(st.angle_deg),
                );
            }
        }
    }

    fn validate_carrier(&self, c: &mut Checker) {
        let k = &self.carrier;
        if k.kind == CarrierKind::Ship && k.ship.legs.is_empty() {
            c.fail(
                "carrier.ship.legs",
                "at least one leg",
                "an empty list".into(),
            );
        }
        if k.kind == CarrierKind::Trajectory && k.trajectory.file.is_empty() {
            let e = "a file name when kind = \"trajectory\"";
            c.fail("carrier.trajectory.file", e, "\"\"".into());
        }
        if k.azimuth_isolation && k.kind == CarrierKind::Static {
            let e = "false for the static carrier (nothing to isolate: kind = \"ship\" or \"trajectory\")";
            c.fail("carrier.azimuth_isolation", e, "true".into());
        }
        // Leg durations: the range check of `params::RANGES` alone (one message, one range).
        crate::carrier::spec::validate_sea(&k.ship.sea, &mut |p, e, g| c.fail(p, e, g));
        let legs_ok = k.ship.legs.iter().all(|l| {
            l.duration_s > 0.0 && l.duration_s <= 1e8 && (l.heading_deg + l.speed_kn).is_finite()
        }) && k.ship.lat_deg.abs() <= 90.0
            && k.ship.height_m.is_finite();
        if k.kind == CarrierKind::Ship && legs_ok {
            let total_s = k.ship.legs.iter().map(|l| l.duration_s).sum();
            if let Some((path, e, g)) = crate::carrier::spec::polar_problem(&k.ship, total_s) {
                c.fail(&path, &e, g);
            }
        }
    }

    fn validate_thermal(&self, c: &mut Checker) {
        let t = &self.thermal;
        let ratio = t.step_s * self.rate_hz;
        if (ratio - ratio.round()).abs() > 1e-9 * ratio.max(1.0) || ratio.round() < 1.0 {
            c.fail(
                "thermal.step_s",
                "a whole multiple of the output interval 1/run.rate_hz",
                format!("{} s at {} Hz", Num(t.step_s), Num(self.rate_hz)),
            );
        }
        let mut last = f64::NEG_INFINITY;
        for (i, p) in t.chamber.profile.iter().enumerate() {
            c.range(
                &format!("thermal.chamber.profile[{i}][1]"),
                p[1],
                CHAMBER_MIN_C,
                CHAMBER_MAX_C,
            );
            if !(p[0].is_finite() && p[0] > last) {
                let got = if i == 0 {
                    Num(p[0]).to_string()
                } else {
                    format!("{} after {}", Num(p[0]), Num(last))
                };
                c.fail(
                    &format!("thermal.chamber.profile[{i}][0]"),
                    "finite times, strictly increasing",
                    got,
                );
            }
            last = p[0];
        }
    }
}
