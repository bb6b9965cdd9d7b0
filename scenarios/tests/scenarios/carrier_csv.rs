//! The run's CSV on a moving carrier: the carrier truth columns equal the plant's truth and the
//! track's closed form (a meridian leg: latitude advances by the meridian-arc rate), the IMU
//! attitude includes the carrier, the columns form a trajectory file the plant reads back, and
//! the static carrier adds no column.

use rins_plant::Plant;
use rins_plant::earth::{WGS84_A_M, WGS84_E2};
use rins_scenario::file::Scenario;
use rins_scenarios::sinks::CsvSink;
use rins_scenarios::sinks::csv::CARRIER_COLUMNS;
use rins_scenarios::{Sink, run};

const KN: f64 = 1852.0 / 3600.0;

/// One hour due north at 12 kn from 36.6° N, calm water: the first leg starts on its own course
/// and speed, so the speed is constant from t = 0.
const MERIDIAN: &str = r#"[scenario]
name = "meridian"
duration_s = 3600.0
[carrier]
kind = "ship"
[carrier.ship]
lat_deg = 36.6
lon_deg = 123.6
legs = [{ heading_deg = 0.0, speed_kn = 12.0, duration_s = 7200.0 }]
[outputs]
decimation = 100
truth = true
"#;

/// Twenty minutes at sea state 5 with a 60° turn and a lever arm.
const SEA: &str = r#"[scenario]
name = "sea"
duration_s = 1200.0
[carrier]
kind = "ship"
lever_arm_m = [1.0, 5.0, -2.0]
[carrier.ship]
legs = [
  { heading_deg = 30.0, speed_kn = 14.0, duration_s = 400.0 },
  { heading_deg = 90.0, speed_kn = 10.0, duration_s = 3600.0 },
]
[carrier.ship.sea]
spectrum = "jonswap"
sea_state = 5
[outputs]
truth = true
"#;

/// Runs `sc` through the CSV sink; returns the header and the rows as numbers (the `position`
/// label as NaN).
fn csv_of(sc: &Scenario) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut sink = CsvSink::new(Vec::new(), sc.outputs, &sc.plant).unwrap();
    {
        let mut sinks: [&mut dyn Sink; 1] = [&mut sink];
        run(sc, sc.samples(), &mut sinks).unwrap();
    }
    let text = String::from_utf8(sink.into_inner()).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(|f| f.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    (header, rows)
}

