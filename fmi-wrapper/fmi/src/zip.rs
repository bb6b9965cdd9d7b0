//! `.fmu` archives through the maintained `zip` crate: stored and deflated entries (method 0
//! and 8, what FMI tools and `zip`/`7z` write), read back with their CRC checked. Written
//! archives are reproducible: every entry carries the fixed timestamp 1980-01-01 00:00 and no
//! extra fields, so the same entries give the same bytes on every build.

use std::io::{self, Cursor, Read, Write};

use ::zip::result::ZipError;
use ::zip::write::SimpleFileOptions;
use ::zip::{CompressionMethod, DateTime, ZipArchive, ZipWriter};

/// How [`write`] stores the entries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compression {
    /// Method 0: the bytes as they are.
    Stored,
    /// Method 8 (deflate, default level): how FMUs are usually packaged.
    Deflated,
}

fn io_err(context: &str, e: ZipError) -> io::Error {
    match e {
        ZipError::Io(e) => io::Error::new(e.kind(), format!("{context}: {e}")),
        e => io::Error::new(io::ErrorKind::InvalidData, format!("{context}: {e}")),
    }
}

/// Writes `entries` (path, bytes) as a ZIP archive with `compression`, the fixed timestamp
/// 1980-01-01 00:00 and Unix modes (0755 for `.so` binaries, 0644 otherwise), so the same
/// inputs give the same bytes.
pub fn write(entries: &[(String, Vec<u8>)], compression: Compression) -> io::Result<Vec<u8>> {
    let method = match compression {
        Compression::Stored => CompressionMethod::Stored,
        Compression::Deflated => CompressionMethod::Deflated,
    };
    let mut z = ZipWriter::new(Cursor::new(Vec::new()));
    for (name, data) in entries {
        let mode = if name.ends_with(".so") { 0o755 } else { 0o644 };
        let options = SimpleFileOptions::default()
            .compression_method(method)
            .last_modified_time(DateTime::default())
            .unix_permissions(mode)
            .large_file(data.len() as u64 >= u64::from(u32::MAX));
        z.start_file(name.as_str(), options)
            .map_err(|e| io_err(name, e))?;
        z.write_all(data)?;
    }
    Ok(z.finish().map_err(|e| io_err("ZIP", e))?.into_inner())
}

/// Reads every file entry of a ZIP archive, stored or deflated (directories skipped), checking
/// each CRC. An entry of another method, or whose path would leave the folder it is unpacked
/// into (`..`, an absolute path), is refused naming the entry.
pub fn read(bytes: &[u8]) -> io::Result<Vec<(String, Vec<u8>)>> {
    let mut archive =
        ZipArchive::new(Cursor::new(bytes)).map_err(|e| io_err("not a readable ZIP archive", e))?;
    let mut out = Vec::with_capacity(archive.len());
    for i in 0..archive.len() {
        let f = archive
            .by_index_raw(i)
            .map_err(|e| io_err(&format!("ZIP entry {i}"), e))?;
        let name = f
            .name()
            .map_err(|e| io_err(&format!("ZIP entry {i}"), e))?
            .into_owned();
        if f.is_dir() {
            continue;
        }
        let method = f.compression();
        if !matches!(
            method,
            CompressionMethod::Stored | CompressionMethod::Deflated
        ) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!(
                    "{name}: compression method {method} is not supported (stored, method 0, and deflate, method 8, are)"
                ),
            ));
        }
        if f.enclosed_name().is_none() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!("{name}: the entry's path leaves the folder it is unpacked into"),
            ));
        }
        drop(f);
        let mut f = archive.by_index(i).map_err(|e| io_err(&name, e))?;
        let mut data = Vec::with_capacity(f.size() as usize);
        f.read_to_end(&mut data)
            .map_err(|e| io::Error::new(e.kind(), format!("{name}: {e}")))?;
        out.push((name, data));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries() -> Vec<(String, Vec<u8>)> {
        // Compressible text and incompressible bytes (a 64-bit LCG, 4 KiB).
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let noise: Vec<u8> = (0..4096)
            .map(|_| {
                x = x
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                (x >> 56) as u8
            })
            .collect();
        vec![
            ("modelDescription.xml".into(), b"<fmi/>\n".repeat(500)),
            ("binaries/linux64/m.so".into(), noise),
            ("documentation/empty.txt".into(), Vec::new()),
        ]
    }

    #[test]
    fn both_methods_round_trip() {
        let e = entries();
        for c in [Compression::Stored, Compression::Deflated] {
            assert_eq!(read(&write(&e, c).unwrap()).unwrap(), e, "{c:?}");
        }
        // Deflate shrinks the repeated text: 3500 bytes stored, far fewer deflated.
        let stored = write(&e, Compression::Stored).unwrap().len();
        let deflated = write(&e, Compression::Deflated).unwrap().len();
        assert!(deflated + 3000 < stored, "{deflated} vs {stored}");
    }

    #[test]
    fn archives_are_reproducible_with_fixed_timestamps_and_modes() {
        for c in [Compression::Stored, Compression::Deflated] {
            let a = write(&entries(), c).unwrap();
            assert_eq!(a, write(&entries(), c).unwrap(), "{c:?}");
            let mut z = ZipArchive::new(Cursor::new(&a)).unwrap();
            for i in 0..z.len() {
                let f = z.by_index(i).unwrap();
                let t = f.last_modified().unwrap();
                assert_eq!(
                    (
                        t.year(),
                        t.month(),
                        t.day(),
                        t.hour(),
                        t.minute(),
                        t.second()
                    ),
                    (1980, 1, 1, 0, 0, 0)
                );
                let want = if f.name().unwrap().ends_with(".so") {
                    0o100755
                } else {
                    0o100644
                };
                assert_eq!(f.unix_mode(), Some(want));
            }
        }
    }

    #[test]
    fn corruption_and_escaping_paths_are_refused_by_name() {
        let e = vec![("a/b.txt".to_string(), b"hello".to_vec())];
        let z = write(&e, Compression::Stored).unwrap();
        // Local header (30 bytes) and the 7-byte name, then "hello".
        assert_eq!(&z[37..42], b"hello");
        let mut bad = z.clone();
        bad[37] ^= 1;
        let msg = read(&bad).unwrap_err().to_string();
        assert!(
            msg.starts_with("a/b.txt:") && msg.contains("checksum"),
            "{msg}"
        );

        let up = write(
            &[("../evil.so".to_string(), vec![1])],
            Compression::Deflated,
        )
        .unwrap();
        let msg = read(&up).unwrap_err().to_string();
        assert!(
            msg.starts_with("../evil.so: the entry's path leaves"),
            "{msg}"
        );

        // Method 12 (bzip2) in the local and central headers: named, with what is supported.
        let mut bz = z.clone();
        bz[8] = 12;
        let cd = (0..bz.len() - 4)
            .find(|&p| bz[p..p + 4] == [0x50, 0x4b, 0x01, 0x02])
            .unwrap();
        bz[cd + 10] = 12;
        let msg = read(&bz).unwrap_err().to_string();
        assert!(
            msg.starts_with("a/b.txt: compression method") && msg.contains("deflate, method 8"),
            "{msg}"
        );

        let msg = read(b"not a zip").unwrap_err().to_string();
        assert!(msg.starts_with("not a readable ZIP archive"), "{msg}");
    }
}
