//! A named session: its iceoryx2 configuration (a prefix of its own, so sessions and tests run
//! side by side), its services, dead-node cleanup and peer-liveness checks.

use std::time::{Duration, Instant};

use iceoryx2::config::Config;
use iceoryx2::prelude::*;
use iceoryx2::service::port_factory::PortFactory as _;
use iceoryx2::service::port_factory::publish_subscribe::PortFactory;

// The rule's length is stated by the error that enforces it; its path is this module.
pub use crate::error::MAX_NAME;
use crate::error::TransportError;
use crate::layout::{ImuBatch, NavCommand, NavSolution};
use crate::services;

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
