//! Strapdown mechanisation in the local-level ENU frame on WGS-84, consuming Δθ/Δv increments.
//!
//! Attitude: q_b^n(k) = q(−ζ_k) ⊗ q_b^n(k−1) ⊗ q(φ_k), with the coning-corrected body rotation
//! φ_k = Δθ_k + (1/12)·Δθ_{k−1} × Δθ_k (two-sample, previous interval) and the navigation-frame
//! rotation ζ_k = ω_in^n·Δt. Velocity: the sculling-corrected specific-force increment
//! Δv_sf = Δv_k + ½Δθ_k × Δv_k + (1/12)(Δθ_{k−1} × Δv_k + Δv_{k−1} × Δθ_k), rotated with
//! (I − ½[ζ×])·C_b^n(k−1), plus (g^n − (2ω_ie^n + ω_en^n) × v^n)·Δt.
//! The vertical channel of a free inertial navigator is unstable; see [`VerticalChannel`].

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use rins_plant::earth::{OMEGA_IE_RPS, radii_of_curvature_sin2};
use rins_plant::trig::GridTrig;

// The equations take it, so it is defined with them; its path is this module.
use crate::mechanisation::Solution;
pub use crate::mechanisation::VerticalChannel;
use crate::subsamples::Subsamples;

/// Position, velocity and attitude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NavState {
    /// Attitude q_b^n (body to ENU).
    pub q_bn: UnitQuaternion<f64>,
    /// Velocity in ENU, m/s.
    pub v_n: Vector3<f64>,
    /// Geodetic latitude, rad.
    pub lat_rad: f64,
    /// Longitude, rad.
    pub lon_rad: f64,
    /// Height, m.
    pub height_m: f64,
}

/// Rotation-vector to quaternion by its series (the plant's isolation loop uses the same).
pub use rins_plant::attitude::quat_from_rotvec;

/// The strapdown navigator.
#[derive(Clone, Debug)]
pub struct Strapdown {
    state: NavState,
    vertical: VerticalChannel,
    dt_s: f64,
    prev_dtheta: Vector3<f64>,
    prev_dv: Vector3<f64>,
    lat_trig: GridTrig,
    steps: u64,
    subsamples: Subsamples,
    /// The intervals of the update under way (the first `pending` of them), when an update
    /// takes several ([`Strapdown::with_subsamples`]).
    pending_dtheta: [Vector3<f64>; MAX_PENDING],
    pending_dv: [Vector3<f64>; MAX_PENDING],
    pending: usize,
}

/// Intervals an update can hold before its last one.
pub(crate) const MAX_PENDING: usize = Subsamples::MAX as usize - 1;

impl Strapdown {
    /// Starts from `state`, consuming increments over intervals of `dt_s`.
    pub fn new(state: NavState, dt_s: f64, vertical: VerticalChannel) -> Self {
        let mut s = Self {
            state,
            vertical,
            dt_s,
            prev_dtheta: Vector3::zeros(),
            prev_dv: Vector3::zeros(),
            lat_trig: GridTrig::default(),
            steps: 0,
            subsamples: Subsamples::ONE,
            pending_dtheta: [Vector3::zeros(); MAX_PENDING],
            pending_dv: [Vector3::zeros(); MAX_PENDING],
            pending: 0,
        };
        if let VerticalChannel::Hold { ref_height_m } = vertical {
            s.state.height_m = ref_height_m;
            s.state.v_n.z = 0.0;
        }
        s
    }

    /// The same navigator updating once every `n` intervals, with the N-sample coning and
    /// sculling combination ([`crate::subsamples`]); its state moves at each update (every
    /// n-th [`Strapdown::update`]). Panics if intervals are held already.
    pub fn with_subsamples(mut self, n: Subsamples) -> Self {
        assert_eq!(self.pending, 0, "subsamples set with an update under way");
        self.subsamples = n;
        self
    }

    /// Intervals per update.
    pub fn subsamples(&self) -> Subsamples {
        self.subsamples
    }

    /// The intervals held for the update under way: Δθ (rad) and Δv (m/s) in order.
    pub fn pending(&self) -> (&[Vector3<f64>], &[Vector3<f64>]) {
        (
            &self.pending_dtheta[..self.pending],
            &self.pending_dv[..self.pending],
        )
    }

    /// Current solution (as of the last update).
    pub fn state(&self) -> &NavState {
        &self.state
    }

    /// Overwrites the solution (used by alignment feedback).
    pub fn set_state(&mut self, state: NavState) {
        self.state = state;
    }

