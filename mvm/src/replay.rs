//! Replays a model on a measured history: for every row, the increments the model expects from
//! the measured attitude, temperatures and site (true kinematics plus the model's deterministic
//! effects), the residual against the measurement, and every candidate effect's regressors
//! (from the plant's own effect catalogue, [`GyroModel::regressors`]). Rows are summed into
//! windows (the effects are linear in their coefficients, so sums lose nothing), and the
//! residual's Allan variance is accumulated on the way.

// Six channels and coefficient columns indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use rayon::prelude::*;
use rins_plant::PlantConfig;
use rins_plant::earth::Site;
use rins_plant::effects::{AccelModel, AccelTerm, GyroModel, GyroTerm, TermContext};
use rins_plant::kinematics::table_increments;
use rins_plant::table::{GimbalAngles, body_to_nav};

use crate::custom::{CustomRef, Declared};
use crate::history::{Attitude, History};
use crate::rows::{Rows, RowsInfo};
use crate::stats::AllanAcc;

/// The six measured channels.
pub const CHANNELS: [&str; 6] = [
    "gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z",
];

/// A candidate effect from the plant's catalogue.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Effect {
    /// A deterministic gyro term.
    Gyro(GyroTerm),
    /// A deterministic accelerometer term.
    Accel(AccelTerm),
    /// A declared effect of the model (`[[sensor.gyro.custom]]`, `[[sensor.accel.custom]]`).
    Custom(CustomRef),
}

impl Effect {
    /// Every candidate, gyro first.
    pub fn all() -> Vec<Effect> {
        GyroTerm::DETERMINISTIC
            .iter()
            .map(|t| Effect::Gyro(*t))
            .chain(AccelTerm::DETERMINISTIC.iter().map(|t| Effect::Accel(*t)))
            .collect()
    }

    /// `gyro.<term>` / `accel.<term>`, as in scenario files.
    pub fn name(self) -> String {
        match self {
            Effect::Gyro(t) => format!("gyro.{}", t.key()),
            Effect::Accel(t) => format!("accel.{}", t.key()),
            Effect::Custom(c) => format!("custom:{}", c.name()),
        }
    }

    /// Parses [`Effect::name`], declared effects of `model` included (`custom:NAME`).
    pub fn parse_in(model: &PlantConfig, s: &str) -> Option<Effect> {
        Effect::parse(s).or_else(|| {
            crate::custom::declared(model)
                .into_iter()
                .map(Effect::Custom)
                .find(|e| e.name() == s)
        })
    }

    /// Scenario key of the effect's switch.
    pub fn enabled_key(self) -> String {
        match self {
            Effect::Custom(c) => c.enabled_key(),
            _ => format!("sensor.{}.enabled", self.name()),
        }
    }

    /// Parses [`Effect::name`].
    pub fn parse(s: &str) -> Option<Effect> {
        Effect::all().into_iter().find(|e| e.name() == s)
    }

    /// Scenario keys of the effect's coefficients on `channel` (0–2 gyro, 3–5 accelerometer),
    /// each with the size of its file unit in SI (the file holds θ / unit).
    pub fn coefficient_keys(self, channel: usize) -> Vec<(String, f64)> {
        match self {
            Effect::Gyro(t) => rins_plant::effects::gyro::coefficient_keys(t, channel),
            Effect::Accel(t) => rins_plant::effects::accel::coefficient_keys(t, channel - 3),
            Effect::Custom(c) => vec![(c.coefficient_key(channel % 3), c.file_unit_si())],
        }
    }

    /// Whether the effect acts on `channel` (0–2 gyro, 3–5 accelerometer).
    pub fn acts_on(self, channel: usize) -> bool {
        matches!(
            (self, channel),
            (Effect::Gyro(_), 0..=2) | (Effect::Accel(_), 3..=5)
        ) || matches!(self, Effect::Custom(c) if c.accel == (channel >= 3) && c.axes >> (channel % 3) & 1 == 1)
    }
}

/// One candidate's regressors on one channel, at `offset..offset+len` of [`Window::x`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Group {
    /// Channel 0–5.
    pub channel: usize,
    /// Effect.
    pub effect: Effect,
    /// Offset into the regressor sums.
    pub offset: usize,
    /// Number of coefficients.
    pub len: usize,
}

impl Group {
    /// The group at each polynomial order it admits: temperature polynomials are tried from
    /// the constant (or linear) term up, so a cubic is not forced on two temperatures.
    pub fn orders(&self) -> Vec<Group> {
        let min = match self.effect {
            Effect::Gyro(GyroTerm::PositionBias) => 1,
            Effect::Gyro(GyroTerm::TemperatureBias) | Effect::Accel(AccelTerm::TemperatureBias) => {
                1
            }
            _ => self.len,
        };
        (min..=self.len).map(|len| Group { len, ..*self }).collect()
    }
}

