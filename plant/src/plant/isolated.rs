//! The plant with azimuth isolation: the seeds' own tables read out from the reference table
//! ([`crate::carrier::own_table`]), the isolation commands, and the switch between one
//! reference table and each seed moving its own.

use super::Plant;
use crate::carrier::isolation::Isolation;
use crate::carrier::own_table::OwnTable;
use crate::output::ImuSample;
use crate::stages::interval::Interval;
use crate::stages::lane::Lane;

impl Plant {
    /// [`Plant::read_out`] on isolated tables: the reference table's interval `x` read out on
    /// this seed's own table and on each of `lanes` (their samples into `out`), then the
    /// reference loop closed with the reference's true increment.
    #[inline(never)]
    pub(super) fn read_out_isolated(
        &mut self,
        index: u64,
        x: &Interval,
        lanes: &mut [Lane],
        out: &mut [ImuSample],
    ) -> ImuSample {
        let tick = self.clock.tick();
        let r = self
            .motion
            .reference_interval(tick)
            .expect("an own table beside the reference loop");
        let gimbal_ref = self.motion.gimbal_truth(tick);
        // Phase by phase over the lanes, this seed's first (see [`Lane::turn`]).
        std::iter::once(&mut self.lane)
            .chain(lanes.iter_mut())
            .for_each(|l| l.turn(x, &r, gimbal_ref));
        std::iter::once(&mut self.lane)
            .chain(lanes.iter_mut())
            .for_each(|l| l.measure_turned());
        std::iter::once(&mut self.lane)
            .chain(lanes.iter_mut())
            .for_each(|l| l.close(&r));
        let own = self.lane.table.expect("just turned");
        let tr = &mut self.truth;
        tr.gimbal = own.gimbal;
        tr.dtheta_true_rad = own.dtheta_true_rad;
        tr.dv_true_mps = own.dv_true_mps;
        tr.temps = self.temperature.temperatures();
        tr.position_weight = x.position_weight;
        let t_s = self.clock.time_s();
        let first = self.lane.turned_sample(index, t_s);
        for (lane, o) in lanes.iter().zip(out) {
            *o = lane.turned_sample(index, t_s);
        }
        self.motion.isolate_reference(&x.dtheta_true_rad, &r);
        first
    }

    /// Switches azimuth isolation on or off from the next output interval (the navigation
    /// computer's command; `[carrier] azimuth_isolation` sets it at start). On: the loop restarts
    /// from the table's attitude now and holds the scheme at its present azimuth in the
    /// navigation frame. Off: the outer offset stays where it is. Refused on the static carrier.
    pub fn command_azimuth_isolation(&mut self, on: bool) -> Result<(), String> {
        let tick = self.clock.tick();
        // The seed's own table before the reference loop restarts: its attitude and offset.
        let own_start = self.isolation_reference.then(|| {
            let offset = self.own_offset_rad(tick);
            (self.attitude_c_bn(), offset)
        });
        self.motion.command_azimuth_isolation(on, tick)?;
        let Some((c_bn, offset)) = own_start else {
            return Ok(());
        };
        match (on, &mut self.lane.own) {
            (false, Some(o)) => o.lp.active = false,
            (false, None) => {}
            (true, _) => {
                let a = self.motion.gimbal_now().angles;
                self.lane.own = Some(OwnTable {
                    lp: Isolation::new(&c_bn, a.inner_rad, a.outer_rad, offset, tick),
                });
            }
        }
        Ok(())
    }

    /// The outer offset of this seed's table at internal tick `tick`, rad: its own loop's, else
    /// the table's (the reference loop's, or 0 without isolation).
    pub(super) fn own_offset_rad(&self, tick: u64) -> f64 {
        match &self.lane.own {
            Some(o) => o.lp.offset_rad(tick, 1),
            None => self
                .motion
                .carrier()
                .map_or(0.0, |c| c.isolation_rad(tick, 1)),
        }
    }

    /// With azimuth isolation, moves one reference table and turns each seed's from it (`true`,
    /// the default; `crate::carrier::own_table`) or moves this seed's own table with its loop
    /// (`false`: the reference the tests compare with; the plant then shares no physics with
    /// other seeds). Only before the first step.
    pub fn set_isolation_reference(&mut self, on: bool) -> Result<(), String> {
        if self.clock.tick() != 0 {
            return Err("the isolation's reference table is switched before the first step".into());
        }
        self.isolation_reference = on;
        self.lane.own = if on {
            self.motion
                .carrier()
                .and_then(|c| c.isolation.clone())
                .map(|lp| OwnTable { lp })
        } else {
            None
        };
        Ok(())
    }
}
