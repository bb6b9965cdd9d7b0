//! Where a recording goes: `save:PATH.rrd`, `spawn` or `connect[:URL]`.

use std::path::PathBuf;
use std::str::FromStr;

/// The viewer's default gRPC proxy endpoint (`rerun` listens there when started without options).
pub const DEFAULT_CONNECT_URL: &str = "rerun+http://127.0.0.1:9876/proxy";

/// Destination of a recording, as given to `--rerun`.
#[derive(Clone, Debug, PartialEq)]
pub enum Target {
    /// Write an `.rrd` file.
    Save(PathBuf),
    /// Start a viewer (the `rerun` executable on PATH) and stream to it.
    Spawn,
    /// Stream to a running viewer at this gRPC proxy URL.
    Connect(String),
}

/// A `--rerun` value that is none of the accepted forms.
#[derive(Debug, PartialEq, thiserror::Error)]
#[error(
    "--rerun {given:?}: {why}; expected save:PATH.rrd, spawn, or connect[:URL] (default URL {DEFAULT_CONNECT_URL}, or HOST:PORT)"
)]
pub struct TargetError {
    given: String,
    why: &'static str,
}

impl FromStr for Target {
    type Err = TargetError;

    fn from_str(s: &str) -> Result<Self, TargetError> {
        let err = |why| TargetError {
            given: s.to_string(),
            why,
        };
        if s == "spawn" {
            return Ok(Target::Spawn);
        }
        if s == "connect" {
            return Ok(Target::Connect(DEFAULT_CONNECT_URL.to_string()));
        }
        if let Some(url) = s.strip_prefix("connect:") {
            if url.is_empty() {
                return Err(err("empty URL"));
            }
            // HOST:PORT is the short form of the proxy URL the viewer prints.
            let url = if url.contains("://") {
                url.to_string()
            } else {
                format!("rerun+http://{url}/proxy")
            };
            return Ok(Target::Connect(url));
        }
        if let Some(path) = s.strip_prefix("save:") {
            if !path.ends_with(".rrd") {
                return Err(err("the file name must end in .rrd"));
            }
            return Ok(Target::Save(PathBuf::from(path)));
        }
        Err(err("unknown destination"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_every_form_and_names_the_bad_one() {
        assert_eq!(
            "save:out/run.rrd".parse(),
            Ok(Target::Save("out/run.rrd".into()))
        );
        assert_eq!("spawn".parse(), Ok(Target::Spawn));
        assert_eq!(
            "connect".parse(),
            Ok(Target::Connect(DEFAULT_CONNECT_URL.into()))
        );
        assert_eq!(
            "connect:10.0.0.2:9876".parse(),
            Ok(Target::Connect("rerun+http://10.0.0.2:9876/proxy".into()))
        );
        assert_eq!(
            "connect:rerun+http://h:1/proxy".parse(),
            Ok(Target::Connect("rerun+http://h:1/proxy".into()))
        );
        let e = "save:out/run.csv"
            .parse::<Target>()
            .unwrap_err()
            .to_string();
        assert!(e.contains("out/run.csv") && e.contains(".rrd"), "{e}");
        assert!(
            "viewer"
                .parse::<Target>()
                .unwrap_err()
                .to_string()
                .contains("unknown destination")
        );
    }
}
