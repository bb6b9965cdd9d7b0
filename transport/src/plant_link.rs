//! The plant's link to its navigator: sends a batch, in lockstep waits for its acknowledgement,
//! and handles what can happen meanwhile — a wrong or foreign command (refused, naming the
//! values), a stop request, a navigator that died, left or stalled, and a (re)joined navigator
//! that needs the batch again.

use std::cell::Cell;
use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};
use std::time::{Duration, Instant};

use iceoryx2::port::{BackpressureAction, BackpressureInfo};
use iceoryx2::prelude::*;
use rins_plant::Plant;

use crate::action::NavAction;
use crate::error::TransportError;
use crate::layout::{
    FLAG_END, FLAG_REFUSED, ImuBatch, LAYOUT_VERSION, NavCommand, StartRecord, kind,
};
use crate::probe::Stage;
use crate::session::{Session, cleanup_dead_nodes, ipc};

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
    /// How long to wait for a navigator to connect (also after it dies), and for a live
    /// navigator to take or acknowledge a batch before it counts as stalled.
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

/// Refuses a command of another layout version or an unknown kind (docs/transport.md).
pub(crate) fn check_command(c: &NavCommand) -> Result<(), TransportError> {
    if c.layout_version != LAYOUT_VERSION {
        return Err(TransportError::CommandVersion {
            got: c.layout_version,
            want: LAYOUT_VERSION,
        });
    }
    if c.kind > kind::AZIMUTH_ISOLATION_OFF {
        return Err(TransportError::CommandRefused {
            kind: c.kind,
            seq: c.ack_seq,
            reason: "this kind is unknown (0 acknowledge, 1 move-to, 2 stop, 3 hello, 4 azimuth isolation on, 5 azimuth isolation off)".into(),
        });
    }
    Ok(())
}

pub(crate) fn apply(
    plant: &mut Plant,
    c: &NavCommand,
    summary: &mut ServeSummary,
) -> Result<(), TransportError> {
    if let Some(action) = NavAction::from_command(c) {
        action
            .apply(plant)
            .map_err(|reason| TransportError::CommandRefused {
                kind: c.kind,
                seq: c.ack_seq,
                reason,
            })?;
        summary.commands.push((plant.samples_done(), *c));
    }
    Ok(())
}

/// How often the waits look for dead or departed peers.
pub const CHECK: Duration = Duration::from_millis(50);

/// Why a blocked send gave up (set by the backpressure handler).
const SEND_OK: u8 = 0;
const SEND_INTERRUPTED: u8 = 1;
const SEND_DEAD: u8 = 2;
const SEND_STALLED: u8 = 3;

/// How the navigator was lost.
enum Loss {
    Died,
    Left,
}

/// The plant's ports and the state of the batch in flight.
pub struct Link<'a> {
    session: &'a Session,
    opts: &'a ServeOptions,
    publisher: iceoryx2::port::publisher::Publisher<ipc::Service, ImuBatch, ()>,
    commands: iceoryx2::port::subscriber::Subscriber<ipc::Service, NavCommand, ()>,
    send_failure: Arc<AtomicU8>,
    /// Subscribers connected when the batch in flight was last sent: a hello from a navigator
    /// among them needs no resend.
    sent_to: Vec<iceoryx2::identifiers::UniqueSubscriberId>,
    /// The navigator asked to end the run.
    pub stop_requested: bool,
    /// Lifecycle probe.
    pub probe: &'a mut dyn FnMut(Stage),
}

impl<'a> Link<'a> {
    /// Creates the plant's ports: the IMU publisher (one per session) and the command
    /// subscriber.
    pub fn new(
        session: &'a Session,
        opts: &'a ServeOptions,
        probe: &'a mut dyn FnMut(Stage),
    ) -> Result<Self, TransportError> {
        let send_failure = Arc::new(AtomicU8::new(SEND_OK));
        let publisher = session.exclusive(
            "plant",
            || {
                session
                    .imu
                    .publisher_builder()
                    .backpressure_strategy(BackpressureStrategy::RetryUntilDelivered)
                    .set_backpressure_handler(backpressure(
                        session.config().clone(),
                        opts.peer_timeout,
                        send_failure.clone(),
                    ))
                    .create()
            },
            || session.imu_publishers(),
        )?;
        let commands = session
            .cmd
            .subscriber_builder()
            .create()
            .map_err(|e| ipc("creating the command subscriber")(&e))?;
        Ok(Self {
            session,
            opts,
            publisher,
            commands,
            send_failure,
            sent_to: Vec::new(),
            stop_requested: false,
            probe,
        })
    }

    /// Waits for a navigator before batch `seq`: samples sent before a subscriber connects are
    /// lost. A navigator that dies before its first batch is cleaned up (and reported to the
    /// probe) here.
    pub fn wait_for_navigator(&mut self, seq: u64) -> Result<(), TransportError> {
        let start = Instant::now();
        (self.probe)(Stage::PlantWaiting(seq));
        while self.session.imu_subscribers() == 0 {
            if self.session.interrupted() {
                return Err(TransportError::Interrupted);
            }
            if start.elapsed() > self.opts.peer_timeout {
                return Err(TransportError::NoPeer {
                    peer: "navigator",
                    timeout_s: self.opts.peer_timeout.as_secs_f64(),
                });
            }
            if self.session.peer_died() {
                (self.probe)(Stage::PlantLostNavigator(seq));
            }
            std::thread::sleep(Duration::from_millis(2));
        }
        Ok(())
    }

