//! The ship scenario the transport tests share: the 16-position scheme on a ship at sea state 5
//! (JONSWAP) with a lever arm, turning from 30° to 120° after 60 s.

use rins_plant::PlantConfig;
use rins_plant::carrier::{CarrierKind, LegSpec, SpectrumKind};

pub fn ship() -> PlantConfig {
    let mut cfg = rins_plant::presets::paper_16pos_config();
    let c = &mut cfg.carrier;
    c.kind = CarrierKind::Ship;
    c.lever_arm_m = [1.0, 5.0, -2.0];
    c.ship.legs = vec![
        LegSpec {
            heading_deg: 30.0,
            speed_kn: 14.0,
            duration_s: 60.0,
        },
        LegSpec {
            heading_deg: 120.0,
            speed_kn: 10.0,
            duration_s: 3600.0,
        },
    ];
    c.ship.sea.spectrum = SpectrumKind::Jonswap;
    c.ship.sea.sea_state = 5;
    cfg
}
