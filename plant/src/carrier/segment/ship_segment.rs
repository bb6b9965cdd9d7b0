//! The ship on the segment rule: building a segment (the full carrier state at the nodes), the
//! per-tick points and tick-end state from the interpolant, and the state codec's part.

use std::sync::Arc;

use nalgebra::{Matrix3, Vector3};

use super::super::carrier_state::CarrierState;
use super::super::ship::{Ship, Trig, angles, compose_with};
use super::super::track::{TrackPoint, TrackPosition};
use super::super::waves::SeaJet;
use super::{CHANNELS, POINT_CHANNELS, SegmentRule, TickMeans, TickPoints};
use crate::earth::LocalEarth;
use crate::kinematics::carrier_point_near;
use crate::table::{GimbalFrame, SmoothTurn};

/// Where the carrier points are taken: Earth switches and the lever arm (from the plant).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointEnv {
    /// Earth rotation on.
    pub rotation: bool,
    /// Gravity on.
    pub gravity: bool,
    /// IMU position from the reference point, carrier axes, m.
    pub lever_c_m: Vector3<f64>,
    /// C_c^v, carrier axes to the table mount's (`None`: the identity, the default mount): the
    /// points are kept in mount axes.
    pub mount_t: Option<Matrix3<f64>>,
}

impl PointEnv {
    /// `v` (carrier axes) in the table mount's axes.
    #[inline]
    pub fn to_mount(&self, v: Vector3<f64>) -> Vector3<f64> {
        match &self.mount_t {
            None => v,
            Some(m) => m * v,
        }
    }
}

/// The ship's segment in progress.
#[derive(Clone, Debug)]
pub struct SegState {
    rule: Arc<SegmentRule>,
    env: PointEnv,
    /// Corners of the mean track, s (see [`super::track::Track::corners_s`]).
    corners_s: Vec<f64>,
    /// Current tick.
    tick: u64,
    /// The segment: its first tick, the mean-track position there and at its end.
    start_tick: u64,
    start_pos: TrackPosition,
    end_pos: TrackPosition,
    /// True when the segment runs the exact per-tick path (it holds a corner).
    exact: bool,
    /// Node values ([`CHANNELS`]).
    y: Vec<[f64; CHANNELS]>,
    /// Scratch: the sea state's jets, the mean track, the composition angles' sines and
    /// cosines, the mean-track velocity and the displacement from the segment start at the
    /// nodes.
    jets: Vec<SeaJet>,
    tracks: Vec<(TrackPoint, Trig)>,
    v: Vec<[f64; 2]>,
    disp: Vec<[f64; 2]>,
    /// Every tick's mean points in body axes ([`SegmentRule::tick_means_all`] of the node
    /// values turned into the body frame `means_frame`), computed at the segment's first
    /// dwelling tick and again if the table dwells elsewhere later in the segment.
    means: TickMeans,
    means_frame: Option<GimbalFrame>,
    /// The node values' point channels (mount axes), apart: what the tick means combine.
    y_pts: Vec<[f64; POINT_CHANNELS]>,
    /// Scratch: the node values' points in body axes.
    y_body: Vec<[f64; POINT_CHANNELS]>,
    /// Every tick's mean points in mount axes ([`SegmentRule::tick_means_all`]), computed at
    /// the segment's first turning tick (`mount_ready`).
    means_mount: TickMeans,
    mount_ready: bool,
}

impl Ship {
    /// Switches the segment rule on for points taken with `env` (call at tick 0). Returns the
    /// segment length in ticks, or `None` when the motion is too fast for it (then the exact
    /// per-tick path stays).
    pub fn enable_segments(&mut self, env: PointEnv) -> Option<u64> {
        assert_eq!(self.tick, 0, "segments are switched on at tick 0");
        let wave_top = self.waves.as_ref().map_or(0.0, |w| w.omega_top_rps());
        let track_top = 2.0 * std::f64::consts::PI / self.track.shortest_change_s();
        let (n, m) = SegmentRule::choose(wave_top.max(track_top), self.tick_s)?;
        let rule = SegmentRule::new(n, m);
        if let Some(w) = self.waves.as_mut() {
            w.set_segment(m, &rule.node_ticks);
        }
        let start = self.pos;
        self.seg = Some(Box::new(SegState {
            rule: Arc::new(rule),
            env,
            corners_s: self.track.corners_s(),
            tick: 0,
            start_tick: 0,
            start_pos: start,
            end_pos: start,
            exact: false,
            y: vec![],
            jets: vec![],
            tracks: vec![],
            v: vec![],
            disp: vec![],
            means: TickMeans::default(),
            means_frame: None,
            y_pts: vec![],
            y_body: vec![],
            means_mount: TickMeans::default(),
            mount_ready: false,
        }));
        self.build_segment(0, start);
        Some(m)
    }

