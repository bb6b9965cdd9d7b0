//! Azimuth isolation commanded by the navigator over shared memory (`kind` 4 and 5): applied
//! from the first tick of the next batch, giving the in-process run with the same commands bit
//! for bit; it changes the run (the table counter-rotates the ship's yaw); a static carrier
//! refuses it and the plant ends the run naming the reason, which reaches the navigator.

use std::time::Duration;

use rins_plant::{Plant, PlantConfig};
use rins_transport::layout::kind;
use rins_transport::{
    Mode, NavAction, NavOptions, ScheduledCommand, ServeOptions, navigate, reference, serve,
};

use crate::ship::ship;

fn session(tag: &str) -> String {
    format!("iso{}{tag}", std::process::id())
}

fn serve_opts() -> ServeOptions {
    ServeOptions {
        mode: Mode::Lockstep,
        batch: 50,
        pace: None,
        peer_timeout: Duration::from_secs(20),
        wait_for_restart: false,
    }
}

/// Serves `samples` of `cfg` to a navigator thread sending `commands`.
fn run(
    tag: &str,
    cfg: &PlantConfig,
    samples: u64,
    commands: &[ScheduledCommand],
) -> (
    Result<rins_transport::ServeSummary, rins_transport::TransportError>,
    Result<rins_transport::NavSummary, rins_transport::TransportError>,
) {
    let name = session(tag);
    let (n2, c2, cmds) = (name.clone(), cfg.clone(), commands.to_vec());
    let nav = std::thread::spawn(move || {
        navigate(
            &n2,
            &c2,
            &NavOptions {
                acknowledge: true,
                commands: cmds,
                peer_timeout: Duration::from_secs(5),
            },
        )
    });
    let mut plant = Plant::new(cfg).unwrap();
    let served = serve(&name, &mut plant, samples, &serve_opts());
    (served, nav.join().unwrap())
}

#[test]
fn isolation_commanded_over_shared_memory_equals_the_in_process_run() {
    const SAMPLES: u64 = 25_000; // 250 s: isolation on before the turn, off after it
    let commands = [
        ScheduledCommand {
            after_seq: 40,
            action: NavAction::AzimuthIsolation(true),
        },
        ScheduledCommand {
            after_seq: 400,
            action: NavAction::AzimuthIsolation(false),
        },
    ];
    let (served, nav) = run("ship", &ship(), SAMPLES, &commands);
    let (summary, got) = (served.unwrap(), nav.unwrap());
    let applied: Vec<(u64, u32)> = summary.commands.iter().map(|(t, c)| (*t, c.kind)).collect();
    assert_eq!(
        applied,
        [
            (41 * 50, kind::AZIMUTH_ISOLATION_ON),
            (401 * 50, kind::AZIMUTH_ISOLATION_OFF)
        ],
        "applied at the first tick of the batch after the acknowledged one"
    );
    let want = reference(&ship(), SAMPLES, 50, &commands);
    assert_eq!(got.nav.samples, SAMPLES);
    assert_eq!(
        got.nav.digest, want.digest,
        "navigation through shared memory equals the in-process run bit for bit"
    );
    // The command acts: without it the table turns with the ship and the increments differ.
    let without = reference(&ship(), SAMPLES, 50, &[]);
    assert_ne!(want.digest, without.digest, "isolation changes the run");
    // Independent of the digests: the ship turns right by 90° (a yaw of −90° about up) while
    // isolation is on, so the outer gimbal turned by about +90° against the carrier (within
    // the wave yaw at the two switching instants, a few degrees at sea state 5).
    let outer_after = |cmds: &[ScheduledCommand]| {
        let mut p = Plant::new(&ship()).unwrap();
        for seq in 0..(SAMPLES / 50) {
            for _ in 0..50 {
                p.step();
            }
            if let Some(c) = cmds.iter().find(|c| c.after_seq == seq) {
                c.action.apply(&mut p).unwrap();
            }
        }
        p.truth().gimbal.angles.outer_rad
    };
    let turned = (outer_after(&commands) - outer_after(&[])).to_degrees();
    let wrapped = (turned + 180.0).rem_euclid(360.0) - 180.0;
    println!("outer gimbal with isolation through the turn: {wrapped:+.1}° from the run without");
    assert!(
        (wrapped - 90.0).abs() < 10.0,
        "the outer gimbal counter-rotated the 90° course change: {wrapped:.1}°"
    );
}

#[test]
fn a_static_carrier_refuses_isolation_and_the_plant_says_why() {
    let commands = [ScheduledCommand {
        after_seq: 3,
        action: NavAction::AzimuthIsolation(true),
    }];
    let cfg = rins_plant::presets::paper_16pos_config();
    let (served, nav) = run("static", &cfg, 2_000, &commands);
    let err = served
        .expect_err("isolation on a static carrier is refused")
        .to_string();
    assert!(
        err.contains("kind 4") && err.contains("moving carrier"),
        "{err}"
    );
    // What is wrong and what is allowed.
    assert!(
        err.contains("carrier is static")
            && err.contains("kind = \"ship\" or \"trajectory\"")
            && !err.contains("not an external one"),
        "{err}"
    );
    // The navigator learns why the run ended: the plant's reason came with its end-of-run
    // batch (not "the plant exited normally").
    let nav_err = nav.expect_err("the run ended refused").to_string();
    assert!(
        nav_err.starts_with("the plant ended the run: ") && nav_err.ends_with(&err),
        "navigator: {nav_err}\nplant: {err}"
    );
    assert!(!nav_err.contains("exited normally"), "{nav_err}");
}
