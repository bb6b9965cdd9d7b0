//! # rins-transport
//!
//! The plant and external navigation software in separate processes over iceoryx2 shared memory
//! (docs/transport.md). The plant publishes [`layout::ImuBatch`] messages on `rins/<session>/imu`;
//! the navigator acknowledges them and may command the table on `rins/<session>/cmd`, and
//! publishes its solution on `rins/<session>/nav`. No sample is lost: safe overflow is off,
//! publishers wait for space (backpressure), the plant waits for a subscriber before the first
//! message, and receivers check sequence numbers. Lockstep makes results independent of the
//! processes' speeds.

pub mod action;
mod error;
pub mod layout;
pub mod nav_side;
pub mod pace;
pub mod plant_link;
pub mod plant_side;
pub mod probe;
pub mod services;
pub mod session;
pub mod signals;

pub use action::NavAction;
pub use error::TransportError;
pub use nav_side::{
    FinalError, NavOptions, NavProcessor, NavSummary, ScheduledCommand, fold_digest, navigate,
    navigate_probed,
};
pub use plant_side::{Mode, ServeOptions, ServeSummary, serve, serve_observed, serve_probed};
pub use probe::Stage;
pub use session::Session;

/// The in-process reference: the same plant and navigator without the transport, with the same
/// commands applied at the same ticks (the first tick of the batch after `after_seq`), the
/// navigator started from the plant's state before its first step ([`layout::StartRecord`]).
pub fn reference(
    cfg: &rins_plant::PlantConfig,
    samples: u64,
    batch: usize,
    commands: &[ScheduledCommand],
) -> NavProcessor {
    let mut plant = rins_plant::Plant::new(cfg).expect("valid configuration");
    let mut nav = NavProcessor::new(cfg);
    nav.begin(&layout::StartRecord::from_plant(&plant));
    let batch = batch.clamp(1, layout::BATCH_CAPACITY) as u64;
    let mut done = 0;
    let mut seq = 0;
    while done < samples {
        let n = (samples - done).min(batch);
        for _ in 0..n {
            let s = plant.step();
            nav.push(&layout::ImuRecord::from_sample(&s));
        }
        done += n;
        if let Some(c) = commands.iter().find(|c| c.after_seq == seq) {
            c.action.apply(&mut plant).expect("valid command");
        }
        seq += 1;
    }
    nav
}
