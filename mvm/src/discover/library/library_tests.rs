//! The library's window sums against closed forms written here (not the plant): a product of
//! two signals is formed as (Σ a·Δt)(Σ b·Δt)/W, which is exact when one factor is constant over
//! the window and otherwise misses exactly W·cov_w(a, b), the factors' covariance over the
//! window. The rows are 1/128 s apart so every Δt and row time is exact in binary and the
//! closed forms need no rounding allowance beyond the sums'.

use rins_plant::config::PlantConfig;
use rins_plant::effects::custom::CustomKind;
use rins_plant::effects::custom::signals::{NodeRef, Signal};
use rins_plant::thermal::node;

use super::{Term, moments};
use crate::history::{Attitude, History};
use crate::replay::{Kinematics, Window};

/// Row spacing, s (a power of two: exact row times).
const DT_S: f64 = 1.0 / 128.0;
/// Rows of a 30 s window, the replay's longest.
const WINDOW_ROWS: usize = 3840;
/// Windows in the test run.
const WINDOWS: usize = 6;

/// A static run at inner angle `inner_rad`: row k ends at (k + 1)·DT_S; the gyro blocks read
/// `block(t)` and the housing `housing(t)`. The first row only opens the run (row k covers
/// (t_{k−1}, t_k]), so the windows hold rows 1 ..= WINDOWS·WINDOW_ROWS.
fn history(inner_rad: f64, block: &dyn Fn(f64) -> f64, housing: &dyn Fn(f64) -> f64) -> History {
    let rows = WINDOWS * WINDOW_ROWS + 1;
    let t_s: Vec<f64> = (0..rows).map(|k| (k + 1) as f64 * DT_S).collect();
    let temps: Vec<f64> = t_s.iter().map(|&t| block(t)).collect();
    History {
        dtheta_rad: std::array::from_fn(|_| vec![0.0; rows]),
        dv_mps: std::array::from_fn(|_| vec![0.0; rows]),
        attitude: Attitude::Gimbal {
            outer_rad: vec![0.0; rows],
            inner_rad: vec![inner_rad; rows],
        },
        gyro_temp_c: std::array::from_fn(|_| temps.clone()),
        housing_temp_c: Some(t_s.iter().map(|&t| housing(t)).collect()),
        accel_temp_c: temps,
        run: vec![0; rows],
        run_names: vec!["closed-form".into()],
        segments: vec![0..rows],
        source: "library_tests".into(),
        t_s,
    }
}

fn windows() -> Vec<Window> {
    (0..WINDOWS)
        .map(|w| Window {
            run: 0,
            t_mid_s: (w as f64 + 0.5) * 30.0,
            t_run_s: (w as f64 + 0.5) * 30.0,
            duration_s: 30.0,
            rows: WINDOW_ROWS as u32,
            moving: false,
            up_z: 1.0,
            azimuth_deg: 0.0,
            // Not read by the window sums.
            f_b_g: [0.0, 0.0, 1.0],
            gyro_temp_c: [0.0; 3],
            accel_temp_c: 0.0,
            rotation_rps: 0.0,
            since_move_s: 0.0,
            y: [0.0; 6],
            x: Vec::new(),
        })
        .collect()
}

/// The bias column (Σ regressor·Δt per window) of `factors` on the x gyro.
fn column(h: &History, factors: &[Signal]) -> Vec<f64> {
    let ws = windows();
    let m = moments(&Kinematics::new(&PlantConfig::default()), h, &ws, &[]);
    let term = Term::Product {
        factors: factors.to_vec(),
        kind: CustomKind::Bias,
    };
    m.column(&term, 0, &ws)
}

/// Σ f(t_k)·Δt over window w's rows, summed here (the exact integral of the row-held product).
fn window_sum(w: usize, f: &dyn Fn(f64) -> f64) -> f64 {
    (1 + w * WINDOW_ROWS..=(w + 1) * WINDOW_ROWS)
        .map(|k| f((k + 1) as f64 * DT_S) * DT_S)
        .sum()
}

const BLOCK: Signal = Signal::Temp(NodeRef::Block);
const HOUSING: Signal = Signal::Temp(NodeRef::Node(node::HOUSING));

fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol,
        "{what}: {a:e} vs {b:e} (diff {:e} > {tol:e})",
        a - b
    );
}

