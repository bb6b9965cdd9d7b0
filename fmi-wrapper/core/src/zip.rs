//! A minimal ZIP writer and reader (stored entries, no compression): enough to package and
//! unpack FMUs without another dependency. Readers that inflate (FMPy, every FMI tool) read
//! stored entries; our reader refuses compressed entries with a clear message.

use std::io;

const fn crc_table() -> [u32; 256] {
    let mut t = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut c = i as u32;
        let mut k = 0;
        while k < 8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
            k += 1;
        }
        t[i] = c;
        i += 1;
    }
    t
}

static CRC: [u32; 256] = crc_table();

/// CRC-32 (IEEE) of `data`.
pub fn crc32(data: &[u8]) -> u32 {
    !data.iter().fold(!0u32, |c, b| {
        CRC[((c ^ *b as u32) & 0xff) as usize] ^ (c >> 8)
    })
}

/// Writes `entries` (path, bytes) as a ZIP archive with stored entries and a fixed timestamp
/// (1980-01-01), so the same inputs give the same bytes.
pub fn write(entries: &[(String, Vec<u8>)]) -> io::Result<Vec<u8>> {
    let mut out = Vec::new();
    let mut central = Vec::new();
    for (name, data) in entries {
        if data.len() > u32::MAX as usize || name.len() > u16::MAX as usize {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("{name}: too large for a ZIP32 entry"),
            ));
        }
        let offset = out.len() as u32;
        let crc = crc32(data);
        let (size, nlen) = (data.len() as u32, name.len() as u16);
        let common = |v: &mut Vec<u8>| {
            v.extend_from_slice(&20u16.to_le_bytes()); // version needed
            v.extend_from_slice(&0u16.to_le_bytes()); // flags
            v.extend_from_slice(&0u16.to_le_bytes()); // stored
            v.extend_from_slice(&0u16.to_le_bytes()); // time
            v.extend_from_slice(&0x21u16.to_le_bytes()); // date 1980-01-01
            v.extend_from_slice(&crc.to_le_bytes());
            v.extend_from_slice(&size.to_le_bytes());
            v.extend_from_slice(&size.to_le_bytes());
            v.extend_from_slice(&nlen.to_le_bytes());
            v.extend_from_slice(&0u16.to_le_bytes()); // extra length
        };
        out.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        common(&mut out);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(data);

        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&0x0314u16.to_le_bytes()); // made by: Unix, 2.0
        common(&mut central);
        central.extend_from_slice(&0u16.to_le_bytes()); // comment length
        central.extend_from_slice(&0u16.to_le_bytes()); // disk
        central.extend_from_slice(&0u16.to_le_bytes()); // internal attributes
        let mode: u32 = if name.ends_with(".so") {
            0o100755
        } else {
            0o100644
        };
        central.extend_from_slice(&(mode << 16).to_le_bytes());
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let cd_offset = out.len() as u32;
    let cd_size = central.len() as u32;
    out.extend_from_slice(&central);
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    out.extend_from_slice(&[0; 4]); // disk numbers
    let n = entries.len() as u16;
    out.extend_from_slice(&n.to_le_bytes());
    out.extend_from_slice(&n.to_le_bytes());
    out.extend_from_slice(&cd_size.to_le_bytes());
    out.extend_from_slice(&cd_offset.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    Ok(out)
}

fn bad(msg: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, msg)
}

/// Reads every entry of a ZIP archive of stored entries (directories skipped).
pub fn read(bytes: &[u8]) -> io::Result<Vec<(String, Vec<u8>)>> {
    let u16_at = |p: usize| {
        bytes
            .get(p..p + 2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]) as usize)
    };
    let u32_at = |p: usize| {
        bytes
            .get(p..p + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let eocd = (0..bytes.len().saturating_sub(21))
        .rev()
        .find(|&p| u32_at(p) == Some(0x0605_4b50))
        .ok_or_else(|| bad("not a ZIP archive (no end of central directory)".into()))?;
    let n = u16_at(eocd + 10).ok_or_else(|| bad("truncated ZIP".into()))?;
    let mut p = u32_at(eocd + 16).ok_or_else(|| bad("truncated ZIP".into()))?;
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        let field =
            |q: Option<usize>| q.ok_or_else(|| bad("truncated ZIP central directory".into()));
        if field(u32_at(p))? != 0x0201_4b50 {
            return Err(bad(format!("bad central directory entry at byte {p}")));
        }
        let method = field(u16_at(p + 10))?;
        let crc = field(u32_at(p + 16))? as u32;
        let csize = field(u32_at(p + 20))?;
        let (nlen, xlen, clen) = (
            field(u16_at(p + 28))?,
            field(u16_at(p + 30))?,
            field(u16_at(p + 32))?,
        );
        let local = field(u32_at(p + 42))?;
        let name = String::from_utf8_lossy(
            bytes
                .get(p + 46..p + 46 + nlen)
                .ok_or_else(|| bad("truncated name".into()))?,
        )
        .into_owned();
        p += 46 + nlen + xlen + clen;
        if name.ends_with('/') {
            continue;
        }
        if method != 0 {
            return Err(bad(format!(
                "{name}: compressed entries (method {method}) are not supported; repack with `zip -0`"
            )));
        }
        let lstart = local + 30 + field(u16_at(local + 26))? + field(u16_at(local + 28))?;
        let data = bytes
            .get(lstart..lstart + csize)
            .ok_or_else(|| bad(format!("{name}: truncated data")))?
            .to_vec();
        if crc32(&data) != crc {
            return Err(bad(format!("{name}: CRC mismatch")));
        }
        out.push((name, data));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc_matches_the_standard_check_value() {
        // The CRC-32 check value of "123456789" (ISO 3309 / ITU-T V.42).
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }

    #[test]
    fn round_trip_and_corruption_detected() {
        let entries = vec![
            ("a/b.txt".to_string(), b"hello".to_vec()),
            ("c.so".to_string(), vec![0u8, 1, 2, 255]),
        ];
        let z = write(&entries).unwrap();
        assert_eq!(read(&z).unwrap(), entries);
        let mut bad = z.clone();
        bad[30 + 7] ^= 1; // first byte of "hello"
        assert!(read(&bad).unwrap_err().to_string().contains("CRC"));
    }
}
