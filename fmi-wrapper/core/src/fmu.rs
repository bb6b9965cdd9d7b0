//! The two FMUs this project ships: their identifiers, headers and instantiation tokens.

use std::sync::OnceLock;

use crate::model::Model;
use crate::rins::RinsModel;
use crate::xml::{FmiVersion, Header, model_description};

/// Model identifier (binary name) of the FMI 2 FMU.
pub const FMI2_ID: &str = "RinsImu";
/// Model identifier (binary name) of the FMI 3 FMU.
pub const FMI3_ID: &str = "RinsImu3";

/// The header of the FMU for `version`: the paper's headline experiment (one week at 100 Hz)
/// as the default experiment.
pub fn header(version: FmiVersion) -> Header {
    Header {
        model_identifier: match version {
            FmiVersion::V2 => FMI2_ID,
            FmiVersion::V3 => FMI3_ID,
        }
        .into(),
        description: "Dual-axis rotating RLG IMU (Seo et al., Sensors 2022, 22, 8355): 16-position table, Earth, thermal network and every gyro/accelerometer error term".into(),
        generation_tool: format!("rins-fmi {}", env!("CARGO_PKG_VERSION")),
        stop_time_s: 604_800.0,
        step_size_s: 0.01,
    }
}

/// modelDescription.xml and token for `version`, computed once (a pure function of the code).
pub fn description(version: FmiVersion) -> &'static (String, String) {
    static V2: OnceLock<(String, String)> = OnceLock::new();
    static V3: OnceLock<(String, String)> = OnceLock::new();
    let cell = match version {
        FmiVersion::V2 => &V2,
        FmiVersion::V3 => &V3,
    };
    cell.get_or_init(|| model_description(version, RinsModel::table(), &header(version)))
}
