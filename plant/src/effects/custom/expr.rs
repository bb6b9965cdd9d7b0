//! The regressor notation: documented signals joined by `*`, each with an optional `^N`.

use super::signals::{FAMILIES, Signal, Unit};

/// Highest power a factor may carry.
pub const MAX_POWER: i32 = 8;

/// Shortest memory time constant a factor may declare, s.
pub const MIN_TAU_S: f64 = 1e-3;
/// Longest memory time constant a factor may declare, s (about three years).
pub const MAX_TAU_S: f64 = 1e8;

/// What a factor does to its signal before the power: nothing, or an operator with memory.
#[derive(Clone, Copy, Debug)]
pub enum Op {
    /// The signal itself.
    Plain,
    /// `lag(SIGNAL, TAU)`: the signal through a first-order lag of time constant `tau_s`
    /// (dy/dt = (x − y)/τ, y = x at the start of a run), discretised exactly for an input held
    /// over each interval; the factor's value over an interval is the lag's mean over it.
    Lag {
        /// Time constant, s.
        tau_s: f64,
    },
    /// `exp(-SIGNAL/TAU)`: a decay in a clock signal (`since_move`, `since_start`, `time`),
    /// e.g. a transient after each table move; its value over an interval is taken at the
    /// interval's middle (relative error below (h/τ)²/24 for an interval h).
    Decay {
        /// Time constant, s.
        tau_s: f64,
    },
}

impl Op {
    /// The time constant, if the operator has one.
    pub fn tau_s(self) -> Option<f64> {
        match self {
            Op::Plain => None,
            Op::Lag { tau_s } | Op::Decay { tau_s } => Some(tau_s),
        }
    }
}

// Time constants are validated finite and positive: comparing bits is equality.
impl PartialEq for Op {
    fn eq(&self, o: &Self) -> bool {
        match (self, o) {
            (Op::Plain, Op::Plain) => true,
            (Op::Lag { tau_s: a }, Op::Lag { tau_s: b })
            | (Op::Decay { tau_s: a }, Op::Decay { tau_s: b }) => a.to_bits() == b.to_bits(),
            _ => false,
        }
    }
}

impl Eq for Op {}

/// One factor of a regressor: `signal^power`, `lag(signal, τ)^power` or `exp(-signal/τ)^power`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Factor {
    /// The signal.
    pub signal: Signal,
    /// Its power, 1 ≤ power ≤ `MAX_POWER`.
    pub power: i32,
    /// What is done to the signal before the power.
    pub op: Op,
}

impl Factor {
    /// A plain factor `signal^power`.
    pub fn plain(signal: Signal, power: i32) -> Self {
        Factor {
            signal,
            power,
            op: Op::Plain,
        }
    }

    /// The factor as a regressor writes it (`temp:block`, `lag(temp:block,900)^2`,
    /// `exp(-since_move/120)`); time constants in Rust's shortest round-trip form, so the text
    /// parses back to the same bits.
    pub fn text(&self) -> String {
        let base = match self.op {
            Op::Plain => self.signal.name(),
            Op::Lag { tau_s } => format!("lag({},{})", self.signal.name(), tau_s),
            Op::Decay { tau_s } => format!("exp(-{}/{})", self.signal.name(), tau_s),
        };
        if self.power == 1 {
            base
        } else {
            format!("{base}^{}", self.power)
        }
    }

    /// The factor's unit: the signal's, dimensionless for a decay; to its power.
    pub fn unit(&self) -> Unit {
        match self.op {
            Op::Decay { .. } => Unit::ONE,
            _ => self.signal.unit().pow(self.power),
        }
    }
}

/// Whether `s` is a clock a decay may read (a time in seconds that never goes negative).
pub fn is_clock(s: Signal) -> bool {
    s.family().clock
}

