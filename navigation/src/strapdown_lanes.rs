//! Up to [`LANES`] strapdown navigators side by side, one per vector lane: the Monte Carlo
//! engine runs the navigators of many seeds (and the uncompensated and compensated navigators of
//! each) this way. The equations are [`crate::mechanisation`]'s, the same operations in the same
//! order as [`Strapdown::update`], so lane i holds exactly the bits a [`Strapdown`] fed lane i's
//! increments holds (tests below); the widest vector unit the CPU has runs them.
#![allow(unsafe_code)]

use nalgebra::{Quaternion, UnitQuaternion, Vector3, Vector4};
use rins_plant::real::{Lanes, Real};
use rins_plant::trig::GridTrig;

use crate::mechanisation::{Solution, up_in_body, update};
use crate::strapdown::{MAX_PENDING, NavState, Strapdown, VerticalChannel};
use crate::subsamples::update_subsamples;

/// Navigators per [`StrapdownLanes`]: one AVX-512 vector of f64 (two AVX2 vectors).
pub const LANES: usize = 8;

type Wide = Lanes<LANES>;

/// Why navigators cannot share lanes.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LanesError {
    /// None, or more than [`LANES`].
    #[error("{0} navigators; lanes take 1 to {LANES}")]
    Count(usize),
    /// Their update intervals or vertical channels differ (one set of equations runs them all).
    #[error("navigator {0} differs from navigator 0 in its update interval or vertical channel")]
    Differs(usize),
}

/// Navigators stepped together, each with its own increments.
#[derive(Clone, Debug)]
pub struct StrapdownLanes {
    kept: Kept,
    dt_s: f64,
    vertical: VerticalChannel,
    used: usize,
    steps: u64,
    subsamples: usize,
    /// Intervals held for the update under way (the same count in every lane).
    pending: usize,
}

/// How a group holds its navigators: the vector update costs the same for all its lanes
/// whether they are used or not, so one navigator stays itself, two take a pair of lanes, and
/// three to eight the widest vector.
#[derive(Clone, Debug)]
enum Kept {
    One(Strapdown),
    Pair(Side<2>),
    Wide(Side<LANES>),
}

/// `N` navigators' solutions lane by lane, with each one's body up direction at its current
/// attitude (for the δβ compensation of the next increments), taken with the update.
#[derive(Clone, Debug)]
struct Side<const N: usize> {
    m: Solution<Lanes<N>>,
    up: [Lanes<N>; 3],
    /// The update's intervals held so far, then its last: Δθ and Δv lane by lane.
    dtheta: [[Lanes<N>; 3]; MAX_PENDING + 1],
    dv: [[Lanes<N>; 3]; MAX_PENDING + 1],
}

impl<const N: usize> Side<N> {
    /// The navigators `navs` (1 to `N`) from where each is now; lanes past the last repeat the
    /// first (their results are never read).
    fn gather(navs: &[Strapdown]) -> Self {
        let first = &navs[0];
        let each: [Solution<f64>; N] =
            std::array::from_fn(|i| navs.get(i).unwrap_or(first).solution());
        let gather3 = |f: fn(&Solution<f64>) -> [f64; 3]| -> [Lanes<N>; 3] {
            std::array::from_fn(|c| Lanes(std::array::from_fn(|l| f(&each[l])[c])))
        };
        let gather = |f: fn(&Solution<f64>) -> f64| Lanes(std::array::from_fn(|l| f(&each[l])));
        let q: [Lanes<N>; 4] =
            std::array::from_fn(|c| Lanes(std::array::from_fn(|l| each[l].q[c])));
        let held = |i: usize, dv: bool| -> [Lanes<N>; 3] {
            std::array::from_fn(|c| {
                Lanes(std::array::from_fn(|l| {
                    let (th, v) = navs.get(l).unwrap_or(first).pending();
                    let x = if dv { v } else { th };
                    x.get(i).map_or(0.0, |x| x[c])
                }))
            })
        };
        Self {
            dtheta: std::array::from_fn(|i| held(i, false)),
            dv: std::array::from_fn(|i| held(i, true)),
            up: up_in_body(&q),
            m: Solution {
                q,
                v: gather3(|s| s.v),
                lat: gather(|s| s.lat),
                lon: gather(|s| s.lon),
                h: gather(|s| s.h),
                prev_dtheta: gather3(|s| s.prev_dtheta),
                prev_dv: gather3(|s| s.prev_dv),
                // Every lane's grid point is taken afresh at the first update (the same bits:
                // the point depends on the latitude only).
                lat_trig: GridTrig::default(),
            },
        }
    }

