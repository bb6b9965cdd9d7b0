//! The plant side: steps the plant, publishes batches, applies the navigator's table commands at
//! defined ticks, and in lockstep waits for each batch's acknowledgement.

use std::time::{Duration, Instant};

use iceoryx2::prelude::BackpressureStrategy;
use rins_plant::{GimbalCommand, ImuSample, Plant, Truth};

use crate::layout::{
    BATCH_CAPACITY, FLAG_END, FLAG_INTERRUPTED, ImuBatch, ImuRecord, NavCommand, kind,
};
use crate::session::{Session, TransportError, ipc};

/// Delivery mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    /// The plant advances only when the navigator has acknowledged the previous batch:
    /// deterministic whatever the speeds. Commands apply at the first tick of the next batch.
    Lockstep,
    /// As fast as the navigator consumes (backpressure, no loss). Commands apply at the first
    /// tick of the next batch sent after they arrive.
    FreeRunning,
}

/// How the plant serves.
#[derive(Clone, Debug)]
pub struct ServeOptions {
    /// Delivery mode.
    pub mode: Mode,
    /// Records per message, 1 … 64.
    pub batch: usize,
    /// Real-time factor (simulated seconds per wall second); `None` runs as fast as possible.
    pub pace: Option<f64>,
    /// How long to wait for a navigator to connect (also after it dies).
    pub peer_timeout: Duration,
    /// After the navigator dies, wait for a new one and resend from the first unacknowledged
    /// batch (instead of failing).
    pub wait_for_restart: bool,
}

/// What the plant did.
#[derive(Debug, Default)]
pub struct ServeSummary {
    /// Samples published.
    pub samples: u64,
    /// Batches published.
    pub batches: u64,
    /// Commands applied: (tick, command).
    pub commands: Vec<(u64, NavCommand)>,
    /// Navigator deaths survived.
    pub restarts: u32,
    /// Messages reporting what happened (peer deaths, restarts).
    pub events: Vec<String>,
    /// Wall time, s.
    pub wall_s: f64,
    /// Ended by SIGINT/SIGTERM.
    pub interrupted: bool,
}

fn apply(
    plant: &mut Plant,
    c: &NavCommand,
    summary: &mut ServeSummary,
) -> Result<(), TransportError> {
    if c.kind == kind::MOVE_TO {
        plant
            .command_gimbal(&GimbalCommand::MoveTo {
                outer_rad: c.outer_rad,
                inner_rad: c.inner_rad,
                rate_rps: c.rate_rps,
            })
            .map_err(|e| TransportError::Ipc {
                what: "navigator command".into(),
                detail: e,
            })?;
        summary.commands.push((plant.samples_done(), *c));
    }
    Ok(())
}

/// Serves `samples` samples of `plant` on session `name`.
pub fn serve(
    name: &str,
    plant: &mut Plant,
    samples: u64,
    opts: &ServeOptions,
) -> Result<ServeSummary, TransportError> {
    serve_observed(name, plant, samples, opts, &mut |_, _| {})
}

