//! The regressor notation: documented signals joined by `*`, each with an optional `^N`.

use super::signals::{FAMILIES, Signal, Unit};

/// Highest power a factor may carry.
pub const MAX_POWER: i32 = 8;

/// One factor of a regressor: `signal^power`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Factor {
    /// The signal.
    pub signal: Signal,
    /// Its power, 1 ≤ power ≤ `MAX_POWER`.
    pub power: i32,
}

/// Parses a regressor (`"u_x*u_z"`, `"temp:block^2"`); the error says which factor is wrong
/// and lists the signals.
pub fn parse_regressor(text: &str) -> Result<Vec<Factor>, String> {
    if text.trim().is_empty() {
        return Err("an empty regressor".into());
    }
    let mut out = Vec::new();
    for f in text.split('*') {
        let f = f.trim();
        let (name, power) = match f.split_once('^') {
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
        let Some(signal) = Signal::parse(name) else {
            let known: Vec<&str> = FAMILIES.iter().map(|f| f.doc_name).collect();
            return Err(format!(
                "unknown signal {name:?}; the signals are {}",
                known.join(", ")
            ));
        };
        out.push(Factor { signal, power });
    }
    Ok(out)
}

/// The unit of a product of factors.
pub fn unit_of(factors: &[Factor]) -> Unit {
    factors
        .iter()
        .fold(Unit::ONE, |u, f| u.times(f.signal.unit().pow(f.power)))
}

/// The largest magnitude of the product over the signals' ranges.
pub fn bound_of(factors: &[Factor]) -> f64 {
    factors
        .iter()
        .map(|f| f.signal.bound().powi(f.power))
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
        assert_eq!(
            f[0],
            Factor {
                signal: Signal::Temp(NodeRef::Block),
                power: 2
            }
        );
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
}