    /// Component `c` of each navigator's increment; lanes past the last repeat the first.
    #[inline(always)]
    fn pick(x: &[Vector3<f64>], c: usize) -> Lanes<N> {
        Lanes(std::array::from_fn(|l| x.get(l).unwrap_or(&x[0])[c]))
    }

    fn state(&self, lane: usize) -> NavState {
        let m = &self.m;
        let q = Vector4::from(std::array::from_fn::<f64, 4, _>(|c| m.q[c].lane(lane)));
        NavState {
            q_bn: UnitQuaternion::new_unchecked(Quaternion::from(q)),
            v_n: Vector3::from(std::array::from_fn(|c| m.v[c].lane(lane))),
            lat_rad: m.lat.lane(lane),
            lon_rad: m.lon.lane(lane),
            height_m: m.h.lane(lane),
        }
    }

    #[inline(always)]
    fn up_b(&self, lane: usize) -> Vector3<f64> {
        let u = &self.up;
        Vector3::new(u[0].0[lane], u[1].0[lane], u[2].0[lane])
    }
}

impl StrapdownLanes {
    /// The navigators `navs` (1 to [`LANES`], the same interval and vertical channel), from
    /// where each is now.
    pub fn new(navs: &[Strapdown]) -> Result<Self, LanesError> {
        if navs.is_empty() || navs.len() > LANES {
            return Err(LanesError::Count(navs.len()));
        }
        let first = &navs[0];
        if let Some(i) = navs.iter().position(|n| {
            n.dt_s() != first.dt_s()
                || n.vertical() != first.vertical()
                || n.subsamples() != first.subsamples()
                || n.pending().0.len() != first.pending().0.len()
        }) {
            return Err(LanesError::Differs(i));
        }
        let kept = match navs.len() {
            1 => Kept::One(first.clone()),
            2 => Kept::Pair(Side::gather(navs)),
            _ => Kept::Wide(Side::gather(navs)),
        };
        Ok(Self {
            kept,
            dt_s: first.dt_s(),
            vertical: first.vertical(),
            used: navs.len(),
            steps: first.steps(),
            subsamples: first.subsamples().get(),
            pending: first.pending().0.len(),
        })
    }

    /// Navigators in use.
    pub fn len(&self) -> usize {
        self.used
    }

    /// True when no navigator is in use (never: [`StrapdownLanes::new`] refuses none).
    pub fn is_empty(&self) -> bool {
        self.used == 0
    }

