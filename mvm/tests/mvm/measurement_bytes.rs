//! A measurement file that is not text is refused with the file byte offset and the data row of
//! the first bad byte, also past the first piece (`csv::PIECE`) the reader parses at a time.

use std::io::Write;

use rins_mvm::reader::read;

const HEADER: &str = "t_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps,outer_deg,inner_deg,temp_gyro_x_c\n";

fn row(k: usize) -> String {
    format!(
        "{:.2},1e-6,2e-6,3e-6,0.0,0.0,0.98,0,0,30.1\n",
        (k + 1) as f64 * 0.01
    )
}

/// Writes `comment`, the header, `rows` rows with byte 0xFF put in place of the first byte of
/// row `bad_row` (1-based); returns the file's offset of that byte.
fn file_with_bad_byte(path: &std::path::Path, rows: usize, bad_row: usize) -> u64 {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    let comment = "# a comment line\n";
    f.write_all(comment.as_bytes()).unwrap();
    f.write_all(HEADER.as_bytes()).unwrap();
    let mut offset = (comment.len() + HEADER.len()) as u64;
    let mut bad = None;
    for k in 0..rows {
        let mut line = row(k).into_bytes();
        if k + 1 == bad_row {
            line[0] = 0xFF;
            bad = Some(offset);
        }
        offset += line.len() as u64;
        f.write_all(&line).unwrap();
    }
    f.flush().unwrap();
    bad.unwrap()
}

/// Reads the file and checks row and offset of the error; returns the offset.
fn check(tag: &str, rows: usize, bad_row: usize) -> u64 {
    let path = std::env::temp_dir().join(format!("rins-bytes-{tag}-{}.csv", std::process::id()));
    let offset = file_with_bad_byte(&path, rows, bad_row);
    let e = read(&path).expect_err("not text");
    let _ = std::fs::remove_file(&path);
    assert_eq!(e.row, bad_row, "{e}");
    assert!(
        e.message
            .contains(&format!("byte 0xff at byte {offset} of the file")),
        "{e}"
    );
    offset
}

#[test]
fn a_bad_byte_in_the_first_piece_names_its_row_and_file_offset() {
    check("small", 10, 4);
}

#[test]
fn a_bad_byte_in_the_header_is_row_0() {
    let path = std::env::temp_dir().join(format!("rins-bytes-header-{}.csv", std::process::id()));
    std::fs::write(&path, b"t_s,dtheta\xff_x_rad\n0.01,1\n").unwrap();
    let e = read(&path).expect_err("not text");
    let _ = std::fs::remove_file(&path);
    assert_eq!(e.row, 0, "{e}");
    assert!(e.message.contains("at byte 10 of the file"), "{e}");
}

#[test]
fn a_bad_byte_after_the_first_64_mb_names_its_row_and_file_offset() {
    // Rows of 40 to 47 bytes: the bad one is past the first piece.
    let offset = check("large", 1_700_000, 1_650_000);
    assert!(offset > rins_mvm::csv::PIECE as u64, "{offset}");
}

/// A reader that counts the bytes taken from `inner` and gives at most `chunk` per read (as a
/// pipe does).
struct Counted<R> {
    inner: R,
    taken: u64,
    chunk: usize,
}

impl<R: std::io::Read> std::io::Read for Counted<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = buf.len().min(self.chunk);
        let got = self.inner.read(&mut buf[..n])?;
        self.taken += got as u64;
        Ok(got)
    }
}

#[test]
fn an_endless_stream_without_line_breaks_stops_at_once_with_bounded_reading() {
    use std::io::Read;
    // 1 TB of NUL bytes, as /dev/zero: the reader takes one piece and stops.
    let piece = rins_mvm::csv::PIECE;
    let mut zeros = Counted {
        inner: std::io::repeat(0).take(1 << 40),
        taken: 0,
        chunk: usize::MAX,
    };
    let start = std::time::Instant::now();
    let e = rins_mvm::csv::read_from(&mut zeros, "zeros", None).expect_err("no lines");
    assert_eq!(e.row, 0, "{e}");
    assert!(
        e.message.contains(&format!("more than {piece} bytes")) && e.message.contains("65536"),
        "{e}"
    );
    // The start is quoted escaped and cut at 80 characters.
    assert!(
        e.message.contains(&format!("\"{}…\"", "\\0".repeat(80))),
        "{e}"
    );
    assert!(e.to_string().len() < 700, "{} bytes", e.to_string().len());
    assert!(
        zeros.taken <= piece as u64 + (64 << 10),
        "{} bytes read",
        zeros.taken
    );
    assert!(start.elapsed().as_secs() < 30, "{:?}", start.elapsed());
    // A 300 MB line after the header and a row: row 2, its byte offset, never echoed.
    let head = format!("{HEADER}{}", row(0));
    let mut long = Counted {
        inner: head.as_bytes().chain(std::io::repeat(b'7').take(300 << 20)),
        taken: 0,
        chunk: usize::MAX,
    };
    let e = rins_mvm::csv::read_from(&mut long, "long.csv", None).expect_err("long line");
    assert_eq!(e.row, 2, "{e}");
    assert!(
        e.message
            .contains(&format!("at byte {} of the file", head.len())),
        "{e}"
    );
    assert!(e.to_string().len() < 500, "{} bytes", e.to_string().len());
    assert!(
        long.taken <= rins_mvm::csv::PIECE as u64 + (64 << 10),
        "{} bytes read",
        long.taken
    );
    // The device itself, through `read` (Linux).
    let dev = std::path::Path::new("/dev/zero");
    if dev.exists() {
        let e = read(dev).expect_err("/dev/zero");
        assert!(
            e.to_string().starts_with("/dev/zero: the whole file: "),
            "{e}"
        );
        assert!(e.message.contains("more than"), "{e}");
    }
}

#[test]
fn a_file_read_from_a_pipe_in_small_pieces_is_the_file() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../docs/examples/measurement-example.csv"
    );
    let whole = read(std::path::Path::new(path)).unwrap();
    let text = std::fs::read(path).unwrap();
    for chunk in [1, 7, 4096] {
        let piped = Counted {
            inner: text.as_slice(),
            taken: 0,
            chunk,
        };
        let m = rins_mvm::csv::read_from(piped, "pipe", None).unwrap();
        assert_eq!(m.columns, whole.columns, "chunk {chunk}");
        assert_eq!(m.labels, whole.labels, "chunk {chunk}");
        assert_eq!(m.segments, whole.segments, "chunk {chunk}");
    }
}
