//! The ship's mean track: legs of course and speed joined by smooth turns and speed changes, on
//! the WGS-84 ellipsoid.
//!
//! Each change follows the cycloidal profile S(x) = x − sin(2πx)/(2π), x = τ/T ∈ [0, 1]: rate and
//! acceleration start and end at zero, so velocity and acceleration are continuous (the
//! quadrature then has no corner to miss). The peak rate 2·Δ/T is the limit: a turn of Δψ at the
//! turn-rate limit r lasts T = 2|Δψ|/r, a speed change of Δu at the acceleration limit a lasts
//! T = 2|Δu|/a.
//!
//! Course ψ (clockwise from north) and speed u are closed-form in time; the ground velocity is
//! v^n = u·[sin ψ, cos ψ, 0] (ENU) and its derivative u̇·[sin ψ, cos ψ, 0] + u·ψ̇·[cos ψ, −sin ψ, 0].
//! Latitude and longitude are integrated tick by tick (see [`TrackPosition`]).

use nalgebra::Vector3;

use super::spec::ShipSpec;
use crate::earth::{EarthPoint, LocalEarth};
use crate::message::Num;
use crate::units::DEG;

/// Knots to m/s.
pub const KNOT_MPS: f64 = 1852.0 / 3600.0;

/// One leg, resolved: start time, start and commanded course and speed, rates.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Leg {
    t0_s: f64,
    psi0_rad: f64,
    /// Signed course change, rad, and turn duration, s.
    turn_rps: f64,
    turn_s: f64,
    u0_mps: f64,
    /// Signed speed change, m/s, and its duration, s.
    acc_mps2: f64,
    acc_s: f64,
}

/// Course and speed with their rates at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrackPoint {
    /// Course ψ, rad clockwise from north.
    pub psi_rad: f64,
    /// ψ̇, rad/s.
    pub psi_rate_rps: f64,
    /// ψ̈, rad/s².
    pub psi_acc_rps2: f64,
    /// Speed u, m/s.
    pub speed_mps: f64,
    /// u̇, m/s².
    pub speed_rate_mps2: f64,
}

impl TrackPoint {
    /// Ground velocity of the mean track, ENU, m/s.
    pub fn v_n(&self) -> Vector3<f64> {
        let (s, c) = self.psi_rad.sin_cos();
        Vector3::new(self.speed_mps * s, self.speed_mps * c, 0.0)
    }

    /// Its time derivative (ENU components), m/s².
    pub fn a_n(&self) -> Vector3<f64> {
        let (s, c) = self.psi_rad.sin_cos();
        let (u, ud, w) = (self.speed_mps, self.speed_rate_mps2, self.psi_rate_rps);
        Vector3::new(ud * s + u * w * c, ud * c - u * w * s, 0.0)
    }
}

/// Course and speed as closed-form functions of time.
#[derive(Clone, Debug, PartialEq)]
pub struct Track {
    legs: Vec<Leg>,
}

/// Wraps an angle to (−π, π].
fn wrap_pi(a: f64) -> f64 {
    let w = a.rem_euclid(2.0 * std::f64::consts::PI);
    if w > std::f64::consts::PI {
        w - 2.0 * std::f64::consts::PI
    } else {
        w
    }
}

impl Track {
    /// Resolves the legs: each leg turns the shorter way at the turn-rate limit and changes speed
    /// at the acceleration limit, both from the leg's start, from wherever the previous leg left
    /// the ship. The first leg starts on its own course and speed.
    pub fn new(spec: &ShipSpec) -> Self {
        let rate = spec.turn_rate_dps * DEG;
        let acc = spec.accel_mps2;
        let mut legs = Vec::with_capacity(spec.legs.len());
        let first = spec.legs.first().copied().unwrap_or(super::spec::LegSpec {
            heading_deg: 0.0,
            speed_kn: 0.0,
            duration_s: 1.0,
        });
        let (mut psi, mut u, mut t0) = (first.heading_deg * DEG, first.speed_kn * KNOT_MPS, 0.0);
        for l in &spec.legs {
            let dpsi = wrap_pi(l.heading_deg * DEG - psi);
            let du = l.speed_kn * KNOT_MPS - u;
            let leg = Leg {
                t0_s: t0,
                psi0_rad: psi,
                turn_rps: dpsi,
                turn_s: 2.0 * dpsi.abs() / rate,
                u0_mps: u,
                acc_mps2: du,
                acc_s: 2.0 * du.abs() / acc,
            };
            legs.push(leg);
            let end = leg.eval(t0 + l.duration_s);
            (psi, u, t0) = (end.psi_rad, end.speed_mps, t0 + l.duration_s);
        }
        if legs.is_empty() {
            legs.push(Leg {
                t0_s: 0.0,
                psi0_rad: 0.0,
                turn_rps: 0.0,
                turn_s: 0.0,
                u0_mps: 0.0,
                acc_mps2: 0.0,
                acc_s: 0.0,
            });
        }
        Self { legs }
    }

