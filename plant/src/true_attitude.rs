//! The true IMU attitude q_b^n in closed form: the carrier's attitude, the table's mount and the
//! two gimbal turns composed as quaternions,
//!
//! q_b^n = q_c^n · q_v^c · q_z(outer) · q_x(inner),
//!
//! the quaternion form of [`crate::table::body_to_nav`]'s C_b^n = C_c^n·C_v^c·R_z(outer)·R_x(inner)
//! (docs/carrier.md, Frames). Each gimbal turn's quaternion is its half angle's cosine and sine,
//! so the truth is exact to a few roundings at every attitude, half turns included, and no
//! matrix is turned back into a quaternion on the way.
//!
//! Every sink of the truth goes through [`TruthMount::q_bn`]: the CSV's `q_bn` columns, the
//! Python arrays, the FMU's `truth.q_bn`, the wire's `TruthRecord` and `StartRecord` (the last
//! two and the FMU through [`crate::Plant::attitude_q_bn`]), so they carry the same bits.

use nalgebra::{Quaternion, UnitQuaternion};

use crate::config::VehicleSpec;
use crate::output::Truth;
use crate::table::GimbalAngles;

/// The turn by `angle_rad` about x, (cos ½a, sin ½a, 0, 0).
#[inline]
pub fn q_x(angle_rad: f64) -> UnitQuaternion<f64> {
    let (s, c) = (0.5 * angle_rad).sin_cos();
    UnitQuaternion::new_unchecked(Quaternion::new(c, s, 0.0, 0.0))
}

/// The turn by `angle_rad` about y, (cos ½a, 0, sin ½a, 0).
#[inline]
pub fn q_y(angle_rad: f64) -> UnitQuaternion<f64> {
    let (s, c) = (0.5 * angle_rad).sin_cos();
    UnitQuaternion::new_unchecked(Quaternion::new(c, 0.0, s, 0.0))
}

/// The turn by `angle_rad` about z, (cos ½a, 0, 0, sin ½a).
#[inline]
pub fn q_z(angle_rad: f64) -> UnitQuaternion<f64> {
    let (s, c) = (0.5 * angle_rad).sin_cos();
    UnitQuaternion::new_unchecked(Quaternion::new(c, 0.0, 0.0, s))
}

/// The gimbals' part of the attitude, q_v^b's inverse q_b^v = q_z(outer)·q_x(inner), written
/// out: (cos ½o·cos ½i, cos ½o·sin ½i, sin ½o·sin ½i, sin ½o·cos ½i), one rounding per
/// component. Its sign follows the half angles, so it turns continuously with the gimbals.
#[inline]
pub fn gimbal_quaternion(g: GimbalAngles) -> UnitQuaternion<f64> {
    let (so, co) = (0.5 * g.outer_rad).sin_cos();
    let (si, ci) = (0.5 * g.inner_rad).sin_cos();
    UnitQuaternion::new_unchecked(Quaternion::new(co * ci, co * si, so * si, so * ci))
}

/// The mount `vehicle` as the quaternion q_v^n (or q_v^c on a moving carrier) in closed form:
/// q_z(azimuth)·q_x(pitch)·q_y(roll), the turns of [`VehicleSpec::c_vn`].
pub fn mount_quaternion(vehicle: &VehicleSpec) -> UnitQuaternion<f64> {
    use crate::units::DEG;
    q_z(vehicle.azimuth_deg * DEG) * q_x(vehicle.pitch_deg * DEG) * q_y(vehicle.roll_deg * DEG)
}

/// The table's mount between the truth's carrier attitude and the gimbals, q_v^c: the
/// identity on the static carrier, whose truth attitude q_c^n already is the `[vehicle]`
/// attitude (the site's carrier is the vehicle), and the `[vehicle]` mount on a moving one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TruthMount {
    /// q_v^c; `None`: the identity (no product, as for the default mount).
    q_vc: Option<UnitQuaternion<f64>>,
}