/// Rows summed over a stretch of constant table state (a dwell or part of a move).
#[derive(Clone, Debug, PartialEq)]
pub struct Window {
    /// Run index.
    pub run: u32,
    /// Mid time of the window, s.
    pub t_mid_s: f64,
    /// Time since the start of its run, s.
    pub t_run_s: f64,
    /// Duration, s.
    pub duration_s: f64,
    /// Rows.
    pub rows: u32,
    /// The table moved.
    pub moving: bool,
    /// Mean z component of the up direction in body axes (+1 Z-up, −1 Z-down).
    pub up_z: f64,
    /// Azimuth of the table position: the heading of the body x axis's horizontal part (of
    /// body y when body x is within 30° of vertical), degrees from north towards east, at the
    /// window's first row. With the tilt (`up_z`) it names the dwell's orientation, so a
    /// residual that follows a field fixed in the navigation frame shows by position.
    pub azimuth_deg: f64,
    /// Mean specific force in body axes, g.
    pub f_b_g: [f64; 3],
    /// Mean gyro block temperatures, °C.
    pub gyro_temp_c: [f64; 3],
    /// Mean accelerometer temperature, °C.
    pub accel_temp_c: f64,
    /// Mean |ω| of the true body rate, rad/s.
    pub rotation_rps: f64,
    /// Time since the table last stopped at the window's middle, s (0 while it moves; from
    /// the segment's start before its first move): where a transient after each move lives.
    pub since_move_s: f64,
    /// Residual sums (measured − model) per channel: rad for gyros, m/s for accelerometers.
    pub y: [f64; 6],
    /// Regressor sums of every group (layout in [`Replay::groups`]).
    pub x: Vec<f64>,
}

/// Static navigation over one segment with the measured increments and with the increments
/// the model expects, from the measured start attitude at the site (horizontal errors, m).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NavTrack {
    /// Run index.
    pub run: u32,
    /// Time since the segment start at each window end, s.
    pub t_s: Vec<f64>,
    /// Horizontal position error navigating on the measurements, m.
    pub measured_m: Vec<f64>,
    /// Horizontal position error navigating on the model's increments, m.
    pub model_m: Vec<f64>,
}

/// What a replay produced.
#[derive(Clone, Debug)]
pub struct Replay {
    /// Windows in history order.
    pub windows: Vec<Window>,
    /// Candidate groups (all channels).
    pub groups: Vec<Group>,
    /// Candidates left out, with the reason.
    pub unavailable: Vec<(String, String)>,
    /// Residual Allan accumulators per channel (rate units: rad/s, m/s²).
    pub allan: Vec<AllanAcc>,
    /// Median row interval, s.
    pub row_dt_s: f64,
    /// Navigation on measured vs modelled increments, per segment.
    pub nav: Vec<NavTrack>,
    /// Rows replayed.
    pub rows: usize,
}

/// Builds the group layout for the candidates available with this history.
fn layout(
    gyro: &GyroModel,
    accel: &AccelModel,
    declared: &Declared,
    info: &RowsInfo,
) -> (Vec<Group>, Vec<(String, String)>) {
    let has_gradient = info.housing;
    let mut groups = Vec::new();
    let mut unavailable = Vec::new();
    let mut offset = 0;
    let ctx = TermContext {
        dt_s: 1.0,
        dtheta_rad: Vector3::zeros(),
        dv_mps: Vector3::zeros(),
        f_b_mps2: Vector3::zeros(),
        up_b: Vector3::z(),
        north_b: Vector3::y(),
        east_b: Vector3::x(),
        gyro_temp_c: Vector3::zeros(),
        gyro_gradient_k: Vector3::zeros(),
        accel_temp_c: 0.0,
    };
    for e in Effect::all()
        .into_iter()
        .chain(declared.refs.iter().map(|c| Effect::Custom(*c)))
    {
        if let Effect::Custom(c) = e {
            let m = declared.model(c.accel);
            if let Some(why) = crate::custom::unavailable(m, c.index as usize, info) {
                unavailable.push((e.name(), why));
                continue;
            }
        }
        if e == Effect::Gyro(GyroTerm::TemperatureGradientBias) && !has_gradient {
            unavailable.push((
                e.name(),
                "needs a housing temperature (temp_housing_c) to form the gradient".into(),
            ));
            continue;
        }
        for channel in 0..6 {
            if !e.acts_on(channel) {
                continue;
            }
            let mut buf = Vec::new();
            match e {
                Effect::Gyro(t) => gyro.regressors(t, &ctx, channel, &mut buf),
                Effect::Accel(t) => accel.regressors(t, &ctx, channel - 3, &mut buf),
                Effect::Custom(_) => buf.push(0.0),
            }
            groups.push(Group {
                channel,
                effect: e,
                offset,
                len: buf.len(),
            });
            offset += buf.len();
        }
    }
    (groups, unavailable)
}

