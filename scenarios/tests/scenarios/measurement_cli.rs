//! Real logs on the command line: `rins measure --format parquet` writes a file that `rins
//! compare` reads to the same report as the CSV, and a logger's CSV (other column names, an
//! extra column) read through `--map` gives the documented file's report, with the map listed;
//! without the map the unknown column is an error that names it and suggests the map.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rins(args: &[&OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rins"))
        .args(args)
        .output()
        .unwrap()
}

fn ok(args: &[&OsStr]) -> Output {
    let o = rins(args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

fn compare_json(model: &Path, data: &Path, map: Option<&Path>) -> serde_json::Value {
    let mut args = vec![
        OsStr::new("compare"),
        OsStr::new("--model"),
        model.as_os_str(),
        OsStr::new("--data"),
        data.as_os_str(),
        OsStr::new("--json"),
    ];
    if let Some(m) = map {
        args.extend([OsStr::new("--map"), m.as_os_str()]);
    }
    serde_json::from_slice(&ok(&args).stdout).unwrap()
}

/// The report without the fields that name the input (its path and the column map).
fn findings(mut v: serde_json::Value) -> serde_json::Value {
    let o = v.as_object_mut().unwrap();
    o.remove("source");
    o.remove("column_map");
    v
}

#[test]
fn parquet_and_a_mapped_logger_file_give_the_documented_files_report() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let truth = root.join("docs/examples/discovery-truth.toml");
    let model = root.join("docs/examples/diagnosis-model.toml");
    let dir = std::env::temp_dir().join(format!("rins-measurement-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (csv, pq) = (dir.join("unit.csv"), dir.join("unit.parquet"));
    let s = OsStr::new;
    ok(&[s("measure"), truth.as_os_str(), s("--out"), csv.as_os_str()]);
    ok(&[
        s("measure"),
        truth.as_os_str(),
        s("--out"),
        pq.as_os_str(),
        s("--format"),
        s("parquet"),
    ]);
    // Parquet is smaller than the CSV and reads to the same report.
    let (csv_len, pq_len) = (
        std::fs::metadata(&csv).unwrap().len(),
        std::fs::metadata(&pq).unwrap().len(),
    );
    assert!(
        pq_len * 2 < csv_len,
        "parquet {pq_len} B vs csv {csv_len} B"
    );
    let documented = compare_json(&model, &csv, None);
    assert!(documented["rows"].as_u64().unwrap() > 100_000);
    assert_eq!(
        findings(compare_json(&model, &pq, None)),
        findings(documented.clone())
    );

    // The logger's file: its own time and chamber names, and a status column.
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    assert!(header.contains(",t_s,") && header.contains(",temp_chamber_c"));
    let mut logger = header
        .replace(",t_s,", ",time_s,")
        .replace(",temp_chamber_c", ",chamber_degC")
        + ",status\n";
    for l in lines {
        logger += l;
        logger += ",OK\n";
    }
    let log = dir.join("logger.csv");
    std::fs::write(&log, logger).unwrap();
    let map = dir.join("logger-map.toml");
    std::fs::write(
        &map,
        "ignore = [\"status\"]\n[columns]\ntime_s = { to = \"t_s\" }\nchamber_degC = { to = \"temp_chamber_c\" }\n",
    )
    .unwrap();
    let mapped = compare_json(&model, &log, Some(&map));
    let listed = mapped["column_map"].to_string();
    assert!(
        listed.contains("status") && listed.contains("time_s"),
        "{listed}"
    );
    assert_eq!(findings(mapped), findings(documented));

    // Without the map: the unknown column is named and the map suggested.
    let o = rins(&[
        s("compare"),
        s("--model"),
        model.as_os_str(),
        s("--data"),
        log.as_os_str(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains("time_s") && err.contains("map"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
