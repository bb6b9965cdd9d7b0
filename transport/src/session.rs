//! A named session: its iceoryx2 configuration (a prefix of its own, so sessions and tests run
//! side by side), its services, dead-node cleanup and peer-liveness checks.

use std::time::{Duration, Instant};

use iceoryx2::config::Config;
use iceoryx2::prelude::*;
use iceoryx2::service::port_factory::PortFactory as _;
use iceoryx2::service::port_factory::publish_subscribe::PortFactory;

use crate::layout::{ImuBatch, NavCommand, NavSolution};
use crate::services;

/// Why a transport run stopped.
#[derive(Debug, thiserror::Error)]
pub enum TransportError {
    /// iceoryx2 failed.
    #[error("{what}: {detail}")]
    Ipc {
        /// What was being done.
        what: String,
        /// The iceoryx2 error.
        detail: String,
    },
    /// A service exists with another type, size or settings (an old run or another version).
    #[error(
        "service {service} exists with another layout or settings ({detail}); a peer built with another rins version, or a stale service from a crashed run. Use another --session, or stop the process that holds it"
    )]
    Mismatch {
        /// Service name.
        service: String,
        /// The iceoryx2 error.
        detail: String,
    },
    /// A service a peer created has a setting rins cannot work with.
    #[error(
        "service {service} exists with {setting} = {existing}, but rins needs {required}: the peer that created it must use the settings in docs/transport.md (Services), or start after rins serve"
    )]
    Setting {
        /// Service name.
        service: String,
        /// The setting (with its iceoryx2 builder method).
        setting: String,
        /// The existing service's value.
        existing: String,
        /// What rins needs.
        required: String,
    },
    /// The session already has a live plant or navigator.
    #[error(
        "session {session} already has a {role} (a live process holds its port); one {role} per session: stop it or use another --session"
    )]
    Busy {
        /// Session name.
        session: String,
        /// "plant" or "navigator".
        role: &'static str,
    },
    /// A command with another layout version.
    #[error(
        "the navigator sends commands with layout_version {got}; this plant uses layout version {want} (docs/transport.md)"
    )]
    CommandVersion {
        /// Navigator's version.
        got: u32,
        /// Ours.
        want: u32,
    },
    /// An acknowledgement of another batch than the one awaiting it.
    #[error(
        "the navigator acknowledged batch {got} (ack_seq), but batch {expected} is the one awaiting acknowledgement: ack_seq must be the seq of the last batch received"
    )]
    WrongAck {
        /// The batch awaiting acknowledgement.
        expected: u64,
        /// The navigator's `ack_seq`.
        got: u64,
    },
    /// The peer ended its process normally (its node left the session) while the run went on.
    #[error(
        "the {peer} exited normally (it left the session; not a crash) while batch {seq} was unfinished"
    )]
    PeerLeft {
        /// Which peer.
        peer: &'static str,
        /// The batch in flight.
        seq: u64,
    },
    /// The peer process lives but makes no progress.
    #[error(
        "the {peer} process is alive but stalled: batch {seq} unfinished for {after_ms} ms (--peer-timeout-s)"
    )]
    Stalled {
        /// Which peer.
        peer: &'static str,
        /// The batch in flight.
        seq: u64,
        /// How long it waited.
        after_ms: u64,
    },
    /// A message with another layout version or record size.
    #[error(
        "peer sends layout version {got_version} with {got_record}-byte records; this build uses version {want_version} with {want_record}-byte records (docs/transport.md)"
    )]
    Layout {
        /// Peer's version.
        got_version: u32,
        /// Peer's record size.
        got_record: u32,
        /// Ours.
        want_version: u32,
        /// Ours.
        want_record: u32,
    },
    /// The stream's sample interval is not the scenario's.
    #[error("the plant streams samples every {stream_s} s, but the navigator's scenario has run.rate_hz = {rate_hz} (every {} s): give both the same scenario", 1.0 / rate_hz)]
    Rate {
        /// Interval seen in the stream, s.
        stream_s: f64,
        /// The navigator's configured rate, Hz.
        rate_hz: f64,
    },
    /// A sequence gap: messages were lost.
    #[error("sequence gap: expected batch {expected}, received {got} ({} batches lost)", got.wrapping_sub(*expected))]
    Gap {
        /// Expected sequence number.
        expected: u64,
        /// Received.
        got: u64,
    },
    /// The peer process died (found dead by iceoryx2's node monitoring).
    #[error(
        "the {peer} process died (detected {after_ms} ms after its last message); its resources were cleaned up"
    )]
    PeerDied {
        /// Which peer.
        peer: &'static str,
        /// Detection delay.
        after_ms: u64,
    },
    /// No peer within the timeout.
    #[error("no {peer} connected within {timeout_s} s")]
    NoPeer {
        /// Which peer.
        peer: &'static str,
        /// Timeout.
        timeout_s: f64,
    },
    /// SIGINT or SIGTERM.
    #[error("interrupted by a signal")]
    Interrupted,
    /// A session name against the rule ([`check_name`]).
    #[error(
        "session name {name:?} {problem}: a session name is 1 to {MAX_NAME} characters, each an ASCII letter (A-Z, a-z), a digit (0-9), '-' or '_' (docs/transport.md, Services)"
    )]
    SessionName {
        /// The name given.
        name: String,
        /// What is wrong with it.
        problem: String,
    },
    /// The plant refused a command of the navigator (a move out of range, isolation on a
    /// static carrier, an unknown kind); it ends the run.
    #[error(
        "the plant refused the navigator's command (kind {kind}) acknowledging batch {seq}: {reason}"
    )]
    CommandRefused {
        /// The command's kind.
        kind: u32,
        /// Its `ack_seq`.
        seq: u64,
        /// The plant's reason.
        reason: String,
    },
    /// The plant ended the run refusing this navigator's command; its reason came with the
    /// end-of-run batch ([`crate::layout::FLAG_REFUSED`]).
    #[error("the plant ended the run: {reason}")]
    PlantEnded {
        /// The plant's reason, as it sent it.
        reason: String,
    },
}

