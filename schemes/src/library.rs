//! The built-in scheme files (`schemes/files/`): the paper's 16- and 8-position schemes,
//! continuous rotation, and 32- and 64-position schemes built by the literature's
//! odd-symmetry principle. A name not among them is read as a file path.

use std::path::Path;

use crate::scheme_file::{SchemeFile, SchemeFileError};

/// Built-in scheme files: (name, text).
pub const BUILT_IN: [(&str, &str); 5] = [
    (
        "sixteen-position",
        include_str!("../files/sixteen-position.toml"),
    ),
    (
        "eight-position",
        include_str!("../files/eight-position.toml"),
    ),
    ("continuous", include_str!("../files/continuous.toml")),
    ("mirror-32", include_str!("../files/mirror-32.toml")),
    ("mirror-64", include_str!("../files/mirror-64.toml")),
];

/// The built-in scheme `name`, if there is one.
pub fn built_in(name: &str) -> Option<SchemeFile> {
    BUILT_IN.iter().find(|(n, _)| *n == name).map(|(n, text)| {
        SchemeFile::parse(text, &format!("built-in scheme {n}"))
            .expect("built-in scheme files are valid (tested)")
    })
}

/// Every built-in scheme, in [`BUILT_IN`] order.
pub fn all_built_in() -> Vec<SchemeFile> {
    BUILT_IN
        .iter()
        .map(|(n, _)| built_in(n).expect("listed"))
        .collect()
}

/// A built-in name or a scheme file's path.
pub fn resolve(arg: &str) -> Result<SchemeFile, SchemeFileError> {
    if let Some(s) = built_in(arg) {
        return Ok(s);
    }
    let path = Path::new(arg);
    if !path.exists() && !arg.ends_with(".toml") {
        return Err(SchemeFileError::Invalid {
            path: arg.into(),
            message: format!(
                "neither a built-in scheme ({}) nor a file",
                BUILT_IN.map(|b| b.0).join(", ")
            ),
        });
    }
    SchemeFile::read(path)
}

/// The steps of a scheme followed by their time mirror (reverse order, reversed senses): the
/// cycle undoes itself, so it closes whatever the first half does. How `mirror-32` is made
/// from the 16-position scheme.
pub fn mirrored(steps: &[rins_plant::table::RotationStep]) -> Vec<rins_plant::table::RotationStep> {
    let mut out = steps.to_vec();
    out.extend(steps.iter().rev().map(|s| rins_plant::table::RotationStep {
        angle_deg: -s.angle_deg,
        ..*s
    }));
    out
}

/// The steps with every azimuth (outer) sense reversed. `mirror-64` is `mirror-32` followed
/// by this of it.
pub fn azimuth_reversed(
    steps: &[rins_plant::table::RotationStep],
) -> Vec<rins_plant::table::RotationStep> {
    steps
        .iter()
        .map(|s| rins_plant::table::RotationStep {
            angle_deg: if s.axis == rins_plant::table::GimbalAxis::Outer {
                -s.angle_deg
            } else {
                s.angle_deg
            },
            ..*s
        })
        .collect()
}