/// True increments over one row and the row's mid attitude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RowKinematics {
    /// True angular increment in body axes (gimbal motion plus Earth rate), rad.
    pub dtheta_rad: Vector3<f64>,
    /// True velocity increment in body axes (specific force at rest on the table), m/s.
    pub dv_mps: Vector3<f64>,
    /// Navigation-to-body matrix C_n^b at the middle of the row.
    pub c_nb: Matrix3<f64>,
    /// The table moved during the row.
    pub moving: bool,
}

/// sin(x)/x, 1 at 0.
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// ∫ over a row of a navigation-frame vector seen in body axes while the table turns at a
/// constant rate through `angle` about the body axis `axis` (unit): `v_mid`·Δt (the vector at
/// the row's middle, times the row) with its part perpendicular to the axis scaled by
/// sinc(angle/2): the exact integral of a vector turning about a fixed axis.
fn turning_integral(v_mid_dt: &Vector3<f64>, axis: &Vector3<f64>, angle: f64) -> Vector3<f64> {
    let along = axis * axis.dot(v_mid_dt);
    along + (v_mid_dt - along) * sinc(0.5 * angle)
}

/// True increments of a table-mounted IMU over one row from the gimbal angles at the row's
/// start (`a0`) and end (`a1`): the plant's own kinematics ([`table_increments`]) at the mid
/// angles, with the Earth rate and specific force integrated exactly over a row in which one
/// gimbal turns at a constant rate (a real unit integrates them continuously; the midpoint
/// rule alone is off by (Δ/2)²/6 of their part across the turning axis: 27 µg of specific
/// force for 1.46° per row, a 10 Hz log of a 14.6 °/s turn). A row in which both gimbals turn
/// keeps the midpoint rule.
pub fn gimbal_true_increments(
    c_vn: &Matrix3<f64>,
    omega_ie_n: &Vector3<f64>,
    f_n: &Vector3<f64>,
    a0: GimbalAngles,
    a1: GimbalAngles,
    dt_s: f64,
) -> RowKinematics {
    let mid = GimbalAngles::new(
        0.5 * (a0.outer_rad + a1.outer_rad),
        0.5 * (a0.inner_rad + a1.inner_rad),
    );
    let (d_outer, d_inner) = (a1.outer_rad - a0.outer_rad, a1.inner_rad - a0.inner_rad);
    let (s, c) = mid.inner_rad.sin_cos();
    let c_nb = body_to_nav(c_vn, mid).transpose();
    let inc = table_increments(&c_nb, s, c, d_outer, d_inner, omega_ie_n, f_n, dt_s);
    // The turning gimbal's axis in body axes: the inner axis is body x; the outer axis, with
    // the inner gimbal still, is R_x(inner)ᵀ·z.
    let turning = match (d_outer != 0.0, d_inner != 0.0) {
        (true, false) => Some((Vector3::new(0.0, s, c), d_outer)),
        (false, true) => Some((Vector3::x(), d_inner)),
        _ => None,
    };
    let (dtheta_rad, dv_mps) = match turning {
        Some((axis, angle)) => {
            let earth = c_nb * omega_ie_n * dt_s;
            (
                inc.dtheta_rad - earth + turning_integral(&earth, &axis, angle),
                turning_integral(&inc.dv_mps, &axis, angle),
            )
        }
        None => (inc.dtheta_rad, inc.dv_mps),
    };
    RowKinematics {
        dtheta_rad,
        dv_mps,
        c_nb,
        moving: d_outer != 0.0 || d_inner != 0.0,
    }
}

/// Which gimbal turned between two angle pairs, and by how much: `Some((outer, angle))` when
/// exactly one did.
fn single_turn(a0: GimbalAngles, a1: GimbalAngles) -> Option<(bool, f64)> {
    let (d_o, d_i) = (a1.outer_rad - a0.outer_rad, a1.inner_rad - a0.inner_rad);
    match (d_o != 0.0, d_i != 0.0) {
        (true, false) => Some((true, d_o)),
        (false, true) => Some((false, d_i)),
        _ => None,
    }
}

