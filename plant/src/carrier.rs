//! The carrier that moves the table: static (the default, the plant's original path), a ship on
//! legs with sea-state motion, or a trajectory file. A carrier is advanced by whole ticks
//! (t = k·h, never accumulated) and gives its state at the two Gauss–Legendre points of each
//! tick ([`GL_OFFSETS`]) and at the tick's end; [`crate::kinematics::moving_base_increments`]
//! turns those into the IMU's exact increments.
//!
//! An external vessel model (an FMU input) drives the carrier the same way: it supplies
//! [`CarrierState`] samples at the ends of each communication step, and the plant interpolates
//! them inside the step (see `docs/carrier.md`).

pub mod carrier_state;
pub mod external;
pub(crate) mod gimbal_trig;
pub mod isolation;
pub(crate) mod own_table;
pub mod run;
pub mod segment;
pub mod ship;
pub mod spec;
pub mod track;
pub mod trajectory;
pub mod trajectory_error;
pub mod trajectory_text;
pub mod waves;
pub mod widths;

pub use carrier_state::{CarrierState, CarrierTruth};
pub use spec::{
    AfterEnd, CarrierKind, CarrierSpec, LegSpec, RaoSpec, SeaRealisation, SeaSpec, ShipRaoSpec,
    ShipSpec, SpectrumKind, TrajectorySpec,
};
pub use trajectory::{Trajectory, TrajectoryError};

use ship::Ship;

/// In-tick fractions of the two-point Gauss–Legendre rule, ½ ∓ √3/6: ∫₀ʰ f ≈ (h/2)(f(τ₁h) +
/// f(τ₂h)), error h⁵·f⁽⁴⁾/4320.
pub const GL_OFFSETS: [f64; 2] = [0.5 - 0.288_675_134_594_812_9, 0.5 + 0.288_675_134_594_812_9];

/// A moving carrier.
#[derive(Clone, Debug)]
pub enum Carrier {
    /// A ship.
    Ship(Box<Ship>),
    /// Trajectory samples, with the current tick and the tick length.
    Trajectory {
        /// The samples.
        data: Box<Trajectory>,
        /// Current tick.
        tick: u64,
        /// Tick length, s.
        tick_s: f64,
    },
}

impl Carrier {
    /// True when the carrier's motion depends on the run seed (a ship in a sea drawn from it,
    /// [`SeaRealisation::PerRun`]).
    pub fn depends_on_seed(&self) -> bool {
        matches!(self, Carrier::Ship(s) if s.waves.is_some() && s.waves_per_run)
    }

    /// The carrier of `spec` for ticks of `tick_s` (`None` for the static carrier). A
    /// trajectory carrier reads its file here.
    pub fn new(spec: &CarrierSpec, seed: u64, tick_s: f64) -> Result<Option<Self>, String> {
        Ok(match spec.kind {
            CarrierKind::Static => None,
            CarrierKind::Ship => Some(Self::Ship(Box::new(Ship::new(
                &spec.ship,
                seed,
                tick_s,
                &GL_OFFSETS,
            )))),
            CarrierKind::Trajectory => Some(Self::Trajectory {
                data: Box::new(Trajectory::read(&spec.trajectory.file).map_err(|e| e.to_string())?),
                tick: 0,
                tick_s,
            }),
        })
    }

    /// A trajectory carrier from samples already in memory.
    pub fn from_trajectory(data: Trajectory, tick_s: f64) -> Self {
        Self::Trajectory {
            data: Box::new(data),
            tick: 0,
            tick_s,
        }
    }

    /// The current tick.
    pub fn tick(&self) -> u64 {
        match self {
            Self::Ship(s) => s.position().0,
            Self::Trajectory { tick, .. } => *tick,
        }
    }

    /// State at the current tick.
    pub fn state_now(&mut self) -> CarrierState {
        match self {
            Self::Ship(s) => s.state_now(),
            Self::Trajectory { data, tick, tick_s } => data.state_at(*tick as f64 * *tick_s),
        }
    }

    /// Advances one tick: fills the states at the [`GL_OFFSETS`] of the tick and returns the
    /// state at its end.
    pub fn advance(&mut self, nodes: &mut [CarrierState; 2]) -> CarrierState {
        match self {
            Self::Ship(s) => s.advance(nodes),
            Self::Trajectory { data, tick, tick_s } => {
                let k = *tick as f64;
                for (n, f) in nodes.iter_mut().zip(GL_OFFSETS) {
                    *n = data.state_at((k + f) * *tick_s);
                }
                *tick += 1;
                data.state_at(*tick as f64 * *tick_s)
            }
        }
    }
}
