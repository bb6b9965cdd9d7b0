//! Why a transport run stopped: the one error type of the session, its services, the plant side
//! and the navigator side.

/// Longest session name, characters.
pub const MAX_NAME: usize = 64;

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
    /// A session name against the rule ([`crate::session::check_name`]).
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
