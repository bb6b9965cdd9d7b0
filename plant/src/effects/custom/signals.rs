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

use crate::thermal::node;

/// Number of values in a [`Frame`].
pub const SLOTS: usize = 30;
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

/// Values of every signal over one interval (slots above).
pub type Frame = [f64; SLOTS];

/// Wraps an angle in degrees to [−180, 180).
#[inline]
pub fn wrap_deg(a: f64) -> f64 {
    (a + 180.0).rem_euclid(360.0) - 180.0
}

/// A unit as powers of kelvin, second and degree of angle (°C counts as K: coefficients per
/// kelvin and per degree Celsius are the same size).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Unit {
    /// Power of K.
    pub k: i32,
    /// Power of s.
    pub s: i32,
    /// Power of ° (angle).
    pub deg: i32,
}

impl Unit {
    /// Dimensionless.
    pub const ONE: Unit = Unit { k: 0, s: 0, deg: 0 };

    /// `self^p`.
    pub fn pow(self, p: i32) -> Unit {
        Unit {
            k: self.k * p,
            s: self.s * p,
            deg: self.deg * p,
        }
    }

    /// `self·o`.
    pub fn times(self, o: Unit) -> Unit {
        Unit {
            k: self.k + o.k,
            s: self.s + o.s,
            deg: self.deg + o.deg,
        }
    }

    /// Parses the unit notation [`Unit`]'s `Display` writes: factors `K` (or `degC`), `s`,
    /// `deg`, each with an optional `^N`, joined by `*`, then optionally `/` and the
    /// denominator's factors joined by `*`; `1` is dimensionless.
    pub fn parse(text: &str) -> Option<Unit> {
        let (num, den) = match text.split_once('/') {
            Some((n, d)) => (n, Some(d)),
            None => (text, None),
        };
        let part = |t: &str| -> Option<Unit> {
            let mut u = Unit::ONE;
            for f in t.split('*') {
                let f = f.trim();
                let (sym, p) = match f.split_once('^') {
                    Some((s, p)) => (s.trim(), p.trim().parse::<i32>().ok()?),
                    None => (f, 1),
                };
                let base = match sym {
                    "K" | "degC" => Unit { k: 1, ..Unit::ONE },
                    "s" => Unit { s: 1, ..Unit::ONE },
                    "deg" => Unit {
                        deg: 1,
                        ..Unit::ONE
                    },
                    "1" => Unit::ONE,
                    _ => return None,
                };
                u = u.times(base.pow(p));
            }
            Some(u)
        };
        let n = part(num)?;
        match den {
            Some(d) => Some(n.times(part(d)?.pow(-1))),
            None => Some(n),
        }
    }
}

impl std::fmt::Display for Unit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (mut num, mut den) = (Vec::new(), Vec::new());
        for (sym, p) in [("K", self.k), ("deg", self.deg), ("s", self.s)] {
            let side = if p > 0 { &mut num } else { &mut den };
            match p.abs() {
                0 => {}
                1 => side.push(sym.to_string()),
                q => side.push(format!("{sym}^{q}")),
            }
        }
        let n = if num.is_empty() {
            "1".to_string()
        } else {
            num.join("*")
        };
        if den.is_empty() {
            write!(f, "{n}")
        } else {
            write!(f, "{n}/{}", den.join("*"))
        }
    }
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
}

/// Every signal name with its unit and description, for messages and docs/effects.md.
pub const SIGNAL_DOCS: [(&str, &str, &str); 11] = [
    (
        "temp:NODE",
        "degC",
        "temperature of NODE (board, gyro_x, gyro_y, gyro_z, accel, housing, or block = the acting axis's block)",
    ),
    ("dtemp_dt:NODE", "K/s", "time derivative of temp:NODE"),
    ("grad:A-B", "K", "temp:A − temp:B"),
    (
        "u_x, u_y, u_z",
        "1",
        "body components of the up direction (specific force at rest / g)",
    ),
    ("w_x, w_y, w_z", "deg/s", "body rate"),
    ("abs_w_x, abs_w_y, abs_w_z", "deg/s", "absolute body rate"),
    (
        "gimbal_outer",
        "deg",
        "outer gimbal angle, wrapped to [-180, 180)",
    ),
    (
        "gimbal_inner",
        "deg",
        "inner gimbal angle, wrapped to [-180, 180)",
    ),
    ("time", "s", "time since the start of the run"),
    (
        "n_x, n_y, n_z",
        "1",
        "body components of the local north direction (a field fixed in the navigation frame)",
    ),
    (
        "e_x, e_y, e_z",
        "1",
        "body components of the local east direction",
    ),
];

