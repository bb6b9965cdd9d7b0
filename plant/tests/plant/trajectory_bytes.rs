//! A trajectory file that is not CSV text (issue 44): zero bytes, random bytes, `/dev/zero`, a
//! NUL inside a row, a line past the limit. Each is refused at its first bad line with the file
//! and line named, in bounded memory (`/dev/zero` is also read under a 1 GiB address-space
//! limit, where reading it whole ended in an allocation failure that aborted the process).

use rand::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rins_plant::carrier::Trajectory;
use rins_plant::carrier::trajectory_text::{MAX_LINE, read_text};

/// `bytes` in a file of this test's own (`tag`), its path returned.
fn file(tag: &str, bytes: &[u8]) -> std::path::PathBuf {
    let p = std::env::temp_dir().join(format!("rins-trajectory-{tag}-{}.csv", std::process::id()));
    std::fs::write(&p, bytes).unwrap();
    p
}

/// The error of reading `path` as a trajectory, as the user sees it.
fn refusal(path: &str) -> String {
    Trajectory::read(path)
        .expect_err("must be refused")
        .to_string()
}

/// The quote of a line of zero bytes: its first 80 characters, escaped, and the cut.
fn zeros_quoted() -> String {
    format!("\"{}…\"", "\\0".repeat(80))
}

#[test]
fn a_file_of_zero_bytes_is_refused_at_its_first_line_by_the_line_limit() {
    let p = file("zeros", &vec![0u8; 200 << 10]);
    let name = p.display().to_string();
    assert_eq!(
        refusal(&name),
        format!(
            "{name}: the whole file: line 1: longer than the limit of 65536 bytes (not a trajectory row: a file without line breaks, or binary data); it starts {} (at byte 0 of the file)",
            zeros_quoted()
        )
    );
    let _ = std::fs::remove_file(&p);
}

#[test]
fn a_file_of_random_bytes_is_refused_naming_the_file_and_line() {
    let mut bytes = vec![0u8; 200 << 10];
    ChaCha8Rng::seed_from_u64(44).fill_bytes(&mut bytes);
    let p = file("random", &bytes);
    let name = p.display().to_string();
    assert_eq!(
        refusal(&name),
        format!("{name}: the whole file: line 1: not UTF-8 text: byte 0xfe at byte 0 of the file")
    );
    let _ = std::fs::remove_file(&p);
}

#[test]
fn a_nul_byte_in_a_row_is_refused_with_its_row_line_and_byte() {
    let text = b"# a comment line: not a row\nt_s,lat_deg,lon_deg,height_m,v_e_mps,v_n_mps,v_u_mps,q_cn_w,q_cn_x,q_cn_y,q_cn_z\n0,45,7,0,0,0,0,1,0,0,0\n0.01,45\0,7,0,0,0,0,1,0,0,0\n";
    let e = read_text(&text[..], "nul.csv").expect_err("must be refused");
    assert_eq!(
        e.to_string(),
        "nul.csv: row 2: line 4: a NUL byte at byte 139 of the file (not CSV text: binary data); the line starts \"0.01,45\\0,7,0,0,0,0,1,0,0,0\""
    );
    assert_eq!(text[139], 0);
}

#[test]
fn a_line_of_the_limit_is_read_and_one_byte_more_is_refused() {
    let mut text = vec![b'x'; MAX_LINE];
    text.push(b'\n');
    assert_eq!(
        read_text(&text[..], "limit.csv").unwrap().len(),
        MAX_LINE + 1
    );
    // Without its line break too (the file's last line).
    assert_eq!(
        read_text(&text[..MAX_LINE], "limit.csv").unwrap().len(),
        MAX_LINE
    );
    let mut longer = vec![b'x'; MAX_LINE + 1];
    longer.push(b'\n');
    let e = read_text(&longer[..], "long.csv").expect_err("one byte over the limit");
    assert!(
        e.message
            .starts_with("line 1: longer than the limit of 65536 bytes"),
        "{e}"
    );
}

/// The child of the next test: reads the file the parent names as a trajectory and prints the
/// error. Does nothing unless the parent set the variable.
#[test]
fn child_reads_a_trajectory_under_an_address_space_limit() {
    let Ok(path) = std::env::var("RINS_TRAJECTORY_UNDER_LIMIT") else {
        return;
    };
    println!("refused: {}", refusal(&path));
}

#[test]
fn dev_zero_is_refused_under_a_one_gib_address_space_limit_without_a_crash() {
    if !std::path::Path::new("/dev/zero").exists() {
        return;
    }
    // RLIMIT_AS through the shell's `ulimit -v` (KiB), then the test binary itself: reading
    // /dev/zero whole would reach the limit within a second and abort on the failed allocation.
    let out = std::process::Command::new("sh")
        .args([
            "-c",
            "ulimit -v 1048576 && exec \"$0\" --exact trajectory_bytes::child_reads_a_trajectory_under_an_address_space_limit --nocapture --test-threads=1",
        ])
        .arg(std::env::current_exe().unwrap())
        .env("RINS_TRAJECTORY_UNDER_LIMIT", "/dev/zero")
        .output()
        .unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(
        out.status.success(),
        "{:?}\nstdout: {stdout}\nstderr: {stderr}",
        out.status
    );
    let expected = format!(
        "refused: /dev/zero: the whole file: line 1: longer than the limit of 65536 bytes (not a trajectory row: a file without line breaks, or binary data); it starts {} (at byte 0 of the file)",
        zeros_quoted()
    );
    // The harness prints the test's name on the same line (--nocapture).
    assert!(
        stdout.contains(&expected),
        "stdout: {stdout}\nstderr: {stderr}"
    );
}
