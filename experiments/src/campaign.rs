//! The temperature campaign as an experiment (Section 4.1, Figure 8): Z-up/Z-down calibrations
//! at many chamber temperatures on both cores, then the δβ(T) fit of `rins_navigation::campaign`.

use rayon::prelude::*;
use rins_navigation::calibration::CalibrationConfig;
use rins_navigation::campaign::{Campaign, CampaignError, CampaignRun, fit_campaign};
use rins_plant::PlantConfig;
use rins_plant::thermal::{CHAMBER_MAX_C, CHAMBER_MIN_C};

use crate::calibration::calibrate;

/// Runs the campaign at `temps_c` on both cores and fits δβ(T).
pub fn run_campaign(
    base: &PlantConfig,
    temps_c: &[f64],
    cfg: &CalibrationConfig,
    ref_temp_c: f64,
) -> Result<Campaign, CampaignError> {
    for (index, &t) in temps_c.iter().enumerate() {
        if !(CHAMBER_MIN_C..=CHAMBER_MAX_C).contains(&t) {
            return Err(CampaignError::TemperatureOutOfRange {
                temp_c: t,
                index,
                min: CHAMBER_MIN_C,
                max: CHAMBER_MAX_C,
            });
        }
    }
    if temps_c.len() < 5 {
        return Err(CampaignError::TooFewRuns(temps_c.len()));
    }
    let t0 = std::time::Instant::now();
    let runs: Vec<CampaignRun> = temps_c
        .par_iter()
        .enumerate()
        .map(|(k, &t)| {
            let mut p = base.clone();
            p.thermal.chamber.temp_c = t;
            p.thermal.chamber.profile.clear();
            p.seed = base.seed.wrapping_add(k as u64 * 7919);
            let calibration =
                calibrate(&p, cfg).map_err(|source| CampaignError::Run { temp_c: t, source })?;
            Ok(CampaignRun {
                chamber_c: t,
                block_temp_c: calibration.down.gyro_temp_c,
                calibration,
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(fit_campaign(runs, ref_temp_c, t0.elapsed().as_secs_f64()))
}