    /// Times where a course or speed change starts or ends, s, ascending: the third derivative
    /// of the course (and the second of the speed) jumps there, so a polynomial across one
    /// is not accurate (the segment rule takes those segments tick by tick).
    pub fn corners_s(&self) -> Vec<f64> {
        let mut c: Vec<f64> = self
            .legs
            .iter()
            .flat_map(|l| {
                // Every leg start (a change cut short by the leg's end leaves a corner there).
                let turn = (l.turn_s > 0.0).then_some(l.t0_s + l.turn_s);
                let acc = (l.acc_s > 0.0).then_some(l.t0_s + l.acc_s);
                std::iter::once(l.t0_s).chain(turn).chain(acc)
            })
            .collect();
        c.sort_by(f64::total_cmp);
        c.dedup();
        c
    }

    /// Shortest course or speed change, s (infinite without one): its profile's angular
    /// frequency 2π/T bounds the mean track's spectrum.
    pub fn shortest_change_s(&self) -> f64 {
        self.legs
            .iter()
            .flat_map(|l| [l.turn_s, l.acc_s])
            .filter(|&d| d > 0.0)
            .fold(f64::INFINITY, f64::min)
    }

    /// Index of the leg holding time `t_s`, searched from `hint` (calls run forward in time).
    pub fn leg_at(&self, t_s: f64, hint: usize) -> usize {
        let mut i = hint.min(self.legs.len() - 1);
        while i > 0 && t_s < self.legs[i].t0_s {
            i -= 1;
        }
        while i + 1 < self.legs.len() && t_s >= self.legs[i + 1].t0_s {
            i += 1;
        }
        i
    }

    /// Course and speed at `t_s` within leg `leg` (from [`Track::leg_at`]).
    #[inline]
    pub fn eval(&self, leg: usize, t_s: f64) -> TrackPoint {
        self.legs[leg].eval(t_s)
    }
}

impl Leg {
    #[inline]
    fn eval(&self, t_s: f64) -> TrackPoint {
        let tau = t_s - self.t0_s;
        let (psi, psi_rate, psi_acc) = cycloidal(self.psi0_rad, self.turn_rps, tau, self.turn_s);
        let (u, u_rate, _) = cycloidal(self.u0_mps, self.acc_mps2, tau, self.acc_s);
        TrackPoint {
            psi_rad: psi,
            psi_rate_rps: psi_rate,
            psi_acc_rps2: psi_acc,
            speed_mps: u,
            speed_rate_mps2: u_rate,
        }
    }
}

/// Value, rate and acceleration of a change of `delta` from `start` over `dur_s` along the
/// cycloidal profile, at `tau` seconds from its start.
#[inline]
pub fn cycloidal(start: f64, delta: f64, tau: f64, dur_s: f64) -> (f64, f64, f64) {
    if tau >= dur_s || dur_s <= 0.0 {
        return (start + delta, 0.0, 0.0);
    }
    let x = tau.max(0.0) / dur_s;
    let w = 2.0 * std::f64::consts::PI;
    let (s, c) = (w * x).sin_cos();
    (
        start + delta * (x - s / w),
        delta * (1.0 - c) / dur_s,
        delta * w * s / (dur_s * dur_s),
    )
}

/// Latitude and longitude of the mean track, advanced one tick at a time (the only integrated
/// carrier state). Over a tick of length h the north and east displacements are the two-point
/// Gauss–Legendre integrals of the closed-form velocity (exact to O(h⁵) within a leg segment),
/// divided by the radii of curvature at the mid-tick latitude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrackPosition {
    /// Latitude, rad.
    pub lat_rad: f64,
    /// Longitude, rad.
    pub lon_rad: f64,
}