impl TransportError {
    /// Whether the plant ends the run because of what a live navigator sent (a refused or
    /// malformed command, a wrong acknowledgement): the navigator is then told why.
    pub fn is_refusal(&self) -> bool {
        matches!(
            self,
            Self::CommandRefused { .. } | Self::CommandVersion { .. } | Self::WrongAck { .. }
        )
    }
}

/// Longest session name, characters.
pub const MAX_NAME: usize = 64;

/// Checks a session name against the rule of docs/transport.md: 1 to [`MAX_NAME`] characters,
/// each an ASCII letter, digit, `-` or `_` (the name becomes part of file names and of the
/// iceoryx2 service names `rins/<session>/…`).
pub fn check_name(name: &str) -> Result<(), TransportError> {
    let bad = |problem: String| {
        Err(TransportError::SessionName {
            name: name.into(),
            problem,
        })
    };
    if name.is_empty() {
        return bad("is empty".into());
    }
    if let Some((i, c)) = name
        .chars()
        .enumerate()
        .find(|(_, c)| !(c.is_ascii_alphanumeric() || *c == '-' || *c == '_'))
    {
        return bad(format!(
            "has {c:?} at character {}, which is not allowed",
            i + 1
        ));
    }
    let n = name.chars().count();
    if n > MAX_NAME {
        return bad(format!("is {n} characters long"));
    }
    Ok(())
}

pub(crate) fn ipc(what: &str) -> impl Fn(&dyn std::fmt::Debug) -> TransportError + '_ {
    move |e| TransportError::Ipc {
        what: what.into(),
        detail: format!("{e:?}"),
    }
}

/// The services of one session.
pub struct Session {
    /// Session name.
    pub name: String,
    /// The node of this process.
    pub node: Node<ipc::Service>,
    /// IMU stream (plant → navigation).
    pub imu: PortFactory<ipc::Service, ImuBatch, ()>,
    /// Commands and acknowledgements (navigation → plant).
    pub cmd: PortFactory<ipc::Service, NavCommand, ()>,
    /// Navigation solutions (navigation → anyone).
    pub nav: PortFactory<ipc::Service, NavSolution, ()>,
    config: Config,
}

/// Messages each subscriber can hold before the publisher waits (no loss: backpressure).
pub const BUFFER: usize = 16;

/// The iceoryx2 configuration of session `name`: its own prefix for every resource. The name
/// is checked first ([`check_name`]).
pub fn config(name: &str) -> Result<Config, TransportError> {
    check_name(name)?;
    let mut config = Config::default();
    let prefix = format!("rins_{name}_");
    config.global.prefix = FileName::new(prefix.as_bytes()).map_err(|e| TransportError::Ipc {
        what: format!("session name {name:?}"),
        detail: format!("{e:?}"),
    })?;
    Ok(config)
}

/// Removes the resources of dead nodes of the session; returns how many were dead.
pub fn cleanup_dead_nodes(config: &Config) -> usize {
    let mut dead = 0;
    let _ = Node::<ipc::Service>::list(config, |state| {
        if let NodeState::Dead(view) = state {
            dead += 1;
            let _ = view.try_remove_stale_resources();
        }
        CallbackProgression::Continue
    });
    dead
}