#[test]
fn exact_cases_are_exact() {
    let ramp = |t: f64| 20.0 + 0.01 * t;
    let inner = 0.3_f64;
    let h = history(inner, &ramp, &|_| 15.0);
    // Body up at inner angle φ about x: u_y = ±sin φ, u_z = cos φ (squares are sign-free).
    // Tolerances: 1e-12 of each sum's size (3840 rows of rounding).
    let (s, c) = inner.sin_cos();
    for w in 0..WINDOWS {
        let at = format!("window {w}");
        let degree_one = column(&h, &[BLOCK])[w];
        close(degree_one, window_sum(w, &ramp), 1e-12 * 30.0 * 30.0, &at);
        // u·u products are summed row by row.
        close(
            column(&h, &[Signal::Up(1), Signal::Up(1)])[w],
            s * s * 30.0,
            1e-12 * 30.0 * 30.0,
            &at,
        );
        close(
            column(&h, &[Signal::Up(2), Signal::Up(2)])[w],
            c * c * 30.0,
            1e-12 * 30.0 * 30.0,
            &at,
        );
        close(
            column(&h, &[Signal::Up(1), Signal::Up(2)])[w].abs(),
            s * c * 30.0,
            1e-12 * 30.0,
            &at,
        );
        // Temperature × an attitude signal in a dwell: the attitude factor is constant.
        close(
            column(&h, &[BLOCK, Signal::Up(2)])[w],
            c * window_sum(w, &ramp),
            1e-12 * 1500.0,
            &at,
        );
        // A constant second factor (the housing here) is exact too.
        close(
            column(&h, &[BLOCK, HOUSING])[w],
            15.0 * window_sum(w, &ramp),
            1e-12 * 15.0 * 1500.0,
            &at,
        );
    }
}

#[test]
fn a_ramp_squared_misses_exactly_its_within_window_variance() {
    // T = T0 + ρt over N rows of Δt: Σ(T − T̄)²Δt = ρ²Δt²(N² − 1)/12 · NΔt.
    for rho_k_per_s in [1e-3, 1.0 / 60.0, 0.1] {
        let ramp = move |t: f64| 25.0 + rho_k_per_s * t;
        let h = history(0.0, &ramp, &|_| 15.0);
        let col = column(&h, &[BLOCK, BLOCK]);
        let n = WINDOW_ROWS as f64;
        let missed = rho_k_per_s.powi(2) * DT_S * DT_S * (n * n - 1.0) / 12.0 * n * DT_S;
        for (w, &got) in col.iter().enumerate() {
            let exact = window_sum(w, &|t| ramp(t).powi(2));
            // W²/12 = 75 s²: the missed term is 2250·ρ² K²s (2.25e-3 at 1e-3 K/s) against
            // Σ T²Δt ≈ 2e4 K²s, whose rounding is ~1e-12 of it.
            close(
                got,
                exact - missed,
                (1e-12 * exact).max(1e-6 * missed),
                &format!("ρ {rho_k_per_s} K/s, window {w}"),
            );
            // Popoviciu: a variance is at most (range)²/4, here (ρW)²/4 per unit time.
            assert!(exact - got <= (rho_k_per_s * 30.0).powi(2) / 4.0 * 30.0);
        }
    }
}

#[test]
fn two_settling_temperatures_miss_exactly_their_covariance() {
    // T1 = A − B·e^(−t/τ1) (block), T2 = C − D·e^(−t/τ2) (housing). With r = e^(−Δt/τ) and
    // E(r) = Σ_k r^(k+1) over the window's rows (a geometric sum), the sums are
    // Σ T1 = N·A − B·E(r1), Σ T2 = N·C − D·E(r2),
    // Σ T1·T2 = N·A·C − A·D·E(r2) − B·C·E(r1) + B·D·E(r1·r2).
    let (a, b, tau1) = (40.0, 20.0, 900.0);
    let (c, d, tau2) = (35.0, 25.0, 2400.0);
    let t1 = move |t: f64| a - b * (-t / tau1).exp();
    let t2 = move |t: f64| c - d * (-t / tau2).exp();
    let h = history(0.0, &t1, &t2);
    let col = column(&h, &[BLOCK, HOUSING]);
    let (r1, r2) = ((-DT_S / tau1).exp(), (-DT_S / tau2).exp());
    let n = WINDOW_ROWS as f64;
    for (w, &got) in col.iter().enumerate() {
        let k0 = (1 + w * WINDOW_ROWS) as i32;
        let e = |r: f64| r.powi(k0 + 1) * (1.0 - r.powi(WINDOW_ROWS as i32)) / (1.0 - r);
        let (s1, s2) = (n * a - b * e(r1), n * c - d * e(r2));
        let s12 = n * a * c - a * d * e(r2) - b * c * e(r1) + b * d * e(r1 * r2);
        let exact = s12 * DT_S;
        let missed = (s12 - s1 * s2 / n) * DT_S; // W·cov_w(T1, T2)
        close(
            exact,
            window_sum(w, &|t| t1(t) * t2(t)),
            1e-10 * exact,
            "closed form vs the row sum",
        );
        close(got, exact - missed, 1e-10 * exact, &format!("window {w}"));
        // For slow signals the missed part is the two ramps' W³·ρ1·ρ2/12 (ρ at the window's
        // middle), and never more than W·σ1·σ2 ≤ W·range1·range2/4 (Cauchy–Schwarz, Popoviciu).
        let (ta, tb) = (k0 as f64 * DT_S, (k0 as f64 + n) * DT_S);
        let tm = 0.5 * (ta + tb);
        let (rho1, rho2) = (b / tau1 * (-tm / tau1).exp(), d / tau2 * (-tm / tau2).exp());
        let linear = 30f64.powi(3) * rho1 * rho2 / 12.0;
        assert!(
            (missed - linear).abs() <= 0.01 * missed,
            "window {w}: missed {missed:e}, W³ρ1ρ2/12 = {linear:e}"
        );
        let bound = 30.0 * (t1(tb) - t1(ta)) * (t2(tb) - t2(ta)) / 4.0;
        assert!(
            missed > 0.0 && missed <= bound,
            "window {w}: {missed:e} > {bound:e}"
        );
    }
}

