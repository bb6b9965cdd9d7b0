//! Named sensor specifications. A scenario file reads the same presets as TOML fragments
//! (`scenarios/scenario/files/presets/NAME.toml`, laid under the file's own `[sensor]` keys); rins-scenarios
//! tests each fragment equal to its constructor here, so a change goes to both.

use crate::config::SensorSpec;

/// Names accepted by [`preset`].
pub const PRESET_NAMES: [&str; 3] = ["paper-table3", "nav-grade-full", "ideal"];

/// The sensor specification called `name`, if any.
pub fn preset(name: &str) -> Option<SensorSpec> {
    match name {
        "paper-table3" => Some(paper_table3()),
        "nav-grade-full" => Some(nav_grade_full()),
        "ideal" => Some(SensorSpec::default()),
        _ => None,
    }
}

/// The plant of the paper's headline experiment (Sec. 3.1): 36.6 N 123.6 E, 16-position scheme
/// (ω_r = 2 °/s, T_s = 180 s, 20 °/s² table), Table 3 sensors, 100 Hz, chamber at 25 °C.
/// The built-in scenario `paper-16pos-week` resolves to exactly this (tested there); the FMU
/// uses it as its start values.
pub fn paper_16pos_config() -> crate::PlantConfig {
    crate::PlantConfig {
        sensor: paper_table3(),
        ..crate::PlantConfig::default()
    }
}

/// Table 3 of the paper, with every magnitude applied with positive sign on every axis:
/// gyro ARW 0.003 °/√h, bias 0.01 °/h, δβ 0.005 °/h, scale factor 5 ppm, misalignment 5″;
/// accelerometer bias 50 µg, scale factor 50 ppm, misalignment 5″. Nothing else is on.
pub fn paper_table3() -> SensorSpec {
    let mut s = SensorSpec::default();
    let g = &mut s.gyro;
    g.angle_random_walk.enabled = true;
    g.angle_random_walk.dpsh = [0.003; 3];
    g.bias.enabled = true;
    g.bias.dph = [0.01; 3];
    g.position_bias.enabled = true;
    g.position_bias.dph = [0.005; 3];
    g.scale_factor.enabled = true;
    g.scale_factor.ppm = [5.0; 3];
    g.misalignment.enabled = true;
    g.misalignment.arcsec = [5.0; 6];
    let a = &mut s.accel;
    a.bias.enabled = true;
    a.bias.ug = [50.0; 3];
    a.scale_factor.enabled = true;
    a.scale_factor.ppm = [50.0; 3];
    a.misalignment.enabled = true;
    a.misalignment.arcsec = [5.0; 6];
    s
}

/// Table 3 plus every other effect the plant models, at magnitudes typical of a navigation-grade
/// dithered RLG IMU; the position-dependent bias follows the paper's Figure 8 shape (X changes by
/// about 0.015 °/h between Z-up and Z-down, Z by about 0.004 °/h, Y hardly).
pub fn nav_grade_full() -> SensorSpec {
    let mut s = paper_table3();
    let g = &mut s.gyro;
    g.position_bias.dph = [0.015, 0.0005, 0.004];
    g.position_bias.dph_per_k = [1.5e-4, 0.0, 5e-5];
    g.position_bias.dph_per_k2 = [-4e-6, 0.0, 1e-6];
    g.position_bias.dph_per_k3 = [5e-8, 0.0, 0.0];
    g.scale_factor_asymmetry.enabled = true;
    g.scale_factor_asymmetry.ppm = [1.0, -1.0, 0.5];
    g.temperature_bias.enabled = true;
    g.temperature_bias.per_k = [2e-4, -1.5e-4, 1e-4];
    g.temperature_bias.per_k2 = [5e-6, 3e-6, -2e-6];
    g.temperature_bias.per_k3 = [-1e-7, 5e-8, 5e-8];
    g.temperature_gradient_bias.enabled = true;
    g.temperature_gradient_bias.dph_per_k = [0.002, -0.001, 0.0015];
    g.g_sensitivity.enabled = true;
    g.g_sensitivity.dph_per_g = [
        [0.001, 0.0005, 0.0],
        [0.0, 0.001, 0.0005],
        [0.0005, 0.0, 0.001],
    ];
    g.dither_bias.enabled = true;
    g.dither_bias.amplitude_change = [0.02; 3];
    g.dither_bias.dph_per_amplitude = [0.05, 0.05, 0.05];
    g.bias_instability.enabled = true;
    g.bias_instability.sigma_dph = [0.002; 3];
    g.bias_instability.tau_s = [3600.0; 3];
    g.rate_random_walk.enabled = true;
    g.rate_random_walk.dph_per_sqrth = [0.0005; 3];
    g.quantization.enabled = true;
    g.quantization.pulse = [0.1; 3];
    let a = &mut s.accel;
    a.temperature_bias.enabled = true;
    a.temperature_bias.per_k = [2.0, -1.5, 1.0];
    a.temperature_bias.per_k2 = [0.05, 0.02, -0.02];
    a.velocity_random_walk.enabled = true;
    a.velocity_random_walk.ug_per_sqrthz = [10.0; 3];
    a.quantization.enabled = true;
    a.quantization.pulse = [1e-5; 3];
    s
}
