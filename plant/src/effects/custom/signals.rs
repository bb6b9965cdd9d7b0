//! The documented signals a declared effect's regressor is built from, their units, their
//! ranges, and the frame of values the plant (and the diagnosis) fills once per interval.
//!
//! Where each value comes from:
//! * in the plant, the physics acts on what really happens: true node temperatures, the true
//!   temperature rate over the last thermal step, the true body rate and gimbal angles;
//! * in the diagnosis (rins-mvm), only what a unit measures: temperature-sensor readings and
//!   their time derivative, encoder angles, the kinematic rate from the encoder angles.
//!
//! This is the same split as the catalogue effects (they use true temperatures in the plant and
//! the readings in the replay of a measured log).
//!
//! Every signal is defined once, in the table [`FAMILIES`]: its name, unit, bound, frame slot,
//! how it is computed per interval from [`FastInputs`] (the same function in the plant and the
//! diagnosis), which inputs it reads and where discovery's library uses it. The plant's
//! [`super::Needs`] and [`super::fill_fast`], the diagnosis's frame, the FMU slot codes (row + 1:
//! append new rows) and the discovery library derive their lists from it, so a new signal
//! computed from [`FastInputs`] is added in this file alone.

use nalgebra::Vector3;

pub use super::unit::Unit;
use crate::table::GimbalAngles;
use crate::thermal::node;

/// Number of values in a [`Frame`].
pub const SLOTS: usize = 32;
/// First slot of the node temperatures (°C), indexed by [`node`].
pub const TEMP: usize = 0;
/// First slot of the node temperature rates (K/s).
pub const DTEMP: usize = 6;
/// First slot of the body up direction u^b (dimensionless; the direction of the specific force
/// at rest, minus the gravity direction).
pub const UP: usize = 12;
/// First slot of the body rate ω_ib^b, °/s.
pub const RATE: usize = 15;
/// First slot of |ω_ib^b| per axis, °/s.
pub const ABS_RATE: usize = 18;
/// Outer gimbal angle, °, wrapped to [−180, 180).
pub const OUTER: usize = 21;
/// Inner gimbal angle, °, wrapped to [−180, 180).
pub const INNER: usize = 22;
/// Time since the start of the run, s.
pub const TIME: usize = 23;
/// First slot of the body components of the navigation frame's north unit vector n^b.
pub const NORTH: usize = 24;
/// First slot of the body components of the navigation frame's east unit vector e^b.
pub const EAST: usize = 27;
/// Seconds since the table last stopped (0 while it moves).
pub const SINCE_MOVE: usize = 30;
/// Seconds since the table last started to move.
pub const SINCE_START: usize = 31;

/// Values of every signal over one interval (slots above).
pub type Frame = [f64; SLOTS];

/// Wraps an angle in degrees to [−180, 180).
#[inline]
pub fn wrap_deg(a: f64) -> f64 {
    (a + 180.0).rem_euclid(360.0) - 180.0
}

/// A temperature node, or the block of the axis the effect acts on (gyro block x/y/z for the
/// gyro axes, the accelerometer cluster for the accelerometers).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeRef {
    /// A node of [`node`].
    Node(usize),
    /// The acting axis's own block.
    Block,
}

impl NodeRef {
    fn parse(s: &str) -> Option<NodeRef> {
        if s == "block" {
            return Some(NodeRef::Block);
        }
        node::NAMES.iter().position(|n| *n == s).map(NodeRef::Node)
    }

    /// The node for the axis `axis` of the gyros (`accel = false`) or accelerometers.
    pub fn resolve(self, accel: bool, axis: usize) -> usize {
        match self {
            NodeRef::Node(n) => n,
            NodeRef::Block if accel => node::ACCEL,
            NodeRef::Block => node::GYRO_X + axis,
        }
    }
}

