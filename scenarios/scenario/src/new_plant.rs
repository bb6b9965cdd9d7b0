//! The plant a scenario's configuration describes, every configuration error in one message.

use anyhow::Result;
use rins_plant::{Plant, PlantConfig};

/// Builds the plant of `cfg`, every configuration error joined into one message after `what`
/// (the scenario's source or a run label).
pub fn new_plant(cfg: &PlantConfig, what: &str) -> Result<Plant> {
    Plant::new(cfg).map_err(|errs| {
        anyhow::anyhow!(
            "{what}: {}",
            errs.iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("; ")
        )
    })
}
