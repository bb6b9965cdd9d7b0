//! Pacing at K × real time, with sleeps a signal cuts short and a restart point that moves
//! after a pause (a navigator restart), so the plant keeps the pace instead of bursting to
//! catch up with the wall time the pause took.

use std::time::{Duration, Instant};

/// Longest single sleep: a SIGTERM is seen within this (the plant stops within one batch,
/// ≤ 100 ms, at any pace).
pub const SLICE: Duration = Duration::from_millis(10);

/// Holds simulated time to K × wall time from an anchor.
#[derive(Debug)]
pub struct Pacer {
    factor: Option<f64>,
    anchor: Instant,
    anchor_sim_s: f64,
}

impl Pacer {
    /// Pacing at `factor` × real time (none: as fast as possible) from simulated time `sim_s`.
    pub fn new(factor: Option<f64>, sim_s: f64) -> Self {
        Self {
            factor,
            anchor: Instant::now(),
            anchor_sim_s: sim_s,
        }
    }

    /// Restarts the pace at `sim_s` now: the time spent paused is not made up.
    pub fn rebase(&mut self, sim_s: f64) {
        self.anchor = Instant::now();
        self.anchor_sim_s = sim_s;
    }

    /// Sleeps until simulated time `sim_s` is due; returns early (true) when `stop()` says so,
    /// checked every [`SLICE`].
    pub fn wait(&self, sim_s: f64, stop: &dyn Fn() -> bool) -> bool {
        let Some(k) = self.factor else {
            return false;
        };
        let due = self.anchor + Duration::from_secs_f64(((sim_s - self.anchor_sim_s) / k).max(0.0));
        loop {
            if stop() {
                return true;
            }
            let now = Instant::now();
            if now >= due {
                return false;
            }
            std::thread::sleep((due - now).min(SLICE));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rebased_pacer_does_not_make_up_the_pause() {
        let mut p = Pacer::new(Some(100.0), 0.0);
        // 1 simulated second at 100x: 10 ms.
        let t = Instant::now();
        assert!(!p.wait(1.0, &|| false));
        let first = t.elapsed();
        assert!(first >= Duration::from_millis(10), "{first:?}");
        std::thread::sleep(Duration::from_millis(50));
        p.rebase(1.0);
        let t = Instant::now();
        p.wait(2.0, &|| false);
        assert!(
            t.elapsed() >= Duration::from_millis(10),
            "after a pause the next simulated second still takes 10 ms: {:?}",
            t.elapsed()
        );
        // A stop request cuts a long sleep short.
        let t = Instant::now();
        assert!(p.wait(1000.0, &|| t.elapsed() > Duration::from_millis(20)));
        assert!(t.elapsed() < Duration::from_millis(60), "{:?}", t.elapsed());
    }
}