/// One documented signal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Signal {
    /// `temp:NODE`, °C.
    Temp(NodeRef),
    /// `dtemp_dt:NODE`, K/s.
    TempRate(NodeRef),
    /// `grad:A-B` = temp:A − temp:B, K.
    Gradient(NodeRef, NodeRef),
    /// `u_x`, `u_y`, `u_z`: body up direction, 1.
    Up(usize),
    /// `w_x`, `w_y`, `w_z`: body rate, °/s.
    Rate(usize),
    /// `abs_w_x`, …: |body rate|, °/s.
    AbsRate(usize),
    /// `gimbal_outer`, °.
    Outer,
    /// `gimbal_inner`, °.
    Inner,
    /// `time`: since the start of the run, s.
    Time,
    /// `n_x`, `n_y`, `n_z`: body components of the local north direction, 1 (with `e_*` and
    /// `u_*`, any field fixed in the navigation frame, e.g. the Earth's magnetic field that an
    /// RLG's bias is sensitive to, is a linear combination).
    North(usize),
    /// `e_x`, `e_y`, `e_z`: body components of the local east direction, 1.
    East(usize),
    /// `since_move`: seconds since the table last stopped (0 while it moves; counted from the
    /// run's start before its first move).
    SinceMove,
    /// `since_start`: seconds since the table last started to move (from the run's start
    /// before its first move).
    SinceStart,
}

/// What follows a family's prefix in a signal name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArgKind {
    /// Nothing: the prefix is the whole name (`time`).
    None,
    /// A node or `block` (`temp:housing`).
    Node,
    /// Two nodes `A-B` (`grad:block-housing`).
    NodePair,
    /// An axis `x`, `y` or `z` (`u_x`).
    Axis,
}

/// The argument of one signal of a family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Args {
    /// No argument.
    None,
    /// A node.
    Node(NodeRef),
    /// Two nodes, A − B.
    NodePair(NodeRef, NodeRef),
    /// An axis 0–2.
    Axis(usize),
}

/// Where the discovery library uses a family's signals.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Library {
    /// Alone and in every product of two, as biases and scale factors (node families: the
    /// acting block, and the housing and the block-to-housing difference when it is measured).
    Products,
    /// Declarable but not searched: the body components of north and east are the catalogue's
    /// `gyro.nav_field_bias` (a field fixed in the navigation frame, one candidate with its
    /// three components: searched one by one, a single component stood in for the field, or on
    /// another axis for a g-sensitivity); a bias linear in a gimbal angle, which wraps at
    /// ±180°, is no physics a search should propose.
    NotSearched,
    /// Only through a decay exp(−x/τ) as a bias, τ searched (the clocks since the table's last
    /// stop and start: a transient after each move); a polynomial in an unbounded clock is no
    /// physics.
    Decay,
}

/// Everything a fast signal (one filled per interval, not per thermal step) can be computed
/// from. The plant fills it from the true motion, the diagnosis from the measured log; a new
/// fast signal reads these and no caller changes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FastInputs {
    /// Body up direction u^b (1).
    pub up_b: Vector3<f64>,
    /// Body north and east directions n^b, e^b (1); the plant computes them only when a
    /// needed family [`Family::reads_heading`].
    pub north_east_b: [Vector3<f64>; 2],
    /// Angle increment over the interval, rad.
    pub dtheta_rad: Vector3<f64>,
    /// Velocity increment over the interval, m/s.
    pub dv_mps: Vector3<f64>,
    /// Interval, s.
    pub h_s: f64,
    /// Gimbal angles at mid-interval (zero when the data carry quaternions: a family that
    /// reads them is [`Family::needs_gimbal`]).
    pub gimbal_mid: GimbalAngles,
    /// Mid-interval time since the start of the run, s; the plant computes it only when a
    /// needed family [`Family::reads_time`].
    pub t_mid_s: f64,
    /// Mid-interval seconds since the table last stopped (0 while it moves) and since it last
    /// started to move; the plant computes them only when a needed family
    /// [`Family::reads_motion`].
    pub since_s: MotionClocks,
}

/// The table's motion clocks at an interval's middle, s.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct MotionClocks {
    /// Since the table last stopped (0 while it moves; from the run's start before any move).
    pub move_s: f64,
    /// Since the table last started to move (from the run's start before any move).
    pub start_s: f64,
}

