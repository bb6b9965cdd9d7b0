//! Unit conversions of the file units (°/h, ppm, µg, …) to SI, written out here rather than
//! taken from the plant so the generator shares no code with what it checks.

use std::f64::consts::PI;

/// One degree, rad.
pub const DEG: f64 = PI / 180.0;
/// One arcsecond, rad.
pub const ARCSEC: f64 = DEG / 3600.0;
/// One degree per hour, rad/s.
pub const DPH: f64 = DEG / 3600.0;
/// One degree per root hour (ARW), rad/√s: 1°/√h = (π/180)/√3600 rad/√s.
pub const DPSH: f64 = DEG / 60.0;
/// One part per million.
pub const PPM: f64 = 1e-6;
/// Standard gravity g₀, m/s² (the unit of g-sensitivity and dither terms, and of µg).
pub const G0: f64 = 9.806_65;
/// One micro-g, m/s² (so 1 µg/√Hz of VRW is `UG` m/s/√s).
pub const UG: f64 = 1e-6 * G0;
/// Reference temperature of every temperature-dependent hidden effect, °C: coefficients
/// multiply (T − 25 °C), the reference the tool writes.
pub const REF_TEMP_C: f64 = 25.0;
