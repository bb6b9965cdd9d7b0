//! In-process checks of the transport's contracts: lockstep equals the in-process reference,
//! a peer with another layout is refused (iceoryx2 size check and our version field), and the
//! receiver detects a sequence gap.

use std::time::Duration;

use iceoryx2::prelude::*;
use rins_transport::layout::{ImuBatch, LAYOUT_VERSION};
use rins_transport::{
    Mode, NavAction, NavOptions, ScheduledCommand, ServeOptions, Session, TransportError, navigate,
    reference, serve,
};

fn session(tag: &str) -> String {
    format!("t{}{tag}", std::process::id())
}

fn cfg() -> rins_plant::PlantConfig {
    rins_plant::presets::paper_16pos_config()
}

#[test]
fn lockstep_in_threads_equals_the_reference_with_a_table_command() {
    let name = session("lock");
    let commands = vec![ScheduledCommand {
        after_seq: 40,
        action: NavAction::MoveTo {
            outer_rad: 1.0,
            inner_rad: 0.5,
            rate_rps: 0.2,
        },
    }];
    let nav_cmds = commands.clone();
    let n2 = name.clone();
    let nav = std::thread::spawn(move || {
        navigate(
            &n2,
            &cfg(),
            &NavOptions {
                acknowledge: true,
                commands: nav_cmds,
                peer_timeout: Duration::from_secs(20),
            },
        )
    });
    let mut plant = rins_plant::Plant::new(&cfg()).unwrap();
    let summary = serve(
        &name,
        &mut plant,
        20_000,
        &ServeOptions {
            mode: Mode::Lockstep,
            batch: 37,
            pace: None,
            peer_timeout: Duration::from_secs(20),
            wait_for_restart: false,
        },
    )
    .unwrap();
    let got = nav.join().unwrap().unwrap();
    let want = reference(&cfg(), 20_000, 37, &commands);
    assert_eq!(summary.commands.len(), 1);
    assert_eq!(
        summary.commands[0].0,
        41 * 37,
        "applied at the first tick of the next batch"
    );
    assert_eq!((got.nav.samples, got.nav.last_tick), (20_000, 19_999));
    assert_eq!(
        got.nav.digest, want.digest,
        "navigation through shared memory equals the in-process run bit for bit"
    );
    assert_eq!(got.nav.state(), want.state());
}

#[derive(Debug, Clone, Copy, ZeroCopySend)]
#[type_name("rins::ImuBatch")]
#[repr(C)]
struct ForeignBatch {
    seq: u64,
    values: [f64; 3],
}

#[test]
#[allow(unsafe_code)]
fn a_peer_with_another_layout_is_refused() {
    let name = session("layout");
    let s = Session::open(&name, "plant").unwrap();
    // Same type name, other size: iceoryx2 refuses to open the service; we say why.
    let node = NodeBuilder::new()
        .config(&rins_transport::session::config(&name).unwrap())
        .create::<ipc::Service>()
        .unwrap();
    let service_name: ServiceName = format!("rins/{name}/imu").as_str().try_into().unwrap();
    let r = node
        .service_builder(&service_name)
        .publish_subscribe::<ForeignBatch>()
        .open();
    assert!(r.is_err(), "a foreign layout must not open the service");
    // Same size, other version: the navigator refuses the first message.
    let publisher = s.imu.publisher_builder().create().unwrap();
    let n2 = name.clone();
    let nav = std::thread::spawn(move || {
        navigate(
            &n2,
            &cfg(),
            &NavOptions {
                acknowledge: true,
                commands: vec![],
                peer_timeout: Duration::from_secs(10),
            },
        )
    });
    while s.imu_subscribers() == 0 {
        std::thread::sleep(Duration::from_millis(5));
    }
    let batch = ImuBatch {
        layout_version: LAYOUT_VERSION + 1,
        ..ImuBatch::default()
    };
    publisher.send_copy(batch).unwrap();
    let e = nav.join().unwrap().unwrap_err();
    assert!(matches!(e, TransportError::Layout { .. }), "{e}");
    assert!(
        e.to_string()
            .contains(&format!("layout version {}", LAYOUT_VERSION + 1)),
        "{e}"
    );
}

#[test]
fn a_sequence_gap_is_detected() {
    let name = session("gap");
    let s = Session::open(&name, "plant").unwrap();
    let publisher = s.imu.publisher_builder().create().unwrap();
    let n2 = name.clone();
    let nav = std::thread::spawn(move || {
        navigate(
            &n2,
            &cfg(),
            &NavOptions {
                acknowledge: false,
                commands: vec![],
                peer_timeout: Duration::from_secs(10),
            },
        )
    });
    while s.imu_subscribers() == 0 {
        std::thread::sleep(Duration::from_millis(5));
    }
    publisher
        .send_copy(ImuBatch {
            seq: 0,
            ..ImuBatch::default()
        })
        .unwrap();
    publisher
        .send_copy(ImuBatch {
            seq: 2,
            ..ImuBatch::default()
        })
        .unwrap();
    let e = nav.join().unwrap().unwrap_err();
    assert!(
        matches!(
            e,
            TransportError::Gap {
                expected: 1,
                got: 2
            }
        ),
        "{e}"
    );
}

