//! WGS-84 Earth: radii of curvature, Earth rate and normal gravity at the site.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::units::DEG;

/// WGS-84 semi-major axis, m.
pub const WGS84_A_M: f64 = 6_378_137.0;
/// WGS-84 flattening.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;
/// WGS-84 first eccentricity squared.
pub const WGS84_E2: f64 = WGS84_F * (2.0 - WGS84_F);
/// WGS-84 Earth rotation rate Ω, rad/s.
pub const OMEGA_IE_RPS: f64 = 7.292_115e-5;
/// WGS-84 gravitational constant GM, m³/s².
pub const WGS84_GM: f64 = 3.986_004_418e14;

/// Geodetic position of the (static) system.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SiteSpec {
    /// Geodetic latitude, degrees, in [-89, 89] (the ENU frame is singular at the poles).
    pub lat_deg: f64,
    /// Longitude, degrees, in [-180, 360).
    pub lon_deg: f64,
    /// Ellipsoidal height, m, in [-1000, 20000].
    pub height_m: f64,
}

impl Default for SiteSpec {
    /// The paper's simulation site: 36.6° N, 123.6° E (Section 3.1).
    fn default() -> Self {
        Self {
            lat_deg: 36.6,
            lon_deg: 123.6,
            height_m: 0.0,
        }
    }
}

/// Switches for the Earth terms.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EarthSpec {
    /// Earth rotation sensed by the gyros. Off for the analytic checks of Eq. 8 and 11,
    /// which the paper derives neglecting Earth rate.
    pub rotation: bool,
    /// Normal gravity sensed by the accelerometers.
    pub gravity: bool,
}

impl Default for EarthSpec {
    fn default() -> Self {
        Self {
            rotation: true,
            gravity: true,
        }
    }
}

/// Earth quantities evaluated once at the site (the vehicle is static).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Site {
    /// Latitude, rad.
    pub lat_rad: f64,
    /// Longitude, rad.
    pub lon_rad: f64,
    /// Height, m.
    pub height_m: f64,
    /// Meridian radius of curvature R_M, m.
    pub rm_m: f64,
    /// Transverse radius of curvature R_N, m.
    pub rn_m: f64,
    /// Magnitude of normal gravity at the site (includes the centrifugal term), m/s².
    pub gravity_mps2: f64,
    /// Earth rate in ENU, rad/s: [0, Ω cos L, Ω sin L].
    pub omega_ie_n: Vector3<f64>,
}

impl Site {
    /// Evaluates the site with the given switches.
    pub fn new(spec: &SiteSpec, earth: &EarthSpec) -> Self {
        let lat = spec.lat_deg * DEG;
        let (rm, rn) = radii_of_curvature(lat);
        let omega = if earth.rotation { OMEGA_IE_RPS } else { 0.0 };
        Self {
            lat_rad: lat,
            lon_rad: spec.lon_deg * DEG,
            height_m: spec.height_m,
            rm_m: rm,
            rn_m: rn,
            gravity_mps2: if earth.gravity {
                normal_gravity(lat, spec.height_m)
            } else {
                0.0
            },
            omega_ie_n: Vector3::new(0.0, omega * lat.cos(), omega * lat.sin()),
        }
    }
}

/// Meridian and transverse radii of curvature (R_M, R_N) at geodetic latitude `lat_rad`.
pub fn radii_of_curvature(lat_rad: f64) -> (f64, f64) {
    let s2 = lat_rad.sin().powi(2);
    let w = (1.0 - WGS84_E2 * s2).sqrt();
    let rn = WGS84_A_M / w;
    let rm = WGS84_A_M * (1.0 - WGS84_E2) / (w * w * w);
    (rm, rn)
}

/// WGS-84 normal gravity: Somigliana's closed form on the ellipsoid with the second-order
/// free-air height correction (NIMA TR8350.2, Eq. 4-1 and 4-3), m/s².
pub fn normal_gravity(lat_rad: f64, height_m: f64) -> f64 {
    const GAMMA_E: f64 = 9.780_325_335_9;
    const K: f64 = 0.001_931_852_652_41;
    let s2 = lat_rad.sin().powi(2);
    let gamma0 = GAMMA_E * (1.0 + K * s2) / (1.0 - WGS84_E2 * s2).sqrt();
    let b = WGS84_A_M * (1.0 - WGS84_F);
    let m = OMEGA_IE_RPS * OMEGA_IE_RPS * WGS84_A_M * WGS84_A_M * b / WGS84_GM;
    let h = height_m;
    gamma0
        * (1.0 - 2.0 / WGS84_A_M * (1.0 + WGS84_F + m - 2.0 * WGS84_F * s2) * h
            + 3.0 * h * h / (WGS84_A_M * WGS84_A_M))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn normal_gravity_matches_published_equator_and_pole_values() {
        // TR8350.2 Table 3.4: gamma_e = 9.7803253359, gamma_p = 9.8321849378.
        assert_relative_eq!(normal_gravity(0.0, 0.0), 9.780_325_335_9, epsilon = 1e-10);
        assert_relative_eq!(
            normal_gravity(90.0 * DEG, 0.0),
            9.832_184_937_8,
            epsilon = 1e-9
        );
        // Free-air gradient near the surface is about -3.086e-6 m/s^2 per metre.
        let grad = normal_gravity(0.7, 100.0) - normal_gravity(0.7, 0.0);
        assert_relative_eq!(grad / 100.0, -3.086e-6, max_relative = 0.01);
    }

    #[test]
    fn radii_reduce_to_semi_axes_at_equator() {
        let (rm, rn) = radii_of_curvature(0.0);
        assert_relative_eq!(rn, WGS84_A_M, epsilon = 1e-6);
        assert_relative_eq!(rm, WGS84_A_M * (1.0 - WGS84_E2), epsilon = 1e-6);
    }
}
