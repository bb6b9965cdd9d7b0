//! The trajectory-file carrier: fed the ship carrier's own truth it reproduces the ship's
//! increments, and bad files are refused with errors naming the row and column.

mod carrier_common;

use carrier_common::{ship_config, with_sea_state};
use nalgebra::{Rotation3, UnitQuaternion};
use rins_plant::Plant;
use rins_plant::carrier::{Carrier, CarrierState, Trajectory};

fn row(t: f64, s: &CarrierState) -> String {
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(s.c_cn));
    format!(
        "{t},{},{},{},{},{},{},{},{},{},{}\n",
        s.lat_rad.to_degrees(),
        s.lon_rad.to_degrees(),
        s.height_m,
        s.v_n.x,
        s.v_n.y,
        s.v_n.z,
        q.w,
        q.i,
        q.j,
        q.k
    )
}

const HEADER: &str =
    "t_s,lat_deg,lon_deg,height_m,v_e_mps,v_n_mps,v_u_mps,q_cn_w,q_cn_x,q_cn_y,q_cn_z\n";

#[test]
fn trajectory_of_the_ships_truth_reproduces_its_increments() {
    // 20 min at sea state 5 with a 60° turn and a speed change, sampled at the plant's 100 Hz.
    let cfg = with_sea_state(ship_config(&[(20.0, 12.0, 400.0), (80.0, 15.0, 1e5)]), 5);
    let n = 120_000u64;
    let mut carrier = Carrier::new(&cfg.carrier, cfg.seed, 0.01).unwrap().unwrap();
    let mut text = String::from(HEADER);
    text += &row(0.0, &carrier.state_now());
    let mut nodes = [carrier.state_now(); 2];
    for k in 1..=n {
        let s = carrier.advance(&mut nodes);
        text += &row(k as f64 * 0.01, &s);
    }
    let traj = Trajectory::parse(&text, "ship-truth.csv").unwrap();
    let mut ship = Plant::new(&cfg).unwrap();
    let mut file = Plant::with_carrier(&cfg, Carrier::from_trajectory(traj, 0.01)).unwrap();
    let (mut th, mut dv, mut th_max, mut dv_max) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for _ in 0..n {
        let (a, b) = (ship.step(), file.step());
        th = th.max((a.dtheta_rad - b.dtheta_rad).amax());
        dv = dv.max((a.dv_mps - b.dv_mps).amax());
        th_max = th_max.max(a.dtheta_rad.amax());
        dv_max = dv_max.max(
            (a.dv_mps - ship.truth().dv_true_mps)
                .amax()
                .max(a.dv_mps.xy().amax()),
        );
    }
    let (pa, pb) = (ship.truth().carrier, file.truth().carrier);
    let pos_m = ((pa.lat_rad - pb.lat_rad).abs() + (pa.lon_rad - pb.lon_rad).abs()) * 6.4e6;
    println!(
        "trajectory vs ship, 20 min sea state 5: |dtheta diff| {th:.2e} rad (steps up to {th_max:.2e}), |dv diff| {dv:.2e} m/s (horizontal steps up to {dv_max:.2e}), end position {pos_m:.2e} m"
    );
    // Bound (docs/carrier.md): constant-rate attitude between rows errs by (1/12)|ω×ω̇|h³ in
    // rotation and ω̇h²/8 in attitude at the quadrature points; with ω ≤ 0.1 rad/s,
    // ω̇ ≤ 0.1 rad/s², h = 0.01 s this is ≤ 1e-9 rad per step and, through g, ≤ 1e-6 m/s.
    assert!(th < 1e-9, "{th:e}");
    assert!(dv < 1e-6, "{dv:e}");
    // The file's positions are the exact path's, which adds a ~1e-8 rad step to latitude and
    // longitude every tick, each addition rounding by up to half an ulp; the ship's segment rule
    // adds once per segment. The reference's own rounding bounds the difference (as in
    // `carrier_segment.rs`).
    let rounding_m = n as f64 * 0.5 * f64::EPSILON * pa.lat_rad.abs().max(pa.lon_rad.abs()) * 6.4e6;
    assert!(
        pos_m < rounding_m,
        "{pos_m:e} (rounding bound {rounding_m:.1e} m)"
    );
    assert!(th_max > 1e-4, "the sea state moved the ship: {th_max:e}");
}

/// A valid five-row file at rest, 100 Hz, with row `r` (1-based) replaced by `f(fields)`.
fn file_with(r: usize, f: impl Fn(&mut Vec<String>)) -> String {
    let mut text = String::from(HEADER);
    for k in 0..5 {
        let mut fields: Vec<String> = format!("{},36.6,123.6,0,0,0,0,1,0,0,0", k as f64 * 0.01)
            .split(',')
            .map(String::from)
            .collect();
        if k + 1 == r {
            f(&mut fields);
        }
        text += &(fields.join(",") + "\n");
    }
    text
}

fn refused(text: &str) -> (usize, String, String) {
    let e = Trajectory::parse(text, "bad.csv").expect_err("must be refused");
    assert!(e.to_string().starts_with("bad.csv: row "), "{e}");
    (e.row, e.column, e.message)
}

#[test]
fn the_unchanged_file_is_accepted() {
    assert!(Trajectory::parse(&file_with(0, |_| {}), "ok.csv").is_ok());
}

#[test]
fn a_time_step_is_refused_with_row_and_column() {
    let (r, c, m) = refused(&file_with(4, |f| f[0] = "0.035".into()));
    assert_eq!((r, c.as_str()), (4, "t_s"), "{m}");
    assert!(m.contains("time step"), "{m}");
}

#[test]
fn a_nan_is_refused_with_row_and_column() {
    let (r, c, m) = refused(&file_with(3, |f| f[5] = "NaN".into()));
    assert_eq!((r, c.as_str()), (3, "v_n_mps"), "{m}");
}

#[test]
fn a_position_jump_is_refused_with_row_and_column() {
    // 1e-4 degree of latitude is 11 m in 10 ms at zero velocity.
    let (r, c, m) = refused(&file_with(3, |f| f[1] = "36.6001".into()));
    assert_eq!((r, c.as_str()), (3, "lat_deg"), "{m}");
    assert!(m.contains("position jump"), "{m}");
}

#[test]
fn a_non_unit_quaternion_is_refused_with_row_and_column() {
    let (r, c, m) = refused(&file_with(2, |f| f[7] = "1.01".into()));
    assert_eq!((r, c.as_str()), (2, "q_cn_w"), "{m}");
    assert!(m.contains("norm"), "{m}");
}
