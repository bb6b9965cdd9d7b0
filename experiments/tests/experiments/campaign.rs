//! The temperature campaign recovers δβ(T) and refuses bad inputs.

use rins_experiments::campaign::run_campaign;
use rins_navigation::calibration::CalibrationConfig;
use rins_navigation::campaign::CampaignError;
use rins_plant::PlantConfig;

fn noise_free_full() -> PlantConfig {
    PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    }
    .noise_free()
}

#[test]
fn noise_free_campaign_recovers_the_temperature_shape_of_dbeta() {
    // Every other effect is on too; they shift the measured delta-beta by constants (g-sensitivity,
    // misalignment on Earth rate) but the temperature coefficients are the plant's own.
    let base = noise_free_full();
    let temps: Vec<f64> = (0..9)
        .map(|k| 6.54 + (58.14 - 6.54) * k as f64 / 8.0)
        .collect();
    let c = run_campaign(&base, &temps, &CalibrationConfig::default(), 25.0).unwrap();
    let pb = &base.sensor.gyro.position_bias;
    // X: linear 1.5e-4 deg/h/K, quadratic -4e-6, cubic 5e-8.
    approx::assert_relative_eq!(c.fits[0].coef[1], pb.dph_per_k[0], max_relative = 0.05);
    approx::assert_relative_eq!(c.fits[0].coef[2], pb.dph_per_k2[0], max_relative = 0.1);
    approx::assert_relative_eq!(c.fits[0].coef[3], pb.dph_per_k3[0], max_relative = 0.1);
    // Z: linear 5e-5, quadratic 1e-6.
    approx::assert_relative_eq!(c.fits[2].coef[1], pb.dph_per_k[2], max_relative = 0.2);
    approx::assert_relative_eq!(c.fits[2].coef[2], pb.dph_per_k2[2], max_relative = 0.2);
    // The swing over the campaign: X about 0.015 deg/h level, Y hardly changes (Figure 8 shape).
    let spec = c.compensation();
    assert!(spec.dph[0] > 0.01 && spec.dph[1].abs() < 0.001, "{spec:?}");
}

#[test]
fn out_of_range_temperatures_and_too_few_runs_are_refused() {
    let base = noise_free_full();
    let e = run_campaign(
        &base,
        &[20.0, 30.0, 140.0, 40.0, 50.0],
        &CalibrationConfig::default(),
        25.0,
    )
    .unwrap_err();
    assert!(
        matches!(e, CampaignError::TemperatureOutOfRange { index: 2, .. }),
        "{e}"
    );
    assert!(
        e.to_string().contains("140") && e.to_string().contains("125"),
        "{e}"
    );
    let e = run_campaign(&base, &[20.0, 30.0], &CalibrationConfig::default(), 25.0).unwrap_err();
    assert!(e.to_string().contains("at least 5"), "{e}");
}
