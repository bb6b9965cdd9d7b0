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
use crate::strapdown::{NavState, Strapdown, VerticalChannel};

/// Navigators per [`StrapdownLanes`]: one AVX-512 vector of f64 (two AVX2 vectors).
pub const LANES: usize = 8;

type Wide = Lanes<LANES>;

/// Up to this many navigators a group updates them one by one: the vector update costs the same
/// for eight lanes as for one, about as much as two navigators alone.
const ALONE_UP_TO: usize = 2;

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
    /// Up to [`ALONE_UP_TO`] navigators: themselves, updated one by one (then `m` and `up`
    /// are not used).
    alone: Vec<Strapdown>,
    m: Solution<Wide>,
    /// Each navigator's body up direction at its current attitude (for the δβ compensation
    /// of the next increments), taken with the update.
    up: [Wide; 3],
    dt_s: f64,
    vertical: VerticalChannel,
    used: usize,
    steps: u64,
}

impl StrapdownLanes {
    /// The navigators `navs` (1 to [`LANES`], the same interval and vertical channel), from
    /// where each is now. Lanes past the last navigator repeat the first (their results are
    /// never read).
    pub fn new(navs: &[Strapdown]) -> Result<Self, LanesError> {
        if navs.is_empty() || navs.len() > LANES {
            return Err(LanesError::Count(navs.len()));
        }
        let first = &navs[0];
        if let Some(i) = navs
            .iter()
            .position(|n| n.dt_s() != first.dt_s() || n.vertical() != first.vertical())
        {
            return Err(LanesError::Differs(i));
        }
        let lane = |i: usize| navs.get(i).unwrap_or(first).solution();
        let each: [Solution<f64>; LANES] = std::array::from_fn(lane);
        let gather3 = |f: fn(&Solution<f64>) -> [f64; 3]| -> [Wide; 3] {
            std::array::from_fn(|c| Lanes(std::array::from_fn(|l| f(&each[l])[c])))
        };
        let gather = |f: fn(&Solution<f64>) -> f64| Lanes(std::array::from_fn(|l| f(&each[l])));
        let q: [Wide; 4] = std::array::from_fn(|c| Lanes(std::array::from_fn(|l| each[l].q[c])));
        Ok(Self {
            alone: if navs.len() <= ALONE_UP_TO {
                navs.to_vec()
            } else {
                Vec::new()
            },
            up: up_in_body(&q),
            m: Solution {
                q: std::array::from_fn(|c| Lanes(std::array::from_fn(|l| each[l].q[c]))),
                v: gather3(|s| s.v),
                lat: gather(|s| s.lat),
                lon: gather(|s| s.lon),
                h: gather(|s| s.h),
                prev_dtheta: gather3(|s| s.prev_dtheta),
                prev_dv: gather3(|s| s.prev_dv),
                // The sine and cosine depend on the latitude alone: no grid point to carry.
                lat_trig: GridTrig::default(),
            },
            dt_s: first.dt_s(),
            vertical: first.vertical(),
            used: navs.len(),
            steps: first.steps(),
        })
    }

    /// Navigators in use.
    pub fn len(&self) -> usize {
        self.used
    }

    /// Never true: a lane group holds at least one navigator.
    pub fn is_empty(&self) -> bool {
        self.used == 0
    }

    /// Consumes one interval's increments Δθ (rad) and Δv (m/s) per navigator, in lane order
    /// ([`Self::len`] of each).
    pub fn update(&mut self, dtheta: &[Vector3<f64>], dv: &[Vector3<f64>]) {
        assert!(
            dtheta.len() == self.used && dv.len() == self.used,
            "one increment per navigator"
        );
        if !self.alone.is_empty() {
            for (n, (a, v)) in self.alone.iter_mut().zip(dtheta.iter().zip(dv)) {
                n.update(a, v);
            }
            self.steps += 1;
            return;
        }
        let pick = |x: &[Vector3<f64>], c: usize| -> Wide {
            Lanes(std::array::from_fn(|l| x.get(l).unwrap_or(&x[0])[c]))
        };
        let dth: [Wide; 3] = std::array::from_fn(|c| pick(dtheta, c));
        let dvs: [Wide; 3] = std::array::from_fn(|c| pick(dv, c));
        update_wide(
            &mut self.m,
            &mut self.up,
            &dth,
            &dvs,
            self.dt_s,
            self.vertical,
        );
        self.steps += 1;
    }

