//! A measurement file that is not text is refused with the file byte offset and the data row of
//! the first bad byte, also past the first 64 MB piece the reader parses at a time.

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
    // Rows of 40 to 47 bytes: the bad one is past the first piece of 64 MB.
    let offset = check("large", 1_700_000, 1_650_000);
    assert!(offset > 64 << 20, "{offset}");
}
