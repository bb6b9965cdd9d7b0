//! The measurement format (docs/measurement-format.md): a good file parses with its segments,
//! every kind of bad file is refused with its row and column, and the shipped example parses.

use rins_mvm::csv::parse;
use rins_mvm::reader::read;

fn good() -> String {
    "t_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps,outer_deg,inner_deg,temp_gyro_x_c,run,segment\n\
     0.1,1e-6,2e-6,3e-6,0.0,0.0,0.98,0,0,30.1,r1,zup\n\
     0.2,1e-6,2e-6,3e-6,0.0,0.0,0.98,0,0,30.1,r1,zup\n\
     0.3,1e-6,2e-6,3e-6,0.0,0.0,0.98,0,0,30.2,r1,zup\n\
     5.0,1e-6,2e-6,3e-6,0.0,0.0,-0.98,180,180,30.2,r1,zdown\n\
     5.1,1e-6,2e-6,3e-6,0.0,0.0,-0.98,180,180,30.3,r1,zdown\n"
        .to_string()
}

fn error(text: &str) -> (usize, String, String) {
    let e = parse(text, "m.csv").expect_err("must be refused");
    let at = if e.row > 0 {
        "m.csv: row "
    } else {
        "m.csv: header, column "
    };
    assert!(e.to_string().starts_with(at), "{e}");
    (e.row, e.column, e.message)
}

/// Issue 44: an error about the whole file, or the header, says so (it read `row 0, column
/// ""`), and a short row names the first column it lacks (it named none).
#[test]
fn file_level_errors_say_so_and_a_short_row_names_its_first_missing_column() {
    let g = good();
    let said = |text: &str| {
        parse(text, "m.csv")
            .expect_err("must be refused")
            .to_string()
    };
    assert_eq!(
        said(""),
        "m.csv: the whole file: empty file: expected a header row"
    );
    let one_row: String = g.lines().take(2).map(|l| format!("{l}\n")).collect();
    assert_eq!(
        said(&one_row),
        "m.csv: the whole file: need at least two data rows, got 1"
    );
    assert_eq!(
        said(&g.replace(",run,segment", ",run,t_s")),
        "m.csv: header, column \"t_s\": duplicate column"
    );
    assert_eq!(
        said(&g.replace(",r1,zup\n0.2", ",r1\n0.2")),
        "m.csv: row 1, column \"segment\": missing: the row ends before this column (11 fields, \
         header has 12)"
    );
    assert_eq!(
        said(&g.replace("30.1,r1,zup\n0.2", "30.1\n0.2")),
        "m.csv: row 1, column \"run\": missing: the row ends before this column (10 fields, \
         header has 12)"
    );
    assert_eq!(
        said(&g.replace(",r1,zup\n0.2", ",r1,zup,7\n0.2")),
        "m.csv: row 1: 13 fields, header has 12 (the last is \"segment\")"
    );
    let missing = std::env::temp_dir().join(format!("rins-no-such-{}.csv", std::process::id()));
    assert_eq!(
        read(&missing).expect_err("no file").to_string(),
        format!(
            "{}: the whole file: cannot read: No such file or directory (os error 2)",
            missing.display()
        )
    );
}

#[test]
fn a_good_file_parses_with_its_segments() {
    let m = parse(&good(), "m.csv").unwrap();
    assert_eq!(m.rows, 5);
    assert_eq!(
        m.segments.len(),
        2,
        "the time gap is allowed between segments"
    );
    assert_eq!(m.temperature_columns(), vec!["temp_gyro_x_c"]);
    assert_eq!(m.col("dv_z_mps").unwrap()[4], -0.98);
}

