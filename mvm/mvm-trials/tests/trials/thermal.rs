//! The closed-form temperatures against a fine RK4 integration of the same network.

use rins_mvm_trials::thermal::RunThermal;
use rins_mvm_trials::{ChamberLeg, UnitThermal};

/// State: housing, blocks x/y/z, accelerometer node, lags of blocks x/y/z.
type State = [f64; 8];

/// The piece of a profile given as (start time, start temperature, slope K/s) that holds t.
fn piece_at(pieces: &[(f64, f64, f64)], t: f64) -> (f64, f64, f64) {
    *pieces.iter().rev().find(|p| t >= p.0).expect("t ≥ 0")
}

fn derivative(u: &UnitThermal, tau_l: f64, c: f64, x: &State) -> State {
    let mut d = [0.0; 8];
    d[0] = (c - x[0]) / u.tau_housing_s;
    for i in 0..3 {
        d[1 + i] = (x[0] + u.block_offset_k[i] - x[1 + i]) / u.tau_block_s[i];
        d[5 + i] = (x[1 + i] - x[5 + i]) / tau_l;
    }
    d[4] = (x[0] + u.accel_offset_k - x[4]) / u.tau_accel_s;
    d
}

/// RK4 with step `h` (the profile's corners fall on steps), compared every 10 s.
fn check(
    unit: UnitThermal,
    tau_l: f64,
    legs: &[ChamberLeg],
    pieces: &[(f64, f64, f64)],
    end_s: f64,
) -> f64 {
    let th = RunThermal::new(legs, &unit, &[tau_l]);
    let c0 = pieces[0].1;
    let mut x: State = [0.0; 8];
    x[0] = c0;
    for i in 0..3 {
        x[1 + i] = c0 + unit.block_offset_k[i];
        x[5 + i] = x[1 + i];
    }
    x[4] = c0 + unit.accel_offset_k;
    let h = 0.1;
    let n = (end_s / h).round() as usize;
    let add = |x: &State, k: &State, f: f64| -> State { std::array::from_fn(|j| x[j] + f * k[j]) };
    let mut worst: f64 = 0.0;
    for s in 0..n {
        let t = s as f64 * h;
        // The chamber is linear over the step (its corners fall on steps): the piece that
        // holds the step's middle.
        let p = piece_at(pieces, t + 0.5 * h);
        let c = |t: f64| p.1 + p.2 * (t - p.0);
        let (c_a, c_m, c_b) = (c(t), c(t + 0.5 * h), c(t + h));
        let k1 = derivative(&unit, tau_l, c_a, &x);
        let k2 = derivative(&unit, tau_l, c_m, &add(&x, &k1, 0.5 * h));
        let k3 = derivative(&unit, tau_l, c_m, &add(&x, &k2, 0.5 * h));
        let k4 = derivative(&unit, tau_l, c_b, &add(&x, &k3, h));
        x = std::array::from_fn(|j| x[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]));
        if (s + 1) % 100 == 0 {
            let t1 = (s + 1) as f64 * h;
            let tm = th.temps(t1);
            let closed = [
                tm.housing,
                tm.block[0],
                tm.block[1],
                tm.block[2],
                tm.accel,
                th.lag(0, 0, t1),
                th.lag(0, 1, t1),
                th.lag(0, 2, t1),
            ];
            assert!((tm.chamber - c(t1)).abs() < 1e-9, "chamber at {t1}");
            for j in 0..8 {
                worst = worst.max((closed[j] - x[j]).abs());
            }
        }
    }
    worst
}

#[test]
fn closed_form_matches_rk4_through_steps_ramps_and_holds() {
    let legs = [
        ChamberLeg::Hold {
            temp_c: 10.0,
            dur_s: 600.0,
        },
        // 35 K at 10 K/min: 210 s.
        ChamberLeg::Ramp {
            to_c: 45.0,
            rate_k_per_min: 10.0,
        },
        ChamberLeg::Hold {
            temp_c: 45.0,
            dur_s: 1190.0,
        },
        // 25 K at 0.5 K/min: 3000 s.
        ChamberLeg::Ramp {
            to_c: 20.0,
            rate_k_per_min: 0.5,
        },
    ];
    let pieces = [
        (0.0, 10.0, 0.0),
        (600.0, 10.0, 10.0 / 60.0),
        (810.0, 45.0, 0.0),
        (2000.0, 45.0, -0.5 / 60.0),
        (5000.0, 20.0, 0.0),
    ];
    let unit = UnitThermal {
        tau_housing_s: 1730.0,
        block_offset_k: [1.3, 3.7, 2.2],
        tau_block_s: [240.0, 610.0, 777.0],
        accel_offset_k: 2.9,
        tau_accel_s: 333.0,
    };
    let worst = check(unit, 4321.0, &legs, &pieces, 7000.0);
    assert!(worst < 1e-9, "closed form vs RK4: {worst:e} K");
}

#[test]
fn closed_form_matches_rk4_when_time_constants_coincide() {
    // The lag's and a block's time constants equal, and a block's equal to the housing's: the
    // resonant u·e^(−u/τ) branches of the closed form.
    let legs = [
        ChamberLeg::Hold {
            temp_c: 30.0,
            dur_s: 300.0,
        },
        ChamberLeg::Ramp {
            to_c: 12.0,
            rate_k_per_min: 6.0,
        },
    ];
    let pieces = [(0.0, 30.0, 0.0), (300.0, 30.0, -0.1), (480.0, 12.0, 0.0)];
    let unit = UnitThermal {
        tau_housing_s: 900.0,
        block_offset_k: [2.0, 1.0, 4.0],
        tau_block_s: [500.0, 900.0, 200.0],
        accel_offset_k: 1.0,
        tau_accel_s: 900.0,
    };
    let worst = check(unit, 500.0, &legs, &pieces, 5000.0);
    assert!(worst < 1e-9, "closed form vs RK4: {worst:e} K");
}