#[test]
fn a_navigator_configured_for_another_rate_is_refused() {
    let name = session("rate");
    let n2 = name.clone();
    // The navigator thinks the plant runs at 100 Hz; the plant runs at 200 Hz.
    let nav = std::thread::spawn(move || {
        navigate(
            &n2,
            &cfg(),
            &NavOptions {
                acknowledge: true,
                commands: vec![],
                peer_timeout: Duration::from_secs(10),
            },
        )
    });
    let fast = rins_plant::PlantConfig {
        rate_hz: 200.0,
        ..cfg()
    };
    let mut plant = rins_plant::Plant::new(&fast).unwrap();
    let served = serve(
        &name,
        &mut plant,
        1000,
        &ServeOptions {
            mode: Mode::Lockstep,
            batch: 10,
            pace: None,
            peer_timeout: Duration::from_secs(10),
            wait_for_restart: false,
        },
    );
    let e = nav.join().unwrap().unwrap_err();
    assert!(matches!(e, TransportError::Rate { .. }), "{e}");
    assert!(e.to_string().contains("run.rate_hz = 100"), "{e}");
    // The plant sees its navigator go away instead of acknowledging.
    assert!(served.is_err());
}

use crate::ship;

/// The in-process navigation run (`rins_experiments::Tracker::at_truth`) of `cfg` started after
/// `skip` samples, over `samples` more: the digest of its states (folded as the transport's
/// navigator folds its own), its final state and the plant's carrier truth at the end.
fn in_process(
    cfg: &rins_plant::PlantConfig,
    skip: u64,
    samples: u64,
) -> (
    u64,
    rins_navigation::strapdown::NavState,
    rins_plant::carrier::CarrierTruth,
) {
    let mut plant = rins_plant::Plant::new(cfg).unwrap();
    for _ in 0..skip {
        plant.step();
    }
    // No error record is due within the run: the truth is never asked for.
    let mut t = rins_experiments::Tracker::at_truth(&plant, 1e9);
    let mut digest = rins_transport::nav_side::DIGEST_START;
    for _ in 0..samples {
        let s = plant.step();
        assert!(t.push(&s, || unreachable!()).is_none());
        digest = rins_transport::fold_digest(digest, t.state());
    }
    (digest, *t.state(), plant.carrier_truth())
}

fn state_bits(s: &rins_navigation::strapdown::NavState) -> Vec<u64> {
    let q = s.q_bn.quaternion();
    [
        s.lat_rad, s.lon_rad, s.height_m, s.v_n.x, s.v_n.y, s.v_n.z, q.w, q.i, q.j, q.k,
    ]
    .iter()
    .map(|x| x.to_bits())
    .collect()
}