    /// Integrates one interval: navigator i takes `dtheta[i]` (rad) and `dv[i]` (m/s). With
    /// several intervals per update the navigators' states move at each update's last interval,
    /// as a [`Strapdown`]'s do. Panics unless both hold one increment per navigator in use.
    pub fn update(&mut self, dtheta: &[Vector3<f64>], dv: &[Vector3<f64>]) {
        assert!(
            dtheta.len() == self.used && dv.len() == self.used,
            "one increment per navigator"
        );
        let (dt_s, vertical, n) = (self.dt_s, self.vertical, self.subsamples);
        self.steps += 1;
        let at = self.pending;
        let last = at + 1 == n;
        self.pending = if last { 0 } else { at + 1 };
        match &mut self.kept {
            Kept::One(nav) => nav.update(&dtheta[0], &dv[0]),
            Kept::Pair(p) => {
                // The baseline build: SSE2 takes the pair in one register, and the wider
                // builds measured slower for two lanes.
                if n == 1 {
                    let dth = std::array::from_fn(|c| Side::<2>::pick(dtheta, c));
                    let dvs = std::array::from_fn(|c| Side::<2>::pick(dv, c));
                    update_body(&mut p.m, &mut p.up, &dth, &dvs, dt_s, vertical);
                } else {
                    // Picked in place: a pair of arrays built and then moved was a memmove
                    // per update (3 % of Table 4's time).
                    p.dtheta[at] = std::array::from_fn(|c| Side::<2>::pick(dtheta, c));
                    p.dv[at] = std::array::from_fn(|c| Side::<2>::pick(dv, c));
                    if last {
                        let (th, v) = (&p.dtheta[..n], &p.dv[..n]);
                        update_body_subsamples(&mut p.m, &mut p.up, th, v, dt_s, vertical);
                    }
                }
            }
            Kept::Wide(w) => {
                if n == 1 {
                    let dth = std::array::from_fn(|c| Side::<LANES>::pick(dtheta, c));
                    let dvs = std::array::from_fn(|c| Side::<LANES>::pick(dv, c));
                    update_wide(&mut w.m, &mut w.up, &dth, &dvs, dt_s, vertical);
                } else {
                    w.dtheta[at] = std::array::from_fn(|c| Side::<LANES>::pick(dtheta, c));
                    w.dv[at] = std::array::from_fn(|c| Side::<LANES>::pick(dv, c));
                    if last {
                        let (th, v) = (&w.dtheta[..n], &w.dv[..n]);
                        update_wide_subsamples(&mut w.m, &mut w.up, th, v, dt_s, vertical);
                    }
                }
            }
        }
    }

    /// Navigator `lane`'s state.
    pub fn state(&self, lane: usize) -> NavState {
        match &self.kept {
            Kept::One(n) => *n.state(),
            Kept::Pair(p) => p.state(lane),
            Kept::Wide(w) => w.state(lane),
        }
    }

    /// Navigator `lane`'s body up direction C_n^b·(0, 0, 1) at its current attitude: the bits
    /// of `state(lane).q_bn.inverse_transform_vector(&Vector3::z())`.
    #[inline]
    pub fn up_b(&self, lane: usize) -> Vector3<f64> {
        match &self.kept {
            Kept::One(n) => n.state().q_bn.inverse_transform_vector(&Vector3::z()),
            Kept::Pair(p) => p.up_b(lane),
            Kept::Wide(w) => w.up_b(lane),
        }
    }

    /// Updates made (those of the navigators before they joined, plus the group's).
    pub fn steps(&self) -> u64 {
        self.steps
    }
}

/// One update of `N` navigators side by side on one interval each, and their up directions.
#[inline(always)]
fn update_body<const N: usize>(
    m: &mut Solution<Lanes<N>>,
    up: &mut [Lanes<N>; 3],
    dtheta: &[Lanes<N>; 3],
    dv: &[Lanes<N>; 3],
    dt_s: f64,
    vertical: VerticalChannel,
) {
    update(m, dtheta, dv, dt_s, vertical);
    *up = up_in_body(&m.q);
}

/// One update of `N` navigators side by side on several intervals each
/// ([`crate::subsamples`]), and their up directions.
#[inline(always)]
fn update_body_subsamples<const N: usize>(
    m: &mut Solution<Lanes<N>>,
    up: &mut [Lanes<N>; 3],
    dtheta: &[[Lanes<N>; 3]],
    dv: &[[Lanes<N>; 3]],
    dt_s: f64,
    vertical: VerticalChannel,
) {
    update_subsamples(m, dtheta, dv, dt_s, vertical);
    *up = up_in_body(&m.q);
}

rins_plant::multiversion! {
    /// [`update`] over [`LANES`] lanes, built for the widest vector unit the CPU has.
    fn update_wide(
        m: &mut Solution<Wide>,
        up: &mut [Wide; 3],
        dtheta: &[Wide; 3],
        dv: &[Wide; 3],
        dt_s: f64,
        vertical: VerticalChannel
    ) = update_body, use update_avx512, update_avx2
}

