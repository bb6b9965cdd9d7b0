//! The trajectory-file carrier: fed the ship carrier's own truth it reproduces the ship's
//! increments, and bad files are refused with errors naming the row and column.

use crate::carrier_common::{ship_config, with_sea_state};
use nalgebra::{Rotation3, UnitQuaternion};
use rins_plant::Plant;
use rins_plant::carrier::trajectory::COLUMNS;
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

/// Issue 44: an error about the whole file, or the header, says so (it read `row 0, column
/// ""`), and a short row names the first column it lacks (it named none).
#[test]
fn file_level_errors_say_so_and_a_short_row_names_its_first_missing_column() {
    let said = |text: &str| {
        Trajectory::parse(text, "bad.csv")
            .expect_err("must be refused")
            .to_string()
    };
    assert_eq!(
        said("# nothing but a comment\n"),
        "bad.csv: the whole file: empty file: expected a header row"
    );
    let good = file_with(0, |_| {});
    let one_row: String = good.lines().take(2).map(|l| format!("{l}\n")).collect();
    assert_eq!(
        said(&one_row),
        "bad.csv: the whole file: need at least two data rows, got 1"
    );
    assert_eq!(
        said(&good.replacen("q_cn_z", "q_cn_z,speed", 1)),
        format!("bad.csv: header, column \"speed\": unknown column; expected {COLUMNS:?}")
    );
    assert_eq!(
        said(&good.replacen(",q_cn_z", "", 1)),
        "bad.csv: header, column \"q_cn_z\": missing required column"
    );
    assert_eq!(
        said(&file_with(3, |f| f.truncate(7))),
        "bad.csv: row 3, column \"q_cn_w\": missing: the row ends before this column (7 fields, \
         the header has 11)"
    );
    assert_eq!(
        said(&file_with(2, |f| f.push("0".into()))),
        "bad.csv: row 2: 12 fields, the header has 11 (the last is \"q_cn_z\")"
    );
    let missing = std::env::temp_dir().join(format!("rins-no-such-{}.csv", std::process::id()));
    let missing = missing.to_str().unwrap();
    assert_eq!(
        Trajectory::read(missing).expect_err("no file").to_string(),
        format!("{missing}: the whole file: cannot read: No such file or directory (os error 2)")
    );
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

/// A file moving along the parallel of `lat_deg` at `v_e` m/s with rows every `dt` s, its
/// longitudes written as `write(lon_deg, row)` (wrapped, or aliased by ±360°), with the closed
/// form lon(t) = lon₀ + v·t/(R_N·cos L) (unwrapped, degrees).
fn along_parallel(
    lat_deg: f64,
    lon0_deg: f64,
    v_e: f64,
    dt: f64,
    rows: usize,
    write: impl Fn(f64, usize) -> f64,
) -> (String, impl Fn(f64) -> f64) {
    let (_, rn) = rins_plant::earth::radii_of_curvature(lat_deg.to_radians());
    let rate_dps = (v_e / (rn * lat_deg.to_radians().cos())).to_degrees();
    let lon = move |t: f64| lon0_deg + rate_dps * t;
    let mut text = String::from(HEADER);
    for k in 0..rows {
        let t = k as f64 * dt;
        text += &format!("{t},{lat_deg},{:?},0,{v_e},0,0,1,0,0,0\n", write(lon(t), k));
    }
    (text, lon)
}

/// Wraps degrees into [−180, 180).
fn wrap_deg(x: f64) -> f64 {
    (x + 180.0).rem_euclid(360.0) - 180.0
}

/// Issue 29: files whose longitude wraps (179.99 → −179.99), or writes a longitude as ±360°
/// off, are accepted (the difference between rows taken the shortest way), and between the
/// rows the carrier follows the closed-form parallel, its truth longitude wrapped.
#[test]
fn files_that_wrap_the_longitude_follow_the_closed_form_across_the_antimeridian() {
    type Writer = fn(f64, usize) -> f64;
    let cases: [(&str, f64, f64, f64, Writer); 5] = [
        ("east across 180", 60.0, 179.99, 8.0, |l, _| wrap_deg(l)),
        ("west across -180", -45.0, -179.995, -8.0, |l, _| {
            wrap_deg(l)
        }),
        ("aliased -360 on odd rows", 10.0, 0.0, 5.0, |l, k| {
            if k % 2 == 1 { l - 360.0 } else { l }
        }),
        ("aliased +360 near 180", 0.0, 179.999, 3.0, |l, k| {
            wrap_deg(l) + if k % 3 == 0 { 360.0 } else { 0.0 }
        }),
        ("high latitude, fast east", 88.5, 178.0, 15.0, |l, _| {
            wrap_deg(l)
        }),
    ];
    for (name, lat, lon0, v_e, write) in cases {
        let (text, lon) = along_parallel(lat, lon0, v_e, 1.0, 61, write);
        let traj = Trajectory::parse(&text, name).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut worst = 0.0f64;
        for k in 0..600 {
            let t = k as f64 * 0.1 + 0.037;
            let s = traj.state_at(t).truth();
            let want = wrap_deg(lon(t));
            let got = s.lon_rad.to_degrees();
            assert!((-180.0..=180.0).contains(&got), "{name}: {got}");
            let d = wrap_deg(got - want).abs();
            worst = worst.max(d);
            // Longitudes written in degrees near ±180° resolve 2.8e-14°, near ±360° 5.7e-14°
            // (6e-9 m at the equator): over a 1 s row that is up to 1e-8 m/s of velocity.
            assert!((s.v_n.x - v_e).abs() < 5e-8, "{name}: v_e {}", s.v_n.x);
            assert!((s.lat_rad.to_degrees() - lat).abs() < 1e-12, "{name}");
        }
        println!("{name}: largest longitude error {worst:.2e} deg");
        assert!(worst < 1e-9, "{name}: {worst:e} deg");
    }
}

/// Issue 29: an external carrier input that writes the longitude as −360° (the same place as
/// 0°) is accepted and moves the carrier the short way.
#[test]
fn an_external_carrier_input_at_minus_360_is_the_same_place_as_0() {
    use rins_plant::carrier::external::{CarrierSample, segment};
    let (_, rn) = rins_plant::earth::radii_of_curvature(0.0);
    let step_deg = (2.0 * 0.01 / rn).to_degrees(); // 2 m/s east over 10 ms
    let s = |lon_deg: f64| CarrierSample {
        lat_deg: 0.0,
        lon_deg,
        height_m: 0.0,
        v_enu_mps: [2.0, 0.0, 0.0],
        q_cn: [1.0, 0.0, 0.0, 0.0],
    };
    for (a, b) in [
        (0.0, -360.0 + step_deg),
        (-360.0, step_deg),
        (180.0 - step_deg / 2.0, -180.0 + step_deg / 2.0),
    ] {
        let mut c = segment(&s(a), &s(b), 2, 0.005).unwrap_or_else(|e| panic!("{a} → {b}: {e}"));
        let mut nodes = [c.state_now(); 2];
        let mid = c.advance(&mut nodes).truth();
        let want = wrap_deg(a + step_deg / 2.0);
        assert!(
            wrap_deg(mid.lon_rad.to_degrees() - want).abs() < 1e-12,
            "{a} → {b}: {} vs {want}",
            mid.lon_rad.to_degrees()
        );
        assert!((mid.v_n.x - 2.0).abs() < 1e-6, "{a} → {b}: {:?}", mid.v_n);
    }
}

/// Latitudes beyond ±89° are refused in a file (as for ships: the local-level frame is
/// singular at the pole).
#[test]
fn a_latitude_beyond_89_is_refused() {
    let (r, c, m) = refused(&file_with(2, |f| f[1] = "89.5".into()));
    assert_eq!((r, c.as_str()), (2, "lat_deg"), "{m}");
    assert!(m.contains("[-89, 89]"), "{m}");
}

/// Past the last row the carrier stops there: the last row's position and attitude at rest
/// (what `after_end = "hold"` asks for; a scenario refuses a short file otherwise).
#[test]
fn past_the_last_row_the_carrier_stops_at_it() {
    // 5 m/s north for 10 s at 1 Hz rows.
    let (rm, _) = rins_plant::earth::radii_of_curvature(36.6f64.to_radians());
    let mut text = String::from(HEADER);
    for k in 0..=10 {
        let lat = 36.6 + (5.0 * k as f64 / rm).to_degrees();
        text += &format!("{k},{lat:?},123.6,0,0,5,0,1,0,0,0\n");
    }
    let traj = Trajectory::parse(&text, "short.csv").unwrap();
    assert_eq!(traj.end_s(), 10.0);
    let at_end = traj.state_at(10.0);
    assert_eq!(at_end.v_n.y, 5.0);
    for t in [10.01, 30.0, 70.0] {
        let s = traj.state_at(t);
        assert_eq!(
            s.v_n.norm() + s.a_n.norm() + s.omega_nc_c.norm(),
            0.0,
            "t = {t}"
        );
        let moved = (s.lat_rad - at_end.lat_rad).abs() + (s.lon_rad - at_end.lon_rad).abs();
        assert!(moved < 1e-15, "t = {t}: moved {moved:e} rad");
    }
}
