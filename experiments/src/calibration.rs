//! The paper's system-level calibration as an experiment (Section 3.2, Figures 4–5): build the
//! Z-up or Z-down calibration plant, self-align, navigate through the sequence, and hand the
//! error records to the estimator of Eq. 17 / 19 (`rins_navigation::calibration`).

use rins_navigation::calibration::{
    CalPosition, Calibration, CalibrationConfig, CalibrationError, PositionEstimate,
    estimate_position,
};
use rins_plant::table::SchemeKind;
use rins_plant::{Plant, PlantConfig};

use crate::session::{Alignment, NavRunConfig, run};

/// Mixed into the seed of the Z-down run (the golden-ratio constant).
pub const Z_DOWN_SEED_MIX: u64 = 0x9E37_79B9_7F4A_7C15;

/// The plant configuration of a calibration run at `pos`, from the scenario's plant `base`.
pub fn calibration_plant(
    base: &PlantConfig,
    pos: CalPosition,
    cfg: &CalibrationConfig,
) -> PlantConfig {
    let mut p = base.clone();
    p.scheme.kind = match pos {
        CalPosition::ZUp => SchemeKind::ZUpCalibration,
        CalPosition::ZDown => SchemeKind::ZDownCalibration,
    };
    p.scheme.dwell_s = cfg.segment_s;
    if pos == CalPosition::ZDown {
        // The two calibrations are separate runs with independent noise; sharing the seed would
        // replay the same noise in both and cancel it from δβ (a false precision).
        p.seed ^= Z_DOWN_SEED_MIX;
    }
    p.scheme.lead_dwell_s = match cfg.alignment {
        Alignment::SelfAlign { coarse_s, fine_s } => coarse_s + fine_s,
        Alignment::Truth => 0.0,
    };
    p
}

/// Runs the calibration sequence at `pos` and estimates β with Eq. 17 or 19.
pub fn calibrate_position(
    base: &PlantConfig,
    pos: CalPosition,
    cfg: &CalibrationConfig,
) -> Result<PositionEstimate, CalibrationError> {
    let samples = (cfg.segment_s * cfg.fit_rate_hz) as usize;
    if samples < 30 {
        return Err(CalibrationError::SegmentTooShort {
            segment_s: cfg.segment_s,
            rate_hz: cfg.fit_rate_hz,
            samples,
            min_s: 30.0 / cfg.fit_rate_hz,
        });
    }
    let pcfg = calibration_plant(base, pos, cfg);
    let mut plant = Plant::new(&pcfg).map_err(|e| {
        CalibrationError::Run(format!(
            "plant configuration: {}",
            e.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join("; ")
        ))
    })?;
    let move_s = plant.schedule().cycle_s() - cfg.segment_s;
    let total = 2.0 * cfg.segment_s + move_s;
    let nav = NavRunConfig {
        alignment: cfg.alignment,
        record_every_s: 1.0 / cfg.fit_rate_hz,
        ..NavRunConfig::default()
    };
    let run = run(&mut plant, total, &nav).map_err(|e| CalibrationError::Run(e.to_string()))?;
    // The gyro temperatures the unit reports; the chamber set point is the experimenter's.
    let readings = plant.temp_readings_c();
    estimate_position(
        &run.records,
        pos,
        cfg,
        plant.site(),
        &pcfg.sensor,
        move_s,
        [readings[1], readings[2], readings[3]],
        plant.chamber_now_c(),
    )
}

/// Z-up then Z-down calibration of the same plant; δβ = β_down − β_up (Section 3.2).
pub fn calibrate(
    base: &PlantConfig,
    cfg: &CalibrationConfig,
) -> Result<Calibration, CalibrationError> {
    let up = calibrate_position(base, CalPosition::ZUp, cfg)?;
    let down = calibrate_position(base, CalPosition::ZDown, cfg)?;
    let delta_beta_dph = [0, 1, 2].map(|i| down.beta_dph[i] - up.beta_dph[i]);
    let delta_beta_se_dph = [0, 1, 2].map(|i| down.se_dph[i].hypot(up.se_dph[i]));
    Ok(Calibration {
        up,
        down,
        delta_beta_dph,
        delta_beta_se_dph,
    })
}