/// True increments over one row (angles `a0` at its start, `a1` at its end, length `dt_s`)
/// in which a move may start or stop: a table turns at a constant rate, so when one gimbal
/// turns in this row and the same gimbal turns the same way in the next row (`next`: its end
/// angles and length) but not in the previous one (`prev`), the move started within the row
/// and took the last f·Δt of it, f = (this row's rate)/(the next row's rate); likewise a move
/// that stops within the row took its first f·Δt. The still part and the turning part are
/// then integrated each exactly ([`gimbal_true_increments`]); a row turning throughout, or
/// one whose neighbours do not tell, is one constant-rate turn. Without this a 10 Hz log of
/// a 20 °/s move that starts mid-row misplaces the turn's 2° by up to half a row and shows
/// hundreds of µg in the accelerometers' residual at every start and stop.
#[allow(clippy::too_many_arguments)]
pub fn gimbal_row_increments(
    c_vn: &Matrix3<f64>,
    omega_ie_n: &Vector3<f64>,
    f_n: &Vector3<f64>,
    prev: Option<(GimbalAngles, f64)>,
    a0: GimbalAngles,
    a1: GimbalAngles,
    next: Option<(GimbalAngles, f64)>,
    dt_s: f64,
) -> RowKinematics {
    let whole = || gimbal_true_increments(c_vn, omega_ie_n, f_n, a0, a1, dt_s);
    let Some((outer, angle)) = single_turn(a0, a1) else {
        return whole();
    };
    // The same gimbal turning the same way in a neighbouring row: its rate.
    let rate_of = |b0: GimbalAngles, b1: GimbalAngles, dt: f64| {
        single_turn(b0, b1)
            .filter(|(o, a)| *o == outer && a.signum() == angle.signum())
            .map(|(_, a)| a / dt)
    };
    let still = |b0: GimbalAngles, b1: GimbalAngles| b0 == b1;
    let before = prev.map(|(p, dt)| (rate_of(p, a0, dt), still(p, a0)));
    let after = next.map(|(n, dt)| (rate_of(a1, n, dt), still(a1, n)));
    let rate = angle / dt_s;
    // (fraction of the row turning, turning at its end).
    let (f, at_end) = match (before, after) {
        (Some((None, true)), Some((Some(r), _))) => ((rate / r).clamp(0.0, 1.0), true),
        (Some((Some(r), _)), Some((None, true))) => ((rate / r).clamp(0.0, 1.0), false),
        _ => return whole(),
    };
    if !(f > 0.0 && f < 1.0) {
        return whole();
    }
    let turn = gimbal_true_increments(c_vn, omega_ie_n, f_n, a0, a1, f * dt_s);
    let rest = if at_end { a0 } else { a1 };
    let hold = gimbal_true_increments(c_vn, omega_ie_n, f_n, rest, rest, (1.0 - f) * dt_s);
    RowKinematics {
        dtheta_rad: turn.dtheta_rad + hold.dtheta_rad,
        dv_mps: turn.dv_mps + hold.dv_mps,
        c_nb: whole().c_nb,
        moving: true,
    }
}

/// True increments over one row when the attitude is given as body-to-ENU quaternions `qa`
/// (row start) and `qb` (row end): the relative rotation plus the Earth rate, resolved through
/// the mid (slerp) attitude.
fn quaternion_true_increments(
    omega_ie_n: &Vector3<f64>,
    f_n: &Vector3<f64>,
    qa: &UnitQuaternion<f64>,
    qb: &UnitQuaternion<f64>,
    dt_s: f64,
) -> RowKinematics {
    let rel = qa.inverse() * qb;
    let mid = qa.slerp(qb, 0.5);
    let c_nb = mid.to_rotation_matrix().matrix().transpose();
    let (earth, f) = (c_nb * omega_ie_n * dt_s, c_nb * f_n * dt_s);
    // A turn about a fixed body axis through the row: the Earth rate and specific force
    // integrated exactly, as for the gimbals (gimbal_true_increments).
    let (earth, f) = match rel.axis_angle() {
        Some((axis, angle)) if angle > 1e-12 => (
            turning_integral(&earth, &axis, angle),
            turning_integral(&f, &axis, angle),
        ),
        _ => (earth, f),
    };
    RowKinematics {
        dtheta_rad: rel.scaled_axis() + earth,
        dv_mps: f,
        c_nb,
        moving: rel.angle() > 1e-12,
    }
}

fn unit_quaternion(q: &[f64; 4]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]))
}

/// [`gimbal_row_increments`] for an attitude given as quaternions: a turn about the same body
/// axis in the same sense in a neighbouring row gives the rate, and a turn that starts or stops
/// within the row is placed by it; the still part and the turning part are integrated exactly.
pub fn quaternion_row_increments(
    omega_ie_n: &Vector3<f64>,
    f_n: &Vector3<f64>,
    prev: Option<([f64; 4], f64)>,
    qa: &[f64; 4],
    qb: &[f64; 4],
    next: Option<([f64; 4], f64)>,
    dt_s: f64,
) -> RowKinematics {
    let (a, b) = (unit_quaternion(qa), unit_quaternion(qb));
    let whole = || quaternion_true_increments(omega_ie_n, f_n, &a, &b, dt_s);
    let rel = a.inverse() * b;
    let Some((axis, angle)) = rel.axis_angle().filter(|(_, an)| *an > 1e-12) else {
        return whole();
    };
    // (rate about the same axis in the same sense, or None; still).
    let turn = |p: UnitQuaternion<f64>, q: UnitQuaternion<f64>, dt: f64| {
        let r = p.inverse() * q;
        match r.axis_angle() {
            Some((ax, an)) if an > 1e-12 => {
                ((ax.dot(&axis) > 1.0 - 1e-9).then_some(an / dt), false)
            }
            _ => (None, true),
        }
    };
    let before = prev.map(|(p, dt)| turn(unit_quaternion(&p), a, dt));
    let after = next.map(|(n, dt)| turn(b, unit_quaternion(&n), dt));
    let rate = angle / dt_s;
    let (f, at_end) = match (before, after) {
        (Some((None, true)), Some((Some(r), _))) => ((rate / r).clamp(0.0, 1.0), true),
        (Some((Some(r), _)), Some((None, true))) => ((rate / r).clamp(0.0, 1.0), false),
        _ => return whole(),
    };
    if !(f > 0.0 && f < 1.0) {
        return whole();
    }
    let moving = quaternion_true_increments(omega_ie_n, f_n, &a, &b, f * dt_s);
    let rest = if at_end { a } else { b };
    let hold = quaternion_true_increments(omega_ie_n, f_n, &rest, &rest, (1.0 - f) * dt_s);
    RowKinematics {
        dtheta_rad: moving.dtheta_rad + hold.dtheta_rad,
        dv_mps: moving.dv_mps + hold.dv_mps,
        c_nb: whole().c_nb,
        moving: true,
    }
}

