//! Transport benchmarks (`cargo bench -p rins-transport`): free-running throughput of 64-record
//! batches to a Rust subscriber (samples/s), and lockstep round-trip latency (batch out,
//! acknowledgement back; median and p99). Publisher and subscriber are separate iceoryx2 nodes
//! in two threads of this process (shared memory either way); the CLI figures in
//! docs/transport.md are between processes.

use std::time::{Duration, Instant};

use rins_transport::Session;
use rins_transport::layout::{BATCH_CAPACITY, ImuBatch, LAYOUT_VERSION, NavCommand, kind};

fn throughput(name: &str, batches: u64) -> f64 {
    let s = Session::open(name, "bench-pub").unwrap();
    let publisher = s
        .imu
        .publisher_builder()
        .backpressure_strategy(iceoryx2::prelude::BackpressureStrategy::RetryUntilDelivered)
        .create()
        .unwrap();
    let n2 = name.to_string();
    let reader = std::thread::spawn(move || {
        let s = Session::open(&n2, "bench-sub").unwrap();
        let sub = s.imu.subscriber_builder().create().unwrap();
        let mut expected = 0u64;
        let mut samples = 0u64;
        while expected < batches {
            if let Some(b) = sub.receive().unwrap() {
                assert_eq!(b.payload().seq, expected, "gap");
                samples += b.payload().count as u64;
                expected += 1;
            }
        }
        samples
    });
    while s.imu_subscribers() == 0 {
        std::thread::sleep(Duration::from_millis(1));
    }
    let t0 = Instant::now();
    let mut batch = ImuBatch {
        count: BATCH_CAPACITY as u32,
        ..ImuBatch::default()
    };
    for seq in 0..batches {
        batch.seq = seq;
        batch.records[0].tick = seq;
        let sample = publisher.loan_uninit().unwrap();
        sample.write_payload(batch).send().unwrap();
    }
    let samples = reader.join().unwrap();
    samples as f64 / t0.elapsed().as_secs_f64()
}

fn round_trips(name: &str, n: usize) -> Vec<f64> {
    let s = Session::open(name, "bench-plant").unwrap();
    let publisher = s.imu.publisher_builder().create().unwrap();
    let acks = s.cmd.subscriber_builder().create().unwrap();
    let n2 = name.to_string();
    let echo = std::thread::spawn(move || {
        let s = Session::open(&n2, "bench-nav").unwrap();
        let sub = s.imu.subscriber_builder().create().unwrap();
        let cmd = s.cmd.publisher_builder().create().unwrap();
        let mut left = n;
        while left > 0 {
            if let Some(b) = sub.receive().unwrap() {
                cmd.send_copy(NavCommand {
                    layout_version: LAYOUT_VERSION,
                    kind: kind::ACK,
                    ack_seq: b.payload().seq,
                    ..NavCommand::default()
                })
                .unwrap();
                left -= 1;
            }
        }
    });
    while s.imu_subscribers() == 0 || s.cmd.dynamic_config_publishers() == 0 {
        std::thread::sleep(Duration::from_millis(1));
    }
    let mut batch = ImuBatch {
        count: 1,
        ..ImuBatch::default()
    };
    let mut out = Vec::with_capacity(n);
    for seq in 0..n as u64 {
        batch.seq = seq;
        let t0 = Instant::now();
        publisher.send_copy(batch).unwrap();
        loop {
            if let Some(a) = acks.receive().unwrap()
                && a.payload().ack_seq == seq
            {
                break;
            }
        }
        out.push(t0.elapsed().as_secs_f64() * 1e6);
    }
    echo.join().unwrap();
    out
}

trait Publishers {
    fn dynamic_config_publishers(&self) -> usize;
}

impl Publishers
    for iceoryx2::service::port_factory::publish_subscribe::PortFactory<
        iceoryx2::prelude::ipc::Service,
        NavCommand,
        (),
    >
{
    fn dynamic_config_publishers(&self) -> usize {
        use iceoryx2::service::port_factory::PortFactory as _;
        self.dynamic_config().number_of_publishers()
    }
}

fn main() {
    let pid = std::process::id();
    let rate = throughput(&format!("bench{pid}a"), 100_000);
    println!(
        "free-running throughput, 64-record batches: {:.2} M samples/s (target >= 2)",
        rate / 1e6
    );
    let mut rtt = round_trips(&format!("bench{pid}b"), 20_000);
    rtt.sort_by(f64::total_cmp);
    let q = |p: f64| rtt[((rtt.len() - 1) as f64 * p) as usize];
    println!(
        "lockstep round trip (batch out, ack back): median {:.1} us, p99 {:.1} us (target median <= 10)",
        q(0.5),
        q(0.99)
    );
}
