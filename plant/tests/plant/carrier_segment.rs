//! The segment rule against the exact per-tick path (`Plant::set_carrier_segments(false)`):
//! increments and tick-end truth over sea states 1–6 with course and speed changes, the
//! 16-position scheme turning the table, and azimuth isolation (the table always turning); the
//! bound is the rule's own interpolation bound (docs/carrier.md "Increments on a moving base").

use crate::carrier_common::{ship_config, with_sea_state};
use rins_plant::carrier::segment::SEGMENT_EPS;
use rins_plant::{Plant, PlantConfig};

/// A ship with a course change at the 2°/s limit, a speed change and the 16-position scheme.
fn config(sea_state: u32) -> PlantConfig {
    let mut cfg = ship_config(&[(30.0, 12.0, 100.0), (140.0, 18.0, 200.0), (80.0, 9.0, 1e5)]);
    cfg.carrier.ship.turn_rate_dps = 2.0;
    cfg.scheme = rins_plant::table::SchemeSpec::default();
    if sea_state > 0 {
        cfg = with_sea_state(cfg, sea_state);
    }
    cfg
}

/// Largest differences between the segment rule and the exact path over `samples`.
#[derive(Debug, Default)]
struct Diff {
    m: u64,
    dtheta: f64,
    dv: f64,
    sum_dtheta: f64,
    sum_dv: f64,
    pos_m: f64,
    vel: f64,
    att: f64,
    rate: f64,
    amp_w: f64,
    amp_f: f64,
    amp_x: f64,
    ll_max: f64,
}

fn compare(cfg: &PlantConfig, samples: u64) -> Diff {
    let mut seg = Plant::new(cfg).unwrap();
    let mut exact = Plant::new(cfg).unwrap();
    let m = seg
        .set_carrier_segments(true)
        .unwrap()
        .expect("segments on");
    assert_eq!(exact.set_carrier_segments(false).unwrap(), None);
    let h = seg.dt_s();
    let mut d = Diff {
        m,
        ..Diff::default()
    };
    let (mut sum_s, mut sum_e) = (
        (nalgebra::Vector3::zeros(), nalgebra::Vector3::zeros()),
        (nalgebra::Vector3::zeros(), nalgebra::Vector3::zeros()),
    );
    let rm = 6.37e6;
    let h0 = exact.truth().carrier.height_m;
    for _ in 0..samples {
        seg.step();
        exact.step();
        let (ta, tb) = (seg.truth(), exact.truth());
        d.dtheta = d
            .dtheta
            .max((ta.dtheta_true_rad - tb.dtheta_true_rad).amax());
        d.dv = d.dv.max((ta.dv_true_mps - tb.dv_true_mps).amax());
        sum_s = (sum_s.0 + ta.dtheta_true_rad, sum_s.1 + ta.dv_true_mps);
        sum_e = (sum_e.0 + tb.dtheta_true_rad, sum_e.1 + tb.dv_true_mps);
        let (ca, cb) = (&ta.carrier, &tb.carrier);
        let dpos = ((ca.lat_rad - cb.lat_rad) * rm)
            .abs()
            .max(((ca.lon_rad - cb.lon_rad) * rm * cb.lat_rad.cos()).abs())
            .max((ca.height_m - cb.height_m).abs());
        d.pos_m = d.pos_m.max(dpos);
        d.vel = d.vel.max((ca.v_n - cb.v_n).amax());
        d.att = d.att.max(ca.q_cn.angle_to(&cb.q_cn));
        d.rate = d.rate.max((ca.omega_nc_c - cb.omega_nc_c).amax());
        // Amplitudes of what is interpolated: the carrier's rate, the specific force, the wave
        // displacement (height about the start).
        d.amp_w = d.amp_w.max(cb.omega_nc_c.amax());
        d.amp_f = d.amp_f.max(tb.dv_true_mps.amax() / h);
        d.amp_x = d.amp_x.max((cb.height_m - h0).abs());
        d.ll_max = d.ll_max.max(cb.lat_rad.abs()).max(cb.lon_rad.abs());
    }
    d.sum_dtheta = (sum_s.0 - sum_e.0).amax();
    d.sum_dv = (sum_s.1 - sum_e.1).amax();
    d
}

