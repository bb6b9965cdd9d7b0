//! The plant side: steps the plant, publishes batches, applies the navigator's table commands at
//! defined ticks, and in lockstep waits for each batch's acknowledgement.

use std::time::Instant;

use rins_plant::{ImuSample, Plant, Truth};

use crate::error::TransportError;
use crate::layout::{
    BATCH_CAPACITY, FLAG_END, FLAG_INTERRUPTED, FLAG_TRUTH, ImuBatch, ImuRecord, StartRecord,
    TruthRecord,
};
use crate::pace::Pacer;
use crate::plant_link::Link;
// The options and summary are the link's too: defined beneath, with it; named here, as what
// serve takes and returns.
pub use crate::plant_link::{Mode, ServeOptions, ServeSummary};
use crate::probe::Stage;
use crate::session::Session;

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
    serve_probed(name, plant, samples, opts, observe, &mut |_| {})
}

/// [`serve_observed`], reporting each lifecycle [`Stage`] to `probe` as it is reached (the
/// chaos tests stop the process there).
pub fn serve_probed(
    name: &str,
    plant: &mut Plant,
    samples: u64,
    opts: &ServeOptions,
    observe: &mut dyn FnMut(&ImuSample, &Truth),
    probe: &mut dyn FnMut(Stage),
) -> Result<ServeSummary, TransportError> {
    let t0 = Instant::now();
    let session = Session::open(name, "plant")?;
    let mut link = Link::new(&session, opts, probe)?;
    let mut summary = ServeSummary::default();
    let batch_len = opts.batch.clamp(1, BATCH_CAPACITY);
    let mut pacer = Pacer::new(opts.pace, plant.time_s());
    link.wait_for_navigator(0)?;
    (link.probe)(Stage::PlantConnected);
    pacer.rebase(plant.time_s());
    let mut seq: u64 = 0;
    let mut done: u64 = 0;
    let mut batch = ImuBatch::default();
    let mut stop = false;
    loop {
        // Checked every batch (a signal also cuts the pacing sleep and every wait short): the
        // plant stops within one batch.
        let interrupted = session.interrupted();
        // Fill the next batch, or an empty end marker after a stop request or a signal.
        batch.seq = seq;
        batch.flags = FLAG_TRUTH;
        // Where a navigator that begins with this batch starts: the state now, before its
        // first record.
        batch.start = StartRecord::from_plant(plant);
        let n = if stop || interrupted {
            0
        } else {
            (samples - done).min(batch_len as u64) as usize
        };
        for k in 0..n {
            let s = plant.step();
            observe(&s, &plant.truth());
            batch.records[k] = ImuRecord::from_sample(&s);
            batch.truth[k] = TruthRecord::from_plant(plant);
        }
        batch.count = n as u32;
        done += n as u64;
        if done >= samples || stop || interrupted {
            batch.flags |= FLAG_END;
        }
        if interrupted {
            batch.flags |= FLAG_INTERRUPTED;
            summary.interrupted = true;
        }
        // A command the plant refuses ends the run; the navigator is told why first.
        let paused = match link.deliver(&batch, plant, &mut summary, opts.mode) {
            Ok(p) => p,
            Err(e) => return Err(link.refuse(plant, &batch, e)),
        };
        stop |= link.stop_requested;
        if paused {
            pacer.rebase(plant.time_s());
        }
        summary.batches += 1;
        summary.samples += n as u64;
        if opts.mode == Mode::FreeRunning {
            if let Err(e) = link.drain_commands(plant, &mut summary) {
                return Err(link.refuse(plant, &batch, e));
            }
            stop |= link.stop_requested;
        }
        seq += 1;
        if batch.flags & FLAG_END != 0 {
            break;
        }
        pacer.wait(plant.time_s(), &|| session.interrupted());
    }
    summary.wall_s = t0.elapsed().as_secs_f64();
    Ok(summary)
}
