//! A named session: its iceoryx2 configuration (a prefix of its own, so sessions and tests run
//! side by side), its services, dead-node cleanup and peer-liveness checks.

use std::time::Duration;

use iceoryx2::config::Config;
use iceoryx2::prelude::*;
use iceoryx2::service::port_factory::PortFactory as _;
use iceoryx2::service::port_factory::publish_subscribe::PortFactory;

use crate::layout::{ImuBatch, NavCommand, NavSolution};

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

/// The iceoryx2 configuration of session `name`: its own prefix for every resource.
pub fn config(name: &str) -> Result<Config, TransportError> {
    let mut config = Config::default();
    let prefix = format!("rins_{name}_");
    config.global.prefix = FileName::new(prefix.as_bytes()).map_err(|e| TransportError::Ipc {
        what: format!("session name {name:?}"),
        detail: format!("{e:?} (letters, digits, '-' and '_' only)"),
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
    /// Joins (or creates) session `name` as node `role`, after cleaning up dead nodes.
    pub fn open(name: &str, role: &str) -> Result<Self, TransportError> {
        let config = config(name)?;
        cleanup_dead_nodes(&config);
        let node = NodeBuilder::new()
            .config(&config)
            .name(&NodeName::new(role).map_err(|e| ipc("node name")(&e))?)
            .signal_handling_mode(SignalHandlingMode::HandleTerminationRequests)
            .create::<ipc::Service>()
            .map_err(|e| ipc("creating the node")(&e))?;
        let service = |suffix: &str| -> Result<ServiceName, TransportError> {
            format!("rins/{name}/{suffix}")
                .as_str()
                .try_into()
                .map_err(|e| ipc("service name")(&e))
        };
        let mismatch = |s: String| {
            move |e: &dyn std::fmt::Debug| TransportError::Mismatch {
                service: s.clone(),
                detail: format!("{e:?}"),
            }
        };
        let imu_name = service("imu")?;
        let imu = node
            .service_builder(&imu_name)
            .publish_subscribe::<ImuBatch>()
            .enable_safe_overflow(false)
            .subscriber_max_buffer_size(BUFFER)
            .history_size(0)
            .max_publishers(2)
            .max_subscribers(8)
            .open_or_create()
            .map_err(|e| mismatch(imu_name.as_str().to_string())(&e))?;
        let cmd_name = service("cmd")?;
        let cmd = node
            .service_builder(&cmd_name)
            .publish_subscribe::<NavCommand>()
            .enable_safe_overflow(false)
            .subscriber_max_buffer_size(BUFFER)
            .history_size(0)
            .max_publishers(4)
            .max_subscribers(2)
            .open_or_create()
            .map_err(|e| mismatch(cmd_name.as_str().to_string())(&e))?;
        let nav_name = service("nav")?;
        let nav = node
            .service_builder(&nav_name)
            .publish_subscribe::<NavSolution>()
            .enable_safe_overflow(true)
            .subscriber_max_buffer_size(BUFFER)
            .history_size(1)
            .max_publishers(2)
            .max_subscribers(8)
            .open_or_create()
            .map_err(|e| mismatch(nav_name.as_str().to_string())(&e))?;
        Ok(Self {
            name: name.into(),
            node,
            imu,
            cmd,
            nav,
            config,
        })
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

    /// Checks for SIGINT/SIGTERM without sleeping.
    pub fn interrupted(&self) -> bool {
        self.node.wait(Duration::ZERO).is_err()
    }
}