fn parse_tau(text: &str, what: &str) -> Result<f64, String> {
    let tau: f64 = text.trim().parse().map_err(|_| {
        format!(
            "the time constant {:?} of {what} is not a number of seconds",
            text.trim()
        )
    })?;
    if !(MIN_TAU_S..=MAX_TAU_S).contains(&tau) {
        return Err(format!(
            "the time constant of {what} is {tau} s; it must lie in [{MIN_TAU_S:e}, {MAX_TAU_S:e}] s"
        ));
    }
    Ok(tau)
}

fn parse_signal(name: &str) -> Result<Signal, String> {
    Signal::parse(name).ok_or_else(|| {
        let known: Vec<&str> = FAMILIES.iter().map(|f| f.doc_name).collect();
        format!(
            "unknown signal {name:?}; the signals are {}, each alone, as lag(SIGNAL, TAU_S) or as exp(-CLOCK/TAU_S)",
            known.join(", ")
        )
    })
}

/// Parses one factor without its power: `signal`, `lag(signal, τ)` or `exp(-clock/τ)`.
fn parse_base(f: &str) -> Result<(Signal, Op), String> {
    if let Some(inner) = f.strip_prefix("lag(") {
        let inner = inner
            .strip_suffix(')')
            .ok_or_else(|| format!("{f:?}: write lag(SIGNAL, TAU_S)"))?;
        let (sig, tau) = inner
            .split_once(',')
            .ok_or_else(|| format!("{f:?}: write lag(SIGNAL, TAU_S)"))?;
        let signal = parse_signal(sig.trim())?;
        let tau_s = parse_tau(tau, f)?;
        return Ok((signal, Op::Lag { tau_s }));
    }
    if let Some(inner) = f.strip_prefix("exp(") {
        let bad = || {
            format!(
                "{f:?}: write exp(-CLOCK/TAU_S) with CLOCK one of since_move, since_start, time"
            )
        };
        let inner = inner.strip_suffix(')').ok_or_else(bad)?;
        let inner = inner.trim().strip_prefix('-').ok_or_else(bad)?;
        let (sig, tau) = inner.split_once('/').ok_or_else(bad)?;
        let signal = parse_signal(sig.trim())?;
        if !is_clock(signal) {
            return Err(format!(
                "{f:?}: exp(-X/TAU_S) reads a clock (since_move, since_start or time), not {}",
                signal.name()
            ));
        }
        let tau_s = parse_tau(tau, f)?;
        return Ok((signal, Op::Decay { tau_s }));
    }
    Ok((parse_signal(f)?, Op::Plain))
}

/// Parses a regressor (`"u_x*u_z"`, `"temp:block^2"`, `"lag(temp:block, 900)"`,
/// `"exp(-since_move/120)"`); the error says which factor is wrong and lists the signals.
pub fn parse_regressor(text: &str) -> Result<Vec<Factor>, String> {
    if text.trim().is_empty() {
        return Err("an empty regressor".into());
    }
    let mut out = Vec::new();
    for f in text.split('*') {
        let f = f.trim();
        // The power follows the closing parenthesis of an operator, or the signal.
        let (name, power) = match f.rsplit_once('^').filter(|(n, _)| !n.ends_with('(')) {
            Some((n, p)) => {
                let power = p
                    .trim()
                    .parse::<i32>()
                    .ok()
                    .filter(|p| (1..=MAX_POWER).contains(p));
                match power {
                    Some(p) => (n.trim(), p),
                    None => {
                        return Err(format!(
                            "power {:?} of {:?}: powers are whole numbers from 1 to {MAX_POWER} (a negative power would be infinite where the signal is 0)",
                            p.trim(),
                            n.trim()
                        ));
                    }
                }
            }
            None => (f, 1),
        };
        let (signal, op) = parse_base(name)?;
        out.push(Factor { signal, power, op });
    }
    Ok(out)
}

/// The regressor text of `factors` (each [`Factor::text`], joined by `*`).
pub fn regressor_text(factors: &[Factor]) -> String {
    factors
        .iter()
        .map(Factor::text)
        .collect::<Vec<_>>()
        .join("*")
}