    /// Back to the exact per-tick path (at tick 0).
    pub fn disable_segments(&mut self) {
        assert_eq!(self.tick, 0, "segments are switched off at tick 0");
        self.seg = None;
        self.set_position(0, self.start);
    }

    /// Restarts the segment rule (if on) from tick 0.
    pub(in crate::carrier) fn restart_segments(&mut self) {
        if self.seg.is_some() {
            self.build_segment(0, self.start);
        }
    }

    /// The segment length in ticks when the segment rule is on.
    pub fn segment_ticks(&self) -> Option<u64> {
        self.seg.as_ref().map(|s| s.rule.m)
    }

    /// Builds segment `index` from the mean-track position `pos0` at its start and sets the
    /// state to its first tick.
    fn build_segment(&mut self, index: u64, pos0: TrackPosition) {
        let mut seg = self.seg.take().expect("segment rule on");
        let (m, h) = (seg.rule.m, self.tick_s);
        let t0 = index * m;
        let (a_s, b_s) = (t0 as f64 * h, (t0 + m) as f64 * h);
        let i = seg.corners_s.partition_point(|&c| c <= a_s);
        seg.exact = seg.corners_s.get(i).is_some_and(|&c| c < b_s);
        (seg.tick, seg.start_tick, seg.start_pos) = (t0, t0, pos0);
        (seg.means_frame, seg.mount_ready) = (None, false);
        if seg.exact {
            self.set_position(t0, pos0);
        } else {
            self.nodes_of(&mut seg, t0, pos0);
        }
        self.seg = Some(seg);
    }

    /// The full carrier state at the nodes of the segment from tick `t0` at `pos0`.
    fn nodes_of(&mut self, seg: &mut SegState, t0: u64, pos0: TrackPosition) {
        let rule = seg.rule.clone();
        let (h, n) = (self.tick_s, rule.n);
        if let Some(w) = self.waves.as_mut() {
            w.seek_segment(t0);
        }
        match self.waves.as_mut() {
            Some(w) => w.node_jets(&mut seg.jets),
            None => {
                seg.jets.clear();
                seg.jets.resize(n, SeaJet::default());
            }
        }
        seg.tracks.clear();
        seg.v.clear();
        let mut trig = Trig::default();
        for (j, jet) in seg.jets.iter().enumerate() {
            let tp = self.track_at((t0 as f64 + rule.node_ticks[j]) * h);
            // Exact sines at the first node, then each node's from the one before (nodes are
            // under a tenth of a segment apart: steps of hundredths of a radian at sea).
            let ang = angles(&tp, jet);
            trig = if j == 0 {
                Trig::exact(ang)
            } else {
                trig.near_wide(ang)
            };
            seg.v
                .push([tp.speed_mps * trig.sin[0], tp.speed_mps * trig.cos[0]]);
            seg.tracks.push((tp, trig));
        }
        let end = rule.displacements(&seg.v, rule.m as f64 * h, &mut seg.disp);
        if self.earth.lat0_rad() != LocalEarth::grid_lat_rad(pos0.lat_rad) {
            self.earth = LocalEarth::near(pos0.lat_rad);
        }
        let here = self.earth.at(pos0.lat_rad);
        let mut p = pos0;
        let (_, _, mid) = p.advance_from(&self.earth, &here, end[1], end[0], self.height_m);
        seg.end_pos = p;
        let (i_rm, i_rn) = (
            1.0 / (mid.rm_m + self.height_m),
            1.0 / ((mid.rn_m + self.height_m) * mid.cos_lat),
        );
        seg.y.resize(n, [0.0; CHANNELS]);
        seg.y_pts.resize(n, [0.0; POINT_CHANNELS]);
        let e = seg.env;
        for j in 0..n {
            let ((tp, trig), d) = (&seg.tracks[j], seg.disp[j]);
            let pos = TrackPosition {
                lat_rad: pos0.lat_rad + d[1] * i_rm,
                lon_rad: pos0.lon_rad + d[0] * i_rn,
            };
            let s = compose_with(
                tp,
                pos,
                self.height_m,
                &seg.jets[j],
                &self.earth,
                &mid,
                trig,
            );
            let pt = carrier_point_near(&s, &self.earth, e.rotation, e.gravity, &e.lever_c_m);
            let c = &s.c_cn;
            let up = Vector3::new(c[(2, 0)], c[(2, 1)], c[(2, 2)]);
            let (w, f, up) = (
                e.to_mount(pt.omega_ic_c),
                e.to_mount(pt.f_c),
                e.to_mount(up),
            );
            let y = &mut seg.y[j];
            y[0..3].copy_from_slice(w.as_slice());
            y[3..6].copy_from_slice(f.as_slice());
            y[6..9].copy_from_slice(up.as_slice());
            y[9] = s.lat_rad - pos0.lat_rad;
            // The shortest way: a node across the antimeridian is wrapped (a no-op otherwise).
            y[10] = super::super::track::wrap_lon_rad(s.lon_rad - pos0.lon_rad);
            y[11] = s.height_m;
            y[12..15].copy_from_slice(s.v_n.as_slice());
            y[15..18].copy_from_slice(s.a_n.as_slice());
            for r in 0..3 {
                for k in 0..3 {
                    y[18 + 3 * r + k] = c[(r, k)];
                }
            }
            y[27..30].copy_from_slice(s.omega_nc_c.as_slice());
            y[30..33].copy_from_slice(s.alpha_nc_c.as_slice());
            seg.y_pts[j] = [w.x, w.y, w.z, f.x, f.y, f.z, up.x, up.y, up.z];
        }
    }