/// One row of the signals table: a family of signals (`u_x, u_y, u_z`) and every property the
/// plant, the diagnosis, the FMU slots and the discovery library read, so a signal is defined
/// once.
#[derive(Clone, Copy, Debug)]
pub struct Family {
    /// The name as documented (`u_x, u_y, u_z`, `temp:NODE`).
    pub doc_name: &'static str,
    /// The name up to its argument (`u_`, `temp:`), or the whole name when it has none.
    pub prefix: &'static str,
    /// What follows the prefix.
    pub arg: ArgKind,
    /// Unit.
    pub unit: Unit,
    /// Description, for messages and docs/effects.md.
    pub description: &'static str,
    /// The largest magnitude the signal can take in a valid scenario (temperatures within the
    /// thermal model's range, table rates within `scheme.rate_dps`, runs within
    /// `scenario.duration_s`): the bound of the non-finite check.
    pub bound: f64,
    /// First frame slot (a node's or axis's slot is this plus its index).
    pub slot: usize,
    /// Short name part for discovery's proposal names (≤ 32 characters in all); a node pair's
    /// is the whole part.
    pub short: &'static str,
    /// Constant while the table dwells (attitude and rate signals): discovery forms a product
    /// with it as the window mean.
    pub dwell_constant: bool,
    /// Formed from gimbal angles, which a log with quaternions does not carry.
    pub needs_gimbal: bool,
    /// Reads the north/east directions (the plant computes them only then).
    pub reads_heading: bool,
    /// Reads the time (the plant computes it only then).
    pub reads_time: bool,
    /// Reads the table's motion clocks (the plant keeps them only then).
    pub reads_motion: bool,
    /// A clock: seconds, never negative, growing with time; a decay exp(−x/τ) may read it.
    pub clock: bool,
    /// How discovery's library uses it.
    pub library: Library,
    /// Fills the family's slots once per interval; `None` for the slow (thermal) families,
    /// which the plant sets at thermal steps and the diagnosis from the readings.
    pub fill: Option<fn(&FastInputs, &mut Frame)>,
}

const K: Unit = Unit { k: 1, s: 0, deg: 0 };
const K_PER_S: Unit = Unit {
    k: 1,
    s: -1,
    deg: 0,
};
const DEG: Unit = Unit { k: 0, s: 0, deg: 1 };
const DEG_PER_S: Unit = Unit {
    k: 0,
    s: -1,
    deg: 1,
};
const SECOND: Unit = Unit { k: 0, s: 1, deg: 0 };

/// A slow family (filled at thermal steps / from readings).
// A row of FAMILIES: the arguments are its columns, in the order the table reads them.
#[allow(clippy::too_many_arguments)]
const fn slow(
    doc_name: &'static str,
    prefix: &'static str,
    arg: ArgKind,
    unit: Unit,
    description: &'static str,
    bound: f64,
    slot: usize,
    short: &'static str,
) -> Family {
    Family {
        doc_name,
        prefix,
        arg,
        unit,
        description,
        bound,
        slot,
        short,
        dwell_constant: false,
        needs_gimbal: false,
        reads_heading: false,
        reads_time: false,
        reads_motion: false,
        clock: false,
        library: Library::Products,
        fill: None,
    }
}

/// A fast family with its fill; the flags default to false and [`Library::Products`].
#[allow(clippy::too_many_arguments)]
const fn fast(
    doc_name: &'static str,
    prefix: &'static str,
    arg: ArgKind,
    unit: Unit,
    description: &'static str,
    bound: f64,
    slot: usize,
    short: &'static str,
    fill: fn(&FastInputs, &mut Frame),
) -> Family {
    Family {
        fill: Some(fill),
        ..slow(doc_name, prefix, arg, unit, description, bound, slot, short)
    }
}

/// Body rate component i, °/s: one expression for `w_*` and `abs_w_*` (same bits).
#[inline]
fn rate_dps(x: &FastInputs, i: usize) -> f64 {
    let to_dps = 180.0 / std::f64::consts::PI / x.h_s;
    x.dtheta_rad[i] * to_dps
}

