//! Tests of the segment rule's weights: tick means, their batch, the quadrature points from
//! them, constants, the error bound and the choice of the rule.

use super::*;

/// The point channels of node values.
fn points_of(y: &[[f64; CHANNELS]]) -> Vec<[f64; POINT_CHANNELS]> {
    y.iter().map(|r| std::array::from_fn(|c| r[c])).collect()
}

#[test]
fn tick_means_sum_to_the_gauss_legendre_rule_and_reproduce_polynomials() {
    // An even and an odd node count (the odd one's middle node pairs with itself in the mirrored
    // combine).
    for n in [SEGMENT_NODES, 21] {
        means_of_polynomials(n);
    }
}

fn means_of_polynomials(n: usize) {
    let rule = SegmentRule::new(n, 64);
    // y(t) = t^(2n−1) on [0, 64] ticks: its per-tick integrals are exact (the interpolant of
    // a degree-(n−1) polynomial is itself) only below degree n; their sum is the n-point
    // rule, exact to degree 2n − 1. Ticks on either side of the middle come from the two signs
    // of the mirrored combine.
    for deg in [n - 1, 2 * n - 1] {
        let f = |t: f64| (t / 64.0).powi(deg as i32);
        let y: Vec<[f64; CHANNELS]> = rule
            .node_ticks
            .iter()
            .map(|&t| {
                let mut c = [0.0; CHANNELS];
                c[0] = f(t);
                c
            })
            .collect();
        let total: f64 = (0..64).map(|k| rule.tick_mean(k, &y)[0]).sum();
        let exact = 64.0 / (deg as f64 + 1.0);
        assert!(
            (total - exact).abs() < 1e-12,
            "degree {deg}: {total} vs {exact}"
        );
        if deg == n - 1 {
            for k in [0usize, 17, 31, 32, 46, 63] {
                let e = 64.0 * ((k as f64 + 1.0) / 64.0).powi(n as i32)
                    - 64.0 * (k as f64 / 64.0).powi(n as i32);
                let m = rule.tick_mean(k, &y)[0] * n as f64;
                assert!((m - e).abs() < 1e-12, "tick {k}: {m} vs {e}");
            }
        }
    }
}

#[test]
fn all_tick_means_at_once_are_the_per_tick_means_bit_for_bit() {
    for n in [SEGMENT_NODES, 21] {
        let rule = SegmentRule::new(n, 64);
        let y: Vec<[f64; CHANNELS]> = (0..n)
            .map(|j| std::array::from_fn(|c| ((j * 7 + c * 3) as f64 * 0.37).sin() * 1e3))
            .collect();
        let mut all = TickMeans::default();
        rule.tick_means_all(&points_of(&y), &mut all);
        for k in 0..64 {
            let one = rule.tick_mean(k, &y);
            for (c, (a, b)) in all.row(k).iter().zip(&one).enumerate() {
                assert_eq!(a.to_bits(), b.to_bits(), "{n} nodes, tick {k} channel {c}");
            }
        }
    }
}

#[test]
fn quadrature_points_from_the_means_err_by_the_cubic_term_they_leave_out() {
    // A 2 rad/s sinusoid of unit amplitude on a 128-tick segment at 100 Hz: the points from
    // the means against the interpolant's own points (which are exact to 1e-10).
    let (h, m, w) = (0.01, 128u64, 2.0);
    let rule = SegmentRule::new(SEGMENT_NODES, m);
    let y: Vec<[f64; CHANNELS]> = rule
        .node_ticks
        .iter()
        .map(|&t| std::array::from_fn(|c| (w * t * h + 0.4 * c as f64).sin()))
        .collect();
    let mut means = TickMeans::default();
    rule.tick_means_all(&points_of(&y), &mut means);
    let (mut odd, mut even) = (0.0f64, 0.0f64);
    for k in 0..m as usize {
        let p = rule.points_from_means(&means, k);
        let exact = [0, 1].map(|i| rule.tick_point(k, i, &y));
        for c in 0..POINT_CHANNELS {
            let (e0, e1) = (p[0][c] - exact[0][c], p[1][c] - exact[1][c]);
            odd = odd.max((0.5 * (e0 - e1)).abs());
            even = even.max((0.5 * (e0 + e1)).abs());
        }
    }
    // |w‴| = w³: the odd part is the cubic term w‴τ³/6 at τ = h/(2√3) (the slope itself is
    // exact to O(h⁵)); the even part is fourth order, w⁗h⁴·(1/1920 − 1/3456).
    let cubic = w.powi(3) * (h / (2.0 * 3f64.sqrt())).powi(3) / 6.0;
    assert!(
        odd <= 1.05 * cubic && odd > 0.95 * cubic,
        "odd {odd:e} vs {cubic:e}"
    );
    let quartic = w.powi(4) * h.powi(4) * (1.0 / 1920.0 - 1.0 / 3456.0);
    assert!(even <= 1.1 * quartic, "even {even:e} vs {quartic:e}");
}

