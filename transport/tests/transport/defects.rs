//! Issue 16 part A: each defect found in the transport, reproduced with a navigator written
//! from docs/transport.md alone (raw iceoryx2, not rins' own navigator). Each test failed
//! before its fix.

use std::time::{Duration, Instant};

use iceoryx2::prelude::*;
use rins_transport::layout::{FLAG_END, ImuBatch, LAYOUT_VERSION, NavCommand, kind};
use rins_transport::{Mode, ServeOptions, ServeSummary, TransportError, serve};

fn session(tag: &str) -> String {
    format!("d{}{tag}", std::process::id())
}

fn opts(pace: Option<f64>, wait_for_restart: bool) -> ServeOptions {
    ServeOptions {
        mode: Mode::Lockstep,
        batch: 10,
        pace,
        peer_timeout: Duration::from_secs(10),
        wait_for_restart,
    }
}

/// A navigator as docs/transport.md describes one: its own node under the session prefix,
/// services opened or created with the documented settings only (iceoryx2's defaults for
/// everything the document does not name).
struct DocPeer {
    _node: Node<ipc::Service>,
    imu: iceoryx2::port::subscriber::Subscriber<ipc::Service, ImuBatch, ()>,
    cmd: iceoryx2::port::publisher::Publisher<ipc::Service, NavCommand, ()>,
}

impl DocPeer {
    fn join(name: &str, imu_safe_overflow: bool) -> Self {
        let mut config = Config::default();
        config.global.prefix = FileName::new(format!("rins_{name}_").as_bytes()).unwrap();
        let node = NodeBuilder::new()
            .config(&config)
            .create::<ipc::Service>()
            .unwrap();
        let svc =
            |s: &str| -> ServiceName { format!("rins/{name}/{s}").as_str().try_into().unwrap() };
        let imu = node
            .service_builder(&svc("imu"))
            .publish_subscribe::<ImuBatch>()
            .enable_safe_overflow(imu_safe_overflow)
            .subscriber_max_buffer_size(16)
            .history_size(0)
            .open_or_create()
            .unwrap();
        let cmd = node
            .service_builder(&svc("cmd"))
            .publish_subscribe::<NavCommand>()
            .enable_safe_overflow(false)
            .subscriber_max_buffer_size(16)
            .open_or_create()
            .unwrap();
        Self {
            imu: imu.subscriber_builder().create().unwrap(),
            cmd: cmd
                .publisher_builder()
                .backpressure_strategy(BackpressureStrategy::RetryUntilDelivered)
                .create()
                .unwrap(),
            _node: node,
        }
    }

    /// The next batch (seq, count, flags), waiting up to 10 s.
    fn next(&self) -> (u64, u32, u32) {
        let t = Instant::now();
        loop {
            if let Some(s) = self.imu.receive().unwrap() {
                let b = s.payload();
                return (b.seq, b.count, b.flags);
            }
            assert!(t.elapsed() < Duration::from_secs(10), "no batch");
            std::thread::sleep(Duration::from_micros(100));
        }
    }

    fn send(&self, kind: u32, ack_seq: u64, layout_version: u32) {
        self.cmd
            .send_copy(NavCommand {
                layout_version,
                kind,
                ack_seq,
                ..NavCommand::default()
            })
            .unwrap();
    }

    /// Acknowledges every batch until the end of the run; returns the samples received.
    fn run_to_end(&self) -> u64 {
        let mut samples = 0;
        loop {
            let (seq, count, flags) = self.next();
            samples += u64::from(count);
            self.send(kind::ACK, seq, LAYOUT_VERSION);
            if flags & FLAG_END != 0 {
                return samples;
            }
        }
    }
}

fn serve_in_thread(
    name: &str,
    samples: u64,
    o: ServeOptions,
) -> std::thread::JoinHandle<Result<ServeSummary, TransportError>> {
    let name = name.to_string();
    std::thread::spawn(move || {
        let mut plant = rins_plant::Plant::new(&rins_plant::presets::paper_16pos_config()).unwrap();
        serve(&name, &mut plant, samples, &o)
    })
}

#[test]
fn a1_a_navigator_from_the_documentation_that_starts_first_is_served() {
    // Before the fix serve failed: the peer's rins/S/cmd had iceoryx2's default of 2
    // publishers, the plant asked for 4.
    let name = session("a1");
    let peer = DocPeer::join(&name, false);
    let plant = serve_in_thread(&name, 200, opts(None, false));
    assert_eq!(peer.run_to_end(), 200);
    let s = plant.join().unwrap().unwrap();
    assert_eq!(s.samples, 200);
}

#[test]
fn a1_a_service_with_a_setting_rins_cannot_use_is_refused_naming_it() {
    let name = session("a1bad");
    let _peer = DocPeer::join(&name, true); // safe overflow on: samples would be overwritten
    let e = serve_in_thread(&name, 200, opts(None, false))
        .join()
        .unwrap()
        .unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, TransportError::Setting { .. }), "{msg}");
    assert!(
        msg.contains("rins/") && msg.contains("/imu") && msg.contains("safe overflow"),
        "{msg}"
    );
    assert!(
        msg.contains("= on") && msg.contains("needs off"),
        "both values: {msg}"
    );
}