impl Session {
    /// Joins (or creates) session `name` as node `role`, after cleaning up dead nodes. Services
    /// a peer created first are accepted if their settings serve rins ([`crate::services`]).
    pub fn open(name: &str, role: &str) -> Result<Self, TransportError> {
        let config = config(name)?;
        cleanup_dead_nodes(&config);
        let node = NodeBuilder::new()
            .config(&config)
            .name(&NodeName::new(role).map_err(|e| ipc("node name")(&e))?)
            .signal_handling_mode(SignalHandlingMode::HandleTerminationRequests)
            .create::<ipc::Service>()
            .map_err(|e| ipc("creating the node")(&e))?;
        // Registers iceoryx2's SIGINT/SIGTERM handler now, not at the first check.
        crate::signals::termination_requested();
        let service = |suffix: &str| -> Result<ServiceName, TransportError> {
            format!("rins/{name}/{suffix}")
                .as_str()
                .try_into()
                .map_err(|e| ipc("service name")(&e))
        };
        let imu = services::open::<ImuBatch>(&node, &config, &service("imu")?, &services::IMU)?;
        let cmd = services::open::<NavCommand>(&node, &config, &service("cmd")?, &services::CMD)?;
        let nav = services::open::<NavSolution>(&node, &config, &service("nav")?, &services::NAV)?;
        Ok(Self {
            name: name.into(),
            node,
            imu,
            cmd,
            nav,
            config,
        })
    }

    /// Creates this process's port with `create`, which fails while the service's publisher
    /// slots are taken; `holders()` counts the publishers after creation (more than one: a
    /// peer created the service with more slots, and another `role` holds one). A slot held by
    /// a dead process is freed by cleaning up dead nodes (a peer may be cleaning it up at this
    /// moment: retried for up to a second while dead nodes remain); one held by a live process
    /// means the session already has a `role`.
    pub fn exclusive<P, E: std::fmt::Debug>(
        &self,
        role: &'static str,
        mut create: impl FnMut() -> Result<P, E>,
        holders: impl Fn() -> usize,
    ) -> Result<P, TransportError> {
        let start = Instant::now();
        let mut last_try = false;
        loop {
            match create() {
                Ok(p) if holders() <= 1 => return Ok(p),
                Ok(p) => drop(p), // a second holder: released, then decided below
                Err(e) if format!("{e:?}").contains("ExceedsMax") => {}
                Err(e) => return Err(ipc(role)(&e)),
            }
            // Only a dead holder is worth waiting for (its cleanup may be under way in another
            // process); a live one makes this process the second `role`. (One more attempt
            // when none is left: the last may just have been removed.)
            let dead = cleanup_dead_nodes(&self.config);
            if dead == 0 && !last_try {
                last_try = true;
                continue;
            }
            if dead == 0 || start.elapsed() > Duration::from_secs(1) {
                return Err(TransportError::Busy {
                    session: self.name.clone(),
                    role,
                });
            }
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Whether a node of the session has died since the last check (its resources are then
    /// cleaned up, so a restarted peer finds a clean service).
    pub fn peer_died(&self) -> bool {
        cleanup_dead_nodes(&self.config) > 0
    }

    /// Number of IMU subscribers connected.
    pub fn imu_subscribers(&self) -> usize {
        self.imu.dynamic_config().number_of_subscribers()
    }

    /// Number of IMU publishers connected.
    pub fn imu_publishers(&self) -> usize {
        self.imu.dynamic_config().number_of_publishers()
    }

    /// Whether SIGINT/SIGTERM arrived (latched: every later call says so too). An atomic
    /// load, cheap enough to check once per batch.
    pub fn interrupted(&self) -> bool {
        crate::signals::termination_requested()
    }

    /// The session's iceoryx2 configuration.
    pub fn config(&self) -> &Config {
        &self.config
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn session_names_follow_the_documented_rule() {
        let long = "x".repeat(MAX_NAME);
        let too_long = "x".repeat(MAX_NAME + 1);
        // (name, accepted, what the refusal must say)
        let cases: &[(&str, bool, &str)] = &[
            ("default", true, ""),
            ("A-z_09", true, ""),
            ("-", true, ""),
            (&long, true, ""),
            ("", false, "is empty"),
            ("a b", false, "' ' at character 2"),
            ("..", false, "'.' at character 1"),
            ("a.b", false, "'.' at character 2"),
            ("ü", false, "'ü' at character 1"),
            ("a/b", false, "'/' at character 2"),
            ("tab\t", false, "'\\t' at character 4"),
            (&too_long, false, "is 65 characters long"),
        ];
        for (name, ok, says) in cases {
            match check_name(name) {
                Ok(()) => assert!(ok, "{name:?} accepted against the rule"),
                Err(e) => {
                    assert!(!ok, "{name:?} refused: {e}");
                    let text = e.to_string();
                    assert!(text.contains(says), "{name:?}: {text}");
                    assert!(
                        text.contains("1 to 64 characters")
                            && text.contains("ASCII letter")
                            && text.contains("'-' or '_'"),
                        "the message says what is allowed: {text}"
                    );
                    assert!(!text.contains("ExceedsMaximumLength"), "{text}");
                    // Session::open refuses it the same way, before touching iceoryx2.
                    assert!(matches!(
                        config(name),
                        Err(TransportError::SessionName { .. })
                    ));
                }
            }
        }
        // The longest allowed name works with iceoryx2 (prefix, node, service names).
        let pid = std::process::id().to_string();
        let longest = format!("{pid}{}", "y".repeat(MAX_NAME - pid.len()));
        let s = Session::open(&longest, "plant").expect("a 64-character name opens");
        assert_eq!(s.name.len(), MAX_NAME);
    }
}