    /// Increments consumed so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Update interval, s.
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }

    /// Vertical-channel handling.
    pub fn vertical(&self) -> VerticalChannel {
        self.vertical
    }

    /// Earth rate ω_ie^n and transport rate ω_en^n at the current solution, rad/s (the terms
    /// of [`crate::mechanisation`]).
    pub fn frame_rates(&self) -> (Vector3<f64>, Vector3<f64>) {
        let s = &self.state;
        let (sl, cl) = GridTrig::default().sin_cos(s.lat_rad);
        let (rm, rn) = radii_of_curvature_sin2(sl * sl);
        let w_ie = Vector3::new(0.0, OMEGA_IE_RPS * cl, OMEGA_IE_RPS * sl);
        let rnh = rn + s.height_m;
        let w_en = Vector3::new(
            -s.v_n.y / (rm + s.height_m),
            s.v_n.x / rnh,
            s.v_n.x * sl / cl / rnh,
        );
        (w_ie, w_en)
    }

    /// Consumes one interval's increments Δθ (rad) and Δv (m/s) (the equations of
    /// [`crate::mechanisation`]); with several intervals per update, holds them until the
    /// update's last.
    pub fn update(&mut self, dtheta: &Vector3<f64>, dv: &Vector3<f64>) {
        self.steps += 1;
        let n = self.subsamples.get();
        if n == 1 {
            let mut m = self.solution();
            crate::mechanisation::update(
                &mut m,
                &(*dtheta).into(),
                &(*dv).into(),
                self.dt_s,
                self.vertical,
            );
            self.set_solution(&m);
            return;
        }
        if self.pending + 1 < n {
            self.pending_dtheta[self.pending] = *dtheta;
            self.pending_dv[self.pending] = *dv;
            self.pending += 1;
            return;
        }
        let th: [[f64; 3]; MAX_PENDING + 1] = std::array::from_fn(|i| {
            if i < self.pending {
                self.pending_dtheta[i].into()
            } else {
                (*dtheta).into()
            }
        });
        let dvs: [[f64; 3]; MAX_PENDING + 1] = std::array::from_fn(|i| {
            if i < self.pending {
                self.pending_dv[i].into()
            } else {
                (*dv).into()
            }
        });
        let mut m = self.solution();
        crate::subsamples::update_subsamples(&mut m, &th[..n], &dvs[..n], self.dt_s, self.vertical);
        self.set_solution(&m);
        self.pending = 0;
    }

    /// The solution and the previous increments as the equations use them.
    pub(crate) fn solution(&self) -> Solution<f64> {
        let s = &self.state;
        Solution {
            q: s.q_bn.coords.into(),
            v: s.v_n.into(),
            lat: s.lat_rad,
            lon: s.lon_rad,
            h: s.height_m,
            prev_dtheta: self.prev_dtheta.into(),
            prev_dv: self.prev_dv.into(),
            lat_trig: self.lat_trig,
        }
    }

    fn set_solution(&mut self, m: &Solution<f64>) {
        self.state = NavState {
            q_bn: UnitQuaternion::new_unchecked(Quaternion::from(nalgebra::Vector4::from(m.q))),
            v_n: m.v.into(),
            lat_rad: m.lat,
            lon_rad: m.lon,
            height_m: m.h,
        };
        self.prev_dtheta = m.prev_dtheta.into();
        self.prev_dv = m.prev_dv.into();
        self.lat_trig = m.lat_trig;
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::Matrix3;
    use rins_plant::earth::normal_gravity_sin2;

    /// The latitude's terms, as the reference update computed them.
    struct Latitude {
        sin: f64,
        cos: f64,
        sin2: f64,
        rm: f64,
        rn: f64,
    }

    impl Latitude {
        #[inline]
        fn of(lat_rad: f64) -> Self {
            let (sin, cos) = GridTrig::default().sin_cos(lat_rad);
            let sin2 = sin.powi(2);
            let (rm, rn) = radii_of_curvature_sin2(sin2);
            Self {
                sin,
                cos,
                sin2,
                rm,
                rn,
            }
        }
    }

    fn frame_rates_at(nav: &Strapdown, l: &Latitude) -> (Vector3<f64>, Vector3<f64>) {
        let s = &nav.state;
        let (rm, rn, sl, cl) = (l.rm, l.rn, l.sin, l.cos);
        let w_ie = Vector3::new(0.0, OMEGA_IE_RPS * cl, OMEGA_IE_RPS * sl);
        let rnh = rn + s.height_m;
        let w_en = Vector3::new(
            -s.v_n.y / (rm + s.height_m),
            s.v_n.x / rnh,
            s.v_n.x * sl / cl / rnh,
        );
        (w_ie, w_en)
    }

    /// The update as first written, with nalgebra's types: the reference the equations of
    /// [`crate::mechanisation`] are checked against bit for bit.
    fn reference_update(nav: &mut Strapdown, dtheta: &Vector3<f64>, dv: &Vector3<f64>) {
        let dt = nav.dt_s;
        let (pth, pdv) = (nav.prev_dtheta, nav.prev_dv);
        let phi = dtheta + pth.cross(dtheta) / 12.0;
        let dv_sf_b = dv + 0.5 * dtheta.cross(dv) + (pth.cross(dv) + pdv.cross(dtheta)) / 12.0;
        nav.prev_dtheta = *dtheta;
        nav.prev_dv = *dv;

        let s = nav.state;
        // The latitude's sine, cosine and radii once per update (the same bits as computing
        // them where each is used).
        let l = Latitude::of(s.lat_rad);
        let (w_ie, w_en) = frame_rates_at(nav, &l);
        assert_eq!((w_ie, w_en), nav.frame_rates());
        let w_in = w_ie + w_en;
        let zeta = w_in * dt;
        let c_bn = s.q_bn.to_rotation_matrix().into_inner();
        let dv_sf_n = (Matrix3::identity() - 0.5 * zeta.cross_matrix()) * (c_bn * dv_sf_b);
        let g_n = Vector3::new(0.0, 0.0, -normal_gravity_sin2(l.sin2, s.height_m));
        let mut v = s.v_n + dv_sf_n + (g_n - (2.0 * w_ie + w_en).cross(&s.v_n)) * dt;

        let (rm, rn) = (l.rm, l.rn);
        let mut h = s.height_m;
        match nav.vertical {
            VerticalChannel::Hold { ref_height_m } => {
                v.z = 0.0;
                h = ref_height_m;
            }
            VerticalChannel::Damped {
                ref_height_m,
                tau_s,
            } => {
                let dh = h - ref_height_m;
                v.z -= dh / (tau_s * tau_s) * dt;
                h += (0.5 * (s.v_n.z + v.z) - 2.0 * dh / tau_s) * dt;
            }
        }
        let v_mid = 0.5 * (s.v_n + v);
        let lat = s.lat_rad + v_mid.y / (rm + s.height_m) * dt;
        let lon = s.lon_rad + v_mid.x / ((rn + s.height_m) * l.cos) * dt;

        let mut q = quat_from_rotvec(&(-zeta)) * s.q_bn * quat_from_rotvec(&phi);
        q.renormalize_fast();
        nav.state = NavState {
            q_bn: q,
            v_n: v,
            lat_rad: lat,
            lon_rad: lon,
            height_m: h,
        };
        nav.steps += 1;
    }

    /// A navigator's state as bits, for exact comparisons.
    pub(crate) fn bits(n: &Strapdown) -> Vec<u64> {
        let s = n.state();
        s.q_bn
            .coords
            .iter()
            .chain(s.v_n.iter())
            .chain([s.lat_rad, s.lon_rad, s.height_m].iter())
            .chain(n.prev_dtheta.iter())
            .chain(n.prev_dv.iter())
            .map(|x| x.to_bits())
            .collect()
    }

    /// Increments of a turning, accelerating IMU: Earth rate and gravity plus a few deg/s and
    /// m/s² of motion and noise, and every 97th interval a turn large enough (> 1e-2 rad) for
    /// the closed-form quaternion.
    pub(crate) fn increments(k: u64) -> (Vector3<f64>, Vector3<f64>) {
        let t = k as f64 * 0.01;
        let wobble = |a: f64, f: f64| a * (f * t).sin();
        let mut dth = Vector3::new(
            wobble(2e-4, 0.7) + 1e-7,
            wobble(-3e-4, 1.3) + 5e-7,
            wobble(5e-4, 0.2) + 6e-7,
        );
        if k.is_multiple_of(97) {
            dth.z += 0.02;
        }
        let dv = Vector3::new(
            wobble(0.02, 0.5),
            wobble(0.03, 0.9),
            0.098 + wobble(0.01, 2.1),
        );
        (dth, dv)
    }

    #[test]
    fn the_equations_give_the_reference_bits() {
        for vertical in [
            VerticalChannel::Hold { ref_height_m: 12.0 },
            VerticalChannel::Damped {
                ref_height_m: 12.0,
                tau_s: 100.0,
            },
        ] {
            let init = NavState {
                q_bn: UnitQuaternion::from_euler_angles(0.01, -0.02, 1.1),
                v_n: Vector3::new(3.0, -4.0, 0.1),
                lat_rad: 0.64,
                lon_rad: 2.15,
                height_m: 15.0,
            };
            let mut a = Strapdown::new(init, 0.01, vertical);
            let mut b = a.clone();
            for k in 1..=20_000 {
                let (dth, dv) = increments(k);
                a.update(&dth, &dv);
                reference_update(&mut b, &dth, &dv);
                assert_eq!(bits(&a), bits(&b), "{vertical:?}, step {k}");
            }
            // The run went somewhere: 200 s at ~5 m/s.
            assert!((a.state().lat_rad - 0.64).abs() > 1e-5);
        }
    }

    #[test]
    fn series_quaternion_matches_exact() {
        let v = Vector3::new(3e-4, -2e-4, 1e-4);
        let a = quat_from_rotvec(&v);
        let b = UnitQuaternion::from_scaled_axis(v);
        assert_relative_eq!(a.coords, b.coords, epsilon = 1e-18);
    }
}
