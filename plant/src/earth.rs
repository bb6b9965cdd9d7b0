//! WGS-84 Earth: radii of curvature, Earth rate and normal gravity at the site.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::real::{Divisor, Real, Reciprocal};
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
    radii_of_curvature_sin2(lat_rad.sin().powi(2))
}

/// [`radii_of_curvature`] from sin²(latitude) (a caller that has the sine already).
/// Generic over [`Real`], so a navigator in vector lanes computes each lane's bits.
#[inline(always)]
pub fn radii_of_curvature_sin2<T: Real>(s2: T) -> (T, T) {
    let w = Reciprocal::of((T::splat(1.0) - T::splat(WGS84_E2) * s2).sqrt());
    radii_of_curvature_w(&w)
}

/// The radii from w = √(1 − e²·sin²L) (with its reciprocal, which a vector build shares with
/// [`normal_gravity_w`]).
#[inline(always)]
fn radii_of_curvature_w<T: Real>(w: &Reciprocal<T>) -> (T, T) {
    let rn = T::splat(WGS84_A_M).div_rec(w);
    let w = w.value;
    let rm = T::splat(WGS84_A_M * (1.0 - WGS84_E2)) / (w * w * w);
    (rm, rn)
}

/// The radii of curvature (R_M, R_N) and normal gravity at sin²(latitude) `s2` and height
/// `height_m` with one square root for both (the bits of [`radii_of_curvature_sin2`] and
/// [`normal_gravity_sin2`]); what a navigator needs every update.
#[inline(always)]
pub fn radii_and_gravity_sin2<T: Real>(s2: T, height_m: T) -> (T, T, T) {
    let w = Reciprocal::of((T::splat(1.0) - T::splat(WGS84_E2) * s2).sqrt());
    let (rm, rn) = radii_of_curvature_w(&w);
    (rm, rn, normal_gravity_w(s2, &w, height_m))
}

/// WGS-84 normal gravity: Somigliana's closed form on the ellipsoid with the second-order
/// free-air height correction (NIMA TR8350.2, Eq. 4-1 and 4-3), m/s².
pub fn normal_gravity(lat_rad: f64, height_m: f64) -> f64 {
    normal_gravity_sin2(lat_rad.sin().powi(2), height_m)
}

/// [`normal_gravity`] from sin²(latitude). Generic over [`Real`], so a navigator in vector
/// lanes computes each lane's bits.
#[inline(always)]
pub fn normal_gravity_sin2<T: Real>(s2: T, height_m: T) -> T {
    let w = Reciprocal::of((T::splat(1.0) - T::splat(WGS84_E2) * s2).sqrt());
    normal_gravity_w(s2, &w, height_m)
}

/// Normal gravity from sin²(latitude) and w = √(1 − e²·sin²L).
#[inline(always)]
fn normal_gravity_w<T: Real>(s2: T, w: &Reciprocal<T>, height_m: T) -> T {
    let one = T::splat(1.0);
    let gamma0 = (T::splat(GAMMA_E_MPS2) * (one + T::splat(SOMIGLIANA_K) * s2)).div_rec(w);
    let b = WGS84_A_M * (1.0 - WGS84_F);
    let m = OMEGA_IE_RPS * OMEGA_IE_RPS * WGS84_A_M * WGS84_A_M * b / WGS84_GM;
    let h = height_m;
    gamma0
        * (one
            - T::splat(2.0 / WGS84_A_M)
                * (T::splat(1.0 + WGS84_F + m) - T::splat(2.0 * WGS84_F) * s2)
                * h
            + (T::splat(3.0) * h * h).div_by(A_SQUARED))
}

/// a² of [`normal_gravity_sin2`]'s height term, as a divisor.
const A_SQUARED: Divisor = Divisor::new(WGS84_A_M * WGS84_A_M);

/// Somigliana's constant k of [`normal_gravity`] (TR8350.2 Eq. 4-1).
const SOMIGLIANA_K: f64 = 0.001_931_852_652_41;
/// Normal gravity on the equator γ_e, m/s².
const GAMMA_E_MPS2: f64 = 9.780_325_335_9;