    /// The segment rule's state now (`None` without it).
    pub(in crate::carrier) fn segment_state_now(&mut self) -> Option<CarrierState> {
        let seg = self.seg.take()?;
        let mut now = CarrierState::at_rest(0.0, 0.0, 0.0, Matrix3::identity());
        if seg.exact {
            // The exact path's state at its tick: the bits its last `advance` returned.
            self.seg = None;
            now = self.state_now();
        } else {
            seg.state_into((seg.tick - seg.start_tick) as usize, &mut now);
        }
        self.seg = Some(seg);
        Some(now)
    }

    /// The interpolated state at the current tick (`None` without the segment rule or while
    /// the segment runs the exact path: its state is the one [`Ship::advance_points`] wrote).
    pub(in crate::carrier) fn segment_state(&self) -> Option<CarrierState> {
        let seg = self.seg.as_ref().filter(|s| !s.exact)?;
        let mut now = CarrierState::at_rest(0.0, 0.0, 0.0, Matrix3::identity());
        seg.state_into((seg.tick - seg.start_tick) as usize, &mut now);
        Some(now)
    }

    /// The interpolated latitude (rad), height (m) and velocity (ENU, m/s) at the current tick
    /// (`None` as for [`Ship::segment_state`]): what the azimuth isolation loop needs every
    /// sample, the bits of those fields of [`Ship::segment_state`] without the rest.
    pub(in crate::carrier) fn segment_lat_height_velocity(
        &self,
    ) -> Option<(f64, f64, Vector3<f64>)> {
        let seg = self.seg.as_ref().filter(|s| !s.exact)?;
        let c = seg
            .rule
            .position_velocity_at((seg.tick - seg.start_tick) as usize, &seg.y);
        Some((
            seg.start_pos.lat_rad + c[0],
            c[2],
            Vector3::new(c[3], c[4], c[5]),
        ))
    }

    /// The interpolated C_c^n at the current tick (`None` as for [`Ship::segment_state`]): what
    /// the thermal network and the attitude accessors need, without the rest of the state.
    pub(in crate::carrier) fn segment_attitude(&self) -> Option<Matrix3<f64>> {
        let seg = self.seg.as_ref().filter(|s| !s.exact)?;
        let c = seg
            .rule
            .attitude_at((seg.tick - seg.start_tick) as usize, &seg.y);
        Some(Matrix3::from_row_slice(&c))
    }