rins_plant::multiversion! {
    /// [`update_subsamples`] over [`LANES`] lanes, built for the widest vector unit the CPU
    /// has. Apart from [`update_wide`]: the two in one function ran the single interval 10 %
    /// slower.
    fn update_wide_subsamples(
        m: &mut Solution<Wide>,
        up: &mut [Wide; 3],
        dtheta: &[[Wide; 3]],
        dv: &[[Wide; 3]],
        dt_s: f64,
        vertical: VerticalChannel
    ) = update_body_subsamples, use update_avx512_subsamples, update_avx2_subsamples
}

#[cfg(target_arch = "x86_64")]
mod on_avx512 {
    //! The lanes' solution in AVX-512 registers and back ([`crate::avx512_lanes`]), for the
    //! functions built for AVX-512 (inlined into them, so built with their features).
    use super::*;
    pub(super) use crate::avx512_lanes::F64x8;

    #[inline(always)]
    pub(super) fn load3(x: &[Wide; 3]) -> [F64x8; 3] {
        [F64x8::load(&x[0]), F64x8::load(&x[1]), F64x8::load(&x[2])]
    }
    #[inline(always)]
    fn store3(x: &[F64x8; 3]) -> [Wide; 3] {
        [x[0].store(), x[1].store(), x[2].store()]
    }
    #[inline(always)]
    fn load4(x: &[Wide; 4]) -> [F64x8; 4] {
        [
            F64x8::load(&x[0]),
            F64x8::load(&x[1]),
            F64x8::load(&x[2]),
            F64x8::load(&x[3]),
        ]
    }
    #[inline(always)]
    fn store4(x: &[F64x8; 4]) -> [Wide; 4] {
        [x[0].store(), x[1].store(), x[2].store(), x[3].store()]
    }

    /// The solution in registers.
    #[inline(always)]
    pub(super) fn load(m: &Solution<Wide>) -> Solution<F64x8> {
        Solution {
            q: load4(&m.q),
            v: load3(&m.v),
            lat: F64x8::load(&m.lat),
            lon: F64x8::load(&m.lon),
            h: F64x8::load(&m.h),
            prev_dtheta: load3(&m.prev_dtheta),
            prev_dv: load3(&m.prev_dv),
            lat_trig: GridTrig::from_parts(load4(&m.lat_trig.into_parts())),
        }
    }

    /// The solution `r` and its up direction back to memory.
    #[inline(always)]
    pub(super) fn store(r: &Solution<F64x8>, m: &mut Solution<Wide>, up: &mut [Wide; 3]) {
        *up = store3(&up_in_body(&r.q));
        *m = Solution {
            q: store4(&r.q),
            v: store3(&r.v),
            lat: r.lat.store(),
            lon: r.lon.store(),
            h: r.h.store(),
            prev_dtheta: store3(&r.prev_dtheta),
            prev_dv: store3(&r.prev_dv),
            lat_trig: GridTrig::from_parts(store4(&r.lat_trig.into_parts())),
        };
    }
}

/// [`update`] on AVX-512 registers ([`crate::avx512_lanes`]): the same operations, one
/// instruction for all lanes.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn update_avx512(
    m: &mut Solution<Wide>,
    up: &mut [Wide; 3],
    dtheta: &[Wide; 3],
    dv: &[Wide; 3],
    dt_s: f64,
    vertical: VerticalChannel,
) {
    use on_avx512::*;
    let mut r = load(m);
    update(&mut r, &load3(dtheta), &load3(dv), dt_s, vertical);
    store(&r, m, up);
}