/// Grid of expansion latitudes of [`LocalEarth`]: 2⁻²⁰ rad (about 6 m), exact in binary.
const LOCAL_EARTH_GRID_RAD: f64 = 1.0 / 1_048_576.0;

/// Largest |L − L₀| a [`LocalEarth`] expands over before evaluating exactly, rad (≈ 64 m).
const LOCAL_EARTH_REACH_RAD: f64 = 1e-5;

/// WGS-84 quantities near a reference latitude L₀, by Taylor expansion: a moving carrier needs
/// the radii, gravity and Earth rate several times per tick within metres of one place, and a
/// sine, a cosine and a square root each time are most of their cost.
///
/// With δ = L − L₀ and q = sin²L: sin L and cos L from sin L₀, cos L₀ and the series of sin δ,
/// cos δ to δ⁵ and δ⁶ (error below δ⁷/5040); u = (1 − e²q)^(−½) to second order in Δq = q − q₀
/// (error below (5/16)e⁶·|Δq|³ ≈ 1e-22 for |δ| ≤ 1e-5); then R_N = a·u, R_M = a(1 − e²)·u³ and
/// γ₀ = γ_e(1 + kq)·u exactly as in [`radii_of_curvature`] and [`normal_gravity`]. Beyond
/// |δ| = 1e-5 rad it evaluates exactly. So it agrees with the closed forms to a few ulps (checked
/// in the tests below) at any L; it is a pure function of L₀ and L.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalEarth {
    lat0_rad: f64,
    sin0: f64,
    cos0: f64,
    q0: f64,
    u0: f64,
    /// du/dq and d²u/dq²/2 at q₀.
    u1: f64,
    u2: f64,
}

/// Earth quantities at one latitude (from [`LocalEarth::at`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EarthPoint {
    /// sin L.
    pub sin_lat: f64,
    /// cos L.
    pub cos_lat: f64,
    /// Meridian radius of curvature R_M, m.
    pub rm_m: f64,
    /// Transverse radius of curvature R_N, m.
    pub rn_m: f64,
    /// sin²L.
    q: f64,
    /// γ on the ellipsoid, m/s² (Somigliana).
    gamma0_mps2: f64,
}

impl LocalEarth {
    /// The expansion about the grid latitude nearest to `lat_rad` (a pure function of it, so a
    /// restored carrier rebuilds the same one).
    pub fn near(lat_rad: f64) -> Self {
        Self::about(Self::grid_lat_rad(lat_rad))
    }

    /// The grid latitude [`LocalEarth::near`] expands about, rad (cheap: no expansion built).
    #[inline]
    pub fn grid_lat_rad(lat_rad: f64) -> f64 {
        (lat_rad / LOCAL_EARTH_GRID_RAD).round() * LOCAL_EARTH_GRID_RAD
    }

    /// The expansion about `lat0_rad`.
    pub fn about(lat0_rad: f64) -> Self {
        let (sin0, cos0) = lat0_rad.sin_cos();
        let q0 = sin0 * sin0;
        let w2 = 1.0 - WGS84_E2 * q0;
        let u0 = 1.0 / w2.sqrt();
        // u = w2^(−½): du/dq = (e²/2)·u³, d²u/dq² = (3e⁴/4)·u⁵.
        let u3 = u0 * u0 * u0;
        Self {
            lat0_rad,
            sin0,
            cos0,
            q0,
            u0,
            u1: 0.5 * WGS84_E2 * u3,
            u2: 0.375 * WGS84_E2 * WGS84_E2 * u3 * u0 * u0,
        }
    }

    /// The expansion latitude L₀, rad.
    pub fn lat0_rad(&self) -> f64 {
        self.lat0_rad
    }

    /// Whether `lat_rad` is within the expansion's reach (else [`LocalEarth::at`] is exact).
    #[inline]
    pub fn covers(&self, lat_rad: f64) -> bool {
        (lat_rad - self.lat0_rad).abs() <= LOCAL_EARTH_REACH_RAD
    }