impl TruthMount {
    /// The mount of `vehicle` on a moving carrier (`moving_carrier`), else the identity.
    pub fn new(moving_carrier: bool, vehicle: &VehicleSpec) -> Self {
        let level = *vehicle == VehicleSpec::default();
        Self {
            q_vc: (moving_carrier && !level).then(|| mount_quaternion(vehicle)),
        }
    }

    /// The mount of the plant `cfg` describes (moving unless its carrier is static). A plant
    /// given an external carrier after building knows better: [`crate::Plant::truth_mount`].
    pub fn of_config(cfg: &crate::PlantConfig) -> Self {
        Self::new(!cfg.carrier.is_static(), &cfg.vehicle)
    }

    /// q_v^c.
    pub fn q_vc(&self) -> UnitQuaternion<f64> {
        self.q_vc.unwrap_or_else(UnitQuaternion::identity)
    }

    /// The true IMU attitude q_b^n = q_c^n·q_v^c·q_z(outer)·q_x(inner) with the carrier's
    /// attitude `q_cn` and the true gimbal angles `g`.
    #[inline]
    pub fn q_bn(&self, q_cn: &UnitQuaternion<f64>, g: GimbalAngles) -> UnitQuaternion<f64> {
        let q_vn = match &self.q_vc {
            Some(m) => q_cn * m,
            None => *q_cn,
        };
        q_vn * gimbal_quaternion(g)
    }

