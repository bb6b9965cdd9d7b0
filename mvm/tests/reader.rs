//! The measurement format (docs/measurement-format.md): a good file parses with its segments,
//! every kind of bad file is refused with its row and column, and the shipped example parses.

use rins_mvm::reader::{parse, read};

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
    assert!(e.to_string().starts_with("m.csv: row "), "{e}");
    (e.row, e.column, e.message)
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
