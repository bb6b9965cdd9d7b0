//! Scheme files: a rotation scheme with its name and where it comes from.
//!
//! ```toml
//! name = "sixteen-position"
//! reference = "Seo et al., Sensors 2022, 22, 8355, Eq. 5-7"
//! description = "Dual-axis 16-position scheme, 180 s dwells, 2 deg/s"
//!
//! [scheme]            # exactly the `[scheme]` table of a scenario file
//! kind = "sixteen-position"
//! rate_dps = 2.0
//! accel_dps2 = 20.0
//! dwell_s = 180.0
//! ```

use std::path::Path;

use rins_plant::PlantConfig;
use rins_plant::table::SchemeSpec;
use serde::{Deserialize, Serialize};

/// A rotation scheme as a file holds it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SchemeFile {
    /// Short name, used in tables and file names.
    pub name: String,
    /// Where the scheme comes from (paper, equation), or how it was made.
    #[serde(default)]
    pub reference: String,
    /// One line on what the scheme is.
    #[serde(default)]
    pub description: String,
    /// The scheme, as in a scenario file's `[scheme]` table.
    pub scheme: SchemeSpec,
}

/// Why a scheme file was refused.
#[derive(Debug, thiserror::Error)]
pub enum SchemeFileError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The error.
        source: std::io::Error,
    },
    /// TOML syntax or a field of the wrong type (the message names line and column).
    #[error("{path}: {message}")]
    Parse {
        /// The file.
        path: String,
        /// The parser's message.
        message: String,
    },
    /// The scheme breaks a rule of the plant's configuration (field and expected range named).
    #[error("{path}: {message}")]
    Invalid {
        /// The file.
        path: String,
        /// Every violation, one per line.
        message: String,
    },
}

impl SchemeFile {
    /// Parses `text` (from `path`, for messages) and checks the scheme against the plant's rules.
    pub fn parse(text: &str, path: &str) -> Result<Self, SchemeFileError> {
        let file: SchemeFile = toml::from_str(text).map_err(|e| SchemeFileError::Parse {
            path: path.into(),
            message: e.to_string().trim_end().to_string(),
        })?;
        file.check(path)?;
        Ok(file)
    }

    /// Reads and parses a scheme file.
    pub fn read(path: &Path) -> Result<Self, SchemeFileError> {
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| SchemeFileError::Io {
            path: shown.clone(),
            source,
        })?;
        Self::parse(&text, &shown)
    }

    /// The plant's own checks of the `[scheme]` table, with field names prefixed as in a
    /// scenario file.
    pub fn check(&self, path: &str) -> Result<(), SchemeFileError> {
        let cfg = PlantConfig {
            scheme: self.scheme.clone(),
            ..PlantConfig::default()
        };
        cfg.validate().map_err(|errs| SchemeFileError::Invalid {
            path: path.into(),
            message: errs
                .iter()
                .filter(|e| e.path.starts_with("scheme"))
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("\n"),
        })?;
        if self.name.trim().is_empty() {
            return Err(SchemeFileError::Invalid {
                path: path.into(),
                message: "name: must not be empty".into(),
            });
        }
        Ok(())
    }

    /// The file as TOML text (what [`SchemeFile::parse`] reads back unchanged).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("a scheme file serialises")
    }
}