/// The site kinematics the replay computes true increments with.
pub(crate) struct Kinematics {
    c_vn: Matrix3<f64>,
    omega_ie_n: Vector3<f64>,
    f_n: Vector3<f64>,
}

impl Kinematics {
    /// The kinematics of `model`'s site and mount.
    pub(crate) fn new(model: &PlantConfig) -> Self {
        let site = Site::new(&model.site, &model.earth);
        Self {
            c_vn: model.vehicle.c_vn(),
            omega_ie_n: site.omega_ie_n,
            f_n: Vector3::new(0.0, 0.0, site.gravity_mps2),
        }
    }

    /// True increments over row k of segment `seg` (from the attitude at the ends of rows
    /// k − 1 and k; with gimbal angles, the rows around it place a move that starts or stops
    /// within the row: [`gimbal_row_increments`]).
    pub(crate) fn row(
        &self,
        h: &History,
        seg: &std::ops::Range<usize>,
        k: usize,
        dt: f64,
    ) -> RowKinematics {
        let j = k - 1;
        match &h.attitude {
            Attitude::Gimbal {
                outer_rad,
                inner_rad,
            } => {
                let at = |i: usize| GimbalAngles::new(outer_rad[i], inner_rad[i]);
                let prev = (j > seg.start).then(|| (at(j - 1), h.t_s[j] - h.t_s[j - 1]));
                let next = (k + 1 < seg.end).then(|| (at(k + 1), h.t_s[k + 1] - h.t_s[k]));
                gimbal_row_increments(
                    &self.c_vn,
                    &self.omega_ie_n,
                    &self.f_n,
                    prev,
                    at(j),
                    at(k),
                    next,
                    dt,
                )
            }
            Attitude::Quaternion(q) => {
                let prev = (j > seg.start).then(|| (q[j - 1], h.t_s[j] - h.t_s[j - 1]));
                let next = (k + 1 < seg.end).then(|| (q[k + 1], h.t_s[k + 1] - h.t_s[k]));
                quaternion_row_increments(&self.omega_ie_n, &self.f_n, prev, &q[j], &q[k], next, dt)
            }
        }
    }
}

