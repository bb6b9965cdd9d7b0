//! Runs the plant and the reference navigator together: alignment, navigation, δβ compensation,
//! and error records against the plant's truth. The navigator sees only the samples (increments,
//! encoder angles, temperature readings); the truth is read here, for the error records.

use nalgebra::{Vector2, Vector3};
use rins_plant::effects::gyro::PositionBiasSpec;
use rins_plant::units::{DPSH, UG};
use rins_plant::{ImuSample, Plant};

use crate::tracker::{Tracker, initial_state};

pub use rins_navigation::alignment::Alignment;
use rins_navigation::alignment::{FineAlignment, coarse, correct_attitude};
use rins_navigation::errors::attitude_error;
pub use rins_navigation::errors::{NavRecord, vehicle_attitude};
use rins_navigation::strapdown::{NavState, Strapdown, VerticalChannel};
use rins_navigation::subsamples::Subsamples;

/// Options of a navigation run.
#[derive(Clone, Debug)]
pub struct NavRunConfig {
    /// Initial alignment.
    pub alignment: Alignment,
    /// Vertical-channel handling.
    pub vertical: VerticalChannel,
    /// δβ compensation in the navigation computer (None: uncompensated).
    pub compensation: Option<PositionBiasSpec>,
    /// Interval of the error records (and of the tRMS samples of Eq. 20), s.
    pub record_every_s: f64,
    /// IMU intervals per navigator update ([`rins_navigation::subsamples`]).
    pub subsamples: Subsamples,
}

impl Default for NavRunConfig {
    fn default() -> Self {
        Self {
            alignment: Alignment::Truth,
            vertical: VerticalChannel::Hold { ref_height_m: 0.0 },
            compensation: None,
            record_every_s: 60.0,
            subsamples: Subsamples::ONE,
        }
    }
}

/// What the alignment achieved.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct AlignmentResult {
    /// Attitude error after coarse alignment (E, N, U), rad.
    pub coarse_err_rad: [f64; 3],
    /// Attitude error after fine alignment, rad.
    pub fine_err_rad: [f64; 3],
    /// Filter 1σ on the attitude at the end, rad.
    pub fine_sigma_rad: [f64; 3],
}

/// A finished navigation run.
#[derive(Clone, Debug)]
pub struct NavRun {
    /// Error records every `record_every_s`.
    pub records: Vec<NavRecord>,
    /// Alignment outcome, if self-aligned.
    pub alignment: Option<AlignmentResult>,
    /// Mean of |φ_U| over the records, rad (the paper's "up-axis average attitude error").
    pub up_att_mean_abs_rad: f64,
}

impl NavRun {
    /// The last record.
    pub fn end(&self) -> NavRecord {
        self.records.last().copied().unwrap_or_default()
    }
}

/// Why a run could not be made.
#[derive(Debug, PartialEq, thiserror::Error)]
pub enum SessionError {
    /// The table moved while the navigator was aligning.
    #[error(
        "the table moved at t = {t_s} s during self-alignment; set scheme.lead_dwell_s >= the alignment time"
    )]
    TableMovedDuringAlignment {
        /// Time of the motion, s.
        t_s: f64,
    },
    /// Zero or negative times.
    #[error("{0}")]
    BadTimes(String),
    /// Self-alignment asked for on a moving carrier.
    #[error(
        "self-alignment needs the static carrier; on a moving carrier the navigator starts aligned from truth (alignment = truth)"
    )]
    MovingBaseAlignment,
    /// The plant configuration was refused (each error names its field and range).
    #[error("invalid plant configuration: {0}")]
    InvalidConfig(String),
}

/// Samples between progress reports of a run (and of a Monte Carlo batch,
/// [`crate::montecarlo`]): a caller that stops long runs from its progress callback (the Python
/// package on Ctrl-C) is called this often.
pub(crate) const PROGRESS_EVERY: u64 = 1 << 16;

/// Aligns (if asked) and navigates for `nav_s` seconds, stepping `plant` as it goes.
pub fn run(plant: &mut Plant, nav_s: f64, cfg: &NavRunConfig) -> Result<NavRun, SessionError> {
    run_with_progress(plant, nav_s, cfg, &|_| {})
}

/// [`run`], with `progress` receiving the navigation samples done every [`PROGRESS_EVERY`]
/// samples and at the end (summing to the run's samples); while self-aligning it is called with
/// 0 as often. The runs are the same bits as [`run`]'s.
pub fn run_with_progress(
    plant: &mut Plant,
    nav_s: f64,
    cfg: &NavRunConfig,
    progress: &dyn Fn(u64),
) -> Result<NavRun, SessionError> {
    if !(nav_s > 0.0 && cfg.record_every_s > 0.0) {
        return Err(SessionError::BadTimes(format!(
            "navigation time {nav_s} s and record interval {} s must be > 0",
            cfg.record_every_s
        )));
    }
    let dt = plant.dt_s();
    let mut init = initial_state(plant);
    // The vertical channel holds (or damps to) the true start height, whatever the alignment.
    let ref_height_m = init.height_m;
    let moving = plant.moving_carrier();
    let mut alignment = None;
    if let Alignment::SelfAlign { coarse_s, fine_s } = cfg.alignment {
        if moving {
            return Err(SessionError::MovingBaseAlignment);
        }
        if !(coarse_s > 0.0 && fine_s >= 0.0) {
            return Err(SessionError::BadTimes(format!(
                "alignment times coarse {coarse_s} s, fine {fine_s} s"
            )));
        }
        let (state, res) = self_align(plant, init, coarse_s, fine_s, progress)?;
        init = state;
        alignment = Some(res);
    }
    let mut tracker = tracker_for(plant, init, ref_height_m, cfg);
    let samples = (nav_s / dt).round() as u64;
    let mut records = Vec::with_capacity((samples / tracker.record_interval() + 1) as usize);
    let mut reported = 0;
    for k in 1..=samples {
        let s = plant.step();
        if let Some(r) = tracker.push(&s, || plant.truth()) {
            records.push(r);
        } else if k == samples {
            records.push(tracker.record(&plant.truth()));
        }
        if k % PROGRESS_EVERY == 0 || k == samples {
            progress(k - reported);
            reported = k;
        }
    }
    let up_att_mean_abs_rad = tracker.up_att_mean_abs_rad();
    Ok(NavRun {
        records,
        alignment,
        up_att_mean_abs_rad,
    })
}