    /// Navigator `lane`'s solution.
    pub fn state(&self, lane: usize) -> NavState {
        if let Some(n) = self.alone.get(lane) {
            return *n.state();
        }
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

    /// Navigator `lane`'s body up direction C_n^b·(0, 0, 1) (the bits of
    /// `q_bn.inverse_transform_vector(&Vector3::z())`), kept from its last update.
    #[inline]
    pub fn up_b(&self, lane: usize) -> Vector3<f64> {
        if let Some(n) = self.alone.get(lane) {
            return n.state().q_bn.inverse_transform_vector(&Vector3::z());
        }
        let u = &self.up;
        Vector3::new(u[0].0[lane], u[1].0[lane], u[2].0[lane])
    }

    /// Increments consumed so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }
}

#[inline(always)]
fn update_body(
    m: &mut Solution<Wide>,
    up: &mut [Wide; 3],
    dtheta: &[Wide; 3],
    dv: &[Wide; 3],
    dt_s: f64,
    vertical: VerticalChannel,
) {
    update(m, dtheta, dv, dt_s, vertical);
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
    use crate::avx512_lanes::F64x8;
    #[inline(always)]
    fn load3(x: &[Wide; 3]) -> [F64x8; 3] {
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
    let mut r = Solution {
        q: load4(&m.q),
        v: load3(&m.v),
        lat: F64x8::load(&m.lat),
        lon: F64x8::load(&m.lon),
        h: F64x8::load(&m.h),
        prev_dtheta: load3(&m.prev_dtheta),
        prev_dv: load3(&m.prev_dv),
        lat_trig: GridTrig::from_parts(load4(&m.lat_trig.into_parts())),
    };
    update(&mut r, &load3(dtheta), &load3(dv), dt_s, vertical);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strapdown::tests::{bits, increments};

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
    /// and a partial one, in both vertical modes; each lane's increments differ (a per-lane
    /// offset), so a mixed-up lane shows.
    #[test]
    fn each_lane_is_the_navigator_alone() {
        for vertical in [
            VerticalChannel::Hold { ref_height_m: 12.0 },
            VerticalChannel::Damped {
                ref_height_m: 12.0,
                tau_s: 100.0,
            },
        ] {
            for used in [LANES, 3, ALONE_UP_TO, 1] {
                let mut alone: Vec<Strapdown> = (0..used)
                    .map(|k| Strapdown::new(start(k), 0.01, vertical))
                    .collect();
                let mut lanes = StrapdownLanes::new(&alone).unwrap();
                for step in 1..=5_000u64 {
                    let inc: Vec<_> = (0..used)
                        .map(|k| {
                            let (a, b) = increments(step + 13 * k as u64);
                            (a * (1.0 + 0.01 * k as f64), b)
                        })
                        .collect();
                    let (dth, dv): (Vec<_>, Vec<_>) = inc.iter().copied().unzip();
                    lanes.update(&dth, &dv);
                    for (n, (a, b)) in alone.iter_mut().zip(&inc) {
                        n.update(a, b);
                    }
                }
                for (k, n) in alone.iter().enumerate() {
                    let mut from_lane = n.clone();
                    from_lane.set_state(lanes.state(k));
                    assert_eq!(
                        bits(&from_lane)[..10],
                        bits(n)[..10],
                        "{vertical:?}, {used} lanes, lane {k}"
                    );
                    assert_eq!(
                        lanes.up_b(k),
                        n.state().q_bn.inverse_transform_vector(&Vector3::z())
                    );
                }
                assert_eq!(lanes.steps(), 5_000);
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