impl TrackPosition {
    /// Advances over one tick given the displacement north and east (m) at mean height `h_m`;
    /// returns the latitude and longitude increments used.
    pub fn advance(&mut self, d_north_m: f64, d_east_m: f64, h_m: f64) -> (f64, f64) {
        self.advance_near(&LocalEarth::near(self.lat_rad), d_north_m, d_east_m, h_m)
    }

    /// [`TrackPosition::advance`] with the radii from `earth` (an expansion near here).
    #[inline]
    pub fn advance_near(
        &mut self,
        earth: &LocalEarth,
        d_north_m: f64,
        d_east_m: f64,
        h_m: f64,
    ) -> (f64, f64) {
        let here = earth.at(self.lat_rad);
        let (dlat, dlon, _) = self.advance_from(earth, &here, d_north_m, d_east_m, h_m);
        (dlat, dlon)
    }

    /// [`TrackPosition::advance_near`] given the Earth quantities `here` at the current latitude;
    /// also returns those at the mid-tick latitude.
    #[inline]
    pub fn advance_from(
        &mut self,
        earth: &LocalEarth,
        here: &EarthPoint,
        d_north_m: f64,
        d_east_m: f64,
        h_m: f64,
    ) -> (f64, f64, EarthPoint) {
        let lat_mid = self.lat_rad + 0.5 * d_north_m / (here.rm_m + h_m);
        let mid = earth.at(lat_mid);
        let dlat = d_north_m / (mid.rm_m + h_m);
        let dlon = d_east_m / ((mid.rn_m + h_m) * mid.cos_lat);
        self.lat_rad += dlat;
        self.lon_rad += dlon;
        // Across the antimeridian the longitude wraps (a no-op, bit for bit, within ±π).
        self.lon_rad = wrap_lon_rad(self.lon_rad);
        (dlat, dlon, mid)
    }
}

/// The furthest from the equator a ship may sail, degrees (as trajectory files and external
/// carrier inputs). The mean track is a sequence of rhumb lines (constant course), which
/// spiral into a pole without passing it, and the local-level (ENU) frame is singular there
/// (the transport rate holds tan L): a leg that would go beyond is refused
/// ([`Track::polar_excursion`]).
pub const MAX_LAT_DEG: f64 = 89.0;

/// A leg that would take the ship beyond ±[`MAX_LAT_DEG`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolarExcursion {
    /// Index of the leg (0-based).
    pub leg: usize,
    /// When the leg reaches its furthest latitude, s from the start.
    pub t_s: f64,
    /// That latitude, degrees, from the leg's northing along the meridian arc (beyond ±90 when
    /// the northing would carry the ship past the pole).
    pub lat_deg: f64,
}

/// Meridian arc from the equator to latitude `lat` at height `h_m` above the ellipsoid,
/// m: Helmert's series to e⁶ plus h·L (dM = (R_M + h)·dL, the mean track's own rule). Defined
/// for any `lat` (past a pole it keeps growing), so a northing that overshoots a pole maps to a
/// latitude beyond ±90°.
fn meridian_arc_m(lat: f64, h_m: f64) -> f64 {
    let a = crate::earth::WGS84_A_M;
    let e2 = crate::earth::WGS84_E2;
    let (e4, e6) = (e2 * e2, e2 * e2 * e2);
    let a0 = 1.0 + 0.75 * e2 + 45.0 / 64.0 * e4 + 175.0 / 256.0 * e6;
    let a2 = 0.75 * e2 + 15.0 / 16.0 * e4 + 525.0 / 512.0 * e6;
    let a4 = 15.0 / 64.0 * e4 + 105.0 / 256.0 * e6;
    let a6 = 35.0 / 512.0 * e6;
    a * (1.0 - e2)
        * (a0 * lat - a2 / 2.0 * (2.0 * lat).sin() + a4 / 4.0 * (4.0 * lat).sin()
            - a6 / 6.0 * (6.0 * lat).sin())
        + h_m * lat
}

/// The latitude whose meridian arc (at height `h_m`) is `m`: Newton steps from a sphere.
fn latitude_of_arc(m: f64, h_m: f64) -> f64 {
    let mut lat = m / 6_367_449.0;
    for _ in 0..8 {
        let (rm, _) = crate::earth::radii_of_curvature(lat);
        lat -= (meridian_arc_m(lat, h_m) - m) / (rm + h_m);
    }
    lat
}

