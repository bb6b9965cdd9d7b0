//! What discovery reports about a kept term: the catalogue effects it is confusable with (and
//! the experiment that would separate them), and the proposal as a ready declared-effect block.

use rins_plant::effects::custom::CustomKind;

use super::library::Term;
use crate::fit::{ChannelData, collinearity, contribution, delta_bic_of, wls};
use crate::replay::{Effect, Group, Window};
use crate::report::Confusable;
use crate::selection::separating_experiment;

/// How to separate a discovered term (`regressor`, `kind`) from a catalogue effect `effect`.
pub fn separating(term: &Term, effect: &str) -> String {
    let r = term.regressor().unwrap_or_default();
    let sf = term.kind() == CustomKind::ScaleFactor;
    if r.contains("dtemp_dt") && effect.contains("temperature_gradient_bias") {
        "a slow chamber ramp at a constant rate and a steady hold at the ramp's end temperature: through the ramp dT/dt is constant while the block-to-housing gradient builds up and settles to its steady value, in the hold dT/dt is 0 while the gradient stays at that value: the rate term follows dT/dt, the gradient bias the gradient".into()
    } else if r.contains("dtemp_dt") && effect.contains("temperature") {
        "hold at two or more steady temperatures (dT/dt = 0 at each) and ramp between them in both directions: the rate term changes sign with the ramp, the temperature bias does not".into()
    } else if r.contains("u_")
        && (effect.contains("g_sensitivity")
            || effect.contains("position_bias")
            || effect.contains("dither"))
    {
        format!(
            "dwell at tilted positions where {r} differs from the single up components (e.g. both gimbals at ±45°): the catalogue effect is linear (g-sensitivity), quadratic in one component (dither) or switches with Z-up/Z-down (δβ)"
        )
    } else if sf && effect.contains("scale_factor") {
        "rotate at the same rate at two or more steady temperatures and in both directions: a constant scale factor (and its asymmetry) does not change with the temperature".into()
    } else if r.contains("time") {
        "repeat the run at a different time since start (or after a warm-up): a time term follows the clock, the catalogue effect its own input".into()
    } else {
        separating_experiment(&r, effect)
    }
}

/// The catalogue effects on the channel whose fitted contribution is collinear (|ρ| > 0.9)
/// with the term's (`col`, fitted alone), each with a bias correction as in the ranking.
pub fn confusable(
    windows: &[Window],
    d: &ChannelData,
    groups: &[Group],
    term: &Term,
    col: &[f64],
    unit: f64,
) -> Vec<Confusable> {
    let x = super::frols::append(
        &crate::fit::Design {
            x: nalgebra::DMatrix::zeros(col.len(), 0),
            unit: Vec::new(),
        },
        col,
        unit,
    );
    let Some(own_fit) = wls(&x, d, None) else {
        return Vec::new();
    };
    let own: Vec<f64> = (0..col.len())
        .map(|r| col[r] * own_fit.theta[0] / d.v[r].sqrt())
        .collect();
    let chi2_0 = wls(&x.select(&[]), d, None).map_or(0.0, |f| f.chi2);
    let own_dbic = -(chi2_0 - own_fit.chi2) / own_fit.chi2_red().max(1.0) + (d.y.len() as f64).ln();
    let bias = groups.iter().find(|g| {
        matches!(
            g.effect,
            Effect::Gyro(rins_plant::effects::GyroTerm::Bias)
                | Effect::Accel(rins_plant::effects::AccelTerm::Bias)
        )
    });
    groups
        .iter()
        .filter(|g| !matches!(g.effect, Effect::Custom(_)))
        .filter_map(|g| {
            let mut alt = vec![*g];
            if let Some(b) = bias.filter(|b| b.effect != g.effect) {
                alt.push(*b);
            }
            let (dbic, fit) = delta_bic_of(windows, d, &[], &alt)?;
            let theirs = contribution(windows, d, &alt, &fit.theta);
            let (rho, vif) = collinearity(&own, &theirs, windows, d, &alt);
            (rho.abs() > 0.9).then(|| Confusable {
                effect: if alt.len() > 1 {
                    format!("{} (with a bias correction)", g.effect.name())
                } else {
                    g.effect.name()
                },
                delta_bic_gap: dbic - own_dbic,
                correlation: rho,
                vif,
                separate_by: separating(term, &g.effect.name()),
            })
        })
        .collect()
}

/// A proposal as a `[[sensor.gyro.custom]]` / `[[sensor.accel.custom]]` block: the term on the
/// axes it was found on, with the fitted coefficients (file units) and their 95 % intervals
/// as a comment.
pub fn toml_block(
    name: &str,
    accel: bool,
    term: &Term,
    coef: [f64; 3],
    found: &[(usize, [f64; 2])],
) -> Option<String> {
    let regressor = term.regressor()?;
    let sensor = if accel { "accel" } else { "gyro" };
    let (kind, unit_name) = match (term.kind(), accel) {
        (CustomKind::Bias, false) => ("bias", "deg/h"),
        (CustomKind::Bias, true) => ("bias", "ug"),
        (CustomKind::ScaleFactor, _) => ("scale-factor", "ppm"),
    };
    let axes: Vec<String> = found
        .iter()
        .map(|(a, _)| format!("\"{}\"", ["x", "y", "z"][*a]))
        .collect();
    let ci: Vec<String> = found
        .iter()
        .map(|(a, ci)| format!("{}: [{:.6e}, {:.6e}]", ["x", "y", "z"][*a], ci[0], ci[1]))
        .collect();
    Some(format!(
        "# discovered: {} ({unit_name} per {}); 95 % intervals {}\n[[sensor.{sensor}.custom]]\nname = \"{name}\"\nkind = \"{kind}\"\nregressor = \"{regressor}\"\nunit = \"{}\"\naxes = [{}]\ncoef = [{:e}, {:e}, {:e}]\n",
        term.describe(),
        term.unit(),
        ci.join(", "),
        term.unit(),
        axes.join(", "),
        coef[0],
        coef[1],
        coef[2]
    ))
}
