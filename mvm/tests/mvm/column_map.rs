//! Real logs: a logger's file with its own names, units and extra columns is read through a
//! column map (docs/measurement-format.md, "Column map") into the same measurement as the
//! documented file; an unmapped unknown column stays an error that suggests the map; map
//! mistakes name the map file and line; Parquet files follow the same rules and give the
//! same measurement as the CSV.

use std::path::PathBuf;

use rins_mvm::colmap::ColumnMap;
use rins_mvm::csv::{parse, parse_with};
use rins_mvm::measurement::{Measurement, classify};
use rins_mvm::reader::{read, read_with};

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
            let mut l = rins_mvm::measurement::LabelColumn::default();
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

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rins-pq-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn parquet_with_every_codec_reads_bit_for_bit_as_the_csv() {
    use parquet::basic::{Compression, GzipLevel, ZstdLevel};
    use parquet::file::properties::WriterProperties;
    let doc = read(&example()).unwrap();
    let dir = temp_dir("codecs");
    let mut sizes = Vec::new();
    for (name, c) in [
        ("uncompressed", Compression::UNCOMPRESSED),
        ("snappy", Compression::SNAPPY),
        ("gzip", Compression::GZIP(GzipLevel::default())),
        ("zstd", Compression::ZSTD(ZstdLevel::default())),
        ("lz4", Compression::LZ4),
        ("lz4_raw", Compression::LZ4_RAW),
    ] {
        let path = dir.join(format!("{name}.parquet"));
        let props = WriterProperties::builder().set_compression(c).build();
        rins_mvm::parquet::write_with(&path, &doc, props).unwrap();
        // The file really is compressed with the codec.
        let f = std::fs::File::open(&path).unwrap();
        let r = parquet::file::reader::SerializedFileReader::new(f).unwrap();
        use parquet::file::reader::FileReader;
        assert_eq!(r.metadata().row_group(0).column(0).compression(), c);
        sizes.push((name, std::fs::metadata(&path).unwrap().len()));
        let m = read(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(m.rows, doc.rows, "{name}");
        assert_eq!(m.columns, doc.columns, "{name}: bit-identical numbers");
        assert_eq!(m.labels, doc.labels, "{name}");
        assert_eq!(m.segments, doc.segments, "{name}");
    }
    // Compression did something (the codecs are not silently off).
    let plain = sizes[0].1;
    for (name, size) in &sizes[1..] {
        assert!(
            *size < plain,
            "{name}: {size} bytes vs {plain} uncompressed"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Writes columns of the example with `t_s` stored as `t_type` (a Parquet schema type and
/// name) from integer ticks, `per_s` ticks a second, starting at `base` ticks.
fn write_time_file(
    path: &std::path::Path,
    doc: &Measurement,
    t_decl: &str,
    ticks: &[i64],
    int96: bool,
) {
    use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int64Type, Int96, Int96Type};
    use parquet::file::properties::WriterProperties;
    use parquet::file::writer::SerializedFileWriter;
    use std::sync::Arc;
    let numeric: Vec<&String> = doc.columns.keys().filter(|k| *k != "t_s").collect();
    let mut fields = vec![t_decl.to_string()];
    for name in doc.labels.keys() {
        fields.push(format!("REQUIRED BYTE_ARRAY {name} (UTF8);"));
    }
    for name in &numeric {
        fields.push(format!("REQUIRED DOUBLE {name};"));
    }
    let schema = parquet::schema::parser::parse_message_type(&format!(
        "message m {{ {} }}",
        fields.join(" ")
    ))
    .unwrap();
    let props = Arc::new(WriterProperties::builder().build());
    let file = std::fs::File::create(path).unwrap();
    let mut w = SerializedFileWriter::new(file, Arc::new(schema), props).unwrap();
    let mut rg = w.next_row_group().unwrap();
    let mut c = rg.next_column().unwrap().unwrap();
    if int96 {
        // Julian day and nanoseconds of the day.
        let v: Vec<Int96> = ticks
            .iter()
            .map(|ns| {
                let day = ns.div_euclid(86_400_000_000_000) + 2_440_588;
                let nanos = ns.rem_euclid(86_400_000_000_000) as u64;
                let mut x = Int96::new();
                x.set_data(nanos as u32, (nanos >> 32) as u32, day as u32);
                x
            })
            .collect();
        c.typed::<Int96Type>().write_batch(&v, None, None).unwrap();
    } else {
        c.typed::<Int64Type>()
            .write_batch(ticks, None, None)
            .unwrap();
    }
    c.close().unwrap();
    for l in doc.labels.values() {
        let mut c = rg.next_column().unwrap().unwrap();
        let v: Vec<ByteArray> = (0..doc.rows).map(|k| ByteArray::from(l.get(k))).collect();
        c.typed::<ByteArrayType>()
            .write_batch(&v, None, None)
            .unwrap();
        c.close().unwrap();
    }
    for name in &numeric {
        let mut c = rg.next_column().unwrap().unwrap();
        c.typed::<DoubleType>()
            .write_batch(&doc.columns[*name], None, None)
            .unwrap();
        c.close().unwrap();
    }
    rg.close().unwrap();
    w.close().unwrap();
}

#[test]
fn parquet_timestamps_become_seconds_since_the_first_row() {
    let doc = read(&example()).unwrap();
    let dir = temp_dir("time");
    let path = dir.join("t.parquet");
    // 2023-11-14 22:13:20 UTC plus the example's times.
    let epoch_s: i64 = 1_700_000_000;
    let t = doc.col("t_s").unwrap();
    for (decl, per_s, int96) in [
        (
            "REQUIRED INT64 t_s (TIMESTAMP(MILLIS,true));",
            1_000i64,
            false,
        ),
        (
            "REQUIRED INT64 t_s (TIMESTAMP(MICROS,true));",
            1_000_000,
            false,
        ),
        (
            "REQUIRED INT64 t_s (TIMESTAMP(NANOS,false));",
            1_000_000_000,
            false,
        ),
        ("REQUIRED INT64 t_s (TIMESTAMP_MILLIS);", 1_000, false),
        ("REQUIRED INT64 t_s (TIME(MICROS,true));", 1_000_000, false),
        ("REQUIRED INT96 t_s;", 1_000_000_000, true),
    ] {
        let base = if decl.contains("TIME(") {
            3600 * per_s
        } else {
            epoch_s * per_s
        };
        let ticks: Vec<i64> = t
            .iter()
            .map(|s| base + (s * per_s as f64).round() as i64)
            .collect();
        write_time_file(&path, &doc, decl, &ticks, int96);
        let m = read(&path).unwrap_or_else(|e| panic!("{decl}: {e}"));
        // The reference: the CSV with t_s written as the tick differences in seconds.
        let mut csv_doc = doc.clone();
        let want: Vec<f64> = ticks
            .iter()
            .map(|k| (k - ticks[0]) as f64 / per_s as f64)
            .collect();
        assert!(
            (want[1] - (t[1] - t[0])).abs() < 1e-9,
            "{decl}: {}",
            want[1]
        );
        csv_doc.columns.insert("t_s".into(), want);
        let csv = to_csv(&csv_doc);
        let via_csv = parse(&csv, "t.csv").unwrap();
        assert_eq!(m.columns, via_csv.columns, "{decl}: bit for bit");
        assert_eq!(m.segments, via_csv.segments, "{decl}");
        assert_eq!(m.t0_ns, Some(ticks[0] * (1_000_000_000 / per_s)), "{decl}");
    }
    // A unit conversion on top of the time type is refused.
    let ticks: Vec<i64> = t.iter().map(|s| (s * 1e3).round() as i64).collect();
    write_time_file(
        &path,
        &doc,
        "REQUIRED INT64 stamp (TIMESTAMP(MILLIS,true));",
        &ticks,
        false,
    );
    let e = read_with(
        &path,
        Some(&map("[columns]\nstamp = { to = \"t_s\", unit = \"ms\" }\n")),
    )
    .expect_err("double conversion");
    assert_eq!((e.row, e.column.as_str()), (0, "stamp"), "{e}");
    assert!(e.message.contains("by name only"), "{e}");
    let ok = read_with(&path, Some(&map("[columns]\nstamp = { to = \"t_s\" }\n"))).unwrap();
    assert_eq!(
        ok.col("t_s").unwrap()[1],
        (ticks[1] - ticks[0]) as f64 / 1e3
    );
    // Read as a plain INT64 (the defect this replaces) the raw count of ns is refused by the
    // range of t_s, not taken for seconds.
    let ns: Vec<i64> = t
        .iter()
        .map(|s| epoch_s * 1_000_000_000 + (s * 1e9).round() as i64)
        .collect();
    write_time_file(&path, &doc, "REQUIRED INT64 t_s;", &ns, false);
    let e = read(&path).expect_err("raw ns");
    assert_eq!((e.row, e.column.as_str()), (1, "t_s"), "{e}");
    assert!(e.message.contains("[-1e10, 1e10]"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The measurement as documented CSV (labels first, then numbers, `{}` of each f64, which
/// reads back to the same bits).
fn to_csv(m: &Measurement) -> String {
    let mut names: Vec<&String> = m.labels.keys().collect();
    names.extend(m.columns.keys());
    let mut out = names
        .iter()
        .map(|s| s.as_str())
        .collect::<Vec<_>>()
        .join(",")
        + "\n";
    for k in 0..m.rows {
        let mut f: Vec<String> = m.labels.values().map(|l| l.get(k).to_string()).collect();
        f.extend(m.columns.values().map(|v| format!("{}", v[k])));
        out += &f.join(",");
        out += "\n";
    }
    out
}

/// CRC-32 (IEEE, reflected, as gzip and the Parquet page checksum), bit by bit.
fn crc32(data: &[u8]) -> u32 {
    let mut c = 0xFFFF_FFFFu32;
    for &b in data {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                (c >> 1) ^ 0xEDB8_8320
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// Thrift compact protocol: an unsigned varint at `b[*p..]`.
fn varint(b: &[u8], p: &mut usize) -> u64 {
    let mut v = 0u64;
    for shift in (0..).step_by(7) {
        let x = b[*p];
        *p += 1;
        v |= ((x & 0x7f) as u64) << shift;
        if x & 0x80 == 0 {
            break;
        }
    }
    v
}

/// Skips a compact-protocol value of type `t`.
fn skip(b: &[u8], p: &mut usize, t: u8) {
    match t {
        1 | 2 => {}
        3 => *p += 1,
        4..=6 => {
            varint(b, p);
        }
        7 => *p += 8,
        8 => {
            let n = varint(b, p) as usize;
            *p += n;
        }
        9 | 10 => {
            let h = b[*p];
            *p += 1;
            let n = if h >> 4 == 15 {
                varint(b, p)
            } else {
                (h >> 4) as u64
            };
            for _ in 0..n {
                if h & 15 <= 2 {
                    *p += 1;
                } else {
                    skip(b, p, h & 15);
                }
            }
        }
        11 => {
            let n = varint(b, p);
            if n > 0 {
                let kv = b[*p];
                *p += 1;
                for _ in 0..n {
                    skip(b, p, kv >> 4);
                    skip(b, p, kv & 15);
                }
            }
        }
        12 => loop {
            let h = b[*p];
            *p += 1;
            if h == 0 {
                break;
            }
            if h >> 4 == 0 {
                varint(b, p);
            }
            skip(b, p, h & 15);
        },
        _ => panic!("thrift type {t}"),
    }
}

/// The page header at `b[start..]`: its length, the page's compressed size, and the position
/// right after the value of field 3 (compressed_page_size), where field 4 (crc) belongs.
fn page_header(b: &[u8], start: usize) -> (usize, usize, usize) {
    let (mut p, mut id, mut size, mut after3) = (start, 0u8, 0usize, 0usize);
    loop {
        let h = b[p];
        p += 1;
        if h == 0 {
            break;
        }
        assert!(h >> 4 > 0, "short-form field headers only");
        id += h >> 4;
        if id == 3 {
            let z = varint(b, &mut p);
            size = ((z >> 1) as i64 ^ -((z & 1) as i64)) as usize;
            after3 = p;
        } else {
            skip(b, &mut p, h & 15);
        }
    }
    (p - start, size, after3)
}

/// Rewrites the Parquet file `src`: with a CRC32 in every page header when `crc` (what a
/// writer with page checksums stores; this crate's writer stores none), and the codec named
/// in the footer of column `codec.0` replaced by `codec.1`, and the row count of every row
/// group replaced by `rows`. Returns the file and, per column,
/// the byte range of the data of its first page.
fn rewrite(
    src: &std::path::Path,
    crc: bool,
    codec: Option<(&str, parquet::basic::Compression)>,
    rows: Option<i64>,
) -> (
    Vec<u8>,
    std::collections::BTreeMap<String, std::ops::Range<usize>>,
) {
    use parquet::file::metadata::ParquetMetaDataWriter;
    use parquet::file::reader::{FileReader, SerializedFileReader};
    let bytes = std::fs::read(src).unwrap();
    let bytes = bytes.as_slice();
    let md = SerializedFileReader::new(std::fs::File::open(src).unwrap())
        .unwrap()
        .metadata()
        .clone();
    let mut out = b"PAR1".to_vec();
    let mut first_page = std::collections::BTreeMap::new();
    let mut groups = Vec::new();
    for rg in md.row_groups() {
        let mut cols = Vec::new();
        let rg_start = out.len();
        for col in rg.columns() {
            let (start, len) = col.byte_range();
            let (start, end) = (start as usize, (start + len) as usize);
            let mut moved = std::collections::BTreeMap::new();
            let new_start = out.len();
            let mut p = start;
            while p < end {
                let (hlen, size, after3) = page_header(bytes, p);
                moved.insert(p as i64, out.len() as i64);
                let data = &bytes[p + hlen..p + hlen + size];
                if crc {
                    out.extend_from_slice(&bytes[p..after3]);
                    out.push(0x15); // field 4 (delta 1), i32
                    let c = crc32(data) as i32;
                    let mut z = ((c << 1) ^ (c >> 31)) as u32;
                    while z >= 0x80 {
                        out.push((z as u8 & 0x7f) | 0x80);
                        z >>= 7;
                    }
                    out.push(z as u8);
                    let next = bytes[after3];
                    assert!(next >> 4 >= 2, "the field after 3 is 5 or later");
                    out.push(next - 0x10);
                    out.extend_from_slice(&bytes[after3 + 1..p + hlen]);
                } else {
                    out.extend_from_slice(&bytes[p..p + hlen]);
                }
                first_page
                    .entry(col.column_descr().name().to_string())
                    .or_insert(out.len()..out.len() + size);
                out.extend_from_slice(data);
                p += hlen + size;
            }
            let mut b = col
                .clone()
                .into_builder()
                .set_data_page_offset(moved[&col.data_page_offset()])
                .set_dictionary_page_offset(col.dictionary_page_offset().map(|d| moved[&d]))
                .set_total_compressed_size((out.len() - new_start) as i64);
            if let Some((name, c)) = codec
                && col.column_descr().name() == name
            {
                b = b.set_compression(c);
            }
            cols.push(b.build().unwrap());
        }
        groups.push(
            rg.clone()
                .into_builder()
                .set_column_metadata(cols)
                .set_file_offset(rg_start as i64)
                .set_num_rows(rows.unwrap_or(rg.num_rows()))
                .build()
                .unwrap(),
        );
    }
    let md = md.into_builder().set_row_groups(groups).build();
    ParquetMetaDataWriter::new(&mut out, &md).finish().unwrap();
    (out, first_page)
}

#[test]
fn parquet_page_checksums_are_verified_and_a_flipped_byte_names_its_column() {
    use parquet::basic::Compression;
    use parquet::file::properties::{EnabledStatistics, WriterProperties};
    // The reference CRC: CRC-32 of "123456789" is 0xCBF43926.
    assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    let doc = read(&example()).unwrap();
    let dir = temp_dir("crc");
    let plain = dir.join("plain.parquet");
    // Uncompressed pages: a flipped byte still decodes, so only the checksum can tell.
    let props = WriterProperties::builder()
        .set_compression(Compression::UNCOMPRESSED)
        .set_statistics_enabled(EnabledStatistics::Chunk)
        .set_offset_index_disabled(true)
        .build();
    rins_mvm::parquet::write_with(&plain, &doc, props).unwrap();
    let (with_crc, pages) = rewrite(&plain, true, None, None);
    assert_eq!(pages.len(), doc.columns.len() + doc.labels.len());
    let good = dir.join("crc.parquet");
    std::fs::write(&good, &with_crc).unwrap();
    // The checksums are right: the file reads as the CSV.
    let m = read(&good).unwrap();
    assert_eq!(m.columns, doc.columns);
    assert_eq!(m.labels, doc.labels);
    // One flipped bit in the first data page of dv_y_mps: refused, naming the file, the
    // column and the rows of its row group.
    let mut bad = with_crc.clone();
    let r = pages["dv_y_mps"].clone();
    bad[r.start + (r.end - r.start) / 2] ^= 0x04;
    let bad_path = dir.join("flipped.parquet");
    std::fs::write(&bad_path, &bad).unwrap();
    let e = read(&bad_path).expect_err("checksum");
    assert_eq!(e.source_name, bad_path.display().to_string());
    assert_eq!((e.row, e.column.as_str()), (1, "dv_y_mps"), "{e}");
    assert!(e.message.contains("checksum (CRC32) does not match"), "{e}");
    assert!(
        e.message.contains(&format!("rows 1 to {}", doc.rows)),
        "{e}"
    );
    // The same flip without checksums decodes to another number: only the range checks stand
    // between it and the comparison.
    let (no_crc, pages) = rewrite(&plain, false, None, None);
    let mut flipped = no_crc.clone();
    let r = pages["dv_y_mps"].clone();
    flipped[r.start + (r.end - r.start) / 2] ^= 0x04;
    std::fs::write(&bad_path, &flipped).unwrap();
    match read(&bad_path) {
        Ok(m) => assert_ne!(m.columns["dv_y_mps"], doc.columns["dv_y_mps"]),
        Err(e) => assert_eq!(e.column, "dv_y_mps", "{e}"),
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_codec_the_reader_lacks_is_named_with_its_own_column() {
    use parquet::basic::{BrotliLevel, Compression};
    let doc = read(&example()).unwrap();
    let dir = temp_dir("brotli");
    let plain = dir.join("plain.parquet");
    rins_mvm::parquet::write(&plain, &doc).unwrap();
    // The footer says one column (not the first) is Brotli.
    let (b, _) = rewrite(
        &plain,
        false,
        Some((
            "temp_housing_c",
            Compression::BROTLI(BrotliLevel::default()),
        )),
        None,
    );
    let path = dir.join("brotli.parquet");
    std::fs::write(&path, &b).unwrap();
    let e = read(&path).expect_err("brotli");
    assert_eq!((e.row, e.column.as_str()), (0, "temp_housing_c"), "{e}");
    assert!(
        e.message.contains("BROTLI")
            && e.message.contains("ZSTD")
            && !e.message.contains("Disabled"),
        "{e}"
    );
    // Unchanged, the rewritten file reads as the original (the rewrite itself is sound).
    let (same, _) = rewrite(&plain, false, None, None);
    std::fs::write(&path, &same).unwrap();
    assert_eq!(read(&path).unwrap().columns, doc.columns);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_page_that_does_not_decompress_is_blamed_on_its_own_column() {
    use parquet::basic::{Compression, GzipLevel, ZstdLevel};
    use parquet::file::properties::{EnabledStatistics, WriterProperties};
    let doc = read(&example()).unwrap();
    let dir = temp_dir("codec-error");
    for (name, c, magic) in [
        (
            "zstd",
            Compression::ZSTD(ZstdLevel::default()),
            0xFD2F_B528u32,
        ),
        ("gzip", Compression::GZIP(GzipLevel::default()), 0x0008_8B1F),
    ] {
        let path = dir.join(format!("{name}.parquet"));
        let props = WriterProperties::builder()
            .set_compression(c)
            .set_statistics_enabled(EnabledStatistics::Chunk)
            .set_offset_index_disabled(true)
            .build();
        rins_mvm::parquet::write_with(&path, &doc, props).unwrap();
        let (mut b, pages) = rewrite(&path, false, None, None);
        // The page starts with the codec's frame magic; break it in one column (not the first).
        let r = pages["dv_x_mps"].clone();
        let head = u32::from_le_bytes(b[r.start..r.start + 4].try_into().unwrap());
        assert_eq!(
            head & if name == "gzip" { 0x00FF_FFFF } else { !0 },
            magic,
            "{name}"
        );
        b[r.start] ^= 0xFF;
        std::fs::write(&path, &b).unwrap();
        let e = read(&path).expect_err("not decodable");
        assert_eq!((e.row, e.column.as_str()), (1, "dv_x_mps"), "{name}: {e}");
        assert!(e.message.contains("row group 0"), "{name}: {e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_footer_that_claims_more_rows_than_the_pages_hold_is_refused_without_allocating_them() {
    let doc = read(&example()).unwrap();
    let dir = temp_dir("rows");
    let plain = dir.join("plain.parquet");
    rins_mvm::parquet::write(&plain, &doc).unwrap();
    // 2^45 rows (a 256 TiB column if allocated up front), then one row more than the pages hold.
    for rows in [1i64 << 45, doc.rows as i64 + 1] {
        let (b, _) = rewrite(&plain, false, None, Some(rows));
        let path = dir.join("rows.parquet");
        std::fs::write(&path, &b).unwrap();
        let e = read(&path).expect_err("rows missing");
        assert_eq!(e.source_name, path.display().to_string(), "{e}");
        assert!(e.message.contains(&format!("{rows} rows")), "{rows}: {e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