/// The signals table: one row per family; a row's position + 1 is its FMU signal code, and
/// the discovery library takes its families in this order.
pub const FAMILIES: [Family; 13] = [
    slow(
        "temp:NODE",
        "temp:",
        ArgKind::Node,
        K,
        "temperature of NODE (board, gyro_x, gyro_y, gyro_z, accel, housing, or block = the acting axis's block)",
        130.0,
        TEMP,
        "t_",
    ),
    slow(
        "dtemp_dt:NODE",
        "dtemp_dt:",
        ArgKind::Node,
        K_PER_S,
        "time derivative of temp:NODE",
        10.0,
        DTEMP,
        "dtdt_",
    ),
    slow(
        "grad:A-B",
        "grad:",
        ArgKind::NodePair,
        K,
        "temp:A − temp:B",
        260.0,
        TEMP,
        "grad_bh",
    ),
    Family {
        dwell_constant: true,
        ..fast(
            "u_x, u_y, u_z",
            "u_",
            ArgKind::Axis,
            Unit::ONE,
            "body components of the up direction (specific force at rest / g)",
            1.0,
            UP,
            "u_",
            |x, f| f[UP..UP + 3].copy_from_slice(x.up_b.as_slice()),
        )
    },
    Family {
        dwell_constant: true,
        ..fast(
            "w_x, w_y, w_z",
            "w_",
            ArgKind::Axis,
            DEG_PER_S,
            "body rate",
            100.0,
            RATE,
            "w_",
            |x, f| {
                for i in 0..3 {
                    f[RATE + i] = rate_dps(x, i);
                }
            },
        )
    },
    Family {
        dwell_constant: true,
        ..fast(
            "abs_w_x, abs_w_y, abs_w_z",
            "abs_w_",
            ArgKind::Axis,
            DEG_PER_S,
            "absolute body rate",
            100.0,
            ABS_RATE,
            "aw_",
            |x, f| {
                for i in 0..3 {
                    f[ABS_RATE + i] = rate_dps(x, i).abs();
                }
            },
        )
    },
    Family {
        dwell_constant: true,
        needs_gimbal: true,
        library: Library::NotSearched,
        ..fast(
            "gimbal_outer",
            "gimbal_outer",
            ArgKind::None,
            DEG,
            "outer gimbal angle, wrapped to [-180, 180)",
            180.0,
            OUTER,
            "outer",
            |x, f| f[OUTER] = wrap_deg(x.gimbal_mid.outer_rad.to_degrees()),
        )
    },
    Family {
        dwell_constant: true,
        needs_gimbal: true,
        library: Library::NotSearched,
        ..fast(
            "gimbal_inner",
            "gimbal_inner",
            ArgKind::None,
            DEG,
            "inner gimbal angle, wrapped to [-180, 180)",
            180.0,
            INNER,
            "inner",
            |x, f| f[INNER] = wrap_deg(x.gimbal_mid.inner_rad.to_degrees()),
        )
    },
    Family {
        reads_time: true,
        clock: true,
        ..fast(
            "time",
            "time",
            ArgKind::None,
            SECOND,
            "time since the start of the run",
            1e7,
            TIME,
            "time",
            |x, f| f[TIME] = x.t_mid_s,
        )
    },
    Family {
        dwell_constant: true,
        reads_heading: true,
        library: Library::NotSearched,
        ..fast(
            "n_x, n_y, n_z",
            "n_",
            ArgKind::Axis,
            Unit::ONE,
            "body components of the local north direction (a field fixed in the navigation frame)",
            1.0,
            NORTH,
            "n_",
            |x, f| f[NORTH..NORTH + 3].copy_from_slice(x.north_east_b[0].as_slice()),
        )
    },
    Family {
        dwell_constant: true,
        reads_heading: true,
        library: Library::NotSearched,
        ..fast(
            "e_x, e_y, e_z",
            "e_",
            ArgKind::Axis,
            Unit::ONE,
            "body components of the local east direction",
            1.0,
            EAST,
            "e_",
            |x, f| f[EAST..EAST + 3].copy_from_slice(x.north_east_b[1].as_slice()),
        )
    },
    Family {
        reads_motion: true,
        clock: true,
        library: Library::Decay,
        ..fast(
            "since_move",
            "since_move",
            ArgKind::None,
            SECOND,
            "seconds since the table last stopped (0 while it moves; from the run's start before its first move)",
            1e7,
            SINCE_MOVE,
            "smove",
            |x, f| f[SINCE_MOVE] = x.since_s.move_s,
        )
    },
    Family {
        reads_motion: true,
        clock: true,
        library: Library::Decay,
        ..fast(
            "since_start",
            "since_start",
            ArgKind::None,
            SECOND,
            "seconds since the table last started to move (from the run's start before its first move)",
            1e7,
            SINCE_START,
            "sstart",
            |x, f| f[SINCE_START] = x.since_s.start_s,
        )
    },
];

