//! The unit of a declared effect's signal, regressor and coefficient: powers of kelvin, second
//! and degree of angle, with the notation scenario files and reports write.

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

#[cfg(test)]
mod tests {
    use super::*;

    /// Every unit with powers in [−3, 3] reads back from what it writes, and the notation is the
    /// documented one (numerator factors K, deg, s; a `/` before the negative powers).
    #[test]
    fn a_unit_reads_back_from_its_notation() {
        for k in -3..=3 {
            for s in -3..=3 {
                for deg in -3..=3 {
                    let u = Unit { k, s, deg };
                    let text = u.to_string();
                    assert_eq!(Unit::parse(&text), Some(u), "{text}");
                }
            }
        }
        assert_eq!(
            Unit {
                k: 2,
                s: -1,
                deg: 1
            }
            .to_string(),
            "K^2*deg/s"
        );
        assert_eq!(
            Unit {
                k: 0,
                s: -2,
                deg: 0
            }
            .to_string(),
            "1/s^2"
        );
        assert_eq!(Unit::ONE.to_string(), "1");
    }
}
