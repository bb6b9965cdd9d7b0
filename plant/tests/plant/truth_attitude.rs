//! The plant's true attitude q_b^n ([`Plant::attitude_q_bn`]) is the closed-form composition
//! q_c^n·q_v^c·q_z(outer)·q_x(inner) of its carrier truth and gimbal angles: it reproduces
//! C_b^n = C_c^n·C_v^c·R_z(outer)·R_x(inner) to 1e-15 at every step through the 16-position
//! scheme's dwells and turns, on the static site (level and tilted mount), at sea (tilted
//! mount) and with azimuth isolation; and a sink composing it from the truth record
//! ([`TruthMount::q_bn_of`]) gets the same bits, except on an isolated table, whose record's
//! outer angle is the reference table's plus the seed's offset difference (equal to rounding).

use nalgebra::Matrix3;
use rins_plant::carrier::{CarrierKind, LegSpec, SpectrumKind};
use rins_plant::table::body_to_nav;
use rins_plant::{Plant, PlantConfig, TruthMount, VehicleSpec};

const TILTED: VehicleSpec = VehicleSpec {
    azimuth_deg: 47.0,
    pitch_deg: -3.0,
    roll_deg: 2.0,
};

/// What [`run`] found.
struct Misfits {
    /// Worst |q_b^n's matrix − C_c^n·C_v^c·R_z(outer)·R_x(inner)|, with the truth record's
    /// C_c^n and gimbal angles and its q_b^n as a sink composes it.
    c_bn: f64,
    /// Worst |q_b^n's matrix − [`Plant::attitude_c_bn`]| (the plant's own C_c^n, which a ship on
    /// the segment rule interpolates apart from the truth's by rounding of its own).
    plant_c_bn: f64,
    /// Worst difference between the plant's q_b^n and the one composed from its truth record.
    sink: f64,
    /// Samples in a turn.
    turning: u64,
    /// Samples at a position of the scheme (outer and inner at multiples of π/2).
    at_position: u64,
}

/// Steps `cfg` for `n` samples, comparing the true attitude after each.
fn run(cfg: &PlantConfig, n: u64) -> Misfits {
    let mut p = Plant::new(cfg).unwrap();
    let (mut worst_c, mut worst_plant, mut worst_sink, mut turning, mut at_position) =
        (0.0f64, 0.0f64, 0.0f64, 0, 0);
    let c_vc = if cfg.carrier.is_static() {
        Matrix3::identity()
    } else {
        cfg.vehicle.c_vn()
    };
    for _ in 0..n {
        p.step();
        let q = p.attitude_q_bn();
        let m = q.to_rotation_matrix().into_inner();
        worst_plant = worst_plant.max((m - p.attitude_c_bn()).amax());
        let tr = p.truth();
        let c_cn = tr.carrier.q_cn.to_rotation_matrix().into_inner();
        let c = body_to_nav(&(c_cn * c_vc), tr.gimbal.angles);
        let sink = TruthMount::of_config(cfg).q_bn_of(&tr);
        worst_c = worst_c.max((sink.to_rotation_matrix().into_inner() - c).amax());
        assert_eq!(p.truth_mount(), TruthMount::of_config(cfg));
        worst_sink = worst_sink.max((sink.coords - q.coords).amax());
        let a = tr.gimbal.angles;
        let quarter = |x: f64| {
            let r = x / std::f64::consts::FRAC_PI_2;
            (r - r.round()).abs() < 1e-12
        };
        turning += tr.gimbal.moving as u64;
        at_position += (quarter(a.outer_rad) && quarter(a.inner_rad)) as u64;
    }
    Misfits {
        c_bn: worst_c,
        plant_c_bn: worst_plant,
        sink: worst_sink,
        turning,
        at_position,
    }
}

#[test]
fn the_truth_attitude_is_exact_on_the_static_site() {
    for vehicle in [VehicleSpec::default(), TILTED] {
        let mut cfg = rins_plant::presets::paper_16pos_config();
        cfg.vehicle = vehicle;
        // The 16 positions' dwells and turns of the scheme's first cycles.
        let m = run(&cfg, 60_000);
        eprintln!(
            "static {vehicle:?}: C_b^n within {:e} (the plant's {:e}), sink within {:e}; {} turning, {} at a position",
            m.c_bn, m.plant_c_bn, m.sink, m.turning, m.at_position
        );
        assert!(m.turning > 1000 && m.at_position > 10_000);
        assert!(m.c_bn < 1e-15, "{vehicle:?}: C_b^n misfit {:e}", m.c_bn);
        assert!(m.plant_c_bn < 1e-15, "{vehicle:?}: {:e}", m.plant_c_bn);
        assert_eq!(m.sink, 0.0, "{vehicle:?}: the sink's q_b^n differs");
    }
}

#[test]
fn the_truth_attitude_is_exact_at_sea_and_with_azimuth_isolation() {
    // The 16-position scheme on a ship at sea state 5 with a course change at 300 s.
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.carrier.kind = CarrierKind::Ship;
    let leg = |heading_deg: f64, duration_s: f64| LegSpec {
        heading_deg,
        speed_kn: 12.0,
        duration_s,
    };
    cfg.carrier.ship.legs = vec![leg(30.0, 300.0), leg(120.0, 1e5)];
    cfg.carrier.ship.sea.spectrum = SpectrumKind::Jonswap;
    cfg.carrier.ship.sea.sea_state = 5;
    cfg.vehicle = TILTED;
    for isolation in [false, true] {
        cfg.carrier.azimuth_isolation = isolation;
        let m = run(&cfg, 60_000);
        eprintln!(
            "sea state 5, isolation {isolation}: C_b^n within {:e} (the plant's {:e}), sink within {:e}; {} turning",
            m.c_bn, m.plant_c_bn, m.sink, m.turning
        );
        assert!(m.turning > 1000, "{}", m.turning);
        // The matrix compared with is four rounded products of its own: the isolated table's
        // outer angles (the scheme's plus an offset) bring it to 5 ulps of 1 (1.1e-15 here).
        let bound = if isolation { 1.5e-15 } else { 1e-15 };
        assert!(m.c_bn < bound, "C_b^n misfit {:e}", m.c_bn);
        // The plant's C_c^n on the segment rule is the truth's to its interpolation's rounding.
        assert!(m.plant_c_bn < 1e-13, "{:e}", m.plant_c_bn);
        if isolation {
            assert!(m.sink < 1e-15, "the sink's q_b^n differs by {:e}", m.sink);
        } else {
            assert_eq!(m.sink, 0.0, "the sink's q_b^n differs by {:e}", m.sink);
        }
    }
}