const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

fn axis_of(c: &str) -> Option<usize> {
    AXIS_NAMES.iter().position(|a| *a == c)
}

fn node_name(n: NodeRef) -> &'static str {
    match n {
        NodeRef::Block => "block",
        NodeRef::Node(i) => node::NAMES[i],
    }
}

impl Signal {
    /// The signal's family (its row of [`FAMILIES`]) and argument: with
    /// [`Signal::from_parts`], the only places that name the variants.
    pub fn parts(self) -> (usize, Args) {
        match self {
            Signal::Temp(n) => (0, Args::Node(n)),
            Signal::TempRate(n) => (1, Args::Node(n)),
            Signal::Gradient(a, b) => (2, Args::NodePair(a, b)),
            Signal::Up(i) => (3, Args::Axis(i)),
            Signal::Rate(i) => (4, Args::Axis(i)),
            Signal::AbsRate(i) => (5, Args::Axis(i)),
            Signal::Outer => (6, Args::None),
            Signal::Inner => (7, Args::None),
            Signal::Time => (8, Args::None),
            Signal::North(i) => (9, Args::Axis(i)),
            Signal::East(i) => (10, Args::Axis(i)),
            Signal::SinceMove => (11, Args::None),
            Signal::SinceStart => (12, Args::None),
        }
    }

    /// The signal of row `family` of [`FAMILIES`] with argument `args`, if they fit.
    pub fn from_parts(family: usize, args: Args) -> Option<Signal> {
        Some(match (family, args) {
            (0, Args::Node(n)) => Signal::Temp(n),
            (1, Args::Node(n)) => Signal::TempRate(n),
            (2, Args::NodePair(a, b)) => Signal::Gradient(a, b),
            (3, Args::Axis(i)) if i < 3 => Signal::Up(i),
            (4, Args::Axis(i)) if i < 3 => Signal::Rate(i),
            (5, Args::Axis(i)) if i < 3 => Signal::AbsRate(i),
            (6, Args::None) => Signal::Outer,
            (7, Args::None) => Signal::Inner,
            (8, Args::None) => Signal::Time,
            (9, Args::Axis(i)) if i < 3 => Signal::North(i),
            (10, Args::Axis(i)) if i < 3 => Signal::East(i),
            (11, Args::None) => Signal::SinceMove,
            (12, Args::None) => Signal::SinceStart,
            _ => return None,
        })
    }

