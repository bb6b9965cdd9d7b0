//! The truth block of layout version 2: a subscriber of a ship scenario's stream receives, with
//! every record, the plant's carrier truth and IMU attitude bit for bit (the attitude also in
//! each batch's start state), and the navigator's result does not depend on it (the navigator
//! side never reads it).

use crate::ship::ship;
use std::time::{Duration, Instant};

use rins_plant::Plant;
use rins_transport::layout::{FLAG_END, LAYOUT_VERSION, NavCommand, TruthRecord, kind};
use rins_transport::{Mode, NavOptions, ServeOptions, Session, navigate, reference, serve};

fn session(tag: &str) -> String {
    format!("tr{}{tag}", std::process::id())
}

fn opts(mode: Mode, batch: usize) -> ServeOptions {
    ServeOptions {
        mode,
        batch,
        pace: None,
        peer_timeout: Duration::from_secs(20),
        wait_for_restart: false,
    }
}

fn bits(r: &TruthRecord) -> Vec<u64> {
    [r.lat_rad, r.lon_rad, r.height_m]
        .iter()
        .chain(&r.v_enu_mps)
        .chain(&r.q_cn)
        .chain(&r.q_bn)
        .map(|x| x.to_bits())
        .collect()
}

#[test]
fn a_subscriber_gets_the_plants_carrier_truth_bit_for_bit() {
    const SAMPLES: u64 = 30_000; // 5 min at 100 Hz: a course change, waves of ~10 s period
    let name = session("ship");
    let n2 = name.clone();
    let plant = std::thread::spawn(move || {
        let mut plant = Plant::new(&ship()).unwrap();
        serve(&n2, &mut plant, SAMPLES, &opts(Mode::Lockstep, 47))
    });
    // A reader as docs/transport.md describes: subscribes, acknowledges every batch.
    let s = Session::open(&name, "truth-reader").unwrap();
    while s.imu_publishers() == 0 {
        std::thread::sleep(Duration::from_millis(2));
    }
    let sub = s.imu.subscriber_builder().create().unwrap();
    let cmd = s
        .cmd
        .publisher_builder()
        .backpressure_strategy(iceoryx2::prelude::BackpressureStrategy::RetryUntilDelivered)
        .create()
        .unwrap();
    let mut want = Plant::new(&ship()).unwrap();
    let (mut n, mut worst_q_bn, mut max_speed) = (0u64, 0.0f64, 0.0f64);
    let t0 = Instant::now();
    loop {
        let Some(sample) = sub.receive().unwrap() else {
            assert!(t0.elapsed() < Duration::from_secs(60), "no batch");
            std::thread::yield_now();
            continue;
        };
        let b = sample.payload();
        assert_eq!(b.layout_version, LAYOUT_VERSION);
        // The start state's attitude: the plant's before the batch's first record.
        let q0 = want.attitude_q_bn();
        assert_eq!(
            b.start.q_bn.map(f64::to_bits),
            [q0.w, q0.i, q0.j, q0.k].map(f64::to_bits),
            "start of batch {}",
            b.seq
        );
        for k in 0..b.count as usize {
            let (r, got) = (&b.records[k], &b.truth[k]);
            let s = want.step();
            assert_eq!(r.tick, s.index);
            // The plant's own truth, field by field and bit for bit.
            // The IMU attitude: the plant's closed-form composition of the carrier and the
            // true gimbal angles, the CSV's and the FMU's.
            let tr = want.truth();
            let t = tr.carrier;
            let q = t.q_cn.quaternion();
            let p = want.attitude_q_bn();
            let p = p.quaternion();
            let plant_truth = TruthRecord {
                lat_rad: t.lat_rad,
                lon_rad: t.lon_rad,
                height_m: t.height_m,
                v_enu_mps: t.v_n.into(),
                q_cn: [q.w, q.i, q.j, q.k],
                q_bn: [p.w, p.i, p.j, p.k],
            };
            assert_eq!(bits(got), bits(&plant_truth), "tick {}", r.tick);
            // And what a sink composes from the truth record (the CSV's route).
            let c = want.truth_mount().q_bn_of(&tr);
            assert_eq!(
                [c.w, c.i, c.j, c.k].map(f64::to_bits),
                got.q_bn.map(f64::to_bits),
                "tick {}",
                r.tick
            );
            // Against C_b^n, the plant's matrix (its C_c^n on the ship's segment rule is the
            // truth's to the interpolation's rounding).
            let m = nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(
                got.q_bn[0],
                got.q_bn[1],
                got.q_bn[2],
                got.q_bn[3],
            ));
            let d = (m.to_rotation_matrix().into_inner() - want.attitude_c_bn()).amax();
            worst_q_bn = worst_q_bn.max(d);
            max_speed = max_speed.max(t.v_n.norm());
            n += 1;
        }
        let (seq, flags) = (b.seq, b.flags);
        drop(sample);
        cmd.send_copy(NavCommand {
            layout_version: LAYOUT_VERSION,
            kind: kind::ACK,
            ack_seq: seq,
            ..NavCommand::default()
        })
        .unwrap();
        if flags & FLAG_END != 0 {
            break;
        }
    }
    while s.imu_publishers() > 0 {
        std::thread::sleep(Duration::from_millis(1));
    }
    let summary = plant.join().unwrap().unwrap();
    assert_eq!((n, summary.samples), (SAMPLES, SAMPLES));
    // Rounding of the carrier's interpolation; a wrong composition would be degrees.
    assert!(worst_q_bn < 1e-13, "C_b^n {worst_q_bn:e}");
    assert!(max_speed > 6.0, "the ship moves: {max_speed} m/s");
    eprintln!(
        "{n} truth records bit-identical to the plant's; q_bn reproduces C_b^n within {worst_q_bn:e}"
    );
}

#[test]
fn the_navigator_does_not_read_the_truth_block() {
    // Lockstep on the ship: the navigator's trajectory digest equals the in-process reference,
    // whose records never had a truth block (reference() feeds ImuRecords only).
    let name = session("nav");
    let n2 = name.clone();
    let nav = std::thread::spawn(move || {
        navigate(
            &n2,
            &ship(),
            &NavOptions {
                acknowledge: true,
                commands: vec![],
                peer_timeout: Duration::from_secs(20),
            },
        )
    });
    let mut plant = Plant::new(&ship()).unwrap();
    serve(&name, &mut plant, 5_000, &opts(Mode::Lockstep, 64)).unwrap();
    let got = nav.join().unwrap().unwrap();
    let want = reference(&ship(), 5_000, 64, &[]);
    assert_eq!(got.nav.digest, want.digest);
}