#[test]
fn bad_files_name_row_and_column() {
    let g = good();
    let (r, c, msg) = error(&g.replace("dtheta_y_rad", "dtheta_y_deg"));
    assert_eq!((r, c.as_str()), (0, "dtheta_y_deg"));
    assert!(msg.contains("expected dtheta_y_rad"), "{msg}");
    let (r, c, _) = error(&g.replace(",dv_z_mps", ",foo_mps"));
    assert_eq!((r, c.as_str()), (0, "foo_mps"));
    let (r, c, msg) = error(&g.replace(",dv_z_mps", ""));
    assert_eq!((r, c.as_str()), (0, "dv_z_mps"));
    assert!(msg.contains("missing"), "{msg}");
    let (r, c, _) = error(&g.replace("0.2,1e-6,2e-6", "0.2,NaN,2e-6"));
    assert_eq!((r, c.as_str()), (2, "dtheta_x_rad"));
    let (r, c, _) = error(&g.replace("0.3,1e-6", "0.15,1e-6"));
    assert_eq!((r, c.as_str()), (3, "t_s"));
    let gap = g.replace(
        "0.3,1e-6,2e-6,3e-6,0.0,0.0,0.98,0,0,30.2,r1,zup",
        "0.9,1e-6,2e-6,3e-6,0.0,0.0,0.98,0,0,30.2,r1,zup",
    );
    let more = gap
        .replace("5.0,", "1.0,")
        .replace("zdown", "zup")
        .replace("5.1,", "1.1,");
    let (r, c, msg) = error(&more);
    assert_eq!(c, "t_s");
    assert!(msg.contains("gap") && r == 3, "{r} {msg}");
    let (r, c, _) = error(
        &g.replace(",temp_gyro_x_c", ",temp_gyro_x_c,extra")
            .replace(",r1,zup\n", ",r1,zup,1\n")
            .replace(",r1,zdown\n", ",r1,zdown,1\n"),
    );
    assert_eq!((r, c.as_str()), (0, "extra"));
    let (r, _, msg) = error(&g.replace(",r1,zup\n0.2", ",r1\n0.2"));
    assert!(r == 1 && msg.contains("fields"), "{r} {msg}");
    let (r, c, _) = error(&g.replace(",outer_deg,inner_deg", ",outer_deg,x_inner"));
    assert_eq!((r, c.as_str()), (0, "x_inner"));
    let (r, c, _) = error(&g.replace("temp_gyro_x_c", "gyro_temperature"));
    assert_eq!((r, c.as_str()), (0, "gyro_temperature"));
    // Attitude and temperature are required as groups.
    let no_att = g
        .replace(",outer_deg,inner_deg", "")
        .replace(",0,0,30", ",30")
        .replace(",180,180,30", ",30");
    let (_, c, msg) = error(&no_att);
    assert!(c == "outer_deg" && msg.contains("q_bn_w"), "{c} {msg}");
    let no_temp = g
        .replace(",temp_gyro_x_c", "")
        .replace(",30.1,", ",")
        .replace(",30.2,", ",")
        .replace(",30.3,", ",");
    let (_, c, _) = error(&no_temp);
    assert_eq!(c, "temp_*_c");
}

#[test]
fn the_shipped_example_parses() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../docs/examples/measurement-example.csv"
    );
    let m = read(std::path::Path::new(path)).unwrap();
    assert!(
        m.rows >= 100 && m.segments.len() == 2,
        "{} rows, {} segments",
        m.rows,
        m.segments.len()
    );
}

/// `good()` with the field of `column` in data row `row` (1-based) replaced by `value`.
fn with_field(text: &str, row: usize, column: &str, value: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let i = lines[0].split(',').position(|c| c == column).unwrap();
    let mut f: Vec<String> = lines[row].split(',').map(str::to_string).collect();
    f[i] = value.to_string();
    lines[row] = f.join(",");
    lines.join("\n") + "\n"
}

/// `good()` with extra columns (site, sample counter) appended with the same value on every row.
fn with_columns(extra: &[(&str, &str)]) -> String {
    let mut out = String::new();
    for (k, line) in good().lines().enumerate() {
        out += line;
        for (name, v) in extra {
            out += ",";
            out += if k == 0 { name } else { v };
        }
        out += "\n";
    }
    out
}