/// Wraps a longitude into [−π, π]: `lon` itself (the same bits) when it is inside, else its
/// equivalent in [−π, π). Also the shortest way between two longitudes, applied to their
/// difference.
#[inline]
pub fn wrap_lon_rad(lon: f64) -> f64 {
    use std::f64::consts::PI;
    if (-PI..=PI).contains(&lon) {
        lon
    } else {
        (lon + PI).rem_euclid(2.0 * PI) - PI
    }
}

impl Track {
    /// The first leg whose mean track, from latitude `lat0_rad` at height `h_m`, goes beyond
    /// ±[`MAX_LAT_DEG`] before `until_s` (the last leg continues to `until_s`), with the
    /// furthest latitude that leg would reach and when; `None` when the track stays inside.
    ///
    /// The latitude is a function of the northing N(t) = ∫ u·cos ψ dt alone (the meridian arc,
    /// Helmert's series, inverted): during a leg's course and speed changes N is integrated by
    /// Gauss–Legendre in steps of at most 10 s; afterwards u·cos ψ is constant, so N is linear
    /// and its extremes are at the ends.
    pub fn polar_excursion(&self, lat0_rad: f64, h_m: f64, until_s: f64) -> Option<PolarExcursion> {
        let limit = MAX_LAT_DEG.to_radians();
        let m0 = meridian_arc_m(lat0_rad, h_m);
        let north = |tp: TrackPoint| tp.speed_mps * tp.psi_rad.cos();
        let g = 0.5 / 3f64.sqrt();
        let mut n = 0.0;
        for (i, leg) in self.legs.iter().enumerate() {
            let end = self
                .legs
                .get(i + 1)
                .map_or(until_s, |l| l.t0_s)
                .min(until_s);
            if leg.t0_s >= end {
                break;
            }
            // (northing, time) of the leg's furthest point from the equator so far.
            let lat_at = |n: f64| latitude_of_arc(m0 + n, h_m);
            let mut worst = (lat_at(n), leg.t0_s);
            let note = |n: f64, t: f64, worst: &mut (f64, f64)| {
                let lat = lat_at(n);
                if lat.abs() > worst.0.abs() {
                    *worst = (lat, t);
                }
            };
            let change_end = (leg.t0_s + leg.turn_s.max(leg.acc_s)).min(end);
            let steps = ((change_end - leg.t0_s) / 10.0).ceil().max(0.0) as usize;
            let dt = if steps > 0 {
                (change_end - leg.t0_s) / steps as f64
            } else {
                0.0
            };
            for k in 0..steps {
                let t = leg.t0_s + k as f64 * dt;
                n += 0.5
                    * dt
                    * (north(leg.eval(t + (0.5 - g) * dt)) + north(leg.eval(t + (0.5 + g) * dt)));
                note(n, t + dt, &mut worst);
            }
            n += north(leg.eval(end)) * (end - change_end);
            note(n, end, &mut worst);
            if worst.0.abs() > limit {
                return Some(PolarExcursion {
                    leg: i,
                    t_s: worst.1,
                    lat_deg: worst.0.to_degrees(),
                });
            }
        }
        None
    }
}

/// A ship leg that would go beyond ±[`MAX_LAT_DEG`] before `until_s` (the last
/// leg continuing), as (path, expected, got) for an error message; `None` when the track
/// stays inside.
pub fn polar_problem(ship: &ShipSpec, until_s: f64) -> Option<(String, String, String)> {
    let track = Track::new(ship);
    let x = track.polar_excursion(ship.lat_deg.to_radians(), ship.height_m, until_s)?;
    let l = ship.legs.get(x.leg)?;
    let last = x.leg + 1 == ship.legs.len();
    let span = if last && until_s > track_end_s(ship) {
        format!("continued to the end of the run at {} s", Num(until_s))
    } else {
        format!("{} s long", Num(l.duration_s))
    };
    Some((
        format!("carrier.ship.legs[{}]", x.leg),
        format!(
            "legs that keep the ship within ±{} ° latitude (a rhumb line spirals into a pole \
             and never passes it, and the local-level frame is singular there): change the \
             leg's heading or shorten it",
            MAX_LAT_DEG
        ),
        format!(
            "leg {} (heading {} °, {} kn, {span}) would reach latitude {:.3} ° at t = {:.0} s",
            x.leg,
            Num(l.heading_deg),
            Num(l.speed_kn),
            x.lat_deg,
            x.t_s
        ),
    ))
}

/// The end of the last leg, s.
fn track_end_s(ship: &ShipSpec) -> f64 {
    ship.legs.iter().map(|l| l.duration_s).sum()
}