fn axis_of(c: &str) -> Option<usize> {
    match c {
        "x" => Some(0),
        "y" => Some(1),
        "z" => Some(2),
        _ => None,
    }
}

impl Signal {
    /// Parses a signal name (`dtemp_dt:block`, `u_x`, `grad:gyro_z-housing`, …).
    pub fn parse(s: &str) -> Option<Signal> {
        if let Some(n) = s.strip_prefix("temp:") {
            return NodeRef::parse(n).map(Signal::Temp);
        }
        if let Some(n) = s.strip_prefix("dtemp_dt:") {
            return NodeRef::parse(n).map(Signal::TempRate);
        }
        if let Some(n) = s.strip_prefix("grad:") {
            let (a, b) = n.split_once('-')?;
            let (a, b) = (NodeRef::parse(a)?, NodeRef::parse(b)?);
            return Some(Signal::Gradient(a, b));
        }
        if let Some(a) = s.strip_prefix("abs_w_") {
            return axis_of(a).map(Signal::AbsRate);
        }
        if let Some(a) = s.strip_prefix("w_") {
            return axis_of(a).map(Signal::Rate);
        }
        if let Some(a) = s.strip_prefix("u_") {
            return axis_of(a).map(Signal::Up);
        }
        if let Some(a) = s.strip_prefix("n_") {
            return axis_of(a).map(Signal::North);
        }
        if let Some(a) = s.strip_prefix("e_") {
            return axis_of(a).map(Signal::East);
        }
        match s {
            "gimbal_outer" => Some(Signal::Outer),
            "gimbal_inner" => Some(Signal::Inner),
            "time" => Some(Signal::Time),
            _ => None,
        }
    }

    /// The signal's unit.
    pub fn unit(self) -> Unit {
        let k = Unit { k: 1, ..Unit::ONE };
        let dps = Unit {
            deg: 1,
            s: -1,
            k: 0,
        };
        match self {
            Signal::Temp(_) | Signal::Gradient(..) => k,
            Signal::TempRate(_) => Unit {
                k: 1,
                s: -1,
                deg: 0,
            },
            Signal::Up(_) | Signal::North(_) | Signal::East(_) => Unit::ONE,
            Signal::Rate(_) | Signal::AbsRate(_) => dps,
            Signal::Outer | Signal::Inner => Unit {
                deg: 1,
                ..Unit::ONE
            },
            Signal::Time => Unit { s: 1, ..Unit::ONE },
        }
    }

    /// The largest magnitude the signal can take in a valid scenario (temperatures within the
    /// thermal model's range, table rates within `scheme.rate_dps`, runs within
    /// `scenario.duration_s`): the bound of the non-finite check.
    pub fn bound(self) -> f64 {
        match self {
            Signal::Temp(_) => 130.0,
            Signal::Gradient(..) => 260.0,
            Signal::TempRate(_) => 10.0,
            Signal::Up(_) | Signal::North(_) | Signal::East(_) => 1.0,
            Signal::Rate(_) | Signal::AbsRate(_) => 100.0,
            Signal::Outer | Signal::Inner => 180.0,
            Signal::Time => 1e7,
        }
    }

    /// The temperature nodes the signal reads on `axis` of the gyros (`accel = false`) or the
    /// accelerometers.
    pub fn nodes(self, accel: bool, axis: usize) -> Vec<usize> {
        match self {
            Signal::Temp(n) | Signal::TempRate(n) => vec![n.resolve(accel, axis)],
            Signal::Gradient(a, b) => vec![a.resolve(accel, axis), b.resolve(accel, axis)],
            _ => Vec::new(),
        }
    }
}
