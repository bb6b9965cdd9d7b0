//! Real logs: a logger's file with its own names, units and extra columns is read through a
//! column map (docs/measurement-format.md, "Column map") into the same measurement as the
//! documented file; an unmapped unknown column stays an error that suggests the map; map
//! mistakes name the map file and line; Parquet files follow the same rules and give the
//! same measurement as the CSV.

use std::path::PathBuf;

use rins_mvm::colmap::ColumnMap;
use rins_mvm::reader::{Measurement, classify, parse, parse_with, read, read_with};

fn example() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/examples/measurement-example.csv")
}

/// The example rewritten as a logger would: other names, angles in arcsec, time in ms, velocity
/// in mm/s, gimbal angles in rad, temperatures in K, and two extra columns.
fn logger_csv(doc: &Measurement) -> String {
    let mut out = String::from(
        "time_ms,gx,gy,gz,ax,ay,az,outer_rad,inner_rad,T_gyro_x_K,status,run,seg,crc\n",
    );
    for k in 0..doc.rows {
        let c = |n: &str| doc.col(n).unwrap()[k];
        out += &format!(
            "{},{},{},{},{},{},{},{},{},{},OK,{},{},{}\n",
            c("t_s") * 1e3,
            c("dtheta_x_rad") / (std::f64::consts::PI / 648_000.0),
            c("dtheta_y_rad") / (std::f64::consts::PI / 648_000.0),
            c("dtheta_z_rad") / (std::f64::consts::PI / 648_000.0),
            c("dv_x_mps") * 1e3,
            c("dv_y_mps") * 1e3,
            c("dv_z_mps") * 1e3,
            c("outer_deg").to_radians(),
            c("inner_deg").to_radians(),
            c("temp_gyro_x_c") + 273.15,
            doc.labels["run"].get(k),
            doc.labels["segment"].get(k),
            k * 7 % 256,
        );
    }
    out
}

const MAP: &str = r#"# a logger's columns
ignore = ["status", "crc"]
[columns]
time_ms = { to = "t_s", unit = "ms" }
gx = { to = "dtheta_x_rad", unit = "arcsec" }
gy = { to = "dtheta_y_rad", unit = "arcsec" }
gz = { to = "dtheta_z_rad", unit = "arcsec" }
ax = { to = "dv_x_mps", factor = 0.001 }
ay = { to = "dv_y_mps", unit = "mm/s" }
az = { to = "dv_z_mps", unit = "mm/s" }
outer_rad = { to = "outer_deg", unit = "rad" }
inner_rad = { to = "inner_deg", unit = "rad" }
T_gyro_x_K = { to = "temp_gyro_x_c", unit = "K" }
seg = { to = "segment" }
"#;

fn map(text: &str) -> ColumnMap {
    ColumnMap::parse(text, "map.toml", classify).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()) + 1e-12
}

#[test]
fn a_logger_file_reads_through_the_map_as_the_documented_file() {
    let doc = read(&example()).unwrap();
    let text = logger_csv(&doc);
    // Without the map: an error naming the unknown column and suggesting the map.
    let e = parse(&text, "log.csv").expect_err("unknown columns");
    assert_eq!((e.row, e.column.as_str()), (0, "time_ms"), "{e}");
    assert!(e.message.contains("--map"), "{e}");
    let m = parse_with(&text, "log.csv", Some(&map(MAP))).unwrap();
    assert_eq!(m.rows, doc.rows);
    assert_eq!(m.segments, doc.segments);
    assert_eq!(m.ignored, vec!["status".to_string(), "crc".to_string()]);
    for (name, want) in [
        ("t_s", "t_s"),
        ("dtheta_x_rad", "dtheta_x_rad"),
        ("dtheta_z_rad", "dtheta_z_rad"),
        ("dv_y_mps", "dv_y_mps"),
        ("dv_x_mps", "dv_x_mps"),
        ("outer_deg", "outer_deg"),
        ("inner_deg", "inner_deg"),
        ("temp_gyro_x_c", "temp_gyro_x_c"),
    ] {
        let (a, b) = (m.col(name).unwrap(), doc.col(want).unwrap());
        for k in 0..m.rows {
            assert!(
                close(a[k], b[k]),
                "{name} row {}: {} vs {}",
                k + 1,
                a[k],
                b[k]
            );
        }
    }
    let s = map(MAP).summary();
    assert!(
        s.mapped
            .contains(&"gx -> dtheta_x_rad (arcsec)".to_string()),
        "{s:?}"
    );
    assert_eq!(s.ignored, vec!["crc".to_string(), "status".to_string()]);
}

