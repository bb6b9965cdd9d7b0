//! Heredity: a term is fitted with its parents. A temperature-dependent bias or scale factor
//! comes with the constant of its channel and kind, a power with its lower powers, a product
//! with its factors' linear terms (strong heredity, Hamada & Wu). Without them the parents'
//! share moves into the child: a scale factor SF(T) = SF₀ + k·T fitted as k·T alone on
//! temperatures near 25 °C biases k by SF₀/T̄.

use rins_plant::PlantConfig;
use rins_plant::effects::custom::{Axis, CustomKind, Signal, Unit};
use rins_plant::effects::{AccelTerm, CustomSpec, GyroTerm};

use crate::replay::Effect;

/// A parent a term needs in its fit.
#[derive(Clone, Debug, PartialEq)]
pub enum Parent {
    /// An effect the model already has candidates for (catalogue or declared).
    Effect(Effect),
    /// A declared effect with this regressor, to be declared with a zero coefficient.
    Declare {
        /// Accelerometer effect (else gyro).
        accel: bool,
        /// Bias or scale factor.
        kind: CustomKind,
        /// Regressor text.
        regressor: String,
    },
}

/// The constant of a channel's bias or scale factor: the parent of every term of that kind.
fn constant(accel: bool, kind: CustomKind) -> Effect {
    match (accel, kind) {
        (false, CustomKind::Bias) => Effect::Gyro(GyroTerm::Bias),
        (false, CustomKind::ScaleFactor) => Effect::Gyro(GyroTerm::ScaleFactor),
        (true, CustomKind::Bias) => Effect::Accel(AccelTerm::Bias),
        (true, CustomKind::ScaleFactor) => Effect::Accel(AccelTerm::ScaleFactor),
    }
}

/// `name^power` factors of a regressor text (`temp:block^2*u_x` → [(temp:block, 2), (u_x, 1)]).
fn factors(regressor: &str) -> Vec<(String, i32)> {
    regressor
        .split('*')
        .map(|f| {
            let f = f.trim();
            match f.split_once('^') {
                Some((n, p)) => (n.trim().to_string(), p.trim().parse().unwrap_or(1)),
                None => (f.to_string(), 1),
            }
        })
        .collect()
}

/// The regressor text of `name^power` factors (zero powers left out), or `None` if empty.
fn text(fs: &[(String, i32)]) -> Option<String> {
    let parts: Vec<String> = fs
        .iter()
        .filter(|(_, p)| *p > 0)
        .map(|(n, p)| {
            if *p == 1 {
                n.clone()
            } else {
                format!("{n}^{p}")
            }
        })
        .collect();
    (!parts.is_empty()).then(|| parts.join("*"))
}

/// Every monomial that divides `regressor` properly, constant excluded (for `a^2*b`: `a*b`,
/// `a^2`, `a`, `b`).
fn lower_monomials(regressor: &str) -> Vec<String> {
    let fs = factors(regressor);
    let mut out: Vec<String> = Vec::new();
    let mut powers: Vec<i32> = vec![0; fs.len()];
    loop {
        // Odometer over 0..=power of each factor.
        let mut i = 0;
        while i < fs.len() {
            if powers[i] < fs[i].1 {
                powers[i] += 1;
                break;
            }
            powers[i] = 0;
            i += 1;
        }
        if i == fs.len() {
            break;
        }
        let mono: Vec<(String, i32)> = fs
            .iter()
            .zip(&powers)
            .map(|((n, _), p)| (n.clone(), *p))
            .collect();
        if powers.iter().zip(&fs).all(|(p, (_, q))| p == q) {
            continue;
        }
        if let Some(t) = text(&mono)
            && !out.contains(&t)
        {
            out.push(t);
        }
    }
    out
}

/// The parents of a declared effect of a sensor (`accel`), `kind` and `regressor`: the
/// constant of its kind and its lower monomials, except the single up components of a bias in
/// the up direction (`u_x*u_z`, `u_z^2`): those are the catalogue's g-sensitivity, three
/// coefficients for each one the term adds, and a second-order sensitivity to the gravity
/// direction (a dither spring's load, an anisoelastic term) has no first-order part by
/// necessity; the product is still fitted with its constant, and the g-sensitivity competes
/// with it as a candidate of its own.
pub fn parents_of_regressor(accel: bool, kind: CustomKind, regressor: &str) -> Vec<Parent> {
    let mut out = vec![Parent::Effect(constant(accel, kind))];
    for m in lower_monomials(&regressor.replace(' ', "")) {
        if kind == CustomKind::Bias && matches!(Signal::parse(&m), Some(Signal::Up(_))) {
            continue;
        }
        out.push(Parent::Declare {
            accel,
            kind,
            regressor: m,
        });
    }
    out
}

