//! A seed's part of a step: its readout and, on an isolated table, its own loop (the seed's
//! table turned from the reference table's, [`crate::carrier::own_table`]). A plant has one
//! lane for its own seed; a batch of seeds sharing its physics has one more per further seed,
//! and every lane is read out by the same code, so a seed's samples are the same bits alone and
//! in a batch.

use nalgebra::Vector3;

use crate::carrier::own_table::{OwnTable, ReferenceInterval};
use crate::output::{ImuSample, Truth};
use crate::stages::interval::Interval;
use crate::stages::readout::{Measured, Readout};
use crate::table::GimbalState;

/// A seed's readout and own table.
#[derive(Clone, Debug)]
pub(crate) struct Lane {
    /// Noise, quantisation, encoders and temperature sensors of the seed.
    pub readout: Readout,
    /// The seed's own isolation loop (`None`: no isolation, or each seed moving its own table).
    pub own: Option<OwnTable>,
    /// On an own table: the last interval's true increments and the table's state at its end
    /// (the seed's truth; the reference table's otherwise).
    pub table: Option<OwnInterval>,
    /// An ideal sensor (every error term off) read out of a plant with errors: it takes the
    /// interval's true increments alone.
    ideal: bool,
    /// On an own table, between the phases of a step: the interval turned onto it, then its
    /// measurement.
    turned: Option<Interval>,
    measured: Option<Measured>,
}

/// The true increments over an interval on a seed's own table and the table at its end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct OwnInterval {
    /// True angular increment, rad.
    pub dtheta_true_rad: Vector3<f64>,
    /// True velocity increment, m/s.
    pub dv_true_mps: Vector3<f64>,
    /// The table at the interval's end.
    pub gimbal: GimbalState,
}

impl Lane {
    /// A lane with `readout` and, on an isolated table, the loop `own`.
    pub fn new(readout: Readout, own: Option<OwnTable>, ideal: bool) -> Self {
        Self {
            readout,
            own,
            ideal,
            table: None,
            turned: None,
            measured: None,
        }
    }

    /// First phase of a step on an own table: the reference interval `x` turned onto this
    /// seed's table ([`OwnTable::turn`]), and the table's state from the reference's
    /// `gimbal_ref` at the interval's end.
    ///
    /// A step runs each phase over every lane before the next: a lane's turn, readout and loop
    /// form a chain from one sample to the next (the loop sets the next interval's offset), and
    /// the lanes' chains are independent, so side by side the CPU overlaps them.
    #[inline(always)]
    pub fn turn(&mut self, x: &Interval, r: &ReferenceInterval, gimbal_ref: GimbalState) {
        let own = self.own.as_ref().expect("a lane on its own table");
        let turned = self.of_sensor(own.turn(x, r));
        self.table = Some(OwnInterval {
            dtheta_true_rad: turned.dtheta_true_rad,
            dv_true_mps: turned.dv_true_mps,
            gimbal: own.gimbal(gimbal_ref, r),
        });
        self.turned = Some(turned);
    }

    /// Second phase: the turned interval measured.
    #[inline(always)]
    pub fn measure_turned(&mut self) {
        let m = self
            .readout
            .measure(self.turned.as_ref().expect("turned first"));
        self.measured = Some(m);
    }

    /// Third phase: the seed's loop closed with its measured increment.
    #[inline(always)]
    pub fn close(&mut self, r: &ReferenceInterval) {
        let m = self.measured.expect("measured first");
        let own = self.own.as_mut().expect("a lane on its own table");
        own.update(&m.dtheta_rad, r);
    }

    /// After the phases, on an own table: the sample the seed's unit outputs, numbered
    /// `index` and ending at `t_s` (its encoders read its own table).
    #[inline(always)]
    pub fn turned_sample(&self, index: u64, t_s: f64) -> ImuSample {
        let m = self.measured.expect("measured first");
        let g = self.table.expect("turned first").gimbal;
        self.readout.sample(index, t_s, &m, g.angles)
    }

    /// The plant's interval `x` as this lane's sensor sees it: without the deterministic errors
    /// for an ideal sensor.
    #[inline(always)]
    fn of_sensor(&self, x: Interval) -> Interval {
        if self.ideal {
            Interval {
                gyro_err_rad: Vector3::zeros(),
                accel_err_mps: Vector3::zeros(),
                ..x
            }
        } else {
            x
        }
    }

    /// The plant's interval `x` measured by this lane (a lane without its own table).
    #[inline(always)]
    pub fn measure(&mut self, x: &Interval) -> Measured {
        if self.ideal {
            let x = self.of_sensor(*x);
            return self.readout.measure(&x);
        }
        self.readout.measure(x)
    }

    /// `t` (the plant's truth) with this lane's noise and quantisation and, on an own table,
    /// its true increments and table state; an ideal sensor's deterministic terms are zero.
    pub fn truth(&self, mut t: Truth) -> Truth {
        self.readout.terms().write_into(&mut t);
        if self.ideal {
            t.gyro_terms_rad = Default::default();
            t.accel_terms_mps = Default::default();
            t.custom_gyro_rad = Vector3::zeros();
            t.custom_accel_mps = Vector3::zeros();
        }
        if let Some(o) = &self.table {
            t.dtheta_true_rad = o.dtheta_true_rad;
            t.dv_true_mps = o.dv_true_mps;
            t.gimbal = o.gimbal;
        }
        t
    }
}