/// Replays `model` on `rows`, summing rows into windows of at most `window_s` seconds: one
/// pass over the chunks, the segments of a chunk side by side on both cores.
pub fn replay(model: &PlantConfig, rows: &(impl Rows + ?Sized), window_s: f64) -> Replay {
    let gyro = GyroModel::new(&model.sensor.gyro);
    let accel = AccelModel::new(&model.sensor.accel);
    let kin = Kinematics::new(model);
    let declared = Declared::new(model);
    let info = rows.info();
    let (groups, unavailable) = layout(&gyro, &accel, &declared, &info);
    let nx = groups.iter().map(|g| g.len).sum::<usize>();
    let row_dt_s = info.median_dt_s;

    let site_state = |c_bn: Matrix3<f64>| rins_navigation::strapdown::NavState {
        q_bn: rins_plant::attitude::quaternion_of(&c_bn),
        v_n: Vector3::zeros(),
        lat_rad: model.site.lat_deg.to_radians(),
        lon_rad: model.site.lon_deg.to_radians(),
        height_m: model.site.height_m,
    };
    let vertical = rins_navigation::strapdown::VerticalChannel::Hold {
        ref_height_m: model.site.height_m,
    };
    let mut per_segment: Vec<(Vec<Window>, Vec<AllanAcc>, NavTrack)> = Vec::new();
    rows.for_each_chunk(&mut |h| {
        let signals = declared.any.then(|| declared.signals(h, &info.run_start_s));
        per_segment.par_extend(h.segments.par_iter().map(|seg| {
            let mut windows = Vec::new();
            let mut allan: Vec<AllanAcc> = (0..6).map(|_| AllanAcc::new()).collect();
            let run_start = h.t_s[seg.start];
            // The end of the last row in which the table turned.
            let mut last_stop = run_start;
            let mut cur: Option<Window> = None;
            let mut buf = Vec::with_capacity(8);
            // The declared effects' memory (lags, decays) runs from the segment's first row.
            let mut mems = [declared.gyro.memory_state(), declared.accel.memory_state()];
            let mut gterms = [Vector3::zeros(); rins_plant::effects::gyro::GYRO_TERMS];
            let mut aterms = [Vector3::zeros(); rins_plant::effects::accel::ACCEL_TERMS];
            // Both navigators start from the attitude at the end of the first row.
            let c_bn0 = match &h.attitude {
                Attitude::Gimbal {
                    outer_rad,
                    inner_rad,
                } => body_to_nav(
                    &kin.c_vn,
                    GimbalAngles::new(outer_rad[seg.start], inner_rad[seg.start]),
                ),
                Attitude::Quaternion(q) => {
                    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                        q[seg.start][0],
                        q[seg.start][1],
                        q[seg.start][2],
                        q[seg.start][3],
                    ))
                    .to_rotation_matrix()
                    .into_inner()
                }
            };
            let mut nav_meas =
                rins_navigation::strapdown::Strapdown::new(site_state(c_bn0), row_dt_s, vertical);
            let mut nav_model = nav_meas.clone();
            let mut track = NavTrack {
                run: h.run[seg.start],
                ..NavTrack::default()
            };
            let horizontal = |n: &rins_navigation::strapdown::Strapdown| {
                let (north, east) = rins_navigation::errors::position_error_m(
                    n.state(),
                    model.site.lat_deg.to_radians(),
                    model.site.lon_deg.to_radians(),
                    model.site.height_m,
                );
                north.hypot(east)
            };
            // The first row of a segment only gives the start attitude: its own start attitude
            // is unknown (the table may already be moving), so it is not compared.
            for k in seg.start + 1..seg.end {
                let dt = h.t_s[k] - h.t_s[k - 1];
                let RowKinematics {
                    dtheta_rad: dtheta,
                    dv_mps: dv,
                    c_nb,
                    moving,
                } = kin.row(h, seg, k, dt);
                let up_b = c_nb.column(2).into_owned();
                let f_b = c_nb * kin.f_n;
                let gt = Vector3::new(
                    h.gyro_temp_c[0][k],
                    h.gyro_temp_c[1][k],
                    h.gyro_temp_c[2][k],
                );
                let ctx = TermContext {
                    dt_s: dt,
                    dtheta_rad: dtheta,
                    dv_mps: dv,
                    f_b_mps2: f_b,
                    up_b,
                    north_b: c_nb.column(1).into_owned(),
                    east_b: c_nb.column(0).into_owned(),
                    gyro_temp_c: gt,
                    gyro_gradient_k: h
                        .housing_temp_c
                        .as_ref()
                        .map_or(Vector3::zeros(), |t| gt.add_scalar(-t[k])),
                    accel_temp_c: h.accel_temp_c[k],
                };
                let mut ge = gyro.increment_error(&ctx, &mut gterms);
                let mut ae = accel.increment_error(&ctx, &mut aterms);
                // Declared effects: the model's own contribution, and the candidates' regressors.
                let frame = signals
                    .as_ref()
                    .map(|s| s.frame(h, k, dt, &c_nb, &dtheta, &dv));
                if let Some(f) = &frame {
                    let [gm, am] = &mut mems;
                    ge += declared.gyro.increment_error(f, gm, dt, &dtheta);
                    ae += declared.accel.increment_error(f, am, dt, &dv);
                }
                let mut r = [0.0; 6];
                for i in 0..3 {
                    r[i] = h.dtheta_rad[i][k] - (dtheta[i] + ge[i]);
                    r[i + 3] = h.dv_mps[i][k] - (dv[i] + ae[i]);
                }
                let measured = (
                    Vector3::new(h.dtheta_rad[0][k], h.dtheta_rad[1][k], h.dtheta_rad[2][k]),
                    Vector3::new(h.dv_mps[0][k], h.dv_mps[1][k], h.dv_mps[2][k]),
                );
                nav_meas.update(&measured.0, &measured.1);
                nav_model.update(&(dtheta + ge), &(dv + ae));
                for (c, acc) in allan.iter_mut().enumerate() {
                    acc.push(r[c] / dt);
                }
                let t_mid = h.t_s[k] - 0.5 * dt;
                let split = match &cur {
                    Some(w) => {
                        w.moving != moving
                            || (w.up_z - up_b.z).abs() > 1e-6 && !moving
                            || w.duration_s + dt > window_s * (1.0 + 1e-9)
                    }
                    None => true,
                };
                if split {
                    if let Some(w) = cur.take() {
                        track.t_s.push(w.t_run_s + 0.5 * w.duration_s);
                        track.measured_m.push(horizontal(&nav_meas));
                        track.model_m.push(horizontal(&nav_model));
                        windows.push(finish(w));
                    }
                    cur = Some(Window {
                        run: h.run[k],
                        t_mid_s: 0.0,
                        t_run_s: t_mid - run_start,
                        duration_s: 0.0,
                        rows: 0,
                        moving,
                        up_z: up_b.z,
                        azimuth_deg: azimuth_deg(&c_nb),
                        f_b_g: [0.0; 3],
                        gyro_temp_c: [0.0; 3],
                        accel_temp_c: 0.0,
                        rotation_rps: 0.0,
                        since_move_s: if moving {
                            0.0
                        } else {
                            h.t_s[k - 1] - last_stop
                        },
                        y: [0.0; 6],
                        x: vec![0.0; nx],
                    });
                }
                if moving {
                    last_stop = h.t_s[k];
                }
                let w = cur.as_mut().expect("window open");
                w.rows += 1;
                w.duration_s += dt;
                w.t_mid_s += t_mid * dt;
                for i in 0..3 {
                    w.f_b_g[i] += f_b[i] / rins_plant::units::G0 * dt;
                    w.gyro_temp_c[i] += gt[i] * dt;
                }
                w.accel_temp_c += h.accel_temp_c[k] * dt;
                w.rotation_rps += dtheta.norm();
                if !moving {
                    w.up_z = up_b.z;
                }
                for c in 0..6 {
                    w.y[c] += r[c];
                }
                for g in &groups {
                    buf.clear();
                    match g.effect {
                        Effect::Gyro(t) => gyro.regressors(t, &ctx, g.channel, &mut buf),
                        Effect::Accel(t) => accel.regressors(t, &ctx, g.channel - 3, &mut buf),
                        Effect::Custom(c) => {
                            let f = frame.as_ref().expect("declared effects present");
                            let input = if c.accel { &dv } else { &dtheta };
                            let m = declared.model(c.accel);
                            buf.push(m.regressor(
                                c.index as usize,
                                g.channel % 3,
                                f,
                                &mems[c.accel as usize],
                                dt,
                                input,
                            ));
                        }
                    }
                    for (x, b) in w.x[g.offset..g.offset + g.len].iter_mut().zip(&buf) {
                        *x += b;
                    }
                }
            }
            if let Some(w) = cur.take() {
                track.t_s.push(w.t_run_s + 0.5 * w.duration_s);
                track.measured_m.push(horizontal(&nav_meas));
                track.model_m.push(horizontal(&nav_model));
                windows.push(finish(w));
            }
            (windows, allan, track)
        }));
    });

    let mut windows = Vec::new();
    let mut nav = Vec::new();
    let mut allan: Vec<AllanAcc> = (0..6).map(|_| AllanAcc::new()).collect();
    for (w, a, t) in per_segment {
        windows.extend(w);
        nav.push(t);
        for (acc, part) in allan.iter_mut().zip(a) {
            acc.merge(&part);
        }
    }
    Replay {
        windows,
        groups,
        unavailable,
        allan,
        row_dt_s,
        nav,
        rows: info.rows,
    }
}

