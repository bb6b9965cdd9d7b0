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