/// The parents of `effect` in `model`: the constant of its kind, and for a declared effect its
/// lower monomials ([`parents_of_regressor`]).
pub fn parents(model: &PlantConfig, effect: Effect) -> Vec<Parent> {
    match effect {
        Effect::Gyro(
            GyroTerm::TemperatureBias
            | GyroTerm::TemperatureGradientBias
            | GyroTerm::GSensitivity
            | GyroTerm::DitherBias
            | GyroTerm::NavFieldBias,
        ) => vec![Parent::Effect(Effect::Gyro(GyroTerm::Bias))],
        Effect::Gyro(GyroTerm::ScaleFactorAsymmetry) => {
            vec![Parent::Effect(Effect::Gyro(GyroTerm::ScaleFactor))]
        }
        Effect::Accel(AccelTerm::TemperatureBias) => {
            vec![Parent::Effect(Effect::Accel(AccelTerm::Bias))]
        }
        Effect::Custom(r) => {
            let list = if r.accel {
                &model.sensor.accel.custom
            } else {
                &model.sensor.gyro.custom
            };
            let Some(spec) = list.get(r.index as usize) else {
                return Vec::new();
            };
            parents_of_regressor(r.accel, spec.kind, &spec.regressor)
        }
        _ => Vec::new(),
    }
}

/// The unit text of a regressor (`temp:block^2` → `K^2`), as a declared effect's `unit`.
pub fn unit_text(regressor: &str) -> String {
    factors(regressor)
        .iter()
        .filter_map(|(n, p)| Signal::parse(n).map(|s| s.unit().pow(*p)))
        .fold(Unit::ONE, Unit::times)
        .to_string()
}

/// `model` with a declared effect of `kind` and `regressor` acting on `axis` (0–2): an existing
/// declaration of the same sensor, kind and regressor gains the axis (with a zero coefficient
/// if the axis is new), otherwise one is added, named after the regressor. Returns the new
/// model and the effect's `custom:NAME`.
pub fn declare(
    model: &PlantConfig,
    accel: bool,
    kind: CustomKind,
    regressor: &str,
    axis: usize,
) -> (PlantConfig, String) {
    let mut m = model.clone();
    let list = if accel {
        &mut m.sensor.accel.custom
    } else {
        &mut m.sensor.gyro.custom
    };
    let same = |s: &CustomSpec| s.kind == kind && s.regressor.replace(' ', "") == regressor;
    if let Some(s) = list.iter_mut().find(|s| same(s)) {
        if !s.enabled {
            s.enabled = true;
            s.coef = [0.0; 3];
        }
        if !s.axes.iter().any(|a| a.index() == axis) {
            s.axes.push(Axis::of(axis));
            s.coef[axis] = 0.0;
        }
        let name = format!("custom:{}", s.name);
        return (m, name);
    }
    let base = format!(
        "{}_{}",
        if kind == CustomKind::Bias { "b" } else { "sf" },
        regressor
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect::<String>()
    );
    let mut name = base.clone();
    let mut k = 2;
    while list.iter().any(|s| s.name == name) {
        name = format!("{base}_{k}");
        k += 1;
    }
    list.push(CustomSpec {
        name: name.clone(),
        enabled: true,
        kind,
        regressor: regressor.to_string(),
        unit: unit_text(regressor),
        axes: vec![Axis::of(axis)],
        coef: [0.0; 3],
    });
    (m, format!("custom:{name}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lower_monomials_of_products_and_powers() {
        assert_eq!(lower_monomials("u_x*u_z"), vec!["u_x", "u_z"]);
        assert_eq!(lower_monomials("temp:block^2"), vec!["temp:block"]);
        let mut m = lower_monomials("a^2*b");
        m.sort();
        assert_eq!(m, vec!["a", "a*b", "a^2", "b"]);
        assert!(lower_monomials("dtemp_dt:block").is_empty());
    }

    #[test]
    fn unit_of_a_power() {
        assert_eq!(unit_text("temp:block^2"), "K^2");
        assert_eq!(unit_text("u_x*u_z"), "1");
    }
}