/// Heading of the body x axis's horizontal part (body y when x is within 30° of vertical), °
/// from north towards east in [0, 360), from C_n^b (ENU navigation frame): body axis i in
/// navigation coordinates is row i of C_n^b.
pub fn azimuth_deg(c_nb: &Matrix3<f64>) -> f64 {
    let row = if c_nb[(0, 2)].abs() < 0.866 { 0 } else { 1 };
    let (e, n) = (c_nb[(row, 0)], c_nb[(row, 1)]);
    e.atan2(n).to_degrees().rem_euclid(360.0)
}

/// Turns time-weighted sums into means.
fn finish(mut w: Window) -> Window {
    let d = w.duration_s.max(f64::MIN_POSITIVE);
    w.t_mid_s /= d;
    for i in 0..3 {
        w.f_b_g[i] /= d;
        w.gyro_temp_c[i] /= d;
    }
    w.accel_temp_c /= d;
    w.rotation_rps /= d;
    w.t_run_s += 0.5 * w.duration_s;
    if !w.moving {
        w.since_move_s += 0.5 * w.duration_s;
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row in which the inner gimbal turns 4° (20 °/s at 5 Hz) on a level mount: the specific
    /// force integrates exactly to g·Δt/Δi·(0, cos i₀ − cos i₁, sin i₁ − sin i₀); the outer
    /// gimbal's turn to the same form about its axis; the midpoint rule alone misses
    /// (Δ/2)²/6 of it.
    #[test]
    fn a_turning_row_integrates_the_specific_force_exactly() {
        let g = 9.8;
        let f_n = Vector3::new(0.0, 0.0, g);
        let w = Vector3::zeros();
        let dt = 0.2;
        let (i0, i1) = (0.3f64, 0.3 + 4f64.to_radians());
        let r = gimbal_true_increments(
            &Matrix3::identity(),
            &w,
            &f_n,
            GimbalAngles::new(0.0, i0),
            GimbalAngles::new(0.0, i1),
            dt,
        );
        let di = i1 - i0;
        let want = Vector3::new(0.0, i0.cos() - i1.cos(), i1.sin() - i0.sin()) * (g * dt / di);
        assert!(
            (r.dv_mps - want).norm() < 1e-14 * g * dt,
            "{} vs {want}",
            r.dv_mps
        );
        // The outer gimbal turning 4° with the inner at 30°: f stays along the outer axis
        // (vertical) on a level mount, so nothing changes; tilt the mount 30° instead.
        let c_vn = Matrix3::new(
            1.0,
            0.0,
            0.0,
            0.0,
            0.5f64.cos(),
            -0.5f64.sin(),
            0.0,
            0.5f64.sin(),
            0.5f64.cos(),
        );
        let (o0, o1) = (0.2f64, 0.2 + 4f64.to_radians());
        let r = gimbal_true_increments(
            &c_vn,
            &w,
            &f_n,
            GimbalAngles::new(o0, 0.5),
            GimbalAngles::new(o1, 0.5),
            dt,
        );
        // Reference: 2000-point midpoint quadrature of C_n^b(t)·f over the row.
        let n = 2000;
        let mut q = Vector3::zeros();
        for k in 0..n {
            let o = o0 + (o1 - o0) * (k as f64 + 0.5) / n as f64;
            q += body_to_nav(&c_vn, GimbalAngles::new(o, 0.5)).transpose() * f_n * (dt / n as f64);
        }
        assert!((r.dv_mps - q).norm() < 1e-9 * g * dt, "{} vs {q}", r.dv_mps);
        let mid =
            body_to_nav(&c_vn, GimbalAngles::new(0.5 * (o0 + o1), 0.5)).transpose() * f_n * dt;
        assert!(
            (mid - q).norm() > 1e-5 * g * dt,
            "the midpoint rule alone differs"
        );
    }

    /// A 20 °/s inner turn that starts 0.06 s into a 0.1 s row and one that stops 0.03 s into
    /// one: the rows around place the turn, and the increments equal a fine quadrature of the
    /// true motion; taken as one constant-rate turn over the row they would miss by far more.
    #[test]
    fn a_move_starting_or_stopping_within_a_row_is_placed_by_its_neighbours() {
        let f_n = Vector3::new(0.0, 0.0, 9.8);
        let w = Vector3::new(0.0, 5e-5, 4e-5);
        let c_vn = Matrix3::identity();
        let rate = 20f64.to_radians();
        let dt = 0.1;
        let ang = |i: f64| GimbalAngles::new(0.3, i);
        // The true inner angle at time t of a turn starting at t0.
        let quad = |i_of: &dyn Fn(f64) -> f64, t0: f64, t1: f64| {
            let n = 4000;
            let (mut dv, mut dth) = (Vector3::zeros(), Vector3::zeros());
            for k in 0..n {
                let t = t0 + (t1 - t0) * (k as f64 + 0.5) / n as f64;
                let c_nb = body_to_nav(&c_vn, ang(i_of(t))).transpose();
                dv += c_nb * f_n * ((t1 - t0) / n as f64);
                dth += c_nb * w * ((t1 - t0) / n as f64);
            }
            (dv, dth + Vector3::x() * (i_of(t1) - i_of(t0)))
        };
        // Start at t = 0.06 in the row [0, 0.1].
        let start = |t: f64| 0.2 + rate * (t - 0.06).max(0.0);
        let r = gimbal_row_increments(
            &c_vn,
            &w,
            &f_n,
            Some((ang(start(-0.1)), dt)),
            ang(start(0.0)),
            ang(start(0.1)),
            Some((ang(start(0.2)), dt)),
            dt,
        );
        let (dv, dth) = quad(&start, 0.0, 0.1);
        assert!((r.dv_mps - dv).norm() < 1e-9, "{} vs {dv}", r.dv_mps);
        assert!(
            (r.dtheta_rad - dth).norm() < 1e-12,
            "{} vs {dth}",
            r.dtheta_rad
        );
        let naive = gimbal_true_increments(&c_vn, &w, &f_n, ang(start(0.0)), ang(start(0.1)), dt);
        assert!((naive.dv_mps - dv).norm() > 1e3 * (r.dv_mps - dv).norm());
        // Stop at t = 0.03.
        let stop = |t: f64| 0.2 + rate * t.min(0.03);
        let r = gimbal_row_increments(
            &c_vn,
            &w,
            &f_n,
            Some((ang(stop(-0.1)), dt)),
            ang(stop(0.0)),
            ang(stop(0.1)),
            Some((ang(stop(0.2)), dt)),
            dt,
        );
        let (dv, _) = quad(&stop, 0.0, 0.1);
        assert!((r.dv_mps - dv).norm() < 1e-9, "{} vs {dv}", r.dv_mps);
    }
}