/// [`serve`], handing every sample and the plant's truth over it to `observe` as it is produced
/// (once each, also when a batch is resent to a restarted navigator): a recorder or logger on
/// the plant side.
pub fn serve_observed(
    name: &str,
    plant: &mut Plant,
    samples: u64,
    opts: &ServeOptions,
    observe: &mut dyn FnMut(&ImuSample, &Truth),
) -> Result<ServeSummary, TransportError> {
    let t0 = Instant::now();
    let session = Session::open(name, "plant")?;
    let publisher = session
        .imu
        .publisher_builder()
        .backpressure_strategy(BackpressureStrategy::RetryUntilDelivered)
        .create()
        .map_err(|e| ipc("creating the IMU publisher")(&e))?;
    let commands = session
        .cmd
        .subscriber_builder()
        .create()
        .map_err(|e| ipc("creating the command subscriber")(&e))?;
    let mut summary = ServeSummary::default();
    let batch_len = opts.batch.clamp(1, BATCH_CAPACITY);
    let wait_for_navigator = |session: &Session| -> Result<(), TransportError> {
        // Samples sent before a subscriber connects are lost: wait for one.
        let start = Instant::now();
        while session.imu_subscribers() == 0 {
            if session.interrupted() {
                return Err(TransportError::Interrupted);
            }
            if start.elapsed() > opts.peer_timeout {
                return Err(TransportError::NoPeer {
                    peer: "navigator",
                    timeout_s: opts.peer_timeout.as_secs_f64(),
                });
            }
            session.peer_died();
            std::thread::sleep(Duration::from_millis(2));
        }
        Ok(())
    };
    wait_for_navigator(&session)?;
    let mut seq: u64 = 0;
    let mut done: u64 = 0;
    let mut batch = ImuBatch::default();
    let mut stop = false;
    loop {
        // Fill the next batch (or the end marker).
        batch.seq = seq;
        batch.flags = 0;
        let n = (samples - done).min(batch_len as u64) as usize;
        for r in batch.records[..n].iter_mut() {
            let s = plant.step();
            observe(&s, plant.truth());
            *r = ImuRecord::from_sample(&s);
        }
        batch.count = n as u32;
        done += n as u64;
        let interrupted = seq.is_multiple_of(256) && session.interrupted();
        if done >= samples || stop || interrupted {
            batch.flags |= FLAG_END;
        }
        if interrupted {
            batch.flags |= FLAG_INTERRUPTED;
            summary.interrupted = true;
        }
        // Send; in lockstep, wait for the acknowledgement (resending after a navigator restart).
        loop {
            let receivers = publisher
                .send_copy(batch)
                .map_err(|e| ipc("sending a batch")(&e))?;
            if receivers == 0 {
                session.peer_died();
                if !opts.wait_for_restart {
                    return Err(TransportError::PeerDied {
                        peer: "navigator",
                        after_ms: 0,
                    });
                }
                summary.events.push(format!(
                    "navigator gone at batch {seq}; waiting for a new one"
                ));
                wait_for_navigator(&session)?;
                summary.restarts += 1;
                continue;
            }
            if opts.mode != Mode::Lockstep && batch.flags & FLAG_END == 0 {
                break;
            }
            // Wait for the acknowledgement of this batch.
            let sent = Instant::now();
            let mut last_check = Instant::now();
            let mut polls: u32 = 0;
            let acked = loop {
                if let Some(c) = commands
                    .receive()
                    .map_err(|e| ipc("receiving commands")(&e))?
                {
                    let c = *c.payload();
                    if c.kind == kind::HELLO {
                        if seq > 0 {
                            summary.events.push(format!("a navigator joined while batch {seq} was unacknowledged; resending it"));
                            summary.restarts += 1;
                        }
                        break false;
                    }
                    if c.ack_seq == seq {
                        apply(plant, &c, &mut summary)?;
                        stop |= c.kind == kind::STOP;
                        break true;
                    }
                    continue;
                }
                polls = polls.wrapping_add(1);
                if polls.is_multiple_of(64) {
                    std::thread::yield_now();
                }
                if last_check.elapsed() > Duration::from_millis(50) {
                    last_check = Instant::now();
                    // Free-running: a subscriber that does not acknowledge is done once it has
                    // read the end marker and left.
                    if opts.mode == Mode::FreeRunning && session.imu_subscribers() == 0 {
                        session.peer_died();
                        break true;
                    }
                    if session.peer_died() || session.imu_subscribers() == 0 {
                        let after_ms = sent.elapsed().as_millis() as u64;
                        if !opts.wait_for_restart {
                            return Err(TransportError::PeerDied {
                                peer: "navigator",
                                after_ms,
                            });
                        }
                        summary.events.push(format!("navigator died {after_ms} ms after batch {seq} was sent; waiting for a new one"));
                        wait_for_navigator(&session)?;
                        summary.restarts += 1;
                        break false;
                    }
                    if session.interrupted() {
                        summary.interrupted = true;
                        break true;
                    }
                }
            };
            if acked {
                break;
            }
        }
        summary.batches += 1;
        summary.samples += n as u64;
        if opts.mode == Mode::FreeRunning {
            while let Some(c) = commands
                .receive()
                .map_err(|e| ipc("receiving commands")(&e))?
            {
                let c = *c.payload();
                apply(plant, &c, &mut summary)?;
                stop |= c.kind == kind::STOP;
            }
        }
        if let Some(k) = opts.pace {
            let ahead = plant.time_s() / k - t0.elapsed().as_secs_f64();
            if ahead > 0.0 {
                std::thread::sleep(Duration::from_secs_f64(ahead));
            }
        }
        seq += 1;
        if batch.flags & FLAG_END != 0 {
            break;
        }
    }
    summary.wall_s = t0.elapsed().as_secs_f64();
    Ok(summary)
}