fn info(gimbal: bool, housing: bool) -> crate::rows::RowsInfo {
    crate::rows::RowsInfo {
        source: "t".into(),
        run_names: vec!["r".into()],
        rows: 2,
        gimbal,
        housing,
        median_dt_s: DT_S,
        mean_dt_s: DT_S,
        rms_dtheta_rad: 0.0,
        rms_dv_mps: 0.0,
        run_start_s: vec![0.0],
    }
}

/// The library's signals as the table derives them, against the list written out here (the
/// order the search's terms come in): with housing and gimbal angles, without either.
#[test]
fn library_signals_follow_the_table_in_its_order() {
    let names = |gimbal, housing| -> Vec<String> {
        super::library_signals(&info(gimbal, housing))
            .into_iter()
            .map(Signal::name)
            .collect()
    };
    let fast = "u_x u_y u_z w_x w_y w_z abs_w_x abs_w_y abs_w_z";
    assert_eq!(
        names(true, true).join(" "),
        format!(
            "temp:block dtemp_dt:block temp:housing dtemp_dt:housing grad:block-housing {fast} \
             time"
        )
    );
    assert_eq!(
        names(false, false).join(" "),
        format!("temp:block dtemp_dt:block {fast} time")
    );
}

/// Every fast signal of the table that the library searches is in it when the data can form it
/// (with gimbal angles, every one; with quaternions, every one that does not need gimbal
/// angles), alone as a bias at least, or, for a clock the library reads through a decay, as
/// exp(−x/τ) at every time constant of the grid; so a new signal in the table is searched for
/// with no change here.
#[test]
fn every_fast_signal_is_in_the_library_when_its_data_are_there() {
    use rins_plant::effects::custom::Op;
    use rins_plant::effects::custom::signals::{FAMILIES, Library};
    let taus = super::tau_grid();
    for gimbal in [true, false] {
        let sig = super::library_signals(&info(gimbal, true));
        let terms = super::product_terms(&sig);
        let memory = super::memory_terms(&info(gimbal, true), &taus);
        for (i, f) in FAMILIES.iter().enumerate() {
            if f.fill.is_none() {
                continue;
            }
            if f.library == Library::NotSearched {
                continue;
            }
            for s in Signal::all_of(i) {
                if f.library == Library::Decay {
                    for &tau_s in &taus {
                        let t = Term::Memory {
                            signal: s,
                            op: Op::Decay { tau_s },
                        };
                        assert!(memory.contains(&t), "{} at {tau_s} s", s.name());
                    }
                    continue;
                }
                let alone = Term::Product {
                    factors: vec![s],
                    kind: CustomKind::Bias,
                };
                assert_eq!(
                    terms.contains(&alone),
                    gimbal || !f.needs_gimbal,
                    "{} (gimbal data: {gimbal})",
                    s.name()
                );
            }
        }
    }
}

/// The grid of time constants: 10 s to 3 h, six per decade (18 steps of 1080^(1/18) = 1.474).
#[test]
fn the_tau_grid_spans_ten_seconds_to_three_hours() {
    let g = super::tau_grid();
    assert_eq!(g.len(), 19);
    assert!((g[0] - 10.0).abs() < 1e-12 && (g[18] - 10_800.0).abs() < 1e-9);
    let r = g[1] / g[0];
    assert!(g.windows(2).all(|w| (w[1] / w[0] / r - 1.0).abs() < 1e-12));
}

