//! The row cache walks a file in chunks of whole segments; the analysis on it must equal, bit
//! for bit, the analysis of the same file read whole into memory (the second method): the
//! windows, the comparison, the diagnosis with discovery and `--iterate`, for CSV and for
//! Parquet read one row group at a time. Error rows count across chunks.

use rins_mvm::reader::{read, stream_with};
use rins_mvm::{History, Options, RowCache, Rows, analyse, iterate, to_history};

use crate::common::{Hidden, history, model};

/// `h` as measurement CSV (shortest round-trip numbers), one segment label per run.
fn csv(h: &History) -> String {
    let rins_mvm::Attitude::Gimbal {
        outer_rad,
        inner_rad,
    } = &h.attitude
    else {
        panic!("gimbal attitude")
    };
    let mut s = String::from(
        "t_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps,outer_deg,inner_deg,temp_gyro_x_c,temp_gyro_y_c,temp_gyro_z_c,temp_accel_c,run,segment\n",
    );
    for k in 0..h.len() {
        s += &format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},dwell\n",
            h.t_s[k],
            h.dtheta_rad[0][k],
            h.dtheta_rad[1][k],
            h.dtheta_rad[2][k],
            h.dv_mps[0][k],
            h.dv_mps[1][k],
            h.dv_mps[2][k],
            outer_rad[k].to_degrees(),
            inner_rad[k].to_degrees(),
            h.gyro_temp_c[0][k],
            h.gyro_temp_c[1][k],
            h.gyro_temp_c[2][k],
            h.accel_temp_c[k],
            h.run_names[h.run[k] as usize],
        );
    }
    s
}

/// A three-run file with a hidden temperature-rate bias on x (so discovery has work).
fn file(name: &str) -> std::path::PathBuf {
    let m = model(true);
    let hidden = Hidden {
        temp_rate_dph_per_kps: [40.0, 0.0, 0.0],
        temp_swing_k: 3.0,
        ..Hidden::default()
    };
    let path = std::env::temp_dir().join(format!("rins-cache-{name}-{}.csv", std::process::id()));
    std::fs::write(&path, csv(&history(&m, &hidden, 7))).unwrap();
    path
}

/// Everything an analysis reports, as text (Debug prints every float to its shortest
/// round-trip form, so equal text is equal bits).
fn fingerprint(rows: &(impl Rows + ?Sized)) -> String {
    let opts = Options {
        diagnose: true,
        discover: true,
        ..Options::default()
    };
    let an = analyse(&model(true), rows, &opts);
    format!(
        "{:?}\n{:?}\n{:?}\n{:?}\n{:?}\n{:?}",
        an.replay.windows,
        an.replay.nav,
        an.noise,
        an.comparison,
        an.diagnosis.as_ref().map(|d| (&d.report, &d.after)),
        rows.info()
    )
}

#[test]
fn the_analysis_on_the_row_cache_equals_the_analysis_in_memory_bit_for_bit() {
    let path = file("same");
    let whole: History = to_history(read(&path).unwrap(), &path.display().to_string()).unwrap();
    // 1000-row chunks: each run's segment (about 14,000 rows) is a chunk of its own.
    let cache = RowCache::read(&path, None, 1000).unwrap();
    assert_eq!(cache.chunks(), 3);
    assert_eq!(cache.info().rows, whole.len());
    // The in-memory figures are computed the old way, over all rows at once.
    let mut d: Vec<f64> = whole
        .segments
        .iter()
        .flat_map(|s| (s.start + 1..s.end).map(|k| whole.t_s[k] - whole.t_s[k - 1]))
        .collect();
    let mid = d.len() / 2;
    let median = *d.select_nth_unstable_by(mid, f64::total_cmp).1;
    assert_eq!(cache.info().median_dt_s.to_bits(), median.to_bits());
    assert_eq!(fingerprint(&cache), fingerprint(&whole));
    // Whole-file chunks (one chunk) give the same too.
    let one = RowCache::read(&path, None, usize::MAX).unwrap();
    assert_eq!(one.chunks(), 1);
    assert_eq!(fingerprint(&one), fingerprint(&whole));
    // --iterate: every step's report and the final model.
    let opts = Options::default();
    let it = |rows: &dyn Fn() -> rins_mvm::Iteration| {
        let i = rows();
        format!("{:?}\n{:?}", i.report, i.model)
    };
    let a = it(&|| iterate(&model(true), &cache, &opts, &Default::default()).unwrap());
    let b = it(&|| iterate(&model(true), &whole, &opts, &Default::default()).unwrap());
    assert_eq!(a, b);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn parquet_streams_one_row_group_at_a_time_with_the_same_analysis() {
    let path = file("parquet");
    let m = read(&path).unwrap();
    let pq = path.with_extension("parquet");
    // Row groups of 5000 rows: groups end inside segments, segments inside groups.
    let props = parquet::file::properties::WriterProperties::builder()
        .set_max_row_group_row_count(Some(5000))
        .build();
    rins_mvm::parquet::write_with(&pq, &m, props).unwrap();
    let csv_cache = RowCache::read(&path, None, 1000).unwrap();
    let pq_cache = RowCache::read(&pq, None, 1000).unwrap();
    assert_eq!(pq_cache.chunks(), 3);
    let strip = |s: String, p: &std::path::Path| s.replace(&p.display().to_string(), "SOURCE");
    assert_eq!(
        strip(fingerprint(&pq_cache), &pq),
        strip(fingerprint(&csv_cache), &path)
    );
    let _ = std::fs::remove_file(&path);
    let _ = std::fs::remove_file(&pq);
}

#[test]
fn chunks_hold_whole_segments_and_errors_count_rows_across_chunks() {
    let path = file("chunks");
    let whole = read(&path).unwrap();
    let mut sizes = Vec::new();
    stream_with(&path, None, 100, &mut |m| {
        // Every chunk is whole segments: its first and last rows' runs start and end there.
        sizes.push((m.rows, m.segments.len()));
        Ok(())
    })
    .unwrap();
    let segs: Vec<usize> = whole.segments.iter().map(|s| s.3 - s.2).collect();
    assert_eq!(sizes, segs.iter().map(|n| (*n, 1)).collect::<Vec<_>>());
    // A value out of range in the third run: its row is counted from the file's first row.
    let text = std::fs::read_to_string(&path).unwrap();
    let bad_row = segs[0] + segs[1] + 5;
    let bad: String = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == bad_row {
                let mut f: Vec<&str> = l.split(',').collect();
                f[12] = "-400";
                f.join(",") + "\n"
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    std::fs::write(&path, bad).unwrap();
    let e = RowCache::read(&path, None, 100)
        .err()
        .expect("out of range");
    assert_eq!(e.row, bad_row, "{e}");
    assert_eq!(e.column, "temp_accel_c", "{e}");
    let _ = std::fs::remove_file(&path);
}
