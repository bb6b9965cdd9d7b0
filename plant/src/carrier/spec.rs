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
    /// Length of the leg, s, in (0, 1e8]; the last leg continues past its end.
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
    /// Shortest and longest component frequency as multiples of the peak frequency.
    pub band: [f64; 2],
    /// Vessel responses.
    pub rao: ShipRaoSpec,
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
        }
    }
}

impl SeaSpec {
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
    /// Start longitude, degrees, in [-180, 360).
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
}
