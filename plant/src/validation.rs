//! [`PlantConfig::validate`]: every parameter against its range in the parameter table
//! ([`crate::params::RANGES`]) plus the structural and physical rules (scheme steps, thermal
//! step, chamber profile, declared effects, carrier legs, sea state), every violation named by
//! its key path. It sits above the configuration and the table it walks (`params` describes
//! `PlantConfig`; the check reads both), so neither imports the other back.

use crate::carrier::CarrierKind;
use crate::carrier::spec::{G_WAVE_MPS2, MAX_STEEPNESS, SeaSpec, SpectrumKind};
use crate::config::{ConfigError, PlantConfig};
use crate::message::{self, Num};
use crate::params::{ParamValue, range_for};
use crate::table::SchemeKind;
use crate::thermal::{CHAMBER_MAX_C, CHAMBER_MIN_C};

/// The violations found so far.
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
        validate_sea(&k.ship.sea, &mut |p, e, g| c.fail(p, e, g));
        let legs_ok = k.ship.legs.iter().all(|l| {
            l.duration_s > 0.0 && l.duration_s <= 1e8 && (l.heading_deg + l.speed_kn).is_finite()
        }) && k.ship.lat_deg.abs() <= 90.0
            && k.ship.height_m.is_finite();
        if k.kind == CarrierKind::Ship && legs_ok {
            let total_s = k.ship.legs.iter().map(|l| l.duration_s).sum();
            if let Some((path, e, g)) = crate::carrier::track::polar_problem(&k.ship, total_s) {
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

/// Checks the sea state against physics, calling `fail(path, expected, got)` for each problem:
/// the band shortest frequency first and not empty, and a significant steepness below
/// [`MAX_STEEPNESS`] (when a spectrum is on).
pub fn validate_sea(sea: &SeaSpec, fail: &mut dyn FnMut(&str, &str, String)) {
    let [lo, hi] = sea.band;
    if lo >= hi {
        fail(
            "carrier.ship.sea.band",
            "the shortest then the longest frequency, band[0] < band[1], each in [0.1, 10] \
             (multiples of the peak frequency; an empty band has no waves)",
            format!("[{}, {}]", Num(lo), Num(hi)),
        );
    }
    let (hs, tp) = sea.hs_tp();
    // A height or period outside its own range is reported by the range check alone (with an
    // infinite or vanishing one the limits below would read "tp_s above inf s").
    let within = |v: f64, path: &str| range_for(path).is_none_or(|(lo, hi)| v >= lo && v <= hi);
    let in_range = within(hs, "carrier.ship.sea.hs_m") && within(tp, "carrier.ship.sea.tp_s");
    if sea.spectrum != SpectrumKind::None && in_range && sea.steepness() >= MAX_STEEPNESS {
        let lambda = G_WAVE_MPS2 * tp * tp / (2.0 * std::f64::consts::PI);
        let tp_min = (hs / MAX_STEEPNESS * 2.0 * std::f64::consts::PI / G_WAVE_MPS2).sqrt();
        fail(
            "carrier.ship.sea.hs_m",
            &format!(
                "a significant wave height below λp/7 = {:.3} m for tp_s = {} s (significant \
                 steepness Hs/λp < 1/7, λp = g·Tp²/(2π) = {:.3} m: steeper waves break), \
                 or tp_s above {:.3} s for this height",
                Num(lambda * MAX_STEEPNESS),
                Num(tp),
                Num(lambda),
                Num(tp_min),
            ),
            format!("hs_m = {} (steepness {:.3})", Num(hs), Num(sea.steepness())),
        );
    }
}