    /// sin L and cos L at latitude `lat_rad`.
    #[inline]
    pub fn sin_cos(&self, lat_rad: f64) -> (f64, f64) {
        let d = lat_rad - self.lat0_rad;
        if d.abs() > LOCAL_EARTH_REACH_RAD {
            return lat_rad.sin_cos();
        }
        // Multiplications by constant reciprocals: a division would lengthen the chain.
        let d2 = d * d;
        let sd = d * (1.0 + d2 * (-1.0 / 6.0 + d2 * (1.0 / 120.0)));
        let cd = 1.0 + d2 * (-0.5 + d2 * (1.0 / 24.0 + d2 * (-1.0 / 720.0)));
        (
            self.sin0 * cd + self.cos0 * sd,
            self.cos0 * cd - self.sin0 * sd,
        )
    }

    /// Sine, cosine, radii of curvature and ellipsoidal gravity at latitude `lat_rad`.
    #[inline]
    pub fn at(&self, lat_rad: f64) -> EarthPoint {
        let (s, c) = self.sin_cos(lat_rad);
        let u = if self.covers(lat_rad) {
            let dq = s * s - self.q0;
            self.u0 + dq * (self.u1 + dq * self.u2)
        } else {
            1.0 / (1.0 - WGS84_E2 * s * s).sqrt()
        };
        let q = s * s;
        let rn = WGS84_A_M * u;
        EarthPoint {
            sin_lat: s,
            cos_lat: c,
            rm_m: rn * (1.0 - WGS84_E2) * u * u,
            rn_m: rn,
            q,
            gamma0_mps2: GAMMA_E_MPS2 * (1.0 + SOMIGLIANA_K * q) * u,
        }
    }
}

impl EarthPoint {
    /// WGS-84 normal gravity at height `height_m` (as [`normal_gravity`]), m/s².
    #[inline]
    pub fn gravity_mps2(&self, height_m: f64) -> f64 {
        const B: f64 = WGS84_A_M * (1.0 - WGS84_F);
        const M: f64 = OMEGA_IE_RPS * OMEGA_IE_RPS * WGS84_A_M * WGS84_A_M * B / WGS84_GM;
        const C2: f64 = 3.0 / (WGS84_A_M * WGS84_A_M);
        let h = height_m;
        self.gamma0_mps2
            * (1.0 - 2.0 / WGS84_A_M * (1.0 + WGS84_F + M - 2.0 * WGS84_F * self.q) * h
                + C2 * h * h)
    }
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

    #[test]
    fn local_earth_matches_the_closed_forms() {
        // Against the closed forms, across the reach and beyond it, at several latitudes.
        let mut worst = [0.0f64; 5];
        for lat0 in [-1.5, -0.9, 0.0, 0.3, 0.6387, 1.2, 1.53] {
            let e = LocalEarth::near(lat0);
            for d in [0.0, 1e-9, -3e-7, 2.5e-6, -9.9e-6, 1e-5, 4e-5, -0.2] {
                let lat: f64 = lat0 + d;
                let p = e.at(lat);
                let (rm, rn) = radii_of_curvature(lat);
                let rel = [
                    (p.sin_lat - lat.sin()).abs(),
                    (p.cos_lat - lat.cos()).abs(),
                    (p.rm_m / rm - 1.0).abs(),
                    (p.rn_m / rn - 1.0).abs(),
                    (p.gravity_mps2(37.5) / normal_gravity(lat, 37.5) - 1.0).abs(),
                ];
                for (w, r) in worst.iter_mut().zip(rel) {
                    *w = w.max(r);
                }
            }
        }
        println!("local Earth vs closed forms (sin, cos, R_M, R_N, γ): {worst:?}");
        // A few ulps: the expansion errs by < 1e-20; the rest is rounding.
        assert!(worst.iter().all(|w| *w < 2e-15), "{worst:?}");
        assert!(LocalEarth::near(0.6387).covers(0.6387 + 9e-6));
        assert!(!LocalEarth::near(0.6387).covers(0.6387 + 2e-5));
    }
}