/// The unit of a product of factors.
pub fn unit_of(factors: &[Factor]) -> Unit {
    factors.iter().fold(Unit::ONE, |u, f| u.times(f.unit()))
}

/// The largest magnitude of the product over the signals' ranges.
pub fn bound_of(factors: &[Factor]) -> f64 {
    factors
        .iter()
        .map(|f| match f.op {
            // exp(−x/τ) of a clock x ≥ 0 lies in (0, 1].
            Op::Decay { .. } => 1.0,
            // A first-order lag stays within the range of its input.
            _ => f.signal.bound().powi(f.power),
        })
        .product()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::custom::signals::NodeRef;

    #[test]
    fn parses_products_powers_and_units() {
        let f = parse_regressor(" u_x * u_z ").unwrap();
        assert_eq!(f.len(), 2);
        assert_eq!(f[0].signal, Signal::Up(0));
        assert_eq!(unit_of(&f), Unit::ONE);
        let f = parse_regressor("temp:block^2*w_z").unwrap();
        assert_eq!(f[0], Factor::plain(Signal::Temp(NodeRef::Block), 2));
        assert_eq!(unit_of(&f).to_string(), "K^2*deg/s");
        assert_eq!(Unit::parse("K^2*deg/s"), Some(unit_of(&f)));
        assert_eq!(Unit::parse("degC*degC*deg/s"), Some(unit_of(&f)));
        let f = parse_regressor("dtemp_dt:block").unwrap();
        assert_eq!(unit_of(&f).to_string(), "K/s");
        let f = parse_regressor("grad:gyro_z-housing*time").unwrap();
        assert_eq!(unit_of(&f).to_string(), "K*s");
        assert!(
            parse_regressor("dtemp:block")
                .unwrap_err()
                .contains("unknown signal")
        );
        assert!(parse_regressor("u_x^0").unwrap_err().contains("power"));
        assert!(parse_regressor("u_x^-1").unwrap_err().contains("power"));
        assert!(parse_regressor("temp:gyro_q").is_err());
        assert!(Unit::parse("K/m").is_none());
    }

    /// Operators with memory: their text round-trips, their units, and bad forms name the fault.
    #[test]
    fn parses_lags_and_decays() {
        let f = parse_regressor("lag(temp:block, 900)^2*exp(-since_move/120.5)").unwrap();
        assert_eq!(f[0].op, Op::Lag { tau_s: 900.0 });
        assert_eq!(f[0].power, 2);
        assert_eq!(f[1].op, Op::Decay { tau_s: 120.5 });
        assert_eq!(f[1].signal, Signal::SinceMove);
        assert_eq!(unit_of(&f).to_string(), "K^2");
        assert_eq!(
            regressor_text(&f),
            "lag(temp:block,900)^2*exp(-since_move/120.5)"
        );
        assert_eq!(parse_regressor(&regressor_text(&f)).unwrap(), f);
        // A time constant round-trips to its bits.
        let tau = 1234.567_891_234_5;
        let g = parse_regressor(&format!("lag(dtemp_dt:housing,{tau})")).unwrap();
        assert_eq!(
            parse_regressor(&regressor_text(&g)).unwrap()[0].op.tau_s(),
            Some(tau)
        );
        assert_eq!(
            unit_of(&parse_regressor("exp(-time/60)").unwrap()),
            Unit::ONE
        );
        for (bad, says) in [
            ("exp(-temp:block/60)", "clock"),
            ("exp(since_move/60)", "exp(-CLOCK/TAU_S)"),
            ("lag(temp:block)", "lag(SIGNAL, TAU_S)"),
            ("lag(temp:block,0)", "[1e-3, 1e8]"),
            ("lag(temp:block,inf)", "[1e-3, 1e8]"),
            ("lag(temp:block,NaN)", "[1e-3, 1e8]"),
            ("lag(temp:blok,60)", "unknown signal"),
            ("lag(temp:block,sixty)", "not a number"),
            ("lag(temp:block,60)^0", "power"),
        ] {
            let e = parse_regressor(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }
}