    fn subscribers(&self) -> Vec<iceoryx2::identifiers::UniqueSubscriberId> {
        let mut ids = Vec::new();
        self.session.imu.dynamic_config().list_subscribers(|d| {
            ids.push(d.subscriber_id);
            CallbackProgression::Continue
        });
        ids
    }

    /// Sends `batch` and, in lockstep (or for the end of the run), waits for its
    /// acknowledgement, resending it to a navigator that replaced a lost one. Returns whether
    /// the run paused for a new navigator (the pace restarts then).
    pub fn deliver(
        &mut self,
        batch: &ImuBatch,
        plant: &mut Plant,
        summary: &mut ServeSummary,
        mode: Mode,
    ) -> Result<bool, TransportError> {
        let mut paused = false;
        let mut resend = false;
        loop {
            if resend {
                (self.probe)(Stage::PlantResending(batch.seq));
            }
            self.sent_to = self.subscribers();
            self.send_failure.store(SEND_OK, Ordering::Relaxed);
            let sent = Instant::now();
            let receivers = match self.publisher.send_copy(*batch) {
                Ok(r) => r,
                Err(e) => match self.send_failure.load(Ordering::Relaxed) {
                    SEND_INTERRUPTED => {
                        summary.interrupted = true;
                        return Ok(paused);
                    }
                    SEND_DEAD => 0,
                    SEND_STALLED => {
                        (self.probe)(Stage::PlantLostNavigator(batch.seq));
                        return Err(TransportError::Stalled {
                            peer: "navigator",
                            seq: batch.seq,
                            after_ms: sent.elapsed().as_millis() as u64,
                        });
                    }
                    _ => return Err(ipc("sending a batch")(&e)),
                },
            };
            if receivers == 0 {
                let loss = if self.session.peer_died() {
                    Loss::Died
                } else {
                    Loss::Left
                };
                self.lost(loss, batch.seq, sent, summary)?;
                paused = true;
                resend = true;
                continue;
            }
            if batch.flags & FLAG_END != 0 {
                (self.probe)(Stage::PlantEndSent(batch.seq));
            }
            if mode != Mode::Lockstep && batch.flags & FLAG_END == 0 {
                return Ok(paused);
            }
            if batch.flags & FLAG_END == 0 {
                (self.probe)(Stage::PlantAwaitingAck(batch.seq));
            }
            if self.await_ack(batch, plant, summary, mode)? {
                return Ok(paused);
            }
            paused = true;
            resend = true;
        }
    }

    /// Reports a lost navigator; with `wait_for_restart`, waits for a new one.
    fn lost(
        &mut self,
        loss: Loss,
        seq: u64,
        sent: Instant,
        summary: &mut ServeSummary,
    ) -> Result<(), TransportError> {
        (self.probe)(Stage::PlantLostNavigator(seq));
        let after_ms = sent.elapsed().as_millis() as u64;
        if !self.opts.wait_for_restart {
            return Err(match loss {
                Loss::Died => TransportError::PeerDied {
                    peer: "navigator",
                    after_ms,
                },
                Loss::Left => TransportError::PeerLeft {
                    peer: "navigator",
                    seq,
                },
            });
        }
        summary.events.push(match loss {
            Loss::Died => format!(
                "navigator died {after_ms} ms after batch {seq} was sent; waiting for a new one"
            ),
            Loss::Left => {
                format!("navigator gone (exited) at batch {seq}; waiting for a new one")
            }
        });
        self.wait_for_navigator(seq)?;
        summary.restarts += 1;
        Ok(())
    }

