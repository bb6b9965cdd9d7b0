//! The plant's own δβ beside what `rins calibrate` and `rins campaign` estimate of it: a
//! simulation knows its truth, so their `--json` (and the report's verdict) says how far the
//! estimate is from it. The truth is the plant's position-dependent bias (Eq. 9,
//! [`GyroModel::position_bias_rps`], the function the plant adds each tick) at the temperatures
//! the estimate is reported at; zero when the scenario has the term off. Whatever else differs
//! between Z-up and Z-down (g-sensitivity along z, scale factor and misalignment on the Earth
//! rate, docs/paper-reproduction.md) enters the estimate too, and is not in this truth.

use rins_navigation::calibration::Calibration;
use rins_navigation::campaign::Campaign;
use rins_plant::PlantConfig;
use rins_plant::effects::gyro::GyroModel;
use rins_plant::units::DPH;
use serde::Serialize;

/// The plant's δβ (Eq. 9, Z-down minus Z-up) at the gyro temperatures `temp_c`, °/h per axis.
pub fn plant_delta_beta_dph(plant: &PlantConfig, temp_c: [f64; 3]) -> [f64; 3] {
    if !plant.sensor.gyro.position_bias.enabled {
        return [0.0; 3];
    }
    let b = GyroModel::new(&plant.sensor.gyro).position_bias_rps(&temp_c.into());
    [0, 1, 2].map(|i| b[i] / DPH)
}

/// `rins calibrate --json`: the calibration, and the plant's δβ beside its estimate.
#[derive(Clone, Debug, Serialize)]
pub struct CalibrationReport {
    /// The Z-up and Z-down estimates and δβ (its keys at the top level, as before).
    #[serde(flatten)]
    pub calibration: Calibration,
    /// The plant's δβ and the estimate's error.
    pub truth: CalibrationTruth,
}

/// The plant's δβ at the Z-down run's gyro temperature readings and the estimate's error.
#[derive(Clone, Debug, Serialize)]
pub struct CalibrationTruth {
    /// The plant's δβ per axis, °/h.
    pub delta_beta_dph: [f64; 3],
    /// Estimate minus truth, °/h.
    pub error_dph: [f64; 3],
    /// The error in standard errors of the estimate (|error| / SE).
    pub error_se: [f64; 3],
}

impl CalibrationReport {
    /// `c`, the calibration of `plant`, with the plant's δβ beside it.
    pub fn new(calibration: Calibration, plant: &PlantConfig) -> Self {
        let truth = plant_delta_beta_dph(plant, calibration.down.gyro_temp_c);
        let error_dph = [0, 1, 2].map(|i| calibration.delta_beta_dph[i] - truth[i]);
        let error_se = [0, 1, 2].map(|i| error_dph[i].abs() / calibration.delta_beta_se_dph[i]);
        Self {
            truth: CalibrationTruth {
                delta_beta_dph: truth,
                error_dph,
                error_se,
            },
            calibration,
        }
    }
}

/// `rins campaign --json`: the campaign, and how far its fitted δβ(T) is from the plant's.
#[derive(Clone, Debug, Serialize)]
pub struct CampaignReport {
    /// The runs and the fits (their keys at the top level, as before).
    #[serde(flatten)]
    pub campaign: Campaign,
    /// The plant's δβ and what the fit leaves of it.
    pub truth: CampaignTruth,
}

/// The plant's δβ at the fit's reference temperature and at each run's, and the fit's error.
#[derive(Clone, Debug, Serialize)]
pub struct CampaignTruth {
    /// The plant's δβ per axis at the reference temperature, °/h (the fit's c₀ estimates it).
    pub at_ref_dph: [f64; 3],
    /// The plant's δβ per axis at each run's gyro block temperature, °/h.
    pub runs_dph: Vec<[f64; 3]>,
    /// The largest |fit − truth| per axis over the runs' temperatures, °/h: what compensating
    /// with the fitted file leaves of δβ over the campaign's range.
    pub fit_error_max_dph: [f64; 3],
}

impl CampaignReport {
    /// `c`, the campaign of `plant`, with the plant's δβ beside its fits.
    pub fn new(campaign: Campaign, plant: &PlantConfig) -> Self {
        let r = campaign.ref_temp_c;
        let runs_dph: Vec<[f64; 3]> = campaign
            .runs
            .iter()
            .map(|run| plant_delta_beta_dph(plant, run.block_temp_c))
            .collect();
        let fit_error_max_dph = [0, 1, 2].map(|i| {
            campaign
                .runs
                .iter()
                .zip(&runs_dph)
                .map(|(run, t)| (campaign.fits[i].eval(run.block_temp_c[i] - r).0 - t[i]).abs())
                .fold(0.0, f64::max)
        });
        Self {
            truth: CampaignTruth {
                at_ref_dph: plant_delta_beta_dph(plant, [r; 3]),
                runs_dph,
                fit_error_max_dph,
            },
            campaign,
        }
    }
}
