//! The `[carrier]` section: what carries the table (static, a ship, a trajectory file).

use serde::{Deserialize, Serialize};

/// Which carrier moves the table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CarrierKind {
    /// Fixed at `[site]` with the `[vehicle]` attitude: the plant's original path, bit for bit.
    #[default]
    Static,
    /// A ship on legs of heading and speed with sea-state motion ([`ShipSpec`]).
    Ship,
    /// Samples read from a CSV file ([`TrajectorySpec`]).
    Trajectory,
}

/// The carrier of the table. The table's outer gimbal axis is fixed to the carrier, so
/// C_b^n = C_c^n · C_v^c · R_z(outer) · R_x(inner), where C_v^c is the `[vehicle]` mount
/// (identity by default) and C_c^n the carrier attitude (right–forward–up carrier axes).
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CarrierSpec {
    /// `static` (default), `ship` or `trajectory`.
    pub kind: CarrierKind,
    /// Position of the table centre (the IMU) from the carrier's reference point, carrier axes
    /// (x starboard, y bow, z up), m, each in [-500, 500].
    pub lever_arm_m: [f64; 3],
    /// The ship (used when `kind = "ship"`).
    pub ship: ShipSpec,
    /// The trajectory file (used when `kind = "trajectory"`).
    pub trajectory: TrajectorySpec,
    /// Azimuth isolation (off by default): the outer gimbal counter-rotates the carrier's yaw,
    /// measured from the IMU's own increments and the inner encoder, so the scheme stays fixed
    /// in the navigation frame ([`super::isolation`]). Needs a moving carrier.
    pub azimuth_isolation: bool,
}

impl CarrierSpec {
    /// True for the static carrier (the plant then takes its original code path).
    pub fn is_static(&self) -> bool {
        self.kind == CarrierKind::Static
    }
}

/// One leg of a ship track.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LegSpec {
    /// Course over ground, degrees clockwise from north, in [-360, 360].
    pub heading_deg: f64,
    /// Speed over ground, knots, in [0, 60].
    pub speed_kn: f64,
    /// Length of the leg, s, in [0.001, 1e8]; the last leg continues past its end. A leg that
    /// would take the ship beyond ±89° latitude is refused (see [`super::track::MAX_LAT_DEG`]).
    pub duration_s: f64,
}

/// Wave spectrum family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpectrumKind {
    /// No waves: the ship follows its track only.
    #[default]
    None,
    /// Pierson–Moskowitz (ITTC two-parameter Bretschneider form).
    PiersonMoskowitz,
    /// JONSWAP with peak enhancement `gamma`.
    Jonswap,
}

/// Which seed draws a sea's realisation (its components' frequencies and phases).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SeaRealisation {
    /// The run's seed (`run.seed`): every seed of a Monte Carlo case sails its own sea.
    #[default]
    PerRun,
    /// `carrier.ship.sea.seed`: every run seed sails the same sea, as every seed follows the
    /// same route, so the seeds of a case differ in their sensors only (and a batch of them
    /// shares the ship's motion, computed once).
    Fixed,
}

/// Response of one degree of freedom to the waves: `gain` × direction factor × forcing ×
/// H(ω), H(ω) = 1 / (1 − (ω/ω_n)² + 2iζ ω/ω_n), ω_n = 2π / `natural_period_s` (H = 1 when the
/// natural period is 0). The forcing is the wave elevation (m) for heave, surge and sway and the
/// wave slope k·a = ω²a/g (rad) for roll, pitch and yaw, so `gain` is m/m or rad/rad.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RaoSpec {
    /// Low-frequency response amplitude, m/m (heave, surge, sway) or rad/rad (roll, pitch, yaw),
    /// in [0, 10].
    pub gain: f64,
    /// Natural period, s, in [0, 100]; 0 = no resonance.
    pub natural_period_s: f64,
    /// Damping ratio ζ, in [0.01, 2].
    pub damping: f64,
}

impl RaoSpec {
    const fn new(gain: f64, natural_period_s: f64, damping: f64) -> Self {
        Self {
            gain,
            natural_period_s,
            damping,
        }
    }
}