fn col(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

/// Meridian arc length from the equator to `lat_rad`, m: ∫ R_M dφ with
/// R_M = a(1−e²)/(1−e² sin²φ)^{3/2}, by composite Simpson on 20 000 panels (independent of the
/// plant's per-tick integration; converged to well below a millimetre).
fn meridian_arc_m(lat_rad: f64) -> f64 {
    let r_m = |p: f64| WGS84_A_M * (1.0 - WGS84_E2) / (1.0 - WGS84_E2 * p.sin().powi(2)).powf(1.5);
    let n = 20_000;
    let h = lat_rad / n as f64;
    let mut s = r_m(0.0) + r_m(lat_rad);
    for i in 1..n {
        s += r_m(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

#[test]
fn a_meridian_leg_writes_the_plants_truth_and_the_closed_form_track() {
    let sc = Scenario::from_toml(MERIDIAN, "meridian.toml").unwrap();
    let (h, rows) = csv_of(&sc);
    assert_eq!(rows.len(), 3600);
    // The carrier columns close the row, in the trajectory file's names.
    assert_eq!(
        &h[h.len() - CARRIER_COLUMNS.len()..],
        &CARRIER_COLUMNS.map(String::from)
    );
    let c = |name| col(&h, name);
    let (lat, lon, height) = (c("lat_deg"), c("lon_deg"), c("height_m"));
    let (ve, vn, vu) = (c("v_e_mps"), c("v_n_mps"), c("v_u_mps"));
    let (qw, qx, qy, qz) = (c("q_cn_w"), c("q_cn_x"), c("q_cn_y"), c("q_cn_z"));
    let q_bn = c("q_bn_w");
    // 1. Each row equals the truth of an independently stepped plant at the row's end, bit for
    // bit (shortest round-trip numbers), and q_bn is the plant's IMU attitude (carrier
    // included), bit for bit: both are the plant's closed-form composition.
    let mut plant = Plant::new(&sc.plant).unwrap();
    for r in &rows {
        for _ in 0..100 {
            plant.step();
        }
        let t = plant.truth().carrier;
        let q = t.q_cn.quaternion();
        let want = [
            t.lat_rad.to_degrees(),
            t.lon_rad.to_degrees(),
            t.height_m,
            t.v_n.x,
            t.v_n.y,
            t.v_n.z,
            q.w,
            q.i,
            q.j,
            q.k,
        ];
        let got = [
            r[lat], r[lon], r[height], r[ve], r[vn], r[vu], r[qw], r[qx], r[qy], r[qz],
        ];
        assert_eq!(got.map(f64::to_bits), want.map(f64::to_bits), "row {r:?}");
        let p = plant.attitude_q_bn();
        let p = p.quaternion();
        let got: [f64; 4] = std::array::from_fn(|k| r[q_bn + k]);
        assert_eq!(
            got.map(f64::to_bits),
            [p.w, p.i, p.j, p.k].map(f64::to_bits),
            "q_bn of row {r:?}"
        );
    }
    // 2. The closed form: north at u = 12 kn, so the meridian arc from the start grows by u·t;
    // no east or up motion; carrier axes = ENU (heading north, no waves).
    let u = 12.0 * KN;
    let arc0 = meridian_arc_m(36.6f64.to_radians());
    let mut worst_m = 0.0f64;
    for r in &rows {
        let t_s = r[1];
        let along = meridian_arc_m(r[lat].to_radians()) - arc0;
        worst_m = worst_m.max((along - u * t_s).abs());
        assert_eq!((r[lon], r[height], r[ve], r[vu]), (123.6, 0.0, 0.0, 0.0));
        assert!((r[vn] - u).abs() < 1e-12, "v_n {}", r[vn]);
        assert_eq!((r[qw], r[qx], r[qy], r[qz]), (1.0, 0.0, 0.0, 0.0));
    }
    let last = rows.last().unwrap();
    assert!(
        (last[lat] - 36.6 - 0.2).abs() < 0.2,
        "one hour at 12 kn moves 0.2° north: {}",
        last[lat]
    );
    assert!(
        worst_m < 1e-3,
        "latitude off the meridian arc by {worst_m:e} m"
    );
    eprintln!("meridian leg: worst along-track error against the arc {worst_m:e} m");
}

#[test]
fn the_carrier_columns_are_a_trajectory_file_the_plant_reads_back() {
    let sc = Scenario::from_toml(SEA, "sea.toml").unwrap();
    let (h, rows) = csv_of(&sc);
    // Time 0 of a trajectory file is its first row: the carrier at the start, then every row.
    let start = Plant::new(&sc.plant).unwrap().truth().carrier;
    let q0 = start.q_cn.quaternion();
    let mut text = format!("t_s,{}\n", CARRIER_COLUMNS.join(","));
    text += &format!(
        "0,{},{},{},{},{},{},{},{},{},{}\n",
        start.lat_rad.to_degrees(),
        start.lon_rad.to_degrees(),
        start.height_m,
        start.v_n.x,
        start.v_n.y,
        start.v_n.z,
        q0.w,
        q0.i,
        q0.j,
        q0.k
    );
    let cols: Vec<usize> = std::iter::once(col(&h, "t_s"))
        .chain(CARRIER_COLUMNS.iter().map(|n| col(&h, n)))
        .collect();
    for r in &rows {
        let f: Vec<String> = cols.iter().map(|&k| r[k].to_string()).collect();
        text += &f.join(",");
        text.push('\n');
    }
    let dir = std::env::temp_dir().join(format!("rins-carrier-csv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("track.csv");
    std::fs::write(&file, text).unwrap();
    // The strict trajectory reader accepts it (position consistent with velocity, unit
    // quaternions), and the trajectory carrier passes through the written states.
    let traj = format!(
        "[scenario]\nname = \"replay\"\nduration_s = 1200.0\n[carrier]\nkind = \"trajectory\"\n[carrier.trajectory]\nfile = {:?}\n",
        file.display().to_string()
    );
    let sc2 = Scenario::from_toml(&traj, "replay.toml").unwrap();
    let mut plant = Plant::new(&sc2.plant).unwrap();
    // The ship itself, stepped alongside: its IMU attitude (carrier roll, pitch and yaw
    // composed with the gimbals) is the CSV's q_bn, bit for bit.
    let mut ship = Plant::new(&sc.plant).unwrap();
    let (lat, q_bn) = (col(&h, "lat_deg"), col(&h, "q_bn_w"));
    let (mut worst_deg, mut max_tilt) = (0.0f64, 0.0f64);
    for r in &rows {
        plant.step();
        ship.step();
        let t = plant.truth().carrier;
        worst_deg = worst_deg.max((t.lat_rad.to_degrees() - r[lat]).abs());
        let q = ship.attitude_q_bn();
        let q = q.quaternion();
        let got: [f64; 4] = std::array::from_fn(|k| r[q_bn + k]);
        assert_eq!(
            got.map(f64::to_bits),
            [q.w, q.i, q.j, q.k].map(f64::to_bits),
            "q_bn at t = {} s",
            r[1]
        );
        let (roll, pitch, _) = ship.truth().carrier.q_cn.euler_angles();
        max_tilt = max_tilt.max(roll.abs().max(pitch.abs()));
    }
    std::fs::remove_dir_all(&dir).ok();
    // Degrees written and read back: a few ulps of 36.6.
    assert!(worst_deg < 1e-12, "{worst_deg:e}");
    assert!(max_tilt.to_degrees() > 2.0, "{}", max_tilt.to_degrees());
    eprintln!(
        "sea state 5: trajectory replay latitude within {worst_deg:e} deg, carrier tilt up to {:.2} deg",
        max_tilt.to_degrees()
    );
    // The ship really moved: 20 min at 10-14 kn with sea state 5.
    let first = &rows[0];
    let last = rows.last().unwrap();
    assert!((last[lat] - first[lat]).abs() > 0.01);
}

#[test]
fn the_static_carrier_adds_no_column() {
    let mut sc = Scenario::load(std::path::Path::new("builtin:paper-16pos-short")).unwrap();
    sc.meta.duration_s = 1.0;
    sc.outputs.truth = true;
    sc.outputs.effects = false;
    let (h, _) = csv_of(&sc);
    for c in CARRIER_COLUMNS {
        assert!(!h.iter().any(|x| x == c), "{c} in {h:?}");
    }
    assert_eq!(h.last().map(String::as_str), Some("q_bn_z"));
}

/// On the static carrier with a tilted mount, through the scheme's dwells and turns (every
/// sample a row), the CSV's q_bn is the plant's closed-form attitude bit for bit.
#[test]
fn the_static_carriers_q_bn_is_the_plants_bit_for_bit() {
    let mut sc = Scenario::load(std::path::Path::new("builtin:paper-16pos-short")).unwrap();
    sc.meta.duration_s = 300.0;
    sc.outputs.truth = true;
    sc.outputs.effects = false;
    sc.outputs.decimation = 1;
    sc.plant.vehicle = rins_plant::VehicleSpec {
        azimuth_deg: 47.0,
        pitch_deg: -3.0,
        roll_deg: 2.0,
    };
    let (h, rows) = csv_of(&sc);
    let q_bn = col(&h, "q_bn_w");
    let mut plant = Plant::new(&sc.plant).unwrap();
    let mut moving = 0;
    for r in &rows {
        plant.step();
        moving += plant.truth().gimbal.moving as u32;
        let q = plant.attitude_q_bn();
        let q = q.quaternion();
        let got: [f64; 4] = std::array::from_fn(|k| r[q_bn + k]);
        assert_eq!(
            got.map(f64::to_bits),
            [q.w, q.i, q.j, q.k].map(f64::to_bits),
            "q_bn at t = {} s",
            r[1]
        );
    }
    assert!(moving > 100, "the table turned: {moving} samples");
}
