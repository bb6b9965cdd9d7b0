//! Property test of the measurement reader (issue 16): arbitrary bytes and mutated copies of the
//! shipped example never panic, and every refusal names the file and where: a data row within
//! the file and a column of its header (or the missing column), the header row, or the byte
//! offset of the first byte that is not UTF-8. A single corrupted field is reported at exactly
//! its row and column.
//!
//! Fixed seeds (ChaCha8): a failure prints the seed and case number to replay.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rins_mvm::csv::parse;
use rins_mvm::measurement::MeasurementError;
use rins_mvm::reader::read;

const SEED: u64 = 0x5eed_0016;
/// Mutated copies of the example, parsed from text.
const MUTATED_CASES: usize = 6000;
/// Single corrupted fields, checked for their exact row and column.
const FIELD_CASES: usize = 4000;
/// Random byte files read through `read` (each call streams through a 64 MB buffer, so fewer).
const FILE_CASES: usize = 100;

fn example() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../docs/examples/measurement-example.csv"
    ))
    .unwrap()
}

/// A line that carries data or the header (not blank, not a comment), as the format says.
fn is_data(line: &str) -> bool {
    let t = line.trim();
    !t.is_empty() && !t.starts_with('#')
}

/// The header's columns and the number of data rows after it.
fn shape(text: &str) -> (Vec<String>, usize) {
    let mut lines = text.lines().filter(|l| is_data(l));
    let header = lines
        .next()
        .map(|h| h.split(',').map(|s| s.trim().to_string()).collect())
        .unwrap_or_default();
    (header, lines.count())
}

/// Checks a refusal of `bytes` names the file and a place inside it.
fn check_refusal(e: &MeasurementError, bytes: &[u8], name: &str, ctx: &str) {
    let text = e.to_string();
    assert_eq!(e.source_name, name, "{ctx}: {text}");
    // Where, as the one location rule writes it: the whole file, the header's column, the row.
    assert!(
        text.starts_with(&format!(
            "{name}: {}: ",
            rins_plant::message::file_location(e.row, &e.column)
        )),
        "{ctx}: {text}"
    );
    if let Err(u) = std::str::from_utf8(bytes) {
        // The first bad byte, by offset in the file.
        let at = format!("at byte {} of the file", u.valid_up_to());
        assert!(e.message.contains(&at), "{ctx}: {text} lacks {at:?}");
        return;
    }
    let source = std::str::from_utf8(bytes).expect("checked");
    let (header, rows) = shape(source);
    assert!(e.row <= rows, "{ctx}: row {} of {rows}: {text}", e.row);
    if header.is_empty() {
        assert!(e.message.contains("empty file"), "{ctx}: {text}");
        return;
    }
    if e.column.is_empty() && e.row == 0 {
        // An error of the whole file: too few rows, or a line too long to be one.
        assert!(
            e.message.contains("need at least two data rows")
                || e.message.contains("longer than the limit"),
            "{ctx}: {text}"
        );
        return;
    }
    if e.column.is_empty() {
        // A row with more fields than the header (a short one names its first missing
        // column): the row and both counts are named.
        assert!(
            e.message.contains(&format!("header has {}", header.len())),
            "{ctx}: no column in {text}"
        );
        return;
    }
    if e.row > 0 {
        assert!(
            header.contains(&e.column),
            "{ctx}: column {:?} is not in the header {header:?}: {text}",
            e.column
        );
    }
}

fn parse_case(bytes: &[u8], ctx: &str) -> bool {
    let name = "fuzz.csv";
    let text = String::from_utf8_lossy(bytes);
    match std::panic::catch_unwind(|| parse(&text, name)) {
        Ok(Ok(_)) => true,
        Ok(Err(e)) => {
            check_refusal(&e, text.as_bytes(), name, ctx);
            false
        }
        Err(_) => panic!("{ctx}: the reader panicked"),
    }
}

fn mutate(rng: &mut ChaCha8Rng, good: &str) -> Vec<u8> {
    let mut b = good.as_bytes().to_vec();
    for _ in 0..rng.random_range(1..4) {
        let k = rng.random_range(0..b.len());
        match rng.random_range(0..5) {
            0 => b[k] = *b",\n.-e0#".get(rng.random_range(0..8)).unwrap_or(&b'x'),
            1 => {
                b.remove(k);
            }
            2 => {
                let j = rng.random_range(k..b.len().min(k + 400));
                b.drain(k..j);
            }
            3 => b.truncate(k),
            _ => {
                let token = ["nan", "inf", "-inf", "1e999", ",", "\n", "", "\"a,b\""]
                    [rng.random_range(0..8)];
                b.splice(k..k, token.bytes());
            }
        }
        if b.is_empty() {
            break;
        }
    }
    b
}

