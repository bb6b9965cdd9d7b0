//! The `[carrier]` section: parsed, range-checked with line and column, and a trajectory file's
//! own errors reported with its row and column.

use rins_plant::Plant;
use rins_plant::carrier::{CarrierKind, SpectrumKind};
use rins_scenario::Scenario;

const SHIP: &str = r#"[scenario]
name = "ship"
duration_s = 10.0
[carrier]
kind = "ship"
lever_arm_m = [1.0, 5.0, -2.0]
[carrier.ship]
legs = [
  { heading_deg = 90.0, speed_kn = 12.0, duration_s = 3600.0 },
  { heading_deg = 180.0, speed_kn = 10.0, duration_s = 3600.0 },
]
[carrier.ship.sea]
spectrum = "jonswap"
sea_state = 5
"#;

fn err(text: &str) -> String {
    Scenario::from_toml(text, "t.toml").unwrap_err().to_string()
}

#[test]
fn a_ship_scenario_loads_and_runs() {
    let s = Scenario::from_toml(SHIP, "ship.toml").unwrap();
    let c = &s.plant.carrier;
    assert_eq!(c.kind, CarrierKind::Ship);
    assert_eq!(c.ship.legs.len(), 2);
    assert_eq!(c.ship.sea.spectrum, SpectrumKind::Jonswap);
    assert_eq!(c.ship.sea.hs_tp(), (3.25, 9.7));
    let mut p = Plant::new(&s.plant).unwrap();
    let v0 = p.truth().carrier.v_n;
    for _ in 0..100 {
        p.step();
    }
    // Heading east at 12 kn, plus the sea state's surge and sway.
    assert!((v0.x - 12.0 * 1852.0 / 3600.0).abs() < 1.5, "{v0:?}");
}

#[test]
fn a_static_scenario_has_the_static_carrier() {
    let s = Scenario::from_toml("[scenario]\nname = \"x\"\n", "t.toml").unwrap();
    assert!(s.plant.carrier.is_static());
}

#[test]
fn an_out_of_range_carrier_value_names_its_line_and_column() {
    let e = err(&SHIP.replace("speed_kn = 10.0", "speed_kn = 99.0"));
    assert!(
        e.contains("line 10, column 37: carrier.ship.legs[1].speed_kn"),
        "{e}"
    );
    assert!(e.contains("[0, 60]") && e.contains("99"), "{e}");
    let e = err(&SHIP.replace("sea_state = 5", "sea_state = 5\nhs_m = -1.0"));
    assert!(
        e.contains("line 15, column 8: carrier.ship.sea.hs_m"),
        "{e}"
    );
}

#[test]
fn an_unknown_carrier_key_or_kind_is_refused_with_its_line() {
    let e = err(&SHIP.replace("sea_state = 5", "sea_stat = 5"));
    assert!(e.contains("line 14") && e.contains("sea_stat"), "{e}");
    let e = err(&SHIP.replace("kind = \"ship\"", "kind = \"boat\""));
    assert!(e.contains("line 5") && e.contains("boat"), "{e}");
}

#[test]
fn a_bad_trajectory_file_is_reported_with_its_row_and_column() {
    let dir = std::env::temp_dir().join(format!("rins-carrier-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("track.csv");
    std::fs::write(
        &csv,
        "t_s,lat_deg,lon_deg,height_m,v_e_mps,v_n_mps,v_u_mps,q_cn_w,q_cn_x,q_cn_y,q_cn_z\n\
         0,36.6,123.6,0,0,0,0,1,0,0,0\n\
         0.01,36.6,123.6,0,0,0,0,1,0,0,0\n\
         0.02,36.6,123.6,0,0,nan,0,1,0,0,0\n",
    )
    .unwrap();
    let toml = dir.join("s.toml");
    std::fs::write(
        &toml,
        "[scenario]\nname = \"x\"\n[carrier]\nkind = \"trajectory\"\ntrajectory.file = \"track.csv\"\n",
    )
    .unwrap();
    let e = Scenario::load(&toml).unwrap_err().to_string();
    assert!(
        e.contains("line 5, column 19: carrier.trajectory.file"),
        "{e}"
    );
    assert!(e.contains("track.csv: row 3, column \"v_n_mps\""), "{e}");
    // Fixed, the relative name resolves against the scenario's folder and the plant runs.
    std::fs::write(
        &csv,
        "t_s,lat_deg,lon_deg,height_m,v_e_mps,v_n_mps,v_u_mps,q_cn_w,q_cn_x,q_cn_y,q_cn_z\n\
         0,36.6,123.6,0,0,0,0,1,0,0,0\n\
         0.01,36.6,123.6,0,0,0,0,1,0,0,0\n",
    )
    .unwrap();
    // Issue 29: a file shorter than the run (0.01 s against the default 3600 s) is refused,
    // naming the file, its last time and the run's duration, unless the scenario says to hold.
    let e = Scenario::load(&toml).unwrap_err().to_string();
    assert!(
        e.contains("track.csv: the last row is at t = 0.01 s")
            && e.contains("scenario.duration_s = 3600 s")
            && e.contains("after_end = \"hold\""),
        "{e}"
    );
    let hold = "trajectory.after_end = \"hold\"\n";
    std::fs::write(&toml, std::fs::read_to_string(&toml).unwrap() + hold).unwrap();
    let s = Scenario::load(&toml).unwrap();
    let mut p = Plant::new(&s.plant).unwrap();
    let d = p.step();
    assert!((d.dv_mps.z - 9.7987 * 0.01).abs() < 1e-4, "{:?}", d.dv_mps);
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 29: the last leg continues to the end of the run, so a run that would take it past
/// ±89° is refused naming the leg and the latitude (its own 100 s are inside).
#[test]
fn a_last_leg_continued_past_the_polar_limit_is_refused() {
    let text = "[scenario]\nname = \"x\"\nduration_s = 200000.0\n[carrier]\nkind = \"ship\"\n\
                [carrier.ship]\nlat_deg = 80.0\n\
                legs = [{ heading_deg = 0.0, speed_kn = 10.0, duration_s = 100.0 }]\n";
    let e = err(text);
    assert!(
        e.contains("carrier.ship.legs[0]")
            && e.contains("continued to the end of the run at 200000 s")
            && e.contains("would reach latitude"),
        "{e}"
    );
    assert!(Scenario::from_toml(&text.replace("200000.0", "3600.0"), "t.toml").is_ok());
}
