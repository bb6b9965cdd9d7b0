//! The plant's complete parameter set, with range validation that names the offending field.

use serde::{Deserialize, Serialize};

use crate::earth::{EarthSpec, SiteSpec};
use crate::effects::{AccelSpec, GyroSpec};
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
    fn range(&mut self, path: &str, v: f64, lo: f64, hi: f64) {
        if !(v.is_finite() && v >= lo && v <= hi) {
            self.errors.push(ConfigError { path: path.into(), expected: format!("a number in [{lo}, {hi}]"), got: format!("{v}") });
        }
    }
    fn all(&mut self, path: &str, v: &[f64], lo: f64, hi: f64) {
        for (i, &x) in v.iter().enumerate() {
            self.range(&format!("{path}[{i}]"), x, lo, hi);
        }
    }
    fn fail(&mut self, path: &str, expected: &str, got: String) {
        self.errors.push(ConfigError { path: path.into(), expected: expected.into(), got });
    }
}

impl PlantConfig {
    /// Output interval, s.
    pub fn dt_s(&self) -> f64 {
        1.0 / self.rate_hz
    }

    /// Checks every parameter against its documented range; returns all violations.
    pub fn validate(&self) -> Result<(), Vec<ConfigError>> {
        let mut c = Checker { errors: Vec::new() };
        c.range("run.rate_hz", self.rate_hz, 1.0, 10_000.0);
        c.range("run.substeps", self.substeps as f64, 1.0, 1000.0);
        c.range("site.lat_deg", self.site.lat_deg, -89.0, 89.0);
        c.range("site.lon_deg", self.site.lon_deg, -180.0, 360.0);
        c.range("site.height_m", self.site.height_m, -1000.0, 20_000.0);
        c.range("vehicle.azimuth_deg", self.vehicle.azimuth_deg, -360.0, 360.0);
        c.range("vehicle.pitch_deg", self.vehicle.pitch_deg, -89.0, 89.0);
        c.range("vehicle.roll_deg", self.vehicle.roll_deg, -180.0, 180.0);
        self.validate_scheme(&mut c);
        self.validate_sensor(&mut c);
        self.validate_thermal(&mut c);
        if c.errors.is_empty() { Ok(()) } else { Err(c.errors) }
    }

    fn validate_scheme(&self, c: &mut Checker) {
        let s = &self.scheme;
        c.range("scheme.rate_dps", s.rate_dps, 1e-6, 100.0);
        if !(s.accel_dps2 > 0.0) {
            c.fail("scheme.accel_dps2", "a number > 0 (inf for constant-rate moves)", format!("{}", s.accel_dps2));
        }
        c.range("scheme.dwell_s", s.dwell_s, 0.0, 1e7);
        c.range("scheme.lead_dwell_s", s.lead_dwell_s, 0.0, 1e8);
        c.range("scheme.initial_outer_deg", s.initial_outer_deg, -360.0, 360.0);
        c.range("scheme.initial_inner_deg", s.initial_inner_deg, -360.0, 360.0);
        if s.kind == SchemeKind::Steps && s.steps.is_empty() {
            c.fail("scheme.steps", "at least one step when kind = \"steps\"", "an empty list".into());
        }
        if s.kind != SchemeKind::Steps && !s.steps.is_empty() {
            c.fail("scheme.steps", "no steps unless kind = \"steps\"", format!("{} steps", s.steps.len()));
        }
        for (i, st) in s.steps.iter().enumerate() {
            let p = format!("scheme.steps[{i}]");
            if st.angle_deg == 0.0 || !st.angle_deg.is_finite() || st.angle_deg.abs() > 3600.0 {
                c.fail(&format!("{p}.angle_deg"), "a non-zero angle in [-3600, 3600]", format!("{}", st.angle_deg));
            }
            c.range(&format!("{p}.rate_dps"), st.rate_dps, 1e-6, 100.0);
            c.range(&format!("{p}.dwell_s"), st.dwell_s, 0.0, 1e7);
        }
        if s.kind == SchemeKind::Steps && s.repeat {
            let moving: f64 = s.steps.iter().map(|st| st.dwell_s + st.angle_deg.abs() / st.rate_dps.max(1e-9)).sum();
            if moving <= 0.0 {
                c.fail("scheme.steps", "a repeating cycle of positive duration", "zero".into());
            }
        }
    }