#[test]
fn a3_a_wrong_ack_seq_is_refused_naming_both_sequences() {
    let name = session("a3");
    let peer = DocPeer::join(&name, false);
    let plant = serve_in_thread(&name, 200, opts(None, false));
    let (seq, _, _) = peer.next();
    assert_eq!(seq, 0);
    peer.send(kind::ACK, 5, LAYOUT_VERSION);
    let e = plant.join().unwrap().unwrap_err();
    assert!(
        matches!(
            e,
            TransportError::WrongAck {
                expected: 0,
                got: 5
            }
        ),
        "{e}"
    );
    let msg = e.to_string();
    assert!(msg.contains("batch 5") && msg.contains("batch 0"), "{msg}");
}

#[test]
fn a3_a_navigator_that_exits_normally_is_not_reported_dead() {
    let name = session("a3exit");
    let peer = DocPeer::join(&name, false);
    let plant = serve_in_thread(&name, 200, opts(None, false));
    let (seq, _, _) = peer.next();
    peer.send(kind::ACK, seq, LAYOUT_VERSION);
    peer.next();
    let left = Instant::now();
    drop(peer); // a normal end: the node leaves the session
    let e = plant.join().unwrap().unwrap_err();
    let detected = left.elapsed();
    assert!(
        matches!(
            e,
            TransportError::PeerLeft {
                peer: "navigator",
                seq: 1
            }
        ),
        "{e}"
    );
    assert!(!e.to_string().contains("died"), "{e}");
    assert!(detected < Duration::from_secs(1), "{detected:?}");
}

#[test]
fn a4_stop_ends_the_run_whatever_batch_it_names() {
    let name = session("a4");
    let peer = DocPeer::join(&name, false);
    let plant = serve_in_thread(&name, 10_000, opts(None, false));
    let (seq, _, _) = peer.next();
    peer.send(kind::ACK, seq, LAYOUT_VERSION);
    let (seq, _, _) = peer.next();
    assert_eq!(seq, 1);
    peer.send(kind::STOP, 0, LAYOUT_VERSION); // names an old batch: still a stop
    let (seq, count, flags) = peer.next();
    assert_eq!((seq, count), (2, 0), "an empty end-of-run batch follows");
    assert_ne!(flags & FLAG_END, 0);
    peer.send(kind::ACK, seq, LAYOUT_VERSION);
    let s = plant.join().unwrap().unwrap();
    assert_eq!((s.samples, s.batches), (20, 3));
}

#[test]
fn a5_a_command_of_another_layout_version_is_refused_naming_both() {
    let name = session("a5");
    let peer = DocPeer::join(&name, false);
    let plant = serve_in_thread(&name, 200, opts(None, false));
    let (seq, _, _) = peer.next();
    // The version after ours (layout version 2 since the truth block).
    let other = LAYOUT_VERSION + 1;
    peer.send(kind::ACK, seq, other);
    let e = plant.join().unwrap().unwrap_err();
    assert!(
        matches!(e, TransportError::CommandVersion { got, want } if got == other && want == LAYOUT_VERSION),
        "{e}"
    );
    let msg = e.to_string();
    assert!(
        msg.contains(&format!("layout_version {other}"))
            && msg.contains(&format!("layout version {LAYOUT_VERSION}")),
        "{msg}"
    );
}

#[test]
fn the_pace_is_kept_after_a_restart_pause() {
    // 20x real time, 10 samples (0.1 s) per batch: one batch per 5 ms.
    let name = session("pace");
    let plant = serve_in_thread(&name, 100_000, opts(Some(20.0), true));
    let first = DocPeer::join(&name, false);
    for _ in 0..10 {
        let (seq, _, _) = first.next();
        first.send(kind::ACK, seq, LAYOUT_VERSION);
    }
    first.next(); // batch 10 stays unacknowledged
    drop(first);
    std::thread::sleep(Duration::from_millis(1000)); // the pause: 200 batches of wall time
    let second = DocPeer::join(&name, false);
    second.send(kind::HELLO, 0, LAYOUT_VERSION);
    let (seq, _, _) = second.next();
    assert_eq!(seq, 10, "the unacknowledged batch is resent");
    second.send(kind::ACK, seq, LAYOUT_VERSION);
    let t = Instant::now();
    let mut batches = 0;
    while t.elapsed() < Duration::from_millis(250) {
        let (seq, _, _) = second.next();
        second.send(kind::ACK, seq, LAYOUT_VERSION);
        batches += 1;
    }
    // Paced: 50 batches in 250 ms. Bursting to catch up the pause: ~250 at once.
    assert!(
        (5..=65).contains(&batches),
        "{batches} batches in 250 ms after the restart, 50 expected at 20x real time"
    );
    second.send(kind::STOP, 0, LAYOUT_VERSION);
    loop {
        let (seq, _, flags) = second.next();
        second.send(kind::ACK, seq, LAYOUT_VERSION);
        if flags & FLAG_END != 0 {
            break;
        }
    }
    let s = plant.join().unwrap().unwrap();
    assert_eq!(s.restarts, 1, "{:?}", s.events);
}