/// A decay of the time since the table stopped, summed by the library's pass, against the
/// closed form: a dwell of D seconds after a move gives Σ e^(−s/τ)·Δt = τ(1 − e^(−D/τ)) up to
/// the midpoint rule; a lag of a temperature step against the lag's closed form.
#[test]
fn memory_sums_match_their_closed_forms() {
    use rins_plant::effects::custom::Op;
    // One run: 10 s still, a 90° outer turn over 9 s, then 300 s still; 10 rows per second;
    // the block temperature steps from 20 to 30 °C at t = 100 s.
    let dt = 0.1;
    let n = 3190;
    let mut t_s = Vec::new();
    let (mut outer, mut inner) = (Vec::new(), Vec::new());
    let mut temp = Vec::new();
    for k in 0..=n {
        let t = k as f64 * dt;
        t_s.push(t);
        let o = if t <= 10.0 {
            0.0
        } else if t < 19.0 {
            (t - 10.0) * 10.0
        } else {
            90.0
        };
        outer.push(o.to_radians());
        inner.push(0.0);
        temp.push(if t < 100.0 { 20.0 } else { 30.0 });
    }
    let h = History {
        t_s: t_s.clone(),
        dtheta_rad: [vec![0.0; n + 1], vec![0.0; n + 1], vec![0.0; n + 1]],
        dv_mps: [vec![0.0; n + 1], vec![0.0; n + 1], vec![0.0; n + 1]],
        attitude: crate::history::Attitude::Gimbal {
            outer_rad: outer,
            inner_rad: inner,
        },
        gyro_temp_c: [temp.clone(), temp.clone(), temp.clone()],
        housing_temp_c: None,
        accel_temp_c: temp,
        run: vec![0; n + 1],
        run_names: vec!["r".into()],
        segments: vec![0..n + 1],
        source: "test".into(),
    };
    // One window per row: the sums are per row.
    let ws: Vec<Window> = (1..=n)
        .map(|k| Window {
            run: 0,
            t_mid_s: t_s[k] - 0.5 * dt,
            t_run_s: t_s[k] - 0.5 * dt,
            duration_s: dt,
            rows: 1,
            moving: false,
            up_z: 1.0,
            azimuth_deg: 0.0,
            f_b_g: [0.0, 0.0, 1.0],
            gyro_temp_c: [0.0; 3],
            accel_temp_c: 0.0,
            rotation_rps: 0.0,
            since_move_s: 0.0,
            y: [0.0; 6],
            x: Vec::new(),
        })
        .collect();
    let (tau_d, tau_l) = (40.0, 60.0);
    let decay = Term::Memory {
        signal: Signal::SinceMove,
        op: Op::Decay { tau_s: tau_d },
    };
    let lag = Term::Memory {
        signal: Signal::Temp(rins_plant::effects::custom::signals::NodeRef::Block),
        op: Op::Lag { tau_s: tau_l },
    };
    let m = moments(
        &Kinematics::new(&PlantConfig::default()),
        &h,
        &ws,
        &[decay.clone(), lag.clone()],
    );
    let dcol = m.column(&decay, 2, &ws);
    let lcol = m.column(&lag, 0, &ws);
    // The turn's rows (10 s < t ≤ 19 s): the clock is 0, e^0·Δt each.
    for k in 101..=190 {
        let row = t_s[k] - t_s[k - 1];
        assert_eq!(dcol[k - 1], row, "row {k}");
    }
    // After the turn: Σ over the dwell = τ(1 − e^(−D/τ)) within the midpoint rule.
    let d = t_s[n] - 19.0;
    let sum: f64 = dcol[190..].iter().sum();
    let want = tau_d * (1.0 - (-d / tau_d).exp());
    assert!((sum / want - 1.0).abs() < 1e-5, "{sum} vs {want}");
    // Before the turn the clock counts from the run's start (the first row's time less a row).
    assert!((dcol[0] / dt - (-(0.5 * dt + dt) / tau_d).exp()).abs() < 1e-12);
    // The lag of the step: ∫ over each row of 30 − 10·e^(−(t − 100)/τ) after the step.
    for k in [1200usize, 1500, 2500] {
        let (t0, t1) = (t_s[k - 1], t_s[k]);
        // The reading of row k is the temperature at its end, held over the row: the lag's
        // input steps at the start of the first row that reads 30 °C.
        let first = (1..=n).find(|&j| h.accel_temp_c[j] == 30.0).unwrap();
        let from = t_s[first - 1];
        let exact = 30.0 * dt
            - 10.0 * tau_l * ((-(t0 - from) / tau_l).exp() - (-(t1 - from) / tau_l).exp());
        assert!(
            (lcol[k - 1] - exact).abs() < 1e-9,
            "row {k}: {} vs {exact}",
            lcol[k - 1]
        );
    }
}