    /// [`TruthMount::q_bn`] of the truth record `tr` (its carrier and gimbal angles).
    #[inline]
    pub fn q_bn_of(&self, tr: &Truth) -> UnitQuaternion<f64> {
        self.q_bn(&tr.carrier.q_cn, tr.gimbal.angles)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::attitude::quaternion_of;
    use crate::table::body_to_nav;
    use nalgebra::Matrix3;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::f64::consts::{FRAC_PI_2, PI};

    /// Largest element of q's matrix minus `c`.
    fn matrix_misfit(q: &UnitQuaternion<f64>, c: &Matrix3<f64>) -> f64 {
        (q.to_rotation_matrix().into_inner() - c).amax()
    }

    /// Largest component of q − p.
    fn quaternion_misfit(q: &UnitQuaternion<f64>, p: &UnitQuaternion<f64>) -> f64 {
        (q.coords - p.coords).amax()
    }

    /// The composition written with nalgebra's product, independently of the written-out one.
    fn composed(
        q_cn: &UnitQuaternion<f64>,
        q_vc: &UnitQuaternion<f64>,
        g: GimbalAngles,
    ) -> UnitQuaternion<f64> {
        q_cn * q_vc * q_z(g.outer_rad) * q_x(g.inner_rad)
    }

    /// Checks q_b^n against the composition and C_b^n at `g`, carrier `c_cn` and `mount`, to
    /// 1e-15 (a few roundings of numbers below 1).
    fn check(
        mount: &TruthMount,
        c_cn: &Matrix3<f64>,
        c_vc: &Matrix3<f64>,
        g: GimbalAngles,
        what: &str,
    ) {
        let q_cn = quaternion_of(c_cn);
        let q = mount.q_bn(&q_cn, g);
        let want = composed(&q_cn, &mount.q_vc(), g);
        let dq = quaternion_misfit(&q, &want);
        assert!(dq < 1e-15, "{what}: {q:?} vs composition {want:?} ({dq:e})");
        let c_bn = body_to_nav(&(c_cn * c_vc), g);
        let dc = matrix_misfit(&q, &c_bn);
        assert!(dc < 1e-15, "{what}: C_b^n misfit {dc:e}");
        assert!(
            (q.as_ref().norm() - 1.0).abs() < 1e-15,
            "{what}: norm {}",
            q.as_ref().norm()
        );
    }

    /// The 16 positions of the schemes (outer and inner at multiples of π/2, docs/schemes.md),
    /// and a few turns beyond, on the static site (level and tilted vehicle).
    #[test]
    fn the_sixteen_positions_are_exact_on_the_static_carrier() {
        let tilted = VehicleSpec {
            azimuth_deg: 30.0,
            pitch_deg: -2.0,
            roll_deg: 1.5,
        };
        for v in [VehicleSpec::default(), tilted] {
            let mount = TruthMount::new(false, &v);
            assert_eq!(mount.q_vc(), UnitQuaternion::identity());
            for o in -4..8 {
                for i in -4..8 {
                    let g = GimbalAngles::new(o as f64 * FRAC_PI_2, i as f64 * FRAC_PI_2);
                    let what = format!("{v:?}, outer {o}·π/2, inner {i}·π/2");
                    check(&mount, &v.c_vn(), &Matrix3::identity(), g, &what);
                }
            }
        }
        // Position C (outer π, inner π) on a level vehicle is the half turn about y.
        let q = TruthMount::new(false, &VehicleSpec::default())
            .q_bn(&UnitQuaternion::identity(), GimbalAngles::new(PI, PI));
        assert!(
            q.w.abs() < 1e-15 && q.i.abs() < 1e-15 && q.k.abs() < 1e-15,
            "{q:?}"
        );
        assert!((q.j - 1.0).abs() < 1e-15, "{q:?}");
    }

    /// During moves (random angles, both gimbals anywhere in ±3 turns) on a moving carrier
    /// (random attitudes) with a level and a tilted mount, and at the 16 positions there.
    #[test]
    fn moves_on_a_moving_carrier_are_exact() {
        let mut rng = ChaCha8Rng::seed_from_u64(0x44);
        let mounts = [
            VehicleSpec::default(),
            VehicleSpec {
                azimuth_deg: -120.0,
                pitch_deg: 3.0,
                roll_deg: -0.7,
            },
        ];
        for v in mounts {
            let mount = TruthMount::new(true, &v);
            let dm = matrix_misfit(&mount.q_vc(), &v.c_vn());
            assert!(dm < 1e-15, "{v:?}: mount misfit {dm:e}");
            for k in 0..2000 {
                let e: [f64; 3] = std::array::from_fn(|_| rng.random_range(-PI..PI));
                let c_cn = UnitQuaternion::from_euler_angles(e[0], e[1] / 2.0, e[2])
                    .to_rotation_matrix()
                    .into_inner();
                let g = if k < 16 {
                    GimbalAngles::new((k / 4) as f64 * FRAC_PI_2, (k % 4) as f64 * FRAC_PI_2)
                } else {
                    let t = 6.0 * PI;
                    GimbalAngles::new(rng.random_range(-t..t), rng.random_range(-t..t))
                };
                check(
                    &mount,
                    &c_cn,
                    &v.c_vn(),
                    g,
                    &format!("{v:?}, draw {k}, {g:?}"),
                );
            }
        }
    }

    /// The gimbals' quaternion turns continuously: a full outer turn negates it (q and −q are
    /// one attitude), and no sign flips between neighbouring angles.
    #[test]
    fn the_gimbal_quaternion_is_continuous_in_the_angles() {
        let mut last = gimbal_quaternion(GimbalAngles::new(0.0, 0.3));
        for k in 1..=4000 {
            let g = GimbalAngles::new(k as f64 * 1e-3 * PI, 0.3 + k as f64 * 1e-3);
            let q = gimbal_quaternion(g);
            assert!(quaternion_misfit(&q, &last) < 1e-2, "step {k}");
            last = q;
        }
        let a = gimbal_quaternion(GimbalAngles::new(0.4, 0.3));
        let b = gimbal_quaternion(GimbalAngles::new(0.4 + 2.0 * PI, 0.3));
        assert!((a.coords + b.coords).amax() < 1e-15);
    }
}