impl Default for RaoSpec {
    fn default() -> Self {
        Self::new(1.0, 0.0, 0.1)
    }
}

/// Response amplitude operators of the six degrees of freedom (a ~100 m displacement hull by
/// default: roll resonant at 10 s, pitch and heave well damped).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ShipRaoSpec {
    /// Roll (about the bow axis), rad per rad of wave slope; direction factor |sin β|.
    pub roll: RaoSpec,
    /// Pitch (about the starboard axis), rad/rad; direction factor |cos β|.
    pub pitch: RaoSpec,
    /// Yaw, rad/rad; direction factor |sin 2β|.
    pub yaw: RaoSpec,
    /// Heave, m/m; direction factor 1.
    pub heave: RaoSpec,
    /// Surge (along the bow axis), m/m; direction factor |cos β|.
    pub surge: RaoSpec,
    /// Sway (along the starboard axis), m/m; direction factor |sin β|.
    pub sway: RaoSpec,
}

impl Default for ShipRaoSpec {
    fn default() -> Self {
        Self {
            roll: RaoSpec::new(1.0, 10.0, 0.2),
            pitch: RaoSpec::new(0.8, 6.0, 0.5),
            yaw: RaoSpec::new(0.2, 0.0, 0.1),
            heave: RaoSpec::new(1.0, 7.0, 0.5),
            surge: RaoSpec::new(0.3, 0.0, 0.1),
            sway: RaoSpec::new(0.3, 0.0, 0.1),
        }
    }
}

/// Sea state: a seeded realisation of a named spectrum.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SeaSpec {
    /// Spectrum family.
    pub spectrum: SpectrumKind,
    /// Sea state number (WMO/NATO open ocean): 4 gives Hs 1.875 m, Tp 8.8 s; 5 gives Hs 3.25 m,
    /// Tp 9.7 s. 0 uses `hs_m` and `tp_s` as written. In [0, 6].
    pub sea_state: u32,
    /// Significant wave height H_s, m, in [0, 20].
    pub hs_m: f64,
    /// Peak period T_p, s, in [2, 30].
    pub tp_s: f64,
    /// JONSWAP peak enhancement γ, in [1, 7].
    pub gamma: f64,
    /// Wave encounter angle β, degrees: 0 following, 90 beam, 180 head seas. Fixed relative to
    /// the ship (it does not follow course changes).
    pub heading_to_waves_deg: f64,
    /// Number of wave components, in [1, 256].
    pub components: u32,
    /// Shortest and longest component frequency as multiples of the peak frequency, each in
    /// [0.1, 10], shortest first (band₀ < band₁: an empty band has no waves).
    pub band: [f64; 2],
    /// Vessel responses.
    pub rao: ShipRaoSpec,
    /// Which seed draws the realisation: `per-run` (the run's) or `fixed` (`seed` below).
    pub realisation: SeaRealisation,
    /// Seed of the realisation when `realisation = "fixed"` (unused otherwise).
    pub seed: u64,
}

impl Default for SeaSpec {
    fn default() -> Self {
        Self {
            spectrum: SpectrumKind::None,
            sea_state: 0,
            hs_m: 1.875,
            tp_s: 8.8,
            gamma: 3.3,
            heading_to_waves_deg: 135.0,
            components: 16,
            band: [0.6, 3.0],
            rao: ShipRaoSpec::default(),
            realisation: SeaRealisation::PerRun,
            seed: 0,
        }
    }
}

/// Largest significant steepness H_s/λ_p accepted (λ_p = g·T_p²/(2π), the deep-water length of
/// the peak wave): 1/7, the Stokes–Miche limit beyond which a regular wave breaks (H/λ ≈ 0.142).
/// A sea whose significant wave height exceeds it would be made of waves steeper than any that
/// exist; real open-ocean seas stay below about 1/15 (DNV-RP-C205 §3.5.5.4), so this refuses
/// only the impossible.
pub const MAX_STEEPNESS: f64 = 1.0 / 7.0;

/// Standard gravity of the deep-water dispersion relation, m/s².
pub const G_WAVE_MPS2: f64 = 9.806_65;

