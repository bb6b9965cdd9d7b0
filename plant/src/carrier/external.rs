//! An externally driven carrier: a vessel model outside the plant (an FMU connected to the IMU
//! FMU's carrier inputs) supplies `CarrierSample`s at the ends of each communication step,
//! and the plant moves between two of them exactly as between two rows of a trajectory file
//! (`carrier::trajectory`): cubic Hermite position from the two positions and velocities,
//! constant-rate attitude between the two attitudes. The segment is a two-row `Trajectory`
//! swapped into the plant's carrier before the step, so no new carrier kind is needed.
//!
//! Two identical samples (bit for bit) hold the carrier at rest at that sample for the step: a
//! master that passes outputs from the start of a step (Jacobi) gives the IMU its first sample
//! twice, and a cubic through one position with a non-zero velocity would invent accelerations
//! of 6·v/h.

use std::fmt::Write;

use crate::carrier::{Carrier, Trajectory};

/// Sample columns in the order [`CarrierSample::row`] writes them (a trajectory file's).
const HEADER: &str =
    "t_s,lat_deg,lon_deg,height_m,v_e_mps,v_n_mps,v_u_mps,q_cn_w,q_cn_x,q_cn_y,q_cn_z";

/// The carrier at one instant as a vessel model gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CarrierSample {
    /// Geodetic latitude of the reference point, degrees, in [-89, 89].
    pub lat_deg: f64,
    /// Longitude, degrees, any finite value: the step from the previous sample is taken the
    /// shortest way (179.99 → −179.99 crosses the antimeridian; −360 is 0).
    pub lon_deg: f64,
    /// Ellipsoidal height, m.
    pub height_m: f64,
    /// Ground velocity east, north, up, m/s.
    pub v_enu_mps: [f64; 3],
    /// Attitude q_c^n (w, x, y, z), norm 1 within 1e-6: carrier axes (x starboard, y bow, z
    /// up) to east-north-up.
    pub q_cn: [f64; 4],
}

impl CarrierSample {
    /// A trajectory row at time `t_s` (`{:?}` prints the shortest text that parses back to the
    /// same bits, so the row carries the sample exactly).
    fn row(&self, t_s: f64, out: &mut String) {
        let _ = write!(
            out,
            "\n{t_s:?},{:?},{:?},{:?}",
            self.lat_deg, self.lon_deg, self.height_m
        );
        for x in self.v_enu_mps.iter().chain(&self.q_cn) {
            let _ = write!(out, ",{x:?}");
        }
    }

    /// At rest: the same position and attitude with no velocity.
    fn at_rest(&self) -> Self {
        Self {
            v_enu_mps: [0.0; 3],
            ..*self
        }
    }
}

/// The carrier moving from `start` (plant-relative time 0) to `end` over `ticks` ticks of
/// `tick_s`, or held at rest at `start` when the two are identical. A sample outside the
/// trajectory rules (latitude beyond ±89°, a quaternion off norm 1, non-finite values, a
/// position jump the velocities do not explain) is refused with the column and the reason.
pub fn segment(
    start: &CarrierSample,
    end: &CarrierSample,
    ticks: u64,
    tick_s: f64,
) -> Result<Carrier, String> {
    let (a, b) = if start == end {
        (start.at_rest(), start.at_rest())
    } else {
        (*start, *end)
    };
    let span_s = ticks.max(1) as f64 * tick_s;
    let mut text = String::from(HEADER);
    a.row(0.0, &mut text);
    b.row(span_s, &mut text);
    let data = Trajectory::parse(&text, "carrier inputs").map_err(|e| {
        let which = if e.row <= 1 { "step start" } else { "step end" };
        format!(
            "carrier inputs at the {which} refused ({}): {}",
            e.column, e.message
        )
    })?;
    Ok(Carrier::from_trajectory(data, tick_s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::earth::radii_of_curvature;

    fn sample(lat_deg: f64, v_n: f64) -> CarrierSample {
        CarrierSample {
            lat_deg,
            lon_deg: 123.6,
            height_m: 0.0,
            v_enu_mps: [0.0, v_n, 0.0],
            q_cn: [1.0, 0.0, 0.0, 0.0],
        }
    }

    /// Due north at a constant 6 m/s: the segment's mid-step state is half the way with the
    /// same velocity and no acceleration (the cubic through two positions and equal
    /// velocities consistent with them is the straight line).
    #[test]
    fn a_constant_velocity_segment_is_the_straight_line() {
        let (rm, _) = radii_of_curvature(36.0f64.to_radians());
        let dlat_deg = (6.0 * 0.01 / rm).to_degrees();
        let mut c = segment(&sample(36.0, 6.0), &sample(36.0 + dlat_deg, 6.0), 2, 0.005).unwrap();
        let mut nodes = [c.state_now(); 2];
        let mid = c.advance(&mut nodes);
        let got = mid.lat_rad.to_degrees() - 36.0;
        assert!(
            (got - dlat_deg / 2.0).abs() < 1e-12,
            "{got} vs {}",
            dlat_deg / 2.0
        );
        // Latitudes in degrees resolve 1.2e-16 rad (0.8 nm) near 36°: over 10 ms that is
        // 8e-8 m/s of velocity the positions can express (the step's ∫a is Δv regardless).
        assert!((mid.v_n.y - 6.0).abs() < 2e-7, "{mid:?}");
        assert!(mid.a_n.norm() < 1e-4, "{mid:?}");
    }

    /// Two identical samples hold the carrier at rest there; a quaternion off norm 1 is
    /// refused naming the column.
    #[test]
    fn identical_samples_hold_at_rest_and_bad_ones_are_refused() {
        let s = sample(36.0, 6.0);
        let mut c = segment(&s, &s, 1, 0.01).unwrap();
        let mut nodes = [c.state_now(); 2];
        let end = c.advance(&mut nodes);
        assert_eq!(end.v_n.norm(), 0.0);
        assert_eq!(nodes[0].a_n.norm(), 0.0);
        assert!((end.lat_rad.to_degrees() - 36.0).abs() < 1e-12);
        let mut bad = s;
        bad.q_cn[0] = 0.9;
        let e = segment(&s, &bad, 1, 0.01).unwrap_err();
        assert!(e.contains("step end") && e.contains("q_cn_w"), "{e}");
    }
}