#[test]
fn mutated_example_files_never_panic_and_refusals_name_where() {
    let good = example();
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let mut accepted = 0;
    for case in 0..MUTATED_CASES {
        let bytes = mutate(&mut rng, &good);
        accepted += parse_case(&bytes, &format!("seed {SEED:#x}, case {case}")) as usize;
    }
    assert!(accepted < MUTATED_CASES, "every mutation accepted");
}

#[test]
fn a_corrupted_field_is_reported_at_its_row_and_column() {
    let good = example();
    let (header, rows) = shape(&good);
    let mut rng = ChaCha8Rng::seed_from_u64(SEED ^ 2);
    let lines: Vec<&str> = good.lines().collect();
    let first_data = lines.iter().position(|l| is_data(l)).unwrap() + 1;
    // Numeric columns: every column but the labels.
    let numeric: Vec<usize> = (0..header.len())
        .filter(|&i| !["run", "segment", "position"].contains(&header[i].as_str()))
        .collect();
    for case in 0..FIELD_CASES {
        let ctx = format!("seed {:#x}, case {case}", SEED ^ 2);
        let row = rng.random_range(1..=rows);
        let col = numeric[rng.random_range(0..numeric.len())];
        let bad = [
            "abc", "1.2.3", "0x10", "--1", "1e", "nan", "NaN", "inf", "-inf", "1e999",
        ][rng.random_range(0..10)];
        let mut out: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        let mut fields: Vec<&str> = lines[first_data + row - 1].split(',').collect();
        fields[col] = bad;
        out[first_data + row - 1] = fields.join(",");
        let text = out.join("\n");
        let e = parse(&text, "f.csv").expect_err(&format!("{ctx}: {bad} accepted"));
        assert_eq!(
            (e.row, e.column.as_str()),
            (row, header[col].as_str()),
            "{ctx}: {bad:?} at row {row}, column {}: {e}",
            header[col]
        );
    }
}

#[test]
fn random_byte_files_never_panic_and_refusals_name_where() {
    let good = example();
    let mut rng = ChaCha8Rng::seed_from_u64(SEED ^ 1);
    let dir = std::env::temp_dir().join(format!("rins-reader-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("m.csv");
    let name = path.display().to_string();
    for case in 0..FILE_CASES {
        let ctx = format!("seed {:#x}, case {case}", SEED ^ 1);
        // Random bytes; half after a valid header and some rows, so the row reader sees them.
        let mut bytes = Vec::new();
        if case % 2 == 1 {
            let cut = rng.random_range(0..good.len() / 4);
            bytes.extend_from_slice(&good.as_bytes()[..cut]);
        }
        let n = rng.random_range(0..2000);
        bytes.extend((0..n).map(|_| rng.random::<u8>()));
        std::fs::write(&path, &bytes).unwrap();
        match std::panic::catch_unwind(|| read(&path)) {
            Ok(Ok(_)) => {}
            Ok(Err(e)) => check_refusal(&e, &bytes, &name, &ctx),
            Err(_) => panic!("{ctx}: the reader panicked"),
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Parquet files with one to three random bits flipped (Snappy; case 305 made the `parquet` crate
/// panic in its bit reader before the reader caught it).
const PARQUET_CASES: usize = 2000;

#[test]
fn parquet_files_with_flipped_bytes_never_panic_and_refusals_name_the_file() {
    let good = read(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../docs/examples/measurement-example.csv"
    )))
    .unwrap();
    let dir = std::env::temp_dir().join(format!("rins-pq-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let src = dir.join("good.parquet");
    rins_mvm::parquet::write(&src, &good).unwrap();
    let bytes = std::fs::read(&src).unwrap();
    let path = dir.join("m.parquet");
    let name = path.display().to_string();
    let mut rng = ChaCha8Rng::seed_from_u64(SEED ^ 3);
    let (mut refused, mut same) = (0, 0);
    for case in 0..PARQUET_CASES {
        let ctx = format!("seed {:#x}, case {case}", SEED ^ 3);
        let mut b = bytes.clone();
        // Past the leading magic, so the file is still taken for Parquet.
        for _ in 0..rng.random_range(1..4) {
            let k = rng.random_range(4..b.len());
            b[k] ^= 1 << rng.random_range(0..8);
        }
        std::fs::write(&path, &b).unwrap();
        match std::panic::catch_unwind(|| read(&path)) {
            Ok(Ok(m)) => same += usize::from(m.columns == good.columns),
            Ok(Err(e)) => {
                refused += 1;
                assert_eq!(e.source_name, name, "{ctx}: {e}");
                assert!(e.row <= good.rows, "{ctx}: {e}");
            }
            Err(_) => panic!("{ctx}: the Parquet reader panicked"),
        }
    }
    assert!(
        refused > 0,
        "every flip accepted ({same} read as the original)"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