#[test]
fn segment_rule_matches_the_exact_path_over_sea_states_and_turns() {
    let h = 0.01;
    let mut lengths = vec![];
    for sea in 0..=6 {
        let cfg = config(sea);
        let d = compare(&cfg, 60_000);
        // The rule's interpolation bound ε at its own segment length, plus the reference's
        // own error: its two-point rule per tick errs by h⁵·max|y⁗|/4320, y⁗ ≤ (2ω_top)⁴·A
        // (products of two motions reach twice the top frequency).
        let sea_spec = &cfg.carrier.ship.sea;
        let w_top = if sea > 0 {
            sea_spec.band[1] * 2.0 * std::f64::consts::PI / sea_spec.hs_tp().1
        } else {
            0.0
        };
        let eps = SEGMENT_EPS + (2.0 * w_top * h).powi(4) / 4320.0;
        let (bound_th, bound_v) = (h * eps * d.amp_w + 1e-16, h * eps * d.amp_f + 1e-14);
        println!(
            "sea state {sea}: M = {}, per step |dtheta| {:.1e} rad (bound {bound_th:.1e}), |dv| {:.1e} m/s (bound {bound_v:.1e}); 10 min sums {:.1e} rad, {:.1e} m/s; truth: position {:.1e} m, velocity {:.1e} m/s, attitude {:.1e} rad, rate {:.1e} rad/s",
            d.m, d.dtheta, d.dv, d.sum_dtheta, d.sum_dv, d.pos_m, d.vel, d.att, d.rate
        );
        assert!(d.dtheta <= bound_th, "sea state {sea}: {d:?}");
        assert!(d.dv <= bound_v, "sea state {sea}: {d:?}");
        // Sums over whole segments are the n-point Gauss–Legendre rule: no drift beyond
        // rounding.
        assert!(
            d.sum_dtheta < 10.0 * bound_th + 1e-12 && d.sum_dv < 10.0 * bound_v + 1e-9,
            "sea state {sea}: {d:?}"
        );
        // Truth: the interpolant at the tick ends.
        assert!(d.att <= eps * 10.0 * d.amp_w.max(1e-3) + 1e-14, "{d:?}");
        assert!(d.rate <= eps * d.amp_w + 1e-15, "{d:?}");
        assert!(d.vel <= eps * d.amp_f + 1e-12, "{d:?}");
        // The exact path adds a ~1e-8 rad step to latitude and longitude every tick, each
        // addition rounding by up to half an ulp (systematically on a steady course); the
        // segment rule adds once per segment. So the reference's own rounding bounds this.
        let n = 60_000.0;
        let ulp_m = 0.5 * f64::EPSILON * d.ll_max * 6.4e6;
        assert!(
            d.pos_m <= n * ulp_m + 1e-9,
            "{d:?} (rounding bound {:.1e} m)",
            n * ulp_m
        );
        lengths.push(d.m);
    }
    // Shorter seas take shorter segments.
    assert!(lengths[1] < lengths[5], "{lengths:?}");
}

#[test]
fn segment_rule_with_the_table_always_turning() {
    // Azimuth isolation turns the outer gimbal every tick: the per-tick Gauss–Legendre points
    // of the interpolant.
    let mut cfg = config(5);
    cfg.carrier.azimuth_isolation = true;
    let d = compare(&cfg, 30_000);
    let h = 0.01;
    println!(
        "isolated, sea state 5: M = {}, |dtheta| {:.1e} rad, |dv| {:.1e} m/s",
        d.m, d.dtheta, d.dv
    );
    assert!(d.dtheta <= h * SEGMENT_EPS * d.amp_w + 1e-16, "{d:?}");
    assert!(d.dv <= h * SEGMENT_EPS * d.amp_f + 1e-14, "{d:?}");
}

#[test]
fn segment_state_restores_bit_identically_inside_exact_and_interpolated_segments() {
    for sea in [1, 5] {
        let cfg = config(sea);
        let mut probe = Plant::new(&cfg).unwrap();
        let m = probe.set_carrier_segments(true).unwrap().unwrap();
        // The course change starts at 100 s (tick 10 000): its segment runs the exact path.
        let corner = 10_000 / m * m;
        for at in [corner + 3, corner + m - 1, corner + m, 20_017, 4096 * 5 + 1] {
            let mut a = Plant::new(&cfg).unwrap();
            for _ in 0..at {
                a.step();
            }
            let mut b = Plant::from_serialized_state(&cfg, &a.serialize_state()).unwrap();
            for _ in 0..(3 * m) {
                let (x, y) = (a.step(), b.step());
                assert_eq!(x, y, "sea state {sea}, restored at {at}");
                assert_eq!(a.truth(), b.truth(), "sea state {sea}, restored at {at}");
            }
        }
    }
}