    fn validate_sensor(&self, c: &mut Checker) {
        let g = &self.sensor.gyro;
        c.all("sensor.gyro.bias.dph", &g.bias.dph, -100.0, 100.0);
        c.all("sensor.gyro.scale_factor.ppm", &g.scale_factor.ppm, -1e5, 1e5);
        c.all("sensor.gyro.scale_factor_asymmetry.ppm", &g.scale_factor_asymmetry.ppm, -1e5, 1e5);
        c.all("sensor.gyro.misalignment.arcsec", &g.misalignment.arcsec, -3600.0, 3600.0);
        c.range("sensor.gyro.temperature_bias.ref_temp_c", g.temperature_bias.ref_temp_c, -60.0, 130.0);
        c.all("sensor.gyro.temperature_bias.per_k", &g.temperature_bias.per_k, -10.0, 10.0);
        c.all("sensor.gyro.temperature_bias.per_k2", &g.temperature_bias.per_k2, -1.0, 1.0);
        c.all("sensor.gyro.temperature_bias.per_k3", &g.temperature_bias.per_k3, -0.1, 0.1);
        c.all("sensor.gyro.temperature_gradient_bias.dph_per_k", &g.temperature_gradient_bias.dph_per_k, -10.0, 10.0);
        for (i, row) in g.g_sensitivity.dph_per_g.iter().enumerate() {
            c.all(&format!("sensor.gyro.g_sensitivity.dph_per_g[{i}]"), row, -100.0, 100.0);
        }
        let pb = &g.position_bias;
        c.all("sensor.gyro.position_bias.dph", &pb.dph, -100.0, 100.0);
        c.range("sensor.gyro.position_bias.ref_temp_c", pb.ref_temp_c, -60.0, 130.0);
        c.all("sensor.gyro.position_bias.dph_per_k", &pb.dph_per_k, -10.0, 10.0);
        c.all("sensor.gyro.position_bias.dph_per_k2", &pb.dph_per_k2, -1.0, 1.0);
        c.all("sensor.gyro.position_bias.dph_per_k3", &pb.dph_per_k3, -0.1, 0.1);
        c.all("sensor.gyro.dither_bias.amplitude_change", &g.dither_bias.amplitude_change, -1.0, 1.0);
        c.all("sensor.gyro.dither_bias.dph_per_amplitude", &g.dither_bias.dph_per_amplitude, -100.0, 100.0);
        c.all("sensor.gyro.angle_random_walk.dpsh", &g.angle_random_walk.dpsh, 0.0, 10.0);
        c.all("sensor.gyro.bias_instability.sigma_dph", &g.bias_instability.sigma_dph, 0.0, 100.0);
        c.all("sensor.gyro.bias_instability.tau_s", &g.bias_instability.tau_s, 1e-3, 1e9);
        c.all("sensor.gyro.rate_random_walk.dph_per_sqrth", &g.rate_random_walk.dph_per_sqrth, 0.0, 100.0);
        c.all("sensor.gyro.quantization.pulse", &g.quantization.pulse, 0.0, 3600.0);
        let a = &self.sensor.accel;
        c.all("sensor.accel.bias.ug", &a.bias.ug, -1e5, 1e5);
        c.all("sensor.accel.scale_factor.ppm", &a.scale_factor.ppm, -1e5, 1e5);
        c.all("sensor.accel.misalignment.arcsec", &a.misalignment.arcsec, -3600.0, 3600.0);
        c.range("sensor.accel.temperature_bias.ref_temp_c", a.temperature_bias.ref_temp_c, -60.0, 130.0);
        c.all("sensor.accel.temperature_bias.per_k", &a.temperature_bias.per_k, -1e4, 1e4);
        c.all("sensor.accel.temperature_bias.per_k2", &a.temperature_bias.per_k2, -1e3, 1e3);
        c.all("sensor.accel.temperature_bias.per_k3", &a.temperature_bias.per_k3, -1e2, 1e2);
        c.all("sensor.accel.velocity_random_walk.ug_per_sqrthz", &a.velocity_random_walk.ug_per_sqrthz, 0.0, 1e4);
        c.all("sensor.accel.quantization.pulse", &a.quantization.pulse, 0.0, 10.0);
    }

    fn validate_thermal(&self, c: &mut Checker) {
        let t = &self.thermal;
        c.range("thermal.step_s", t.step_s, 1e-3, 3600.0);
        let ratio = t.step_s * self.rate_hz;
        if (ratio - ratio.round()).abs() > 1e-9 * ratio.max(1.0) || ratio.round() < 1.0 {
            c.fail("thermal.step_s", "a whole multiple of the output interval 1/run.rate_hz", format!("{} s at {} Hz", t.step_s, self.rate_hz));
        }
        c.range("thermal.chamber.temp_c", t.chamber.temp_c, CHAMBER_MIN_C, CHAMBER_MAX_C);
        let mut last = f64::NEG_INFINITY;
        for (i, p) in t.chamber.profile.iter().enumerate() {
            c.range(&format!("thermal.chamber.profile[{i}][1]"), p[1], CHAMBER_MIN_C, CHAMBER_MAX_C);
            if !(p[0].is_finite() && p[0] > last) {
                c.fail(&format!("thermal.chamber.profile[{i}][0]"), "times strictly increasing", format!("{} after {}", p[0], last));
            }
            last = p[0];
        }
        c.all("thermal.capacitance_j_per_k", &t.capacitance_j_per_k, 1e-3, 1e9);
        c.all("thermal.power_w", &t.power_w, 0.0, 1e4);
        c.range("thermal.g_board_housing_w_per_k", t.g_board_housing_w_per_k, 0.0, 1e6);
        c.all("thermal.g_gyro_housing_w_per_k", &t.g_gyro_housing_w_per_k, 0.0, 1e6);
        c.range("thermal.g_accel_housing_w_per_k", t.g_accel_housing_w_per_k, 0.0, 1e6);
        c.range("thermal.g_housing_chamber_w_per_k", t.g_housing_chamber_w_per_k, 1e-6, 1e6);
        c.range("thermal.g_gyro_gyro_w_per_k", t.g_gyro_gyro_w_per_k, 0.0, 1e6);
        c.all("thermal.g_board_gyro_w_per_k", &t.g_board_gyro_w_per_k, 0.0, 1e6);
        c.all("thermal.g_board_gyro_convection_w_per_k", &t.g_board_gyro_convection_w_per_k, 0.0, 1e6);
        c.all("thermal.board_to_block_dir_body", &t.board_to_block_dir_body, -1.0, 1.0);
    }
}