#[test]
fn map_mistakes_name_the_map_line() {
    let e = |text: &str| ColumnMap::parse(text, "map.toml", classify).expect_err("refused");
    // Line 3: a unit of another quantity.
    let x = e("ignore = []\n[columns]\ngx = { to = \"dtheta_x_rad\", unit = \"ms\" }\n");
    assert_eq!(x.row, 3, "{x}");
    assert!(
        x.to_string().contains("map.toml") && x.message.contains("angle"),
        "{x}"
    );
    // An unknown unit lists the accepted ones.
    let x = e("[columns]\n\ngx = { to = \"dtheta_x_rad\", unit = \"furlong\" }\n");
    assert_eq!(x.row, 3, "{x}");
    assert!(x.message.contains("arcsec"), "{x}");
    // A target that is not a documented column.
    let x = e("[columns]\ngx = { to = \"dtheta_x_deg\" }\n");
    assert_eq!(x.row, 2, "{x}");
    // A label converted, a syntax error.
    let x = e("[columns]\nr = { to = \"run\", factor = 2.0 }\n");
    assert!(x.message.contains("label"), "{x}");
    let x = e("[columns]\n\n\ngx = { to = \n");
    assert_eq!(x.row, 4, "{x}");
    // A mapped column the data lack: named with the map line.
    let doc = read(&example()).unwrap();
    let text = logger_csv(&doc);
    let bad = map(&format!("{MAP}gq = {{ to = \"temp_board_c\" }}\n"));
    let x = parse_with(&text, "log.csv", Some(&bad)).expect_err("gq is not in the file");
    assert_eq!((x.row, x.column.as_str()), (15, "gq"), "{x}");
    // A conversion that overflows names the data row and the source column.
    let text = "t_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,big,outer_deg,inner_deg,temp_chamber_c\n\
                0.1,0,0,0,0,0,0.98,0,0,25\n\
                0.2,0,0,0,0,0,1e10,0,0,25\n";
    let big = map("[columns]\nbig = { to = \"dv_z_mps\", factor = 1e300 }\n");
    let x = parse_with(text, "log.csv", Some(&big)).expect_err("overflow");
    assert_eq!((x.row, x.column.as_str()), (2, "big"), "{x}");
}

#[test]
fn parquet_reads_as_the_csv_and_follows_the_same_rules() {
    let doc = read(&example()).unwrap();
    let dir = std::env::temp_dir().join(format!("rins-pq-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("example.parquet");
    rins_mvm::parquet::write(&path, &doc).unwrap();
    let m = read(&path).unwrap();
    assert_eq!(m.rows, doc.rows);
    assert_eq!(m.segments, doc.segments);
    assert_eq!(m.columns, doc.columns, "bit-identical numbers");
    assert_eq!(m.labels, doc.labels);
    // The logger's file as Parquet: the same map applies.
    let log = parse_with(&logger_csv(&doc), "log.csv", Some(&map(MAP))).unwrap();
    let raw = parse_raw(&logger_csv(&doc));
    let lp = dir.join("log.parquet");
    rins_mvm::parquet::write(&lp, &raw).unwrap();
    assert!(read(&lp).is_err(), "unknown columns without the map");
    let via = read_with(&lp, Some(&map(MAP))).unwrap();
    assert_eq!(via.columns, log.columns);
    assert_eq!(via.ignored.len(), 2);
    // A time step backwards is refused with its row, as in CSV.
    let mut bad = doc.clone();
    bad.columns.get_mut("t_s").unwrap()[10] = 0.0;
    let bp = dir.join("bad.parquet");
    rins_mvm::parquet::write(&bp, &bad).unwrap();
    let e = read(&bp).expect_err("time not increasing");
    assert_eq!((e.row, e.column.as_str()), (11, "t_s"), "{e}");
    let mut nan = doc.clone();
    nan.columns.get_mut("dv_z_mps").unwrap()[4] = f64::NAN;
    rins_mvm::parquet::write(&bp, &nan).unwrap();
    let e = read(&bp).expect_err("NaN");
    assert_eq!((e.row, e.column.as_str()), (5, "dv_z_mps"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The logger's file parsed as it is (every column kept under its own name) by mapping each
/// column onto a documented family name and back: here simply a measurement whose columns are
/// the logger's names, for writing as Parquet.
fn parse_raw(text: &str) -> Measurement {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut m = Measurement::default();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    m.rows = rows.len();
    for (i, h) in header.iter().enumerate() {
        if ["status", "run", "seg"].contains(h) {
            let mut l = rins_mvm::reader::LabelColumn::default();
            l.names = rows
                .iter()
                .map(|r| r[i].to_string())
                .collect::<std::collections::BTreeSet<_>>()
                .into_iter()
                .collect();
            l.index = rows
                .iter()
                .map(|r| l.names.iter().position(|n| n == r[i]).unwrap() as u32)
                .collect();
            m.labels.insert(h.to_string(), l);
        } else {
            m.columns.insert(
                h.to_string(),
                rows.iter().map(|r| r[i].parse().unwrap()).collect(),
            );
        }
    }
    m
}
