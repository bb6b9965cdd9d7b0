//! Finds the line of a dotted key path in TOML text, so range errors can name it.

/// 1-based line of `path` (e.g. `sensor.gyro.bias.dph[1]`) in `text`, if it is written there.
/// Handles `[section]` headers and dotted keys; values that came from defaults return `None`.
pub fn locate_key(text: &str, path: &str) -> Option<usize> {
    let path = path.split('[').next().unwrap_or(path);
    let (section, key) = match path.rsplit_once('.') {
        Some((s, k)) => (s, k),
        None => ("", path),
    };
    let mut current = String::new();
    for (n, line) in text.lines().enumerate() {
        let l = line.trim();
        if let Some(h) = l.strip_prefix('[') {
            current = h
                .trim_start_matches('[')
                .trim_end_matches(']')
                .trim()
                .to_string();
            continue;
        }
        let Some((k, _)) = l.split_once('=') else {
            continue;
        };
        let full = if current.is_empty() {
            k.trim().to_string()
        } else {
            format!("{current}.{}", k.trim())
        };
        let want = if section.is_empty() {
            key.to_string()
        } else {
            format!("{section}.{key}")
        };
        if full == want {
            return Some(n + 1);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_keys_under_sections_and_dotted() {
        let t = "[scenario]\nname = \"x\"\n\n[sensor.gyro.bias]\nenabled = true\ndph = [1, 2, 3]\n[site]\nlat_deg = 99\n";
        assert_eq!(locate_key(t, "sensor.gyro.bias.dph[2]"), Some(6));
        assert_eq!(locate_key(t, "site.lat_deg"), Some(8));
        assert_eq!(locate_key(t, "site.lon_deg"), None);
    }
}