#[test]
fn values_out_of_their_physical_range_are_refused_with_value_and_range() {
    // Rows are 0.1 s apart: 2000 deg/s x 0.1 s = 3.4907 rad, 100 g x 0.1 s = 98.0665 m/s.
    let rate_bound = 2000f64.to_radians() * 0.1;
    let accel_bound: f64 = 100.0 * 9.806_65 * 0.1;
    assert!((rate_bound - 3.490_658_5).abs() < 1e-6 && (accel_bound - 98.0665).abs() < 1e-9);
    let g = good();
    // (row, column, value, accepted, text the refusal must contain)
    let cases: &[(usize, &str, &str, bool, &str)] = &[
        (2, "temp_gyro_x_c", "-400", false, "[-100, 200]"),
        (2, "temp_gyro_x_c", "200.5", false, "[-100, 200]"),
        (2, "temp_gyro_x_c", "-99.5", true, ""),
        (2, "temp_gyro_x_c", "199.9", true, ""),
        (3, "dtheta_y_rad", "3.49", true, ""),
        (3, "dtheta_y_rad", "-3.5", false, "2000 °/s"),
        (3, "dtheta_y_rad", "1e300", false, "1e300"),
        // The first row of a segment is bounded with the segment's median interval.
        (4, "dtheta_z_rad", "3.6", false, "over a row of 0.09999"),
        (2, "dv_z_mps", "98.06", true, ""),
        (2, "dv_z_mps", "98.07", false, "100 g"),
        (5, "dv_x_mps", "-1e300", false, "-1e300"),
        (2, "outer_deg", "1e30", false, "[-1e8, 1e8]"),
        (2, "inner_deg", "-7200", true, ""),
        (1, "t_s", "-1e30", false, "[-1e10, 1e10]"),
        (2, "t_s", "0.1000001", false, "outside [1e-6, 86400] s"),
    ];
    for &(row, col, value, ok, want) in cases {
        let text = with_field(&g, row, col, value);
        match parse(&text, "m.csv") {
            Ok(_) => assert!(ok, "{col} = {value} accepted"),
            Err(e) => {
                assert!(!ok, "{col} = {value} refused: {e}");
                let col_want = if col == "t_s" && want.starts_with("outside [1e-6") {
                    // The interval 1e-7 s is row 2's (t_s of row 2 minus row 1's).
                    (2, "t_s")
                } else {
                    (row, col)
                };
                assert_eq!((e.row, e.column.as_str()), col_want, "{e}");
                assert!(e.message.contains(want), "{col} = {value}: {e}");
                assert!(e.message.contains(value) || value.len() > 6, "{e}");
                // A 1e300 is shown as 1e300, not as 301 digits.
                assert!(e.to_string().len() < 400, "{e}");
            }
        }
    }
    // The site and the sample counter (the site is the model's [site] range).
    let site: &[(&str, &str, bool, &str)] = &[
        ("lat_deg", "1000", false, "[-89, 89]"),
        ("lat_deg", "89", true, ""),
        ("lat_deg", "-89.5", false, "[-89, 89]"),
        ("lon_deg", "360", false, "[-180, 360)"),
        ("lon_deg", "-180", true, ""),
        ("lon_deg", "359.9", true, ""),
        ("height_m", "1e30", false, "[-1000, 20000]"),
        ("height_m", "20000", true, ""),
        ("height_m", "-1000.5", false, "[-1000, 20000]"),
        ("sample", "1.5", false, "whole number"),
        ("sample", "-1", false, "whole number"),
        ("sample", "12", true, ""),
    ];
    for &(col, value, ok, want) in site {
        let mut extra = vec![
            ("lat_deg", "36.6"),
            ("lon_deg", "123.6"),
            ("height_m", "10"),
        ];
        extra.push(("sample", "3"));
        let text = with_field(&with_columns(&extra), 3, col, value);
        match parse(&text, "m.csv") {
            Ok(_) => assert!(ok, "{col} = {value} accepted"),
            Err(e) => {
                assert!(!ok, "{col} = {value} refused: {e}");
                assert_eq!((e.row, e.column.as_str()), (3, col), "{e}");
                assert!(e.message.contains(want), "{e}");
            }
        }
    }
}