impl SeaSpec {
    /// The seed that draws the realisation for a run of seed `run_seed`.
    pub fn realisation_seed(&self, run_seed: u64) -> u64 {
        match self.realisation {
            SeaRealisation::PerRun => run_seed,
            SeaRealisation::Fixed => self.seed,
        }
    }

    /// Significant steepness H_s/λ_p of the sea ([`MAX_STEEPNESS`]) after the preset.
    pub fn steepness(&self) -> f64 {
        let (hs, tp) = self.hs_tp();
        hs / (G_WAVE_MPS2 * tp * tp / (2.0 * std::f64::consts::PI))
    }

    /// (H_s m, T_p s) after the sea-state preset.
    pub fn hs_tp(&self) -> (f64, f64) {
        match self.sea_state {
            1 => (0.05, 2.5),
            2 => (0.3, 5.0),
            3 => (0.875, 7.5),
            4 => (1.875, 8.8),
            5 => (3.25, 9.7),
            6 => (5.0, 12.4),
            _ => (self.hs_m, self.tp_s),
        }
    }
}

/// The ship: start point, legs, limits and sea state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ShipSpec {
    /// Start latitude, degrees, in [-80, 80].
    pub lat_deg: f64,
    /// Start longitude, degrees, in [-180, 360] (the truth reports longitudes wrapped into
    /// [-180, 180]; 360 is 0).
    pub lon_deg: f64,
    /// Mean height of the reference point, m, in [-1000, 1000].
    pub height_m: f64,
    /// Legs in order; the ship starts on the first leg's heading and speed.
    pub legs: Vec<LegSpec>,
    /// Peak rate of turn, deg/s, in [0.01, 10] (turns follow a cycloidal profile, see
    /// [`super::track`]).
    pub turn_rate_dps: f64,
    /// Peak along-track acceleration, m/s², in [0.001, 5].
    pub accel_mps2: f64,
    /// Sea-state motion.
    pub sea: SeaSpec,
}

impl Default for ShipSpec {
    fn default() -> Self {
        Self {
            lat_deg: 36.6,
            lon_deg: 123.6,
            height_m: 0.0,
            legs: vec![LegSpec {
                heading_deg: 0.0,
                speed_kn: 12.0,
                duration_s: 86_400.0,
            }],
            turn_rate_dps: 1.0,
            accel_mps2: 0.05,
            sea: SeaSpec::default(),
        }
    }
}

/// A trajectory file (see `docs/carrier.md` for the columns).
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TrajectorySpec {
    /// Path of the CSV file (read when the plant is built).
    pub file: String,
    /// What the carrier does after the file's last row: by default a file shorter than the
    /// run is an error.
    pub after_end: AfterEnd,
}

