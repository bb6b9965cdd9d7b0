//! Development aid: the noise-free Table 4 pair under different modelling choices.
use rins_experiments::{Alignment, NavRunConfig};
use rins_plant::effects::gyro::Transition;
use rins_verification::paper::{Table4Options, table4};

fn main() {
    let base = rins_scenarios_free_config();
    let days = 7.0;
    let mut variants: Vec<(&str, rins_plant::PlantConfig, NavRunConfig)> = Vec::new();
    variants.push((
        "default: cosine transition, 20 deg/s^2",
        base.clone(),
        NavRunConfig::default(),
    ));
    let mut v = base.clone();
    v.sensor.gyro.position_bias.transition = Transition::Step;
    variants.push(("step transition", v, NavRunConfig::default()));
    let mut v = base.clone();
    v.scheme.accel_dps2 = f64::INFINITY;
    variants.push(("constant-rate moves (Eq. 6)", v, NavRunConfig::default()));
    let mut v = base.clone();
    v.scheme.lead_dwell_s = 900.0;
    variants.push((
        "self-alignment 300 s coarse + 600 s fine",
        v,
        NavRunConfig {
            alignment: Alignment::SelfAlign {
                coarse_s: 300.0,
                fine_s: 600.0,
            },
            ..NavRunConfig::default()
        },
    ));
    for (name, plant, nav) in variants {
        let r = table4(
            &Table4Options {
                plant,
                runs: 0,
                duration_s: days * 86_400.0,
                nav,
                compensation: None,
            },
            &|_| {},
        );
        let (u, c) = (r.noise_free.uncompensated, r.noise_free.compensated);
        println!(
            "{name:<44} unc lat {:+.3} lon {:+.3} nmi up {:.4} deg | comp lat {:+.3} lon {:+.3} nmi up {:.4} deg",
            u.lat_nm, u.lon_nm, u.up_att_mean_deg, c.lat_nm, c.lon_nm, c.up_att_mean_deg
        );
    }
}

fn rins_scenarios_free_config() -> rins_plant::PlantConfig {
    rins_plant::PlantConfig {
        sensor: rins_plant::presets::paper_table3(),
        ..rins_plant::PlantConfig::default()
    }
}