    /// Waits for the acknowledgement of `batch`; false: resend it (a navigator (re)joined).
    fn await_ack(
        &mut self,
        batch: &ImuBatch,
        plant: &mut Plant,
        summary: &mut ServeSummary,
        mode: Mode,
    ) -> Result<bool, TransportError> {
        let seq = batch.seq;
        let sent = Instant::now();
        let mut last_check = Instant::now();
        let mut polls: u32 = 0;
        loop {
            if let Some(c) = self
                .commands
                .receive()
                .map_err(|e| ipc("receiving commands")(&e))?
            {
                let c = *c.payload();
                check_command(&c)?;
                match c.kind {
                    kind::HELLO => {
                        // A navigator connected after the last send needs the batch; one that
                        // was connected has it already (no duplicate).
                        let now = self.subscribers();
                        if now.iter().any(|id| !self.sent_to.contains(id)) {
                            summary.events.push(format!(
                                "a navigator joined while batch {seq} was unacknowledged; resending it"
                            ));
                            summary.restarts += u32::from(seq > 0);
                            return Ok(false);
                        }
                    }
                    // Stop ends the run, whatever batch it names (docs/transport.md).
                    kind::STOP => {
                        self.stop_requested = true;
                        return Ok(true);
                    }
                    // After a stop the navigator may still acknowledge the batches it had
                    // received before it saw the end: not an error.
                    _ if self.stop_requested && c.ack_seq < seq => {}
                    _ => {
                        if c.ack_seq != seq {
                            return Err(TransportError::WrongAck {
                                expected: seq,
                                got: c.ack_seq,
                            });
                        }
                        apply(plant, &c, summary)?;
                        return Ok(true);
                    }
                }
                continue;
            }
            polls = polls.wrapping_add(1);
            if polls.is_multiple_of(64) {
                std::thread::yield_now();
            }
            if last_check.elapsed() < CHECK {
                continue;
            }
            last_check = Instant::now();
            if self.session.interrupted() {
                summary.interrupted = true;
                return Ok(true);
            }
            let died = self.session.peer_died();
            if died || self.session.imu_subscribers() == 0 {
                // Free-running: a subscriber that does not acknowledge is done once it has
                // read the end marker and left.
                if mode == Mode::FreeRunning && !died {
                    return Ok(true);
                }
                self.lost(
                    if died { Loss::Died } else { Loss::Left },
                    seq,
                    sent,
                    summary,
                )?;
                return Ok(false);
            }
            if sent.elapsed() > self.opts.peer_timeout {
                (self.probe)(Stage::PlantLostNavigator(seq));
                return Err(TransportError::Stalled {
                    peer: "navigator",
                    seq,
                    after_ms: sent.elapsed().as_millis() as u64,
                });
            }
        }
    }

    /// Ends the run after `sent` (the last batch sent) because of `e`: when `e` is a refusal of
    /// what a live navigator sent ([`TransportError::is_refusal`]) and the run had not ended
    /// yet, sends the navigator an empty end-of-run batch flagged [`FLAG_REFUSED`] with the
    /// reason, and waits (up to the peer timeout) for its acknowledgement or its departure, so
    /// that the navigator's output says why the run ended. Returns `e`.
    pub fn refuse(&mut self, plant: &Plant, sent: &ImuBatch, e: TransportError) -> TransportError {
        if !e.is_refusal() || sent.flags & FLAG_END != 0 {
            return e;
        }
        let mut end = ImuBatch {
            seq: sent.seq + 1,
            count: 0,
            flags: FLAG_END | FLAG_REFUSED,
            start: StartRecord::from_plant(plant),
            ..ImuBatch::default()
        };
        end.set_reason(&e.to_string());
        if self.publisher.send_copy(end).unwrap_or(0) == 0 {
            return e;
        }
        let start = Instant::now();
        let mut last_check = Instant::now();
        while start.elapsed() < self.opts.peer_timeout && !self.session.interrupted() {
            match self.commands.receive() {
                Ok(Some(c)) => {
                    let c = *c.payload();
                    if c.ack_seq == end.seq || c.kind == kind::STOP {
                        break;
                    }
                }
                Ok(None) => {
                    if self.session.imu_subscribers() == 0 {
                        break;
                    }
                    if last_check.elapsed() > CHECK {
                        last_check = Instant::now();
                        if self.session.peer_died() {
                            break;
                        }
                    }
                    std::thread::sleep(Duration::from_micros(200));
                }
                Err(_) => break,
            }
        }
        e
    }

    /// Free-running: applies the commands that arrived (acknowledgements are optional there).
    pub fn drain_commands(
        &mut self,
        plant: &mut Plant,
        summary: &mut ServeSummary,
    ) -> Result<(), TransportError> {
        while let Some(c) = self
            .commands
            .receive()
            .map_err(|e| ipc("receiving commands")(&e))?
        {
            let c = *c.payload();
            check_command(&c)?;
            apply(plant, &c, summary)?;
            self.stop_requested |= c.kind == kind::STOP;
        }
        Ok(())
    }
}

/// While a subscriber's buffer is full the publisher retries; this handler ends the retries
/// on SIGINT/SIGTERM, when a node of the session died (a killed navigator never frees its
/// buffer) and when a live navigator has not taken a message for `stall` (it stopped reading).
fn backpressure(
    config: Config,
    stall: Duration,
    failure: Arc<AtomicU8>,
) -> impl Fn(&BackpressureInfo) -> BackpressureAction + Send + 'static {
    let next_check = Cell::new(CHECK);
    move |info: &BackpressureInfo| {
        let fail = |why: u8| {
            failure.store(why, Ordering::Relaxed);
            BackpressureAction::DiscardDataAndFail
        };
        if crate::signals::termination_requested() {
            return fail(SEND_INTERRUPTED);
        }
        if info.retries == 0 {
            next_check.set(CHECK); // a new blocked send
        }
        if info.elapsed_time < next_check.get() {
            return BackpressureAction::Retry;
        }
        next_check.set(info.elapsed_time + CHECK);
        if cleanup_dead_nodes(&config) > 0 {
            return fail(SEND_DEAD);
        }
        if info.elapsed_time > stall {
            return fail(SEND_STALLED);
        }
        BackpressureAction::Retry
    }
}
