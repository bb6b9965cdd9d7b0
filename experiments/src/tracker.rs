//! The reference navigator fed one sample at a time, with error records against the plant's
//! truth: what [`crate::run`] does inside its loop, usable from any sink that sees the plant's
//! samples and truth (the Rerun sink, the CLI, the transport's contract tests).
//!
//! A [`Tracker`] is a strapdown navigator and its [`Bookkeeping`]: the navigation computer's δβ
//! compensation and the error records. The Monte Carlo engine runs the navigators of many
//! trackers side by side in vector lanes ([`rins_navigation::StrapdownLanes`]) and keeps each one's
//! bookkeeping here, so a tracker gives the same records whichever way its navigator runs.

use nalgebra::{Matrix3, Vector3};
use rins_navigation::compensation::PositionBiasCompensation;
use rins_navigation::errors::{
    NavRecord, Trms, attitude_error, position_error_m, vehicle_attitude,
};
use rins_navigation::strapdown::{NavState, Strapdown, VerticalChannel};
use rins_navigation::subsamples::Subsamples;
use rins_plant::earth::Site;
use rins_plant::effects::gyro::PositionBiasSpec;
use rins_plant::{ImuSample, Plant, Truth};

/// The navigator's start aligned from truth: the table's attitude, and the site at rest (static
/// carrier) or the carrier's reference point with its velocity (moving carrier: the navigator
/// starts aligned from truth on the moving base; there is no moored dwell).
pub(crate) fn initial_state(plant: &Plant) -> NavState {
    if plant.moving_carrier() {
        let c = plant.truth().carrier;
        return NavState {
            q_bn: plant.attitude_q_bn(),
            v_n: c.v_n,
            lat_rad: c.lat_rad,
            lon_rad: c.lon_rad,
            height_m: c.height_m,
        };
    }
    let site = *plant.site();
    NavState {
        q_bn: plant.attitude_q_bn(),
        v_n: Vector3::zeros(),
        lat_rad: site.lat_rad,
        lon_rad: site.lon_rad,
        height_m: site.height_m,
    }
}

/// A strapdown navigator with δβ compensation and error records every `record_every_s`.
pub struct Tracker {
    nav: Strapdown,
    book: Bookkeeping,
}

/// Everything of a [`Tracker`] but its strapdown navigator.
pub(crate) struct Bookkeeping {
    comp: Option<PositionBiasCompensation>,
    dt_s: f64,
    site: Site,
    c_vn: Matrix3<f64>,
    every: u64,
    k: u64,
    /// Samples left until the next record (a countdown: `k % every` costs a division every
    /// sample).
    until_record: u64,
    trms: Trms,
    up_sum: f64,
    records: u64,
    /// Encoder angles of the last pushed sample: the navigator's view of the table.
    encoder: rins_plant::table::GimbalAngles,
    /// On a moving carrier: the table mount C_v^c; the errors are then taken against the
    /// carrier's truth (position, velocity, attitude) instead of the site.
    moving_mount: Option<Matrix3<f64>>,
}

impl Tracker {
    /// A navigator started at `init` (aligned already) at the plant's `site` and mount `c_vn`,
    /// with optional δβ compensation (Eq. 9 with the navigator's own up direction).
    pub fn new(
        init: NavState,
        dt_s: f64,
        vertical: VerticalChannel,
        site: Site,
        c_vn: Matrix3<f64>,
        compensation: Option<&PositionBiasSpec>,
        record_every_s: f64,
    ) -> Self {
        Self {
            nav: Strapdown::new(init, dt_s, vertical),
            book: Bookkeeping {
                comp: compensation.map(PositionBiasCompensation::new),
                dt_s,
                site,
                c_vn,
                every: ((record_every_s / dt_s).round() as u64).max(1),
                k: 0,
                until_record: ((record_every_s / dt_s).round() as u64).max(1),
                trms: Trms::default(),
                up_sum: 0.0,
                records: 0,
                encoder: rins_plant::table::GimbalAngles::default(),
                moving_mount: None,
            },
        }
    }

    /// The same tracker with its navigator updating once every `n` intervals
    /// ([`Strapdown::with_subsamples`]).
    pub fn with_subsamples(mut self, n: Subsamples) -> Self {
        self.nav = self.nav.with_subsamples(n);
        self
    }

    /// The same tracker on a moving carrier with table mount `mount` (C_v^c): errors against the
    /// carrier's truth (reference point position and velocity, C_c^n·C_v^c·R_z·R_x attitude).
    pub fn on_moving_carrier(mut self, mount: Matrix3<f64>) -> Self {
        self.book.moving_mount = Some(mount);
        self
    }