/// What a trajectory carrier does after the file's last row.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AfterEnd {
    /// A file that ends before the run does is refused (naming the file, its last time and
    /// the run's duration).
    #[default]
    Error,
    /// The carrier stops at the last row: its position and attitude, with zero velocity,
    /// acceleration and rates (a file that still moves at its last row then stops in one
    /// tick: end it at rest).
    Hold,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PlantConfig;

    /// A ship at sea state 0 with the given JONSWAP sea (H_s, T_p, band).
    fn ship_with(f: impl Fn(&mut ShipSpec)) -> PlantConfig {
        let mut cfg = PlantConfig::default();
        cfg.carrier.kind = CarrierKind::Ship;
        cfg.carrier.ship.sea.spectrum = SpectrumKind::Jonswap;
        f(&mut cfg.carrier.ship);
        cfg
    }

    /// The validation errors as "path: expected …, got …" lines.
    fn errors(cfg: &PlantConfig) -> Vec<String> {
        cfg.validate()
            .err()
            .unwrap_or_default()
            .iter()
            .map(|e| e.to_string())
            .collect()
    }

    /// Issue 29, sea state: every input family's case, with the field the error must name
    /// (`None`: accepted). The steepness limit is checked against λ_p = g·T_p²/(2π) computed
    /// here: just below 1/7 is accepted, just above refused.
    #[test]
    fn sea_states_are_validated_against_physics() {
        let lambda = |tp: f64| 9.806_65 * tp * tp / (2.0 * std::f64::consts::PI);
        type Case = (
            &'static str,
            Box<dyn Fn(&mut ShipSpec)>,
            Option<&'static str>,
        );
        let cases: Vec<Case> = vec![
            ("defaults", Box::new(|_| {}), None),
            (
                "band reversed",
                Box::new(|s| s.sea.band = [3.0, 0.6]),
                Some("carrier.ship.sea.band"),
            ),
            (
                "band empty",
                Box::new(|s| s.sea.band = [1.0, 1.0]),
                Some("carrier.ship.sea.band"),
            ),
            (
                "band narrow but ordered",
                Box::new(|s| s.sea.band = [1.0, 1.01]),
                None,
            ),
            (
                "Hs 20 m at Tp 2 s (steepness 3.2)",
                Box::new(|s| (s.sea.hs_m, s.sea.tp_s) = (20.0, 2.0)),
                Some("carrier.ship.sea.hs_m"),
            ),
            (
                "just below 1/7 at Tp 2 s",
                Box::new(move |s| (s.sea.hs_m, s.sea.tp_s) = (0.999 * lambda(2.0) / 7.0, 2.0)),
                None,
            ),
            (
                "just above 1/7 at Tp 2 s",
                Box::new(move |s| (s.sea.hs_m, s.sea.tp_s) = (1.001 * lambda(2.0) / 7.0, 2.0)),
                Some("carrier.ship.sea.hs_m"),
            ),
            (
                "Hs 20 m at Tp 9.5 s (just below: Tp > 9.47 s)",
                Box::new(|s| (s.sea.hs_m, s.sea.tp_s) = (20.0, 9.5)),
                None,
            ),
            (
                "steep numbers without a spectrum",
                Box::new(|s| {
                    s.sea.spectrum = SpectrumKind::None;
                    (s.sea.hs_m, s.sea.tp_s) = (20.0, 2.0)
                }),
                None,
            ),
            ("preset 6", Box::new(|s| s.sea.sea_state = 6), None),
            ("preset 1", Box::new(|s| s.sea.sea_state = 1), None),
        ];
        for (name, f, want) in cases {
            let e = errors(&ship_with(f));
            match want {
                None => assert!(e.is_empty(), "{name}: {e:?}"),
                Some(path) => {
                    assert_eq!(e.len(), 1, "{name}: {e:?}");
                    assert!(e[0].starts_with(path), "{name}: {e:?}");
                }
            }
        }
        // The messages give the allowed range.
        let e = errors(&ship_with(|s| s.sea.band = [3.0, 0.6]));
        assert!(
            e[0].contains("band[0] < band[1]") && e[0].contains("[3, 0.6]"),
            "{e:?}"
        );
        let e = errors(&ship_with(|s| (s.sea.hs_m, s.sea.tp_s) = (20.0, 2.0)));
        assert!(
            e[0].contains("below λp/7 = 0.892 m") && e[0].contains("9.47"),
            "{e:?}"
        );
        // Every preset is far inside the limit (the steepest, sea state 1, at 0.005).
        for n in 1..=6 {
            let s = SeaSpec {
                sea_state: n,
                ..SeaSpec::default()
            };
            assert!(s.steepness() < 0.04, "preset {n}: {}", s.steepness());
        }
    }

    /// Issue 29, legs and start: one message with one range for a zero duration, and the
    /// start longitude's range as documented ([-180, 360]).
    #[test]
    fn leg_and_start_fields_quote_one_range() {
        let e = errors(&ship_with(|s| s.legs[0].duration_s = 0.0));
        assert_eq!(e.len(), 1, "{e:?}");
        assert!(
            e[0].starts_with("carrier.ship.legs[0].duration_s: expected a number in [0.001, 1e8]"),
            "{e:?}"
        );
        for (lon, ok) in [
            (-180.0, true),
            (359.9, true),
            (360.0, true),
            (360.5, false),
            (-180.5, false),
        ] {
            let e = errors(&ship_with(|s| s.lon_deg = lon));
            assert_eq!(e.is_empty(), ok, "{lon}: {e:?}");
        }
    }
}
