//! The model as a scenario file (docs/scenario-format.md), so a failing trial can be replayed
//! alone: `rins diagnose --model MODEL.toml --data LOG.csv`. Only what the generator reads is
//! written (site, mount, row rate and the base terms, [`crate::check_model`]); everything else
//! is the scenario defaults, which a model the generator accepts has anyway.

use std::fmt::Write as _;
use std::io;
use std::path::Path;

use rins_plant::PlantConfig;

/// The scenario text of `model`, named `name`.
pub fn model_toml(model: &PlantConfig, name: &str) -> String {
    let (g, a) = (&model.sensor.gyro, &model.sensor.accel);
    let v3 = |x: [f64; 3]| format!("[{:?}, {:?}, {:?}]", x[0], x[1], x[2]);
    let mut s = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(
        s,
        "[scenario]\nname = {:?}\n\n[run]\nrate_hz = {:?}\n\n[site]\nlat_deg = {:?}\nlon_deg = {:?}\nheight_m = {:?}\n",
        name.replace(['"', '\\', '\n'], " "),
        model.rate_hz,
        model.site.lat_deg,
        model.site.lon_deg,
        model.site.height_m
    );
    let _ = writeln!(
        s,
        "[earth]\nrotation = {}\ngravity = {}\n\n[vehicle]\nazimuth_deg = {:?}\npitch_deg = {:?}\nroll_deg = {:?}\n",
        model.earth.rotation,
        model.earth.gravity,
        model.vehicle.azimuth_deg,
        model.vehicle.pitch_deg,
        model.vehicle.roll_deg
    );
    let terms = [
        ("gyro.bias", g.bias.enabled, "dph", g.bias.dph),
        (
            "gyro.scale_factor",
            g.scale_factor.enabled,
            "ppm",
            g.scale_factor.ppm,
        ),
        (
            "gyro.angle_random_walk",
            g.angle_random_walk.enabled,
            "dpsh",
            g.angle_random_walk.dpsh,
        ),
        ("accel.bias", a.bias.enabled, "ug", a.bias.ug),
        (
            "accel.scale_factor",
            a.scale_factor.enabled,
            "ppm",
            a.scale_factor.ppm,
        ),
        (
            "accel.velocity_random_walk",
            a.velocity_random_walk.enabled,
            "ug_per_sqrthz",
            a.velocity_random_walk.ug_per_sqrthz,
        ),
    ];
    for (term, on, key, x) in terms {
        let _ = writeln!(s, "[sensor.{term}]\nenabled = {on}\n{key} = {}\n", v3(x));
    }
    s
}

/// Writes [`model_toml`] of `model` to `path`.
pub fn write_model(model: &PlantConfig, name: &str, path: impl AsRef<Path>) -> io::Result<()> {
    std::fs::write(path, model_toml(model, name))
}
