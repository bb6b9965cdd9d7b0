//! Conditioning: the same realisation written with gimbal angles and with a quaternion attitude
//! must give the same diagnosis, and a coefficient the data cannot excite (the body x axis is
//! the inner gimbal axis and stays horizontal, so nothing depends on the specific force along
//! it) is reported as null, never gated and never written by `--apply`.

use crate::common::{Hidden, history, model, to_quaternion};
use rins_mvm::{Analysis, DiagnoseReport, Effect, History, Options, RankedEffect, analyse};
use rins_plant::effects::{AccelTerm, GyroTerm, MISALIGNMENT_PAIRS};

const G_SENS: [[f64; 3]; 3] = [[0.0, 0.02, 0.015], [0.0, 0.015, -0.01], [0.0, -0.01, 0.02]];

fn run(h: &History, noise: bool) -> Analysis {
    let opts = Options {
        diagnose: true,
        apply: vec![
            Effect::Gyro(GyroTerm::GSensitivity),
            Effect::Accel(AccelTerm::Misalignment),
        ],
        ..Options::default()
    };
    analyse(&model(noise), h, &opts)
}

/// Whether the scenario key names a coefficient this table cannot excite: a gyro's
/// g-sensitivity to the x specific force, an accelerometer's misalignment onto body x.
fn unexcitable(key: &str) -> bool {
    if key.starts_with("sensor.gyro.g_sensitivity.dph_per_g[") && key.ends_with("[0]") {
        return true;
    }
    if let Some(n) = key
        .strip_prefix("sensor.accel.misalignment.arcsec[")
        .and_then(|s| s.strip_suffix(']'))
    {
        let n: usize = n.parse().expect("index");
        return MISALIGNMENT_PAIRS[n].1 == 0;
    }
    false
}

/// No ranked or accepted coefficient the data cannot excite is non-null, and `--apply` writes
/// none of them.
fn check_unexcitable_null(an: &Analysis, what: &str) {
    let r = &an.diagnosis.as_ref().expect("asked for").report;
    let mut seen = 0;
    for (i, e) in r.ranking.iter().chain(&r.accepted).enumerate() {
        for (k, (c, ci)) in e.keys.iter().zip(e.coefficient.iter().zip(&e.ci95)) {
            if unexcitable(k) {
                seen += usize::from(i < r.ranking.len());
                assert!(
                    c.is_nan() && ci[0].is_nan() && ci[1].is_nan(),
                    "{what}: {k} = {c} [{}, {}] should be null (not identifiable)",
                    ci[0],
                    ci[1]
                );
            }
        }
    }
    // g-sensitivity to x on three gyros, misalignment onto x on accelerometers y and z.
    assert_eq!(seen, 5, "{what}: {seen} unexcitable coefficients ranked");
    let applied = an.applied.as_ref().expect("asked for").as_ref().unwrap();
    for (k, v) in &applied.set {
        assert!(!unexcitable(k), "{what}: --apply wrote {k} = {v}");
    }
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    a.is_nan() && b.is_nan() || (a - b).abs() <= 1e-6 * a.abs().max(b.abs()).max(scale)
}

fn same_ranking(g: &[RankedEffect], q: &[RankedEffect]) {
    assert_eq!(g.len(), q.len());
    // Matched by effect and channel: candidates the data make identical (a dither bias on an
    // axis that never tilts is its bias) tie in ΔBIC, and rounding orders a tie either way.
    let key = |e: &&RankedEffect| (e.channel.clone(), e.effect.clone());
    let (mut g, mut q): (Vec<&RankedEffect>, Vec<&RankedEffect>) =
        (g.iter().collect(), q.iter().collect());
    g.sort_by_key(key);
    q.sort_by_key(key);
    for (a, b) in g.into_iter().zip(q) {
        assert_eq!((&a.effect, &a.channel), (&b.effect, &b.channel));
        assert_eq!(a.passes_gate, b.passes_gate, "{a:#?} {b:#?}");
        assert!(close(a.delta_bic, b.delta_bic, 1.0), "{a:#?} {b:#?}");
        for k in 0..a.coefficient.len() {
            // Relative to the coefficient, or to its interval for one compatible with zero.
            let half = 0.5 * (a.ci95[k][1] - a.ci95[k][0]);
            assert!(
                close(a.coefficient[k], b.coefficient[k], half),
                "{} {}: {} vs {}",
                a.effect,
                a.keys[k],
                a.coefficient[k],
                b.coefficient[k]
            );
        }
    }
}

fn report(an: &Analysis) -> &DiagnoseReport {
    &an.diagnosis.as_ref().expect("asked for").report
}

#[test]
fn gimbal_and_quaternion_attitude_give_the_same_diagnosis() {
    let hidden = Hidden {
        g_sens_dph_per_g: G_SENS,
        ..Hidden::default()
    };
    let m = model(true);
    let hg = history(&m, &hidden, 11);
    let hq = to_quaternion(&m, &hg);
    let (g, q) = (run(&hg, true), run(&hq, true));
    let (rg, rq) = (report(&g), report(&q));
    same_ranking(&rg.ranking, &rq.ranking);
    same_ranking(&rg.accepted, &rq.accepted);
    // The hidden effect is found on every gyro, the same way.
    for ch in ["gyro_x", "gyro_y", "gyro_z"] {
        assert!(
            rg.accepted
                .iter()
                .any(|e| e.channel == ch && e.effect == "gyro.g_sensitivity"),
            "{ch}: {:#?}",
            rg.accepted
        );
    }
    check_unexcitable_null(&g, "gimbal");
    check_unexcitable_null(&q, "quaternion");
    // --apply writes the same coefficients.
    let (ag, aq) = (
        g.applied.as_ref().unwrap().as_ref().unwrap(),
        q.applied.as_ref().unwrap().as_ref().unwrap(),
    );
    assert_eq!(ag.set.len(), aq.set.len());
    for ((kg, vg), (kq, vq)) in ag.set.iter().zip(&aq.set) {
        assert_eq!(kg, kq);
        assert!(close(*vg, *vq, 1e-3), "{kg}: {vg} vs {vq}");
    }
}

#[test]
fn noise_free_data_gate_no_unexcitable_coefficient() {
    // Noise-free: the residual is the hidden effect plus rounding, so only a noise floor tied
    // to the numbers' resolution keeps rounding in an unexcited column from looking like
    // information.
    for (label, hidden) in [
        ("control", Hidden::default()),
        (
            "g-sensitivity",
            Hidden {
                g_sens_dph_per_g: G_SENS,
                ..Hidden::default()
            },
        ),
    ] {
        let hidden = Hidden {
            noise: false,
            ..hidden
        };
        let m = model(false);
        let hg = history(&m, &hidden, 5);
        let hq = to_quaternion(&m, &hg);
        for (att, h) in [("gimbal", &hg), ("quaternion", &hq)] {
            let an = run(h, false);
            check_unexcitable_null(&an, &format!("{label}, {att}, noise-free"));
            if label == "control" {
                let r = report(&an);
                assert!(
                    r.ranking.iter().all(|e| !e.passes_gate),
                    "{att}: {:#?}",
                    r.ranking
                        .iter()
                        .filter(|e| e.passes_gate)
                        .collect::<Vec<_>>()
                );
            }
        }
    }
}
