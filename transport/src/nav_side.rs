//! The navigation side: consumes the IMU stream, navigates (the reference strapdown), publishes
//! its solution, acknowledges batches (lockstep) and may command the table. The same
//! [`NavProcessor`] runs in-process for the reference result.

use std::time::{Duration, Instant};

use nalgebra::Vector3;
use rins_navigation::strapdown::{NavState, Strapdown, VerticalChannel};
use rins_plant::PlantConfig;

use crate::action::NavAction;
use crate::error::TransportError;
use crate::layout::{
    FLAG_END, FLAG_INTERRUPTED, FLAG_REFUSED, FLAG_TRUTH, ImuBatch, ImuRecord, LAYOUT_VERSION,
    NavCommand, NavSolution, StartRecord, TruthRecord, kind,
};
use crate::probe::Stage;
use crate::session::{Session, ipc};
use iceoryx2::service::port_factory::PortFactory as _;

/// The reference navigation over the stream, with a digest of every state it passes through.
#[derive(Debug)]
pub struct NavProcessor {
    strapdown: Option<Strapdown>,
    dt_s: f64,
    /// The state it started from (the first batch's [`StartRecord`]).
    pub start: Option<StartRecord>,
    /// Samples consumed.
    pub samples: u64,
    /// First tick consumed.
    pub first_tick: Option<u64>,
    /// Last tick consumed.
    pub last_tick: u64,
    /// FNV-1a over the bits of every navigation state: equal digests, equal trajectories.
    pub digest: u64,
}

/// The FNV-1a offset basis [`NavProcessor::digest`] starts from.
pub const DIGEST_START: u64 = 0xcbf2_9ce4_8422_2325;

/// Folds the bits of `s` (latitude, longitude, height, velocity, attitude quaternion) into the
/// FNV-1a `digest` ([`NavProcessor::digest`]; a test folds another navigator's states alike).
pub fn fold_digest(digest: u64, s: &NavState) -> u64 {
    let q = s.q_bn.quaternion();
    let mut d = digest;
    for x in [
        s.lat_rad, s.lon_rad, s.height_m, s.v_n.x, s.v_n.y, s.v_n.z, q.w, q.i, q.j, q.k,
    ] {
        for b in x.to_bits().to_le_bytes() {
            d = (d ^ b as u64).wrapping_mul(0x0100_0000_01b3);
        }
    }
    d
}

impl NavProcessor {
    /// A navigator at the output rate of `cfg` (`run.rate_hz`), not started yet: it starts from
    /// the [`StartRecord`] of the first batch it receives ([`NavProcessor::begin`]).
    pub fn new(cfg: &PlantConfig) -> Self {
        Self {
            strapdown: None,
            dt_s: 1.0 / cfg.rate_hz,
            start: None,
            samples: 0,
            first_tick: None,
            last_tick: 0,
            digest: DIGEST_START,
        }
    }

    /// Starts the navigation at `start`, as the in-process run started in that state does
    /// (`rins_experiments::Tracker::at_truth`): that position, velocity and attitude, the
    /// vertical channel held at its height. Ignored once started.
    pub fn begin(&mut self, start: &StartRecord) {
        if self.strapdown.is_some() {
            return;
        }
        let state = start.nav_state();
        self.strapdown = Some(Strapdown::new(
            state,
            self.dt_s,
            VerticalChannel::Hold {
                ref_height_m: state.height_m,
            },
        ));
        self.start = Some(*start);
    }

    /// Whether [`NavProcessor::begin`] has been called.
    pub fn started(&self) -> bool {
        self.strapdown.is_some()
    }

    /// Consumes one record. Panics before [`NavProcessor::begin`] (a navigator has no state to
    /// integrate from).
    pub fn push(&mut self, r: &ImuRecord) {
        let sd = self
            .strapdown
            .as_mut()
            .expect("NavProcessor::push before begin: start from the batch's StartRecord first");
        sd.update(&Vector3::from(r.dtheta_rad), &Vector3::from(r.dv_mps));
        self.digest = fold_digest(self.digest, sd.state());
        self.first_tick.get_or_insert(r.tick);
        self.samples += 1;
        self.last_tick = r.tick;
    }

    /// The current solution.
    pub fn state(&self) -> Option<&NavState> {
        self.strapdown.as_ref().map(Strapdown::state)
    }

    /// The solution as a message.
    pub fn solution(&self, seq: u64) -> NavSolution {
        let mut out = NavSolution {
            seq,
            tick: self.last_tick,
            ..NavSolution::default()
        };
        if let Some(s) = self.state() {
            let q = s.q_bn.quaternion();
            out.lat_rad = s.lat_rad;
            out.lon_rad = s.lon_rad;
            out.height_m = s.height_m;
            out.v_n = [s.v_n.x, s.v_n.y, s.v_n.z];
            out.q_bn = [q.w, q.i, q.j, q.k];
        }
        out
    }
}