/// The navigator of `cfg` started at `init` on `plant`'s site or carrier, its vertical channel
/// held (or damped) to `ref_height_m`.
pub(crate) fn tracker_for(
    plant: &Plant,
    init: NavState,
    ref_height_m: f64,
    cfg: &NavRunConfig,
) -> Tracker {
    let vertical = match cfg.vertical {
        VerticalChannel::Hold { .. } => VerticalChannel::Hold { ref_height_m },
        VerticalChannel::Damped { tau_s, .. } => VerticalChannel::Damped {
            ref_height_m,
            tau_s,
        },
    };
    let tracker = Tracker::new(
        init,
        plant.dt_s(),
        vertical,
        *plant.site(),
        plant.vehicle_to_nav(),
        cfg.compensation.as_ref(),
        cfg.record_every_s,
    )
    .with_subsamples(cfg.subsamples);
    if plant.moving_carrier() {
        tracker.on_moving_carrier(plant.config().vehicle.c_vn())
    } else {
        tracker
    }
}

/// Coarse then fine alignment while the table dwells.
fn self_align(
    plant: &mut Plant,
    init: NavState,
    coarse_s: f64,
    fine_s: f64,
    progress: &dyn Fn(u64),
) -> Result<(NavState, AlignmentResult), SessionError> {
    let dt = plant.dt_s();
    let n_coarse = (coarse_s / dt).round() as u64;
    let (mut f_sum, mut w_sum) = (Vector3::zeros(), Vector3::zeros());
    // The navigation computer sees the table through its encoders: a changed reading is motion.
    let mut last_encoder = None;
    let mut moved = |s: &ImuSample| {
        let m = last_encoder.is_some_and(|e| e != s.encoder);
        last_encoder = Some(s.encoder);
        m
    };
    for k in 1..=n_coarse {
        let s = plant.step();
        if moved(&s) {
            return Err(SessionError::TableMovedDuringAlignment { t_s: s.t_s });
        }
        if k % PROGRESS_EVERY == 0 {
            progress(0);
        }
        f_sum += s.dv_mps;
        w_sum += s.dtheta_rad;
    }
    let c_bn = coarse(&f_sum, &w_sum);
    let q0 = rins_plant::attitude::quaternion_of(&c_bn);
    let coarse_err = attitude_error(&c_bn, &plant.attitude_c_bn());

    let cfg = plant.config().sensor.clone();
    let arw = if cfg.gyro.angle_random_walk.enabled {
        cfg.gyro.angle_random_walk.dpsh[0] * DPSH
    } else {
        0.0
    };
    let vrw = if cfg.accel.velocity_random_walk.enabled {
        cfg.accel.velocity_random_walk.ug_per_sqrthz[0] * UG
    } else {
        0.0
    };
    let kf_dt = 1.0;
    let per_update = ((kf_dt / dt).round() as u64).max(1);
    let mut kf = FineAlignment::new(init.lat_rad, per_update as f64 * dt, arw, vrw);
    let mut nav = Strapdown::new(
        NavState { q_bn: q0, ..init },
        dt,
        VerticalChannel::Hold {
            ref_height_m: init.height_m,
        },
    );
    let n_fine = (fine_s / dt).round() as u64;
    for k in 1..=n_fine {
        let s = plant.step();
        if moved(&s) {
            return Err(SessionError::TableMovedDuringAlignment { t_s: s.t_s });
        }
        nav.update(&s.dtheta_rad, &s.dv_mps);
        if k % PROGRESS_EVERY == 0 {
            progress(0);
        }
        if k % per_update == 0 {
            let st = *nav.state();
            let x = kf.step(&Vector2::new(st.v_n.x, st.v_n.y));
            let q = correct_attitude(&st.q_bn, &Vector3::new(x[0], x[1], x[2]));
            // Position is known during alignment; velocity is reset to the estimate's residual.
            nav.set_state(NavState {
                q_bn: q,
                v_n: Vector3::new(st.v_n.x - x[3], st.v_n.y - x[4], 0.0),
                lat_rad: init.lat_rad,
                lon_rad: init.lon_rad,
                height_m: init.height_m,
            });
        }
    }
    let st = *nav.state();
    let fine_err = attitude_error(
        &st.q_bn.to_rotation_matrix().into_inner(),
        &plant.attitude_c_bn(),
    );
    let aligned = NavState {
        q_bn: st.q_bn,
        v_n: Vector3::zeros(),
        lat_rad: init.lat_rad,
        lon_rad: init.lon_rad,
        height_m: init.height_m,
    };
    Ok((
        aligned,
        AlignmentResult {
            coarse_err_rad: coarse_err.into(),
            fine_err_rad: fine_err.into(),
            fine_sigma_rad: kf.attitude_sigma().into(),
        },
    ))
}