/// Horizontal position error (m, longitude difference wrapped) and velocity error (m/s) of
/// `s` against the carrier truth `c`.
fn errors(
    s: &rins_navigation::strapdown::NavState,
    c: &rins_plant::carrier::CarrierTruth,
) -> (f64, f64) {
    let dlon = (s.lon_rad - c.lon_rad + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
        - std::f64::consts::PI;
    let (n, e) = rins_navigation::errors::position_error_m(
        &rins_navigation::strapdown::NavState {
            lon_rad: c.lon_rad + dlon,
            ..*s
        },
        c.lat_rad,
        c.lon_rad,
        c.height_m,
    );
    (n.hypot(e), (s.v_n - c.v_n).xy().norm())
}

/// The ship of issue 29: on the equator at 179.99° E heading east at 30 kn (it crosses the
/// antimeridian after about 72 s), the `[site]` left at the paper's 36.6° N 123.6° E.
fn dateline_ship() -> rins_plant::PlantConfig {
    let mut cfg = ship::ship();
    let s = &mut cfg.carrier.ship;
    (s.lat_deg, s.lon_deg) = (0.0, 179.99);
    s.legs = vec![rins_plant::carrier::LegSpec {
        heading_deg: 90.0,
        speed_kn: 30.0,
        duration_s: 3600.0,
    }];
    cfg
}

fn lockstep(batch: usize, wait_for_restart: bool) -> ServeOptions {
    ServeOptions {
        mode: Mode::Lockstep,
        batch,
        pace: None,
        peer_timeout: Duration::from_secs(20),
        wait_for_restart,
    }
}

fn nav_opts() -> NavOptions {
    NavOptions {
        acknowledge: true,
        commands: vec![],
        peer_timeout: Duration::from_secs(20),
    }
}

#[test]
fn the_separate_navigator_starts_where_the_in_process_run_starts_static_and_at_sea() {
    const SAMPLES: u64 = 12_000; // 120 s: the ship's course change at 60 s, the dateline at ~72 s
    for (tag, cfg) in [
        ("static", cfg()),
        ("ship", ship::ship()),
        ("dateline", dateline_ship()),
    ] {
        let name = session(&format!("start{tag}"));
        let (n2, c2) = (name.clone(), cfg.clone());
        let nav = std::thread::spawn(move || navigate(&n2, &c2, &nav_opts()));
        let mut plant = rins_plant::Plant::new(&cfg).unwrap();
        serve(&name, &mut plant, SAMPLES, &lockstep(37, false)).unwrap();
        let got = nav.join().unwrap().unwrap();
        let (digest, state, truth) = in_process(&cfg, 0, SAMPLES);
        assert_eq!(got.nav.samples, SAMPLES, "{tag}");
        assert_eq!(
            got.nav.digest, digest,
            "{tag}: every state of the separate navigator equals the in-process run's"
        );
        assert_eq!(
            state_bits(got.nav.state().unwrap()),
            state_bits(&state),
            "{tag}"
        );
        // Independent of the digests: the solution follows the carrier (a navigator started
        // at the site at rest was thousands of km and 15 m/s off on the dateline ship).
        let (pos_m, vel_mps) = errors(&state, &truth);
        // The navigator's own error figure (from the truth block) says the same.
        let fe = got.final_error().expect("rins serve publishes the truth");
        assert!(
            (fe.horizontal_m - pos_m).abs() < 1e-6 && (fe.velocity_mps - vel_mps).abs() < 1e-9,
            "{tag}: {fe:?} against {pos_m} m, {vel_mps} m/s"
        );
        let speed = truth.v_n.xy().norm();
        eprintln!(
            "{tag}: equal to the in-process run bit for bit; after 120 s {pos_m:.2} m and {vel_mps:.4} m/s from the truth (speed {speed:.2} m/s)"
        );
        assert!(
            pos_m < 50.0 && vel_mps < 0.5,
            "{tag}: {pos_m} m, {vel_mps} m/s"
        );
        if tag == "dateline" {
            assert!((speed - 30.0 * 1852.0 / 3600.0).abs() < 0.5, "{speed}");
            assert!(
                truth.lon_rad.to_degrees().rem_euclid(360.0) > 180.0,
                "crossed"
            );
        }
    }
}

/// A first navigator that acknowledges batches 0 … `leave_at` − 1, receives batch `leave_at`
/// and leaves the session without acknowledging it (as one killed there would).
fn navigator_leaving_at(name: &str, leave_at: u64) {
    use rins_transport::layout::{NavCommand, kind};
    let s = Session::open(name, "first-navigator").unwrap();
    let cmd = s
        .cmd
        .publisher_builder()
        .backpressure_strategy(BackpressureStrategy::RetryUntilDelivered)
        .create()
        .unwrap();
    let sub = s.imu.subscriber_builder().create().unwrap();
    let t0 = std::time::Instant::now();
    loop {
        let Some(b) = sub.receive().unwrap() else {
            assert!(t0.elapsed() < Duration::from_secs(60), "no batch");
            std::thread::yield_now();
            continue;
        };
        let seq = b.payload().seq;
        if seq == leave_at {
            return;
        }
        cmd.send_copy(NavCommand {
            layout_version: LAYOUT_VERSION,
            kind: kind::ACK,
            ack_seq: seq,
            ..NavCommand::default()
        })
        .unwrap();
    }
}

#[test]
fn a_replacement_navigator_starts_from_the_state_at_the_batch_it_joins() {
    const SAMPLES: u64 = 9_000;
    const BATCH: u64 = 50;
    const JOIN: u64 = 70; // batch 70: tick 3500, 35 s into the run, on the ship's first leg
    for (tag, cfg) in [("static", cfg()), ("ship", ship::ship())] {
        let name = session(&format!("rejoin{tag}"));
        let (n2, c2) = (name.clone(), cfg.clone());
        let plant = std::thread::spawn(move || {
            let mut plant = rins_plant::Plant::new(&c2).unwrap();
            serve(&n2, &mut plant, SAMPLES, &lockstep(BATCH as usize, true))
        });
        navigator_leaving_at(&name, JOIN);
        let got = navigate(&name, &cfg, &nav_opts()).unwrap();
        let served = plant.join().unwrap().unwrap();
        assert_eq!(served.restarts, 1, "{tag}: {:?}", served.events);
        let start = got.nav.start.unwrap();
        assert_eq!(
            (start.tick, got.nav.first_tick, got.nav.samples),
            (JOIN * BATCH, Some(JOIN * BATCH), SAMPLES - JOIN * BATCH),
            "{tag}: joins at the unacknowledged batch, no sample lost or duplicated"
        );
        let (digest, state, truth) = in_process(&cfg, JOIN * BATCH, SAMPLES - JOIN * BATCH);
        assert_eq!(
            got.nav.digest,
            digest,
            "{tag}: equal to an in-process run started from the state at tick {}",
            JOIN * BATCH
        );
        assert_eq!(
            state_bits(got.nav.state().unwrap()),
            state_bits(&state),
            "{tag}"
        );
        let (pos_m, vel_mps) = errors(&state, &truth);
        eprintln!(
            "{tag}: the replacement from tick {} equals the in-process run bit for bit; {pos_m:.2} m, {vel_mps:.4} m/s from the truth at the end",
            JOIN * BATCH
        );
        assert!(
            pos_m < 50.0 && vel_mps < 0.5,
            "{tag}: {pos_m} m, {vel_mps} m/s"
        );
    }
}
