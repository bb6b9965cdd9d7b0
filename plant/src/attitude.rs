//! The attitude quaternion of a rotation matrix, in closed form.
//!
//! Every place that turns a direction-cosine matrix (C_c^n, a measured C_b^n) into a unit
//! quaternion goes through [`quaternion_of`]. The true IMU attitude q_b^n is not converted from
//! its matrix: it is composed from the carrier's attitude and the gimbal angles
//! ([`crate::true_attitude`]). A small rotation vector's quaternion goes through
//! [`quat_from_rotvec`], shared by the navigator and the azimuth isolation loop.

use nalgebra::{Matrix3, Quaternion, Rotation3, UnitQuaternion, Vector3};

/// The unit quaternion of the rotation matrix `c` (orthonormal to rounding), in closed form
/// (Shepperd's method: the root is taken of 1 + trace when the trace is positive, else of the
/// largest diagonal term, so half turns, where w = 0, are as exact as any other attitude).
/// The sign is whichever the branch gives (q and −q are the same attitude). Unlike
/// `UnitQuaternion::from_matrix`, which iterates from the identity, it does not stall at 180°
/// and costs a few nanoseconds.
pub fn quaternion_of(c: &Matrix3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*c))
}

/// The quaternion of the rotation vector `v` by its series, exact to O(|v|⁶): cos(|v|/2) and
/// sin(|v|/2)/|v| to their |v|⁴ terms (the next are below 1e-17 relative for |v| ≤ 1e-2 rad,
/// a strapdown step's rotation); a larger rotation takes the closed form
/// (`UnitQuaternion::from_scaled_axis`, a sine and a cosine).
#[inline]
pub fn quat_from_rotvec(v: &Vector3<f64>) -> UnitQuaternion<f64> {
    let n2 = v.norm_squared();
    if n2 > 1e-4 {
        return UnitQuaternion::from_scaled_axis(*v);
    }
    let c = 1.0 - n2 / 8.0 + n2 * n2 / 384.0;
    let s = 0.5 - n2 / 48.0 + n2 * n2 / 3840.0;
    UnitQuaternion::new_unchecked(Quaternion::new(c, s * v.x, s * v.y, s * v.z))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::{GimbalAngles, body_to_nav};
    use nalgebra::{Quaternion, Rotation3, Unit, Vector3};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::f64::consts::PI;

    /// Largest element of q's matrix minus `c`, and |‖q‖ − 1|.
    fn misfit(c: &Matrix3<f64>) -> (f64, f64) {
        let q = quaternion_of(c);
        let d = (q.to_rotation_matrix().into_inner() - c).amax();
        (d, (q.as_ref().norm() - 1.0).abs())
    }

    fn assert_reproduces(c: &Matrix3<f64>, what: &str) {
        let (d, n) = misfit(c);
        assert!(d < 1e-12, "{what}: matrix misfit {d:e}");
        assert!(n < 1e-14, "{what}: norm off by {n:e}");
    }

    fn axis_angle(axis: Vector3<f64>, angle_rad: f64) -> Matrix3<f64> {
        Rotation3::from_axis_angle(&Unit::new_normalize(axis), angle_rad).into_inner()
    }

    /// The 16-position scheme's position C (outer π, inner π) is a half turn about y:
    /// q = (0, 0, ±1, 0), which the iterative conversion from the identity misses.
    #[test]
    fn position_c_is_a_half_turn_about_y() {
        let c = body_to_nav(&Matrix3::identity(), GimbalAngles::new(PI, PI));
        assert_reproduces(&c, "position C");
        let q = quaternion_of(&c);
        assert!(
            q.w.abs() < 1e-15 && q.i.abs() < 1e-15 && q.k.abs() < 1e-15,
            "{q:?}"
        );
        assert!((q.j.abs() - 1.0).abs() < 1e-15, "{q:?}");
    }

    /// Half turns about each axis and an oblique one, and turns within 1e-9 rad of a half turn
    /// about each axis (either side), reproduce their matrix.
    #[test]
    fn half_turns_and_their_neighbours_reproduce_the_matrix() {
        let axes = [
            Vector3::x(),
            Vector3::y(),
            Vector3::z(),
            Vector3::new(1.0, 2.0, 3.0),
            Vector3::new(-1.0, 1.0, 1e-3),
        ];
        for a in axes {
            for d in [0.0, 1e-9, -1e-9, 1e-12] {
                assert_reproduces(&axis_angle(a, PI + d), &format!("axis {a:?}, π + {d:e}"));
            }
        }
        // Every gimbal position of the schemes: outer and inner at multiples of π/2.
        for o in 0..4 {
            for i in 0..4 {
                let g = GimbalAngles::new(o as f64 * PI / 2.0, i as f64 * PI / 2.0);
                let c = body_to_nav(&Matrix3::identity(), g);
                assert_reproduces(&c, &format!("gimbal {o}·π/2, {i}·π/2"));
            }
        }
    }

    /// Random rotations (seeded draws from the cube, normalised) reproduce their
    /// matrix, and the quaternion equals the one drawn up to sign.
    #[test]
    fn random_rotations_reproduce_the_matrix() {
        let mut rng = ChaCha8Rng::seed_from_u64(0x9a7);
        for k in 0..1000 {
            let v: [f64; 4] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
            let q0 = UnitQuaternion::from_quaternion(Quaternion::new(v[0], v[1], v[2], v[3]));
            let c = q0.to_rotation_matrix().into_inner();
            assert_reproduces(&c, &format!("draw {k}"));
            let q = quaternion_of(&c);
            let same = (q.coords - q0.coords)
                .amax()
                .min((q.coords + q0.coords).amax());
            assert!(same < 1e-14, "draw {k}: {q:?} vs {q0:?}");
        }
    }
}
