//! Shared set-ups for the carrier tests.
#![allow(dead_code)]

use nalgebra::Vector3;
use rins_plant::PlantConfig;
use rins_plant::carrier::{CarrierKind, LegSpec, SpectrumKind};
use rins_plant::table::{SchemeKind, SchemeSpec};

/// An ideal, static-table plant on a ship with the given legs (heading °, speed kn, duration s);
/// no waves unless set later.
pub fn ship_config(legs: &[(f64, f64, f64)]) -> PlantConfig {
    let mut cfg = PlantConfig {
        scheme: SchemeSpec {
            kind: SchemeKind::Static,
            ..SchemeSpec::default()
        },
        ..PlantConfig::default()
    };
    cfg.carrier.kind = CarrierKind::Ship;
    cfg.carrier.ship.legs = legs
        .iter()
        .map(|&(heading_deg, speed_kn, duration_s)| LegSpec {
            heading_deg,
            speed_kn,
            duration_s,
        })
        .collect();
    cfg
}

/// Sea state `n` of a JONSWAP spectrum with the default responses.
pub fn with_sea_state(mut cfg: PlantConfig, n: u32) -> PlantConfig {
    cfg.carrier.ship.sea.spectrum = SpectrumKind::Jonswap;
    cfg.carrier.ship.sea.sea_state = n;
    cfg
}

/// Meridian arc length from the equator to geodetic latitude `lat` (Helmert's series to e⁶),
/// m: independent of the plant's radii of curvature.
pub fn meridian_arc_m(lat: f64) -> f64 {
    let a = 6_378_137.0;
    let f = 1.0 / 298.257_223_563;
    let e2: f64 = f * (2.0 - f);
    let (e4, e6) = (e2 * e2, e2 * e2 * e2);
    let a0 = 1.0 + 0.75 * e2 + 45.0 / 64.0 * e4 + 175.0 / 256.0 * e6;
    let a2 = 0.75 * e2 + 15.0 / 16.0 * e4 + 525.0 / 512.0 * e6;
    let a4 = 15.0 / 64.0 * e4 + 105.0 / 256.0 * e6;
    let a6 = 35.0 / 512.0 * e6;
    a * (1.0 - e2)
        * (a0 * lat - a2 / 2.0 * (2.0 * lat).sin() + a4 / 4.0 * (4.0 * lat).sin()
            - a6 / 6.0 * (6.0 * lat).sin())
}

/// Composite 5-point Gauss–Legendre quadrature of `f` over [a, b] in `n` pieces.
pub fn quad<F: Fn(f64) -> Vector3<f64>>(f: F, a: f64, b: f64, n: usize) -> Vector3<f64> {
    let r = (245.0 - 14.0 * 70f64.sqrt()).sqrt() / 21.0;
    let s = (245.0 + 14.0 * 70f64.sqrt()).sqrt() / 21.0;
    let wr = (322.0 + 13.0 * 70f64.sqrt()) / 900.0;
    let ws = (322.0 - 13.0 * 70f64.sqrt()) / 900.0;
    let x = [0.0, -r, r, -s, s];
    let w = [128.0 / 225.0, wr, wr, ws, ws];
    let h = (b - a) / n as f64;
    let mut sum = Vector3::zeros();
    for i in 0..n {
        let m = a + (i as f64 + 0.5) * h;
        for (x, w) in x.iter().zip(w) {
            sum += f(m + 0.5 * h * x) * (0.5 * h * w);
        }
    }
    sum
}