/// A command the navigator sends after a given batch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScheduledCommand {
    /// Sent with the acknowledgement of this batch; the plant applies it from the next batch.
    pub after_seq: u64,
    /// What it asks.
    pub action: NavAction,
}

/// How the navigator runs.
#[derive(Clone, Debug)]
pub struct NavOptions {
    /// Acknowledge every batch (the plant waits for it in lockstep).
    pub acknowledge: bool,
    /// Table commands to send.
    pub commands: Vec<ScheduledCommand>,
    /// Give up when nothing arrives for this long: no plant connected, or a live plant that
    /// stalled.
    pub peer_timeout: Duration,
}

/// What the navigator saw.
#[derive(Debug)]
pub struct NavSummary {
    /// The navigation.
    pub nav: NavProcessor,
    /// Batches received.
    pub batches: u64,
    /// Resent batches dropped as already seen.
    pub duplicates: u64,
    /// The plant ended the run early.
    pub interrupted: bool,
    /// The plant's truth at the last sample consumed, when the plant published it
    /// ([`crate::layout::FLAG_TRUTH`]): for error measures only, never read by the navigation.
    pub truth: Option<TruthRecord>,
}

/// The final solution's error against the plant's truth at the last sample consumed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FinalError {
    /// North position error, m.
    pub north_m: f64,
    /// East position error, m (the longitude difference wrapped to ±180°).
    pub east_m: f64,
    /// Horizontal position error, m.
    pub horizontal_m: f64,
    /// Horizontal velocity error, m/s.
    pub velocity_mps: f64,
}

impl NavSummary {
    /// The final solution's error against the truth the plant published with the last sample
    /// (`None` when it published none, or nothing was navigated). An error measure only.
    pub fn final_error(&self) -> Option<FinalError> {
        let (s, t) = (self.nav.state()?, self.truth?);
        let pi = std::f64::consts::PI;
        let dlon = (s.lon_rad - t.lon_rad + pi).rem_euclid(2.0 * pi) - pi;
        let at_truth_lon = NavState {
            lon_rad: t.lon_rad + dlon,
            ..*s
        };
        let (north_m, east_m) = rins_navigation::errors::position_error_m(
            &at_truth_lon,
            t.lat_rad,
            t.lon_rad,
            t.height_m,
        );
        Some(FinalError {
            north_m,
            east_m,
            horizontal_m: north_m.hypot(east_m),
            velocity_mps: (s.v_n.x - t.v_enu_mps[0]).hypot(s.v_n.y - t.v_enu_mps[1]),
        })
    }
}

/// Runs the navigator of session `name` for the plant `cfg` until the plant ends the run.
pub fn navigate(
    name: &str,
    cfg: &PlantConfig,
    opts: &NavOptions,
) -> Result<NavSummary, TransportError> {
    navigate_probed(name, cfg, opts, &mut |_| {})
}