#[test]
fn constants_are_reproduced_bit_for_bit() {
    for m in [16, 64, 256] {
        let rule = SegmentRule::new(SEGMENT_NODES, m);
        let y = vec![[1.0; CHANNELS]; SEGMENT_NODES];
        for k in 0..m as usize {
            assert_eq!(rule.tick_mean(k, &y), [1.0; POINT_CHANNELS]);
            assert_eq!(rule.tick_point(k, 1, &y), [1.0; POINT_CHANNELS]);
            assert_eq!(rule.state_at(k + 1, &y), [1.0; CHANNELS - POINT_CHANNELS]);
        }
    }
}

#[test]
fn error_bound_is_the_closed_form_and_holds_for_a_sinusoid() {
    // κ₂ = 2²·(2!)²/4! = 2/3: bound (x/2)²·(2/3)/2.
    let x = 0.7f64;
    assert!((SegmentRule::error_bound(2, x) - (x / 2.0).powi(2) / 3.0).abs() < 1e-15);
    // sin(ωt) on a 256-tick segment at 100 Hz, ω = 3 rad/s: the interpolant's largest
    // error over the tick boundaries stays below the bound.
    let (h, m) = (0.01, 256u64);
    let rule = SegmentRule::new(SEGMENT_NODES, m);
    let w = 3.0;
    let y: Vec<[f64; CHANNELS]> = rule
        .node_ticks
        .iter()
        .map(|&t| {
            let mut c = [0.0; CHANNELS];
            c[POINT_CHANNELS] = (w * t * h + 0.3).sin();
            c
        })
        .collect();
    let worst = (0..=m as usize)
        .map(|i| (rule.state_at(i, &y)[0] - (w * i as f64 * h + 0.3).sin()).abs())
        .fold(0.0, f64::max);
    let bound = SegmentRule::error_bound(SEGMENT_NODES, w * m as f64 * h);
    assert!(
        worst <= bound && worst > 1e-3 * bound,
        "{worst:e} vs {bound:e}"
    );
}

#[test]
fn the_chosen_rule_meets_the_bound_with_the_fewest_nodes_for_its_length() {
    let h = 0.01;
    // Top frequencies of sea states 1 and 5 and of a calm track whose shortest change takes 60 s.
    for top in [7.366, 1.8986, 2.0 * std::f64::consts::PI / 60.0] {
        let (n, m) = SegmentRule::choose(top, h).expect("a rule qualifies");
        let wt = |m: u64| 2.0 * top * m as f64 * h;
        assert!(
            SegmentRule::error_bound(n, wt(m)) <= SEGMENT_EPS,
            "{top}: ({n}, {m})"
        );
        assert!(
            n == SEGMENT_MIN_NODES || SegmentRule::error_bound(n - 1, wt(m)) > SEGMENT_EPS,
            "{top}: {n} nodes on {m} ticks, {} would do",
            n - 1
        );
        // No cheaper rule qualifies: every (n', M') is either outside the bound or costs more.
        let cost = SegmentRule::cost_per_tick;
        for n2 in SEGMENT_MIN_NODES..=SEGMENT_MAX_NODES {
            let mut m2 = SEGMENT_MIN_TICKS;
            while m2 <= SEGMENT_MAX_TICKS {
                if SegmentRule::error_bound(n2, wt(m2)) <= SEGMENT_EPS {
                    assert!(
                        cost(n2, m2) >= cost(n, m),
                        "{top}: ({n2}, {m2}) beats ({n}, {m})"
                    );
                }
                m2 *= 2;
            }
        }
    }
    // Sea state 5 at 100 Hz: 21 nodes on 256 ticks (16 would need 128-tick segments).
    assert_eq!(SegmentRule::choose(1.8986, h), Some((21, 256)));
    // Motion too fast for any segment of 16 ticks or more: the exact path.
    assert_eq!(SegmentRule::choose(400.0, h), None);
}

/// The position and velocity channels alone are those channels of the whole state, bit for
/// bit, at every tick boundary (the isolation loop reads them every sample).
#[test]
fn position_and_velocity_alone_equal_those_channels_of_the_state() {
    let rule = SegmentRule::new(SEGMENT_NODES, 64);
    // Node values that differ per node and channel, of mixed magnitude and sign.
    let y: Vec<[f64; CHANNELS]> = (0..SEGMENT_NODES)
        .map(|j| {
            std::array::from_fn(|c| {
                ((j * 31 + c * 7) as f64 * 0.37).sin() * 10f64.powi(c as i32 % 7 - 3)
            })
        })
        .collect();
    for i in 0..=64 {
        let whole = rule.state_at(i, &y);
        let part = rule.position_velocity_at(i, &y);
        for c in 0..6 {
            assert_eq!(
                part[c].to_bits(),
                whole[c].to_bits(),
                "boundary {i}, channel {c}"
            );
        }
    }
}