    /// The signal's row of [`FAMILIES`].
    pub fn family(self) -> &'static Family {
        &FAMILIES[self.parts().0]
    }

    /// Parses a signal name (`dtemp_dt:block`, `u_x`, `grad:gyro_z-housing`, …).
    pub fn parse(s: &str) -> Option<Signal> {
        FAMILIES.iter().enumerate().find_map(|(i, f)| {
            let args = match f.arg {
                ArgKind::None => (s == f.prefix).then_some(Args::None)?,
                ArgKind::Node => Args::Node(NodeRef::parse(s.strip_prefix(f.prefix)?)?),
                ArgKind::NodePair => {
                    let (a, b) = s.strip_prefix(f.prefix)?.split_once('-')?;
                    Args::NodePair(NodeRef::parse(a)?, NodeRef::parse(b)?)
                }
                ArgKind::Axis => Args::Axis(axis_of(s.strip_prefix(f.prefix)?)?),
            };
            Signal::from_parts(i, args)
        })
    }

    /// The name as a declared effect's regressor writes it (`u_x`, `grad:block-housing`).
    pub fn name(self) -> String {
        let (i, args) = self.parts();
        let p = FAMILIES[i].prefix;
        match args {
            Args::None => p.to_string(),
            Args::Node(n) => format!("{p}{}", node_name(n)),
            Args::NodePair(a, b) => format!("{p}{}-{}", node_name(a), node_name(b)),
            Args::Axis(a) => format!("{p}{}", AXIS_NAMES[a]),
        }
    }

    /// A short name part (discovery's proposal names): the family's short part and the
    /// node or axis (a node pair's short part stands alone).
    pub fn short(self) -> String {
        let (i, args) = self.parts();
        let p = FAMILIES[i].short;
        match args {
            Args::None | Args::NodePair(..) => p.to_string(),
            Args::Node(n) => format!("{p}{}", node_name(n)),
            Args::Axis(a) => format!("{p}{}", AXIS_NAMES[a]),
        }
    }

    /// The signal's unit.
    pub fn unit(self) -> Unit {
        self.family().unit
    }

    /// The largest magnitude the signal can take in a valid scenario: [`Family::bound`].
    pub fn bound(self) -> f64 {
        self.family().bound
    }

    /// The frame slot(s) of the signal on `axis` of the gyros (`accel = false`) or the
    /// accelerometers: `(a, Some(b))` for a difference a − b.
    pub fn slots(self, accel: bool, axis: usize) -> (usize, Option<usize>) {
        let (i, args) = self.parts();
        let base = FAMILIES[i].slot;
        match args {
            Args::None => (base, None),
            Args::Node(n) => (base + n.resolve(accel, axis), None),
            Args::NodePair(a, b) => (
                base + a.resolve(accel, axis),
                Some(base + b.resolve(accel, axis)),
            ),
            Args::Axis(a) => (base + a, None),
        }
    }

    /// The temperature nodes the signal reads on `axis` of the gyros (`accel = false`) or the
    /// accelerometers.
    pub fn nodes(self, accel: bool, axis: usize) -> Vec<usize> {
        match self.parts().1 {
            Args::Node(n) => vec![n.resolve(accel, axis)],
            Args::NodePair(a, b) => vec![a.resolve(accel, axis), b.resolve(accel, axis)],
            _ => Vec::new(),
        }
    }

    /// Every signal of row `family` of [`FAMILIES`] over the axes (for a node family, over the
    /// nodes and `block`).
    pub fn all_of(family: usize) -> Vec<Signal> {
        let nodes = || {
            (0..node::COUNT)
                .map(NodeRef::Node)
                .chain([NodeRef::Block])
                .collect::<Vec<_>>()
        };
        let args: Vec<Args> = match FAMILIES[family].arg {
            ArgKind::None => vec![Args::None],
            ArgKind::Axis => (0..3).map(Args::Axis).collect(),
            ArgKind::Node => nodes().into_iter().map(Args::Node).collect(),
            ArgKind::NodePair => nodes()
                .into_iter()
                .flat_map(|a| nodes().into_iter().map(move |b| Args::NodePair(a, b)))
                .collect(),
        };
        args.into_iter()
            .filter_map(|a| Signal::from_parts(family, a))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inputs() -> FastInputs {
        FastInputs {
            up_b: Vector3::new(0.1, -0.2, 0.97),
            north_east_b: [Vector3::new(0.3, 0.9, 0.1), Vector3::new(0.95, -0.3, 0.02)],
            dtheta_rad: Vector3::new(1e-6, -2e-4, 3e-4),
            dv_mps: Vector3::new(0.01, 0.02, 0.098),
            h_s: 0.01,
            gimbal_mid: GimbalAngles::new(3.5, -1.2),
            t_mid_s: 100.005,
            since_s: MotionClocks {
                move_s: 12.5,
                start_s: 20.125,
            },
        }
    }

    /// Every signal of every family: its name parses back to it, its slots lie in the frame,
    /// its unit is the family's.
    #[test]
    fn every_signal_parses_back_and_has_slots_in_the_frame() {
        let mut count = 0;
        for (i, family) in FAMILIES.iter().enumerate() {
            let all = Signal::all_of(i);
            assert!(!all.is_empty(), "{}", family.doc_name);
            for s in all {
                count += 1;
                assert_eq!(s.parts().0, i);
                assert_eq!(Signal::parse(&s.name()), Some(s), "{}", s.name());
                assert_eq!(s.unit(), family.unit);
                for axis in 0..3 {
                    let (a, b) = s.slots(true, axis);
                    assert!(a < SLOTS && b.is_none_or(|b| b < SLOTS), "{}", s.name());
                }
            }
        }
        // temp and dtemp_dt over 7 nodes (6 and block), grad over 49 pairs, u, w, abs_w, n, e
        // over 3 axes, and 5 single signals.
        assert_eq!(count, 7 + 7 + 49 + 5 * 3 + 5);
        assert_eq!(Signal::parse("u_w"), None);
        assert_eq!(Signal::parse("gimbal_outer_x"), None);
        assert_eq!(Signal::parse("grad:block"), None);
    }

    /// A fast family's fill writes exactly its own slots (three for an axis family, one
    /// otherwise), so the fast families never overwrite one another and none writes the slow
    /// slots the thermal steps set; no two families share a slot except the gradient, which
    /// reads the temperatures' slots.
    #[test]
    fn each_fill_writes_exactly_its_own_slots() {
        let mut owner = [None::<usize>; SLOTS];
        for (i, f) in FAMILIES.iter().enumerate() {
            let width = match f.arg {
                ArgKind::None => 1,
                ArgKind::Axis => 3,
                ArgKind::Node => node::COUNT,
                ArgKind::NodePair => continue,
            };
            for (s, o) in owner.iter_mut().enumerate().skip(f.slot).take(width) {
                assert_eq!(*o, None, "slot {s} of {} taken", f.doc_name);
                *o = Some(i);
            }
            let Some(fill) = f.fill else {
                assert_eq!(
                    f.arg,
                    ArgKind::Node,
                    "{}: only node families are slow",
                    f.doc_name
                );
                continue;
            };
            let mut frame = [f64::NAN; SLOTS];
            fill(&inputs(), &mut frame);
            let written: Vec<usize> = (0..SLOTS).filter(|s| !frame[*s].is_nan()).collect();
            assert_eq!(
                written,
                (f.slot..f.slot + width).collect::<Vec<_>>(),
                "{}",
                f.doc_name
            );
        }
        assert!(owner.iter().all(|o| o.is_some()), "every slot has a family");
    }

    /// The fills against the definitions written out here.
    #[test]
    fn fills_equal_their_definitions() {
        let x = inputs();
        let mut f = [0.0; SLOTS];
        for fam in &FAMILIES {
            if let Some(fill) = fam.fill {
                fill(&x, &mut f);
            }
        }
        let dps = |i: usize| x.dtheta_rad[i] * (180.0 / std::f64::consts::PI / x.h_s);
        for i in 0..3 {
            assert_eq!(f[UP + i], x.up_b[i]);
            assert_eq!(f[NORTH + i], x.north_east_b[0][i]);
            assert_eq!(f[EAST + i], x.north_east_b[1][i]);
            assert_eq!(f[RATE + i].to_bits(), dps(i).to_bits());
            assert_eq!(f[ABS_RATE + i].to_bits(), dps(i).abs().to_bits());
        }
        assert_eq!(f[RATE + 1], -2e-4 / 0.01 * 180.0 / std::f64::consts::PI);
        // 3.5 rad = 200.535…° wraps to −159.46…°.
        assert!((f[OUTER] - (3.5f64.to_degrees() - 360.0)).abs() < 1e-12);
        assert!((f[INNER] - (-1.2f64).to_degrees()).abs() < 1e-12);
        assert_eq!(f[TIME], 100.005);
        assert_eq!(f[SINCE_MOVE], 12.5);
        assert_eq!(f[SINCE_START], 20.125);
    }

    /// The properties the plant and discovery rely on: the heading and time families ask for
    /// their inputs, the gimbal families are marked as needing gimbal data, and a
    /// linear-only family needs none (discovery holds those on every history).
    #[test]
    fn table_flags_match_the_inputs_the_fills_read() {
        for f in &FAMILIES {
            assert_eq!(
                f.reads_heading,
                matches!(f.prefix, "n_" | "e_"),
                "{}",
                f.doc_name
            );
            assert_eq!(f.reads_time, f.prefix == "time", "{}", f.doc_name);
            assert_eq!(
                f.reads_motion,
                f.prefix.starts_with("since_"),
                "{}",
                f.doc_name
            );
            // Every clock is a second count; decays read only clocks.
            if f.clock {
                assert_eq!(f.unit, SECOND, "{}", f.doc_name);
            }
            if f.library == Library::Decay {
                assert!(f.clock, "{}", f.doc_name);
            }
            assert_eq!(
                f.needs_gimbal,
                f.prefix.starts_with("gimbal_"),
                "{}",
                f.doc_name
            );

            assert!(f.bound > 0.0 && !f.description.is_empty());
        }
    }
}