/// [`navigate`], reporting each lifecycle [`Stage`] to `probe` as it is reached.
pub fn navigate_probed(
    name: &str,
    cfg: &PlantConfig,
    opts: &NavOptions,
    probe: &mut dyn FnMut(Stage),
) -> Result<NavSummary, TransportError> {
    let session = Session::open(name, "navigator")?;
    // The command publisher first: its single slot makes this the session's only navigator,
    // and a refused second one never subscribes (it would hold the plant back).
    let cmd = session.exclusive(
        "navigator",
        || {
            session
                .cmd
                .publisher_builder()
                .backpressure_strategy(iceoryx2::prelude::BackpressureStrategy::RetryUntilDelivered)
                .create()
        },
        || session.cmd.dynamic_config().number_of_publishers(),
    )?;
    let sub = session
        .imu
        .subscriber_builder()
        .create()
        .map_err(|e| ipc("creating the IMU subscriber")(&e))?;
    let sol = session
        .nav
        .publisher_builder()
        .create()
        .map_err(|e| ipc("creating the solution publisher")(&e))?;
    // Announce ourselves: a plant waiting on a batch our dead predecessor took resends it.
    cmd.send_copy(NavCommand {
        layout_version: LAYOUT_VERSION,
        kind: kind::HELLO,
        ..NavCommand::default()
    })
    .map_err(|e| ipc("sending hello")(&e))?;
    probe(Stage::NavJoined);
    let mut nav = NavProcessor::new(cfg);
    let mut truth = None;
    let mut duplicates = 0u64;
    let mut expected: Option<u64> = None;
    let mut batches = 0;
    let mut last_message = Instant::now();
    let mut last_check = Instant::now();
    let mut polls: u32 = 0;
    loop {
        let Some(sample) = sub.receive().map_err(|e| ipc("receiving")(&e))? else {
            polls = polls.wrapping_add(1);
            if polls.is_multiple_of(64) {
                std::thread::yield_now();
            }
            if last_check.elapsed() > Duration::from_millis(50) {
                last_check = Instant::now();
                if session.interrupted() {
                    return Err(TransportError::Interrupted);
                }
                let next = expected.unwrap_or(0);
                let silent_ms = last_message.elapsed().as_millis() as u64;
                if session.peer_died() {
                    probe(Stage::NavLostPlant(next));
                    return Err(TransportError::PeerDied {
                        peer: "plant",
                        after_ms: silent_ms,
                    });
                }
                let plants = session.imu_publishers();
                if plants == 0 && expected.is_some() {
                    // The plant that served us is gone and did not die: it exited normally.
                    probe(Stage::NavLostPlant(next));
                    return Err(TransportError::PeerLeft {
                        peer: "plant",
                        seq: next,
                    });
                }
                if last_message.elapsed() > opts.peer_timeout {
                    probe(Stage::NavLostPlant(next));
                    return Err(if plants == 0 {
                        TransportError::NoPeer {
                            peer: "plant",
                            timeout_s: opts.peer_timeout.as_secs_f64(),
                        }
                    } else {
                        TransportError::Stalled {
                            peer: "plant",
                            seq: next,
                            after_ms: silent_ms,
                        }
                    });
                }
            }
            continue;
        };
        last_message = Instant::now();
        let b: &ImuBatch = sample.payload();
        if b.layout_version != LAYOUT_VERSION
            || b.record_size as usize != std::mem::size_of::<ImuRecord>()
        {
            return Err(TransportError::Layout {
                got_version: b.layout_version,
                got_record: b.record_size,
                want_version: LAYOUT_VERSION,
                want_record: std::mem::size_of::<ImuRecord>() as u32,
            });
        }
        // The first batch after (re)start defines the restart point; after it, no gap. A batch
        // seen already (resent after a hello) is dropped here, once.
        match expected {
            Some(e) if b.seq < e => {
                duplicates += 1;
                continue;
            }
            Some(e) if e != b.seq => {
                return Err(TransportError::Gap {
                    expected: e,
                    got: b.seq,
                });
            }
            _ => {}
        }
        expected = Some(b.seq + 1);
        batches += 1;
        let records = &b.records[..b.count as usize];
        // The navigator integrates at its scenario's rate: refuse a stream at another one.
        if let [a, c, ..] = records {
            let stream_s = c.t_s - a.t_s;
            if (stream_s * cfg.rate_hz - 1.0).abs() > 1e-6 {
                return Err(TransportError::Rate {
                    stream_s,
                    rate_hz: cfg.rate_hz,
                });
            }
        }
        // The first batch received gives the state to start from: the run's start, or the
        // state at the batch a replacement navigator joins at.
        nav.begin(&b.start);
        for r in records {
            nav.push(r);
        }
        if b.flags & FLAG_TRUTH != 0 && !records.is_empty() {
            truth = Some(b.truth[records.len() - 1]);
        }
        let reason = (b.flags & FLAG_REFUSED != 0).then(|| b.reason_text());
        let (seq, flags) = (b.seq, b.flags);
        drop(sample);
        probe(if flags & FLAG_END != 0 {
            Stage::NavEndReceived(seq)
        } else {
            Stage::NavReceived(seq)
        });
        let _ = sol.send_copy(nav.solution(seq));
        if opts.acknowledge || flags & FLAG_END != 0 {
            let mut c = NavCommand {
                layout_version: LAYOUT_VERSION,
                kind: kind::ACK,
                ack_seq: seq,
                ..NavCommand::default()
            };
            if let Some(sc) = opts.commands.iter().find(|c| c.after_seq == seq) {
                sc.action.write(&mut c);
            }
            cmd.send_copy(c)
                .map_err(|e| ipc("sending the acknowledgement")(&e))?;
        }
        if flags & FLAG_END != 0 {
            linger_until_plant_left(&session, opts.peer_timeout);
            if let Some(reason) = reason {
                return Err(TransportError::PlantEnded { reason });
            }
            return Ok(NavSummary {
                nav,
                batches,
                duplicates,
                interrupted: flags & FLAG_INTERRUPTED != 0,
                truth,
            });
        }
    }
}

/// After acknowledging the end of the run, stays until the plant has left (or died, or
/// `timeout` passed, or a signal came). iceoryx2 drops the samples of a publisher that is gone
/// before the subscriber has connected to it (iceoryx2 issue #39): a replacement navigator that
/// acknowledged a resent end and exited at once could leave the plant without that
/// acknowledgement, waiting for a navigator that never came.
fn linger_until_plant_left(session: &Session, timeout: Duration) {
    let start = Instant::now();
    while session.imu_publishers() > 0
        && start.elapsed() < timeout
        && !session.interrupted()
        && !session.peer_died()
    {
        std::thread::sleep(Duration::from_millis(1));
    }
}