#[test]
fn an_attitude_quaternion_must_have_unit_norm() {
    let header = "t_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps,q_bn_w,q_bn_x,q_bn_y,q_bn_z,temp_c_c";
    let file = |w: f64| {
        let mut s = format!("{header}\n");
        for k in 1..=4 {
            let q = if k == 3 { w } else { 1.0 };
            s += &format!("{},0,0,0,0,0,0.98,{q},0,0,0,25\n", k as f64 * 0.1);
        }
        s
    };
    assert!(parse(&file(1.0009), "q.csv").is_ok());
    assert!(parse(&file(0.9991), "q.csv").is_ok());
    for w in [0.998, 0.5, 0.0] {
        let e = parse(&file(w), "q.csv").expect_err("not a unit quaternion");
        assert_eq!((e.row, e.column.as_str()), (3, "q_bn_w"), "{e}");
        assert!(
            e.message.contains("norm") && e.message.contains("0.001 of 1"),
            "{e}"
        );
    }
    // A component beyond 1 + 1e-3 is out of range by itself.
    let e = parse(&file(1.5), "q.csv").expect_err("component");
    assert_eq!((e.row, e.column.as_str()), (3, "q_bn_w"), "{e}");
    assert!(e.message.contains("[-1.001, 1.001]"), "{e}");
}

#[test]
fn an_over_long_line_is_reported_by_length_and_start_not_echoed() {
    let g = good();
    // A data row of 100 000 bytes: its length and first 80 characters, not the line.
    let long = format!("0.15,{}", "7".repeat(100_000 - 5));
    let text = g.replacen("0.2,", &format!("{long}\n0.2,"), 1);
    let e = parse(&text, "m.csv").expect_err("over-long line");
    assert_eq!(e.row, 2, "{e}");
    assert!(e.message.contains("line of 100000 bytes"), "{e}");
    assert!(e.message.contains("65536"), "{e}");
    assert!(
        e.message.contains(&format!("\"0.15,{}…\"", "7".repeat(75))),
        "{e}"
    );
    assert!(e.to_string().len() < 400, "{} bytes", e.to_string().len());
    // A line of exactly the limit is not refused for its length (its first field is not a
    // number); one byte more is.
    for (len, long) in [(65_536, false), (65_537, true)] {
        let line = format!("{}\n", "x".repeat(len));
        let text = g.replacen("0.2,", &format!("{line}0.2,"), 1);
        let e = parse(&text, "m.csv").expect_err("not a row");
        assert_eq!(e.row, 2, "{e}");
        assert_eq!(
            e.message.contains("longer than the limit"),
            long,
            "{len}: {e}"
        );
        assert_eq!(e.message.contains("not a number"), !long, "{len}: {e}");
    }
    // An over-long header.
    let e = parse(&format!("{}\n", "a,".repeat(40_000)), "m.csv").expect_err("header");
    assert!(
        e.row == 0 && e.message.contains("line of 80001 bytes"),
        "{e}"
    );
    // A field that is not a number is quoted to 80 characters.
    let text = with_field(&g, 2, "dv_x_mps", &"x".repeat(10_000));
    let e = parse(&text, "m.csv").expect_err("not a number");
    assert_eq!((e.row, e.column.as_str()), (2, "dv_x_mps"), "{e}");
    assert!(
        e.message.contains(&format!("\"{}…\"", "x".repeat(80))),
        "{e}"
    );
    assert!(e.to_string().len() < 200, "{e}");
}

#[test]
fn a_model_on_a_moving_carrier_is_refused_with_the_reason() {
    use rins_mvm::history::check_model;
    use rins_plant::PlantConfig;
    use rins_plant::carrier::CarrierKind;
    assert_eq!(check_model(&PlantConfig::default()), Ok(()));
    for (kind, name) in [
        (CarrierKind::Ship, "\"ship\""),
        (CarrierKind::Trajectory, "\"trajectory\""),
    ] {
        let mut model = PlantConfig::default();
        model.carrier.kind = kind;
        let e = check_model(&model).expect_err("moving carrier");
        assert!(e.contains(name), "{e}");
        assert!(e.contains("static carrier only"), "{e}");
        assert!(e.contains("kind = \"static\""), "{e}");
    }
}

#[test]
fn a_long_column_name_is_quoted_to_80_characters() {
    let name = format!("temp_{}_c", "y".repeat(5000));
    let text = good()
        .replace("temp_gyro_x_c", &name)
        .replace(",30.2,r1,zup", ",-400,r1,zup");
    let e = parse(&text, "m.csv").expect_err("temperature");
    assert_eq!((e.row, e.column.as_str()), (3, name.as_str()), "{e}");
    let shown = e.to_string();
    assert!(
        shown.contains(&format!("column \"temp_{}…\"", "y".repeat(75))),
        "{shown}"
    );
    assert!(shown.len() < 400, "{} bytes", shown.len());
}