    /// A navigator aligned to the truth of a freshly built plant (before its first step), at rest,
    /// with the vertical channel held at the site height.
    pub fn at_truth(plant: &Plant, record_every_s: f64) -> Self {
        let site = *plant.site();
        let init = initial_state(plant);
        let t = Self::new(
            init,
            plant.dt_s(),
            VerticalChannel::Hold {
                ref_height_m: init.height_m,
            },
            site,
            plant.vehicle_to_nav(),
            None,
            record_every_s,
        );
        if plant.moving_carrier() {
            t.on_moving_carrier(plant.config().vehicle.c_vn())
        } else {
            t
        }
    }

    /// Integrates one sample; returns the error record when one is due, against the truth
    /// `truth` gives (asked for then only: on a moving carrier the truth is interpolated when
    /// asked for, and a record is due once in many samples).
    pub fn push(&mut self, s: &ImuSample, truth: impl FnOnce() -> Truth) -> Option<NavRecord> {
        let nav = &self.nav;
        let dtheta = self.book.dtheta(s, || {
            nav.state().q_bn.inverse_transform_vector(&Vector3::z())
        });
        self.nav.update(&dtheta, &s.dv_mps);
        self.book
            .advance(s)
            .then(|| self.book.record(self.nav.state(), &truth()))
    }

    /// The error record now, against `truth` (the plant's truth after the last pushed sample).
    pub fn record(&mut self, truth: &Truth) -> NavRecord {
        self.book.record(self.nav.state(), truth)
    }

    /// Samples between error records.
    pub fn record_interval(&self) -> u64 {
        self.book.every
    }

    /// Mean of |φ_U| over the records so far, rad.
    pub fn up_att_mean_abs_rad(&self) -> f64 {
        self.book.up_att_mean_abs_rad()
    }

    /// The navigation state now.
    pub fn state(&self) -> &NavState {
        self.nav.state()
    }

    /// The navigator and the bookkeeping apart (the Monte Carlo engine runs the navigator in a
    /// lane).
    pub(crate) fn into_parts(self) -> (Strapdown, Bookkeeping) {
        (self.nav, self.book)
    }
}

impl Bookkeeping {
    /// The sample's Δθ as the navigator integrates it: less the δβ correction (Eq. 9) with the
    /// navigator's body up direction `up_b` (asked for only when compensating).
    #[inline]
    pub(crate) fn dtheta(
        &mut self,
        s: &ImuSample,
        up_b: impl FnOnce() -> Vector3<f64>,
    ) -> Vector3<f64> {
        let mut dtheta = s.dtheta_rad;
        if let Some(c) = &mut self.comp {
            dtheta -= c.correction(self.dt_s, &up_b(), &s.gyro_temps_c());
        }
        dtheta
    }

    /// Counts the sample the navigator has just integrated; true when an error record is due.
    #[inline]
    pub(crate) fn advance(&mut self, s: &ImuSample) -> bool {
        self.encoder = s.encoder;
        self.k += 1;
        self.until_record -= 1;
        if self.until_record == 0 {
            self.until_record = self.every;
        }
        self.until_record == self.every
    }

    /// Samples between error records.
    pub(crate) fn record_interval(&self) -> u64 {
        self.every
    }

    /// Mean of |φ_U| over the records so far, rad.
    pub(crate) fn up_att_mean_abs_rad(&self) -> f64 {
        self.up_sum / self.records.max(1) as f64
    }

    /// The error record of the navigator's state `st` against `truth`.
    pub(crate) fn record(&mut self, st: &NavState, truth: &Truth) -> NavRecord {
        let (c_vn, lat, lon, h, v_true) = match self.moving_mount {
            Some(mount) => {
                let c = &truth.carrier;
                let c_vn = c.q_cn.to_rotation_matrix().into_inner() * mount;
                (c_vn, c.lat_rad, c.lon_rad, c.height_m, c.v_n)
            }
            None => (
                self.c_vn,
                self.site.lat_rad,
                self.site.lon_rad,
                self.site.height_m,
                Vector3::zeros(),
            ),
        };
        let c_bn_true = rins_plant::table::body_to_nav(&c_vn, truth.gimbal.angles);
        let c_bn_nav = st.q_bn.to_rotation_matrix().into_inner();
        let phi = attitude_error(&c_bn_nav, &c_bn_true);
        // The carrier attitude as the navigation computer knows it: through the encoders.
        let c_vn_nav = vehicle_attitude(&c_bn_nav, self.encoder);
        let phi_v = attitude_error(&c_vn_nav, &c_vn);
        let (north, east) = position_error_m(st, lat, lon, h);
        let horizontal = north.hypot(east);
        self.trms.push(horizontal);
        self.up_sum += phi.z.abs();
        self.records += 1;
        NavRecord {
            t_s: self.k as f64 * self.dt_s,
            att_err_rad: phi.into(),
            vehicle_att_err_rad: phi_v.into(),
            vel_err_mps: (st.v_n - v_true).into(),
            north_m: north,
            east_m: east,
            horizontal_m: horizontal,
            trms_m: self.trms.value(),
        }
    }
}