/// [`update_subsamples`] on AVX-512 registers.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn update_avx512_subsamples(
    m: &mut Solution<Wide>,
    up: &mut [Wide; 3],
    dtheta: &[[Wide; 3]],
    dv: &[[Wide; 3]],
    dt_s: f64,
    vertical: VerticalChannel,
) {
    use on_avx512::*;
    let mut r = load(m);
    let n = dtheta.len();
    let th: [[F64x8; 3]; MAX_PENDING + 1] = std::array::from_fn(|i| load3(&dtheta[i.min(n - 1)]));
    let dvs: [[F64x8; 3]; MAX_PENDING + 1] = std::array::from_fn(|i| load3(&dv[i.min(n - 1)]));
    update_subsamples(&mut r, &th[..n], &dvs[..n], dt_s, vertical);
    store(&r, m, up);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strapdown::tests::{bits, increments};
    use crate::subsamples::Subsamples;

    fn start(k: usize) -> NavState {
        NavState {
            q_bn: UnitQuaternion::from_euler_angles(0.01 * k as f64, -0.02, 1.1 + 0.3 * k as f64),
            v_n: Vector3::new(3.0 - k as f64, -4.0, 0.1),
            lat_rad: 0.64 - 0.1 * k as f64,
            lon_rad: 2.15,
            height_m: 15.0,
        }
    }

    /// Every lane equals a navigator run alone on its increments, bit for bit, with a full group
    /// and a partial one, in both vertical modes, updating every interval or every 2 to 4 (the
    /// group formed with an update under way, so the held intervals are gathered too); each
    /// lane's increments differ (a per-lane offset), so a mixed-up lane shows.
    #[test]
    fn each_lane_is_the_navigator_alone() {
        let inc = |step: u64, k: usize| {
            let (a, b) = increments(step + 13 * k as u64);
            (a * (1.0 + 0.01 * k as f64), b)
        };
        for vertical in [
            VerticalChannel::Hold { ref_height_m: 12.0 },
            VerticalChannel::Damped {
                ref_height_m: 12.0,
                tau_s: 100.0,
            },
        ] {
            for sub in 1..=Subsamples::MAX {
                for used in [LANES, 3, 2, 1] {
                    let mut alone: Vec<Strapdown> = (0..used)
                        .map(|k| {
                            Strapdown::new(start(k), 0.01, vertical)
                                .with_subsamples(Subsamples::new(sub).unwrap())
                        })
                        .collect();
                    for (k, n) in alone.iter_mut().enumerate() {
                        let (a, b) = inc(0, k);
                        n.update(&a, &b);
                    }
                    let mut lanes = StrapdownLanes::new(&alone).unwrap();
                    for step in 1..=5_000u64 {
                        let inc: Vec<_> = (0..used).map(|k| inc(step, k)).collect();
                        let (dth, dv): (Vec<_>, Vec<_>) = inc.iter().copied().unzip();
                        lanes.update(&dth, &dv);
                        for (n, (a, b)) in alone.iter_mut().zip(&inc) {
                            n.update(a, b);
                        }
                    }
                    for (k, n) in alone.iter().enumerate() {
                        let mut from_lane = n.clone();
                        from_lane.set_state(lanes.state(k));
                        let what =
                            format!("{vertical:?}, {sub} subsamples, {used} lanes, lane {k}");
                        assert_eq!(bits(&from_lane)[..10], bits(n)[..10], "{what}");
                        assert_eq!(
                            lanes.up_b(k),
                            n.state().q_bn.inverse_transform_vector(&Vector3::z()),
                            "{what}"
                        );
                    }
                    assert_eq!(lanes.steps(), 5_001);
                }
            }
        }
    }

    #[test]
    fn navigators_that_differ_are_refused() {
        let a = Strapdown::new(start(0), 0.01, VerticalChannel::Hold { ref_height_m: 0.0 });
        let b = Strapdown::new(start(1), 0.02, VerticalChannel::Hold { ref_height_m: 0.0 });
        assert_eq!(
            StrapdownLanes::new(&[a.clone(), b]).unwrap_err(),
            LanesError::Differs(1)
        );
        assert_eq!(StrapdownLanes::new(&[]).unwrap_err(), LanesError::Count(0));
        assert_eq!(
            StrapdownLanes::new(&vec![a; LANES + 1]).unwrap_err(),
            LanesError::Count(LANES + 1)
        );
    }
}
