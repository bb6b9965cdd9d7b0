//! Opening the session's services so that a peer which created them first (a subscriber
//! written from docs/transport.md, started before `rins serve`) is accepted when its settings
//! serve rins, and refused with the one setting named when they do not.
//!
//! iceoryx2 compares, on open, every setting the opener states explicitly against the existing
//! service ("at least" for counts and sizes, "equal" for safe overflow). Stating the creation
//! values when opening would refuse a peer that used iceoryx2's defaults for the settings
//! rins does not care about (issue 16, A1). So a service is opened with no stated settings, and
//! its static configuration is then checked against [`ServiceSpec`]'s requirements only.

use std::time::{Duration, Instant};

use iceoryx2::prelude::*;
use iceoryx2::service::port_factory::PortFactory as _;
use iceoryx2::service::port_factory::publish_subscribe::PortFactory;
use iceoryx2::service::static_config::messaging_pattern::MessagingPattern as StaticPattern;

use crate::error::TransportError;

/// Messages each subscriber can hold before the publisher waits (no loss: backpressure).
pub const BUFFER: usize = 16;

/// The settings rins creates a service with, and what it requires of one a peer created.
#[derive(Clone, Copy, Debug)]
pub struct ServiceSpec {
    /// Safe overflow (required equal): off means a full buffer makes the sender wait.
    pub safe_overflow: bool,
    /// Subscriber buffer, messages (created with; any value ≥ 1 is accepted).
    pub buffer: usize,
    /// History, messages (created with; required equal when `history_must_match`).
    pub history: usize,
    /// Whether a different history is refused (a history replays acknowledged batches).
    pub history_must_match: bool,
    /// Publishers (created with; at least 1 required).
    pub max_publishers: usize,
    /// Subscribers (created with; at least 1 required).
    pub max_subscribers: usize,
}

/// `rins/S/imu`: one plant, no loss, no replay.
pub const IMU: ServiceSpec = ServiceSpec {
    safe_overflow: false,
    buffer: BUFFER,
    history: 0,
    history_must_match: true,
    max_publishers: 1,
    max_subscribers: 8,
};

/// `rins/S/cmd`: one navigator commands the plant, no loss.
pub const CMD: ServiceSpec = ServiceSpec {
    safe_overflow: false,
    buffer: BUFFER,
    history: 0,
    history_must_match: true,
    max_publishers: 1,
    max_subscribers: 2,
};

/// `rins/S/nav`: the latest solution for anyone (overwriting is fine).
pub const NAV: ServiceSpec = ServiceSpec {
    safe_overflow: true,
    buffer: BUFFER,
    history: 1,
    history_must_match: false,
    max_publishers: 2,
    max_subscribers: 8,
};

fn setting(service: &str, setting: &str, existing: String, required: String) -> TransportError {
    TransportError::Setting {
        service: service.into(),
        setting: setting.into(),
        existing,
        required,
    }
}

/// Opens service `name` with payload `T`, or creates it with `spec`; a service created by a
/// peer is checked against `spec`'s requirements, naming the first setting that differs.
pub fn open<T: std::fmt::Debug + ZeroCopySend + 'static>(
    node: &Node<ipc::Service>,
    config: &Config,
    name: &ServiceName,
    spec: &ServiceSpec,
) -> Result<PortFactory<ipc::Service, T, ()>, TransportError> {
    use iceoryx2::service::builder::publish_subscribe::{
        PublishSubscribeCreateError as C, PublishSubscribeOpenError as O,
    };
    let service = name.as_str();
    let start = Instant::now();
    loop {
        let open = node.service_builder(name).publish_subscribe::<T>().open();
        let e = match open {
            Ok(f) => {
                check(service, f.static_config(), spec)?;
                return Ok(f);
            }
            Err(O::DoesNotExist) => {
                let created = node
                    .service_builder(name)
                    .publish_subscribe::<T>()
                    .enable_safe_overflow(spec.safe_overflow)
                    .subscriber_max_buffer_size(spec.buffer)
                    .history_size(spec.history)
                    .max_publishers(spec.max_publishers)
                    .max_subscribers(spec.max_subscribers)
                    .create();
                match created {
                    Ok(f) => return Ok(f),
                    // Another process created it at the same moment: open theirs.
                    Err(C::AlreadyExists | C::IsBeingCreatedByAnotherInstance) => {
                        format!("{:?}", C::AlreadyExists)
                    }
                    Err(e) => {
                        return Err(TransportError::Ipc {
                            what: format!("creating service {service}"),
                            detail: format!("{e:?}"),
                        });
                    }
                }
            }
            Err(O::IncompatibleTypes) => return Err(type_mismatch::<T>(config, name)),
            Err(e @ (O::InsufficientPermissions | O::IncompatibleMessagingPattern)) => {
                return Err(TransportError::Mismatch {
                    service: service.into(),
                    detail: format!("{e:?}"),
                });
            }
            // Being created or removed by another process right now: retry shortly.
            Err(e) => format!("{e:?}"),
        };
        if start.elapsed() > Duration::from_secs(2) {
            return Err(TransportError::Mismatch {
                service: service.into(),
                detail: e,
            });
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Checks a service a peer created against what rins needs of it.
fn check(
    service: &str,
    s: &iceoryx2::service::static_config::publish_subscribe::StaticConfig,
    spec: &ServiceSpec,
) -> Result<(), TransportError> {
    let onoff = |b: bool| if b { "on" } else { "off" }.to_string();
    if s.has_safe_overflow() != spec.safe_overflow {
        return Err(setting(
            service,
            "safe overflow (enable_safe_overflow)",
            onoff(s.has_safe_overflow()),
            onoff(spec.safe_overflow),
        ));
    }
    if spec.history_must_match && s.history_size() != spec.history {
        return Err(setting(
            service,
            "history size (history_size)",
            s.history_size().to_string(),
            spec.history.to_string(),
        ));
    }
    for (what, got) in [
        ("maximum publishers (max_publishers)", s.max_publishers()),
        ("maximum subscribers (max_subscribers)", s.max_subscribers()),
        (
            "subscriber buffer size (subscriber_max_buffer_size)",
            s.subscriber_max_buffer_size(),
        ),
    ] {
        if got < 1 {
            return Err(setting(service, what, got.to_string(), "at least 1".into()));
        }
    }
    Ok(())
}

/// The payload type the existing service has, against ours.
fn type_mismatch<T: ZeroCopySend>(config: &Config, name: &ServiceName) -> TransportError {
    let ours = format!(
        "{} ({} bytes, alignment {})",
        std::any::type_name::<T>()
            .rsplit("::")
            .next()
            .map(|t| format!("rins::{t}"))
            .unwrap_or_default(),
        std::mem::size_of::<T>(),
        std::mem::align_of::<T>()
    );
    let existing = match ipc::Service::details(name, config, MessagingPattern::PublishSubscribe) {
        Ok(Some(d)) => match d.static_details.messaging_pattern() {
            StaticPattern::PublishSubscribe(p) => {
                let t = &p.message_type_details().payload;
                format!(
                    "{} ({} bytes, alignment {})",
                    t.type_name(),
                    t.size(),
                    t.alignment()
                )
            }
            other => format!("{other:?}"),
        },
        _ => "unreadable".into(),
    };
    setting(name.as_str(), "payload type", existing, ours)
}