    /// One tick with the segment rule on: the tick's points (in mount axes at its quadrature
    /// points while the table turns, `turning`; while it dwells, the tick's means already in
    /// the body axes of `frame`). While the segment runs the exact path the state at the
    /// tick's end goes to `end`; an interpolated segment leaves `end` alone (its state is
    /// `Ship::segment_state`, computed when asked for).
    pub fn advance_points(
        &mut self,
        frame: &GimbalFrame,
        turning: bool,
        end: &mut CarrierState,
    ) -> TickPoints {
        let mut seg = self.seg.take().expect("segment rule on");
        let k = (seg.tick - seg.start_tick) as usize;
        let pts = if seg.exact {
            let mut nodes = [*end; 2];
            *end = self.advance(&mut nodes);
            let e = &seg.env;
            TickPoints::Nodes(nodes.map(|n| {
                let p = carrier_point_near(&n, &self.earth, e.rotation, e.gravity, &e.lever_c_m);
                let up = n.c_cn.row(2).transpose();
                [p.omega_ic_c, p.f_c, up].map(|v| e.to_mount(v))
            }))
        } else if turning {
            TickPoints::Nodes(seg.quadrature_points(k))
        } else {
            TickPoints::BodyMean(seg.body_mean(frame, k))
        };
        self.finish_tick(seg, end);
        pts
    }

    /// The common tick, while the table dwells: the tick's means in the body axes of `frame`
    /// (ω_ic without the gimbals' part, f, up), or `None` without an interpolated segment
    /// (then [`Ship::advance_points`] runs). `end` as there.
    #[inline]
    pub fn dwell_means(
        &mut self,
        frame: &GimbalFrame,
        end: &mut CarrierState,
    ) -> Option<[Vector3<f64>; 3]> {
        let mut seg = self.seg.take_if(|s| !s.exact)?;
        let means = seg.body_mean(frame, (seg.tick - seg.start_tick) as usize);
        self.finish_tick(seg, end);
        Some(means)
    }

    /// A tick on which the table turns smoothly (`turn`, `frame` the gimbal frame at the tick's
    /// middle): the tick's means in body axes (ω_ic without the gimbals' part, f, up) from the
    /// mount-axis tick means and their slopes ([`SmoothTurn::mean_in_body`]), or `None` without
    /// an interpolated segment. `end` as in [`Ship::advance_points`].
    #[inline]
    pub fn turn_means(
        &mut self,
        frame: &GimbalFrame,
        turn: &SmoothTurn,
        end: &mut CarrierState,
    ) -> Option<[Vector3<f64>; 3]> {
        let mut seg = self.seg.take_if(|s| !s.exact)?;
        let k = (seg.tick - seg.start_tick) as usize;
        seg.ensure_mount_means();
        let (mean, diff) = seg.rule.mean_and_slope(&seg.means_mount, k);
        let (mean, diff) = (TickPoints::split(&mean), TickPoints::split(&diff));
        // Written out: as an array map the compiler kept the call behind a closure.
        let out = [
            turn.mean_in_body(frame, &mean[0], &diff[0]),
            turn.mean_in_body(frame, &mean[1], &diff[1]),
            turn.mean_in_body(frame, &mean[2], &diff[2]),
        ];
        self.finish_tick(seg, end);
        Some(out)
    }

    /// Closes a tick of segment `seg` (taken out of `self`): the next tick, or the next
    /// segment after its last.
    #[inline]
    fn finish_tick(&mut self, mut seg: Box<SegState>, end: &mut CarrierState) {
        seg.tick += 1;
        if seg.tick == seg.start_tick + seg.rule.m {
            self.next_segment(seg, end);
        } else {
            self.seg = Some(seg);
        }
    }

    /// Builds the segment after `seg` (once every M ticks: kept out of the per-tick path).
    #[cold]
    #[inline(never)]
    fn next_segment(&mut self, seg: Box<SegState>, end: &mut CarrierState) {
        let (next, m) = (seg.tick, seg.rule.m);
        let pos = if seg.exact { self.pos } else { seg.end_pos };
        self.seg = Some(seg);
        self.build_segment(next / m, pos);
        if self.seg.as_deref().is_some_and(|s| s.exact) {
            *end = self.state_now();
        }
    }

