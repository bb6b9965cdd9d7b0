//! One row of a run, integrated exactly: the row (t_{k−1}, t_k] is cut where the table starts
//! or stops a move or a chamber leg begins, so every piece is smooth; the gimbals' part of Δθ is
//! the exact angle difference, and the Earth-rate part of Δθ, Δv and every hidden effect's
//! rate are integrated over each piece by five-point Gauss–Legendre quadrature at the exact
//! attitude and temperatures.

use nalgebra::{Matrix3, Vector3};
use rins_plant::PlantConfig;
use rins_plant::earth::Site;

use crate::design::{Design, RunDesign};
use crate::quadrature;
use crate::rotation::{body_to_nav, mount};
use crate::table::Timeline;
use crate::thermal::{RunThermal, Temps};

/// What every row of a design shares: the mount, the Earth rate and gravity at the site.
#[derive(Clone, Copy, Debug)]
pub struct Setup {
    /// C_v^n with the design's roll.
    pub c_vn: Matrix3<f64>,
    /// ω_ie^n = Ω(0, cos L, sin L), rad/s.
    pub omega_ie_n: Vector3<f64>,
    /// Normal gravity at the site, m/s².
    pub gravity_mps2: f64,
}

impl Setup {
    /// The setup of `model` on `design` (the design's mount roll replaces the model's).
    pub fn new(model: &PlantConfig, design: &Design) -> Self {
        let v = &model.vehicle;
        let site = Site::new(&model.site, &model.earth);
        Self {
            c_vn: mount(v.azimuth_deg, v.pitch_deg, design.mount_roll_deg),
            omega_ie_n: site.omega_ie_n,
            gravity_mps2: site.gravity_mps2,
        }
    }
}

/// A quadrature node of a row: an instant and its weight, with the state there.
#[derive(Clone, Copy, Debug)]
pub struct Node {
    /// Weight, s.
    pub w: f64,
    /// Run time, s.
    pub t: f64,
    /// C_n^b.
    pub c_nb: Matrix3<f64>,
    /// Body rate ω_ib^b, rad/s.
    pub omega_b: Vector3<f64>,
    /// Seconds since the table last stopped.
    pub since_stop: f64,
    /// True temperatures.
    pub temps: Temps,
    /// Chamber leg index (for the extra lags).
    pub leg: usize,
}

impl Node {
    /// Body up direction u^b = C_n^b·(0, 0, 1).
    pub fn up(&self) -> Vector3<f64> {
        self.c_nb.column(2).into_owned()
    }
}

/// One row's exact figures.
#[derive(Clone, Debug, Default)]
pub struct Row {
    /// Start, s of run time.
    pub t0: f64,
    /// End, s.
    pub t1: f64,
    /// True angular increment, rad.
    pub dtheta: Vector3<f64>,
    /// True velocity increment, m/s.
    pub dv: Vector3<f64>,
    /// Gimbal angles at the end (outer, inner), rad.
    pub angles_end: (f64, f64),
    /// True temperatures at the start and the end.
    pub temps_start: Temps,
    /// True temperatures at the end.
    pub temps_end: Temps,
    /// Table segment that holds the end.
    pub segment_end: usize,
    /// Quadrature nodes.
    pub nodes: Vec<Node>,
}

/// The rows of one run, in order.
#[derive(Clone, Debug)]
pub struct RunRows {
    /// Shared setup.
    pub setup: Setup,
    /// Table timeline.
    pub timeline: Timeline,
    /// Temperatures.
    pub thermal: RunThermal,
    /// Row interval, s.
    pub dt: f64,
    /// Number of rows.
    pub rows: usize,
    seg_hint: usize,
    leg_hint: usize,
}

impl RunRows {
    /// The rows of `run` at `rate_hz`, with extra temperature lags at `lag_taus_s`.
    pub fn new(setup: Setup, design: &Design, run: &RunDesign, lag_taus_s: &[f64]) -> Self {
        let dt = 1.0 / design.rate_hz;
        Self {
            setup,
            timeline: Timeline::new(&run.table),
            thermal: RunThermal::new(&run.chamber, &design.thermal, lag_taus_s),
            dt,
            rows: (run.duration_s * design.rate_hz).round() as usize,
            seg_hint: 0,
            leg_hint: 0,
        }
    }

    /// Fills `row` with row `k` (1-based: it covers ((k − 1)·dt, k·dt]).
    pub fn row(&mut self, k: usize, row: &mut Row) {
        let (t0, t1) = ((k - 1) as f64 * self.dt, k as f64 * self.dt);
        row.t0 = t0;
        row.t1 = t1;
        row.nodes.clear();
        let mut gimbal = Vector3::zeros();
        let mut a = t0;
        let mut seg_end = self.seg_hint;
        while a < t1 {
            let si = self.timeline.segment_at(a, self.seg_hint);
            let li = self.thermal.leg_at(a, self.leg_hint);
            (self.seg_hint, self.leg_hint, seg_end) = (si, li, si);
            let seg = self.timeline.segments[si];
            let b = t1.min(seg.t1).min(self.thermal.leg_end(li));
            gimbal += seg.gimbal_increment(a, b);
            let rate = seg.gimbal_rate_body();
            for (t, w) in quadrature::nodes(a, b) {
                let (o, i) = seg.angles(t);
                let c_nb = body_to_nav(&self.setup.c_vn, o, i).transpose();
                row.nodes.push(Node {
                    w,
                    t,
                    c_nb,
                    omega_b: rate + c_nb * self.setup.omega_ie_n,
                    since_stop: seg.since_stop(t),
                    temps: self.thermal.temps_on(li, t),
                    leg: li,
                });
            }
            a = b;
        }
        let g = self.setup.gravity_mps2;
        let (mut earth, mut dv) = (Vector3::zeros(), Vector3::zeros());
        for n in &row.nodes {
            earth += n.c_nb * self.setup.omega_ie_n * n.w;
            dv += n.up() * (g * n.w);
        }
        row.dtheta = gimbal + earth;
        row.dv = dv;
        row.segment_end = seg_end;
        row.angles_end = self.timeline.segments[seg_end].angles(t1);
        row.temps_start = self.thermal.temps(t0);
        row.temps_end = self
            .thermal
            .temps_on(self.thermal.leg_at(t1, self.leg_hint), t1);
    }
}