    /// What the state codec saves with the segment rule on: the current segment's first tick
    /// and the mean-track position there.
    pub fn segment_position(&self) -> Option<(u64, TrackPosition)> {
        self.seg.as_ref().map(|s| (s.start_tick, s.start_pos))
    }

    /// Restores from [`Ship::segment_position`] and continues at tick `tick` of that segment.
    pub fn restore_segment(
        &mut self,
        start_tick: u64,
        pos: TrackPosition,
        tick: u64,
    ) -> Result<(), String> {
        let m = self.segment_ticks().ok_or("segment rule off")?;
        if !start_tick.is_multiple_of(m) || tick < start_tick || tick - start_tick >= m {
            return Err(format!(
                "carrier state: segment start {start_tick} does not hold tick {tick} (segments of {m} ticks)"
            ));
        }
        self.build_segment(start_tick / m, pos);
        let exact = self.seg.as_ref().is_some_and(|s| s.exact);
        let mut end = CarrierState::at_rest(0.0, 0.0, 0.0, Matrix3::identity());
        let frame = GimbalFrame::from_sin_cos((0.0, 1.0), (0.0, 1.0));
        for _ in start_tick..tick {
            if exact {
                self.advance_points(&frame, true, &mut end);
            } else if let Some(s) = self.seg.as_mut() {
                s.tick += 1;
            }
        }
        Ok(())
    }
}

impl SegState {
    /// The points at the two Gauss–Legendre instants of tick `k` (mount axes), from the tick
    /// means ([`SegmentRule::points_from_means`]).
    #[inline]
    fn quadrature_points(&mut self, k: usize) -> [[Vector3<f64>; 3]; 2] {
        self.ensure_mount_means();
        self.rule
            .points_from_means(&self.means_mount, k)
            .map(|p| TickPoints::split(&p))
    }

    /// Computes every tick's mean points in mount axes (`means_mount`) at the segment's first
    /// turning tick.
    #[inline]
    fn ensure_mount_means(&mut self) {
        if !self.mount_ready {
            self.rule.tick_means_all(&self.y_pts, &mut self.means_mount);
            self.mount_ready = true;
        }
    }

    /// Tick `k`'s mean points in the body axes of `frame` (ω_ic without the gimbals' part, f,
    /// up), from the segment's means, computed first if they are for another frame.
    #[inline]
    fn body_mean(&mut self, frame: &GimbalFrame, k: usize) -> [Vector3<f64>; 3] {
        if self.means_frame != Some(*frame) {
            self.body_means(frame);
        }
        TickPoints::split(&self.means.row(k))
    }

    /// Every tick's mean points in the body axes of `frame`: the node values' points turned
    /// into the body frame (the rotation commutes with the interpolation), then combined.
    fn body_means(&mut self, frame: &GimbalFrame) {
        self.y_body.clear();
        self.y_body.extend(self.y_pts.iter().map(|y| {
            let v = |o: usize| frame.to_body(&Vector3::new(y[o], y[o + 1], y[o + 2]));
            let (w, f, up) = (v(0), v(3), v(6));
            [w.x, w.y, w.z, f.x, f.y, f.z, up.x, up.y, up.z]
        }));
        self.rule.tick_means_all(&self.y_body, &mut self.means);
        self.means_frame = Some(*frame);
    }

    /// The interpolated carrier state at tick boundary `i` of the segment, into `s`.
    #[inline]
    fn state_into(&self, i: usize, s: &mut CarrierState) {
        let c = self.rule.state_at(i, &self.y);
        let v = |o: usize| Vector3::new(c[o], c[o + 1], c[o + 2]);
        s.lat_rad = self.start_pos.lat_rad + c[0];
        s.lon_rad = self.start_pos.lon_rad + c[1];
        s.height_m = c[2];
        s.v_n = v(3);
        s.a_n = v(6);
        s.c_cn = Matrix3::new(c[9], c[10], c[11], c[12], c[13], c[14], c[15], c[16], c[17]);
        s.omega_nc_c = v(18);
        s.alpha_nc_c = v(21);
    }
}
