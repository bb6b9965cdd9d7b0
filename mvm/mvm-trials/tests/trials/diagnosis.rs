//! `rins diagnose --iterate` on logs this crate writes from closed-form physics: the cases
//! issue 42 names (a temperature-linear scale factor on two designs that rank its square and its
//! linear term first, a transient after each move, a lagged temperature bias) and a 20-trial
//! subset of the randomised benchmark.

use rins_mvm::{IterateOptions, Iteration, Options, analyse, iterate};
use rins_mvm_trials::bench::{plan, run};
use rins_mvm_trials::classes::Class;
use rins_mvm_trials::expect::kept_terms;
use rins_mvm_trials::{ChamberLeg, Design, Gimbal, HiddenEffect, RunDesign, TableLeg, generate};
use rins_plant::PlantConfig;
use rins_plant::effects::CustomSpec;
use rins_plant::effects::custom::{Axis, CustomKind};

/// The benchmark's base model with the constant scale factor on z, 3 ppm.
fn base_model() -> PlantConfig {
    let mut m = crate::base_model();
    m.sensor.gyro.scale_factor.ppm[2] = 3.0;
    m
}

fn diagnose(model: &PlantConfig, design: &Design, hidden: &[HiddenEffect], seed: u64) -> Iteration {
    let h = generate(model, design, hidden, seed);
    iterate(model, &h, &Options::default(), &IterateOptions::default()).unwrap()
}

fn print(it: &Iteration) {
    for s in &it.report.steps {
        let lv: Vec<String> = s
            .levels
            .iter()
            .map(|l| format!("{} {:.2}", l.channel, l.ratio))
            .collect();
        eprintln!("step {}: {}", s.step, lv.join(", "));
        for a in &s.accepted {
            eprintln!(
                "  {} {} kept {} tau {:?}",
                a.channel, a.effect, a.kept, a.tau
            );
        }
        for c in &s.coefficients {
            eprintln!("    {} = {:?} {:?}", c.key, c.fitted, c.ci95);
        }
    }
    eprintln!("stop: {}", it.report.stop);
}

/// The last interval the iteration wrote for a key matching `pred`.
fn written(it: &Iteration, pred: impl Fn(&str) -> bool) -> Option<(f64, [f64; 2])> {
    it.report
        .steps
        .iter()
        .flat_map(|s| &s.coefficients)
        .filter(|c| pred(&c.key))
        .filter_map(|c| Some((c.fitted?, c.ci95?)))
        .next_back()
}

fn every_gyro_at_its_floor(it: &Iteration) {
    let last = it.report.steps.last().unwrap();
    for l in last.levels.iter().filter(|l| l.channel.starts_with("gyro")) {
        assert!(
            l.ratio <= 1.10,
            "{} at {:.3}× its floor",
            l.channel,
            l.ratio
        );
    }
}

/// A design like the issue's, cooler and turning more: chamber steps 10 → 30, 30 → 15 and
/// 12 → 28 °C and a steady 20 °C; the four azimuths Z-up, a tilted dwell and the four Z-down
/// with 100 s dwells and moves at 10 °/s, over and over.
fn other_steps() -> Design {
    let mut d = Design::chamber_steps_four_azimuths();
    let mv = |gimbal, delta_deg| TableLeg::Move {
        gimbal,
        delta_deg,
        rate_dps: 10.0,
    };
    let dwell = TableLeg::Dwell { dur_s: 100.0 };
    let mut cycle = vec![dwell];
    for _ in 0..3 {
        cycle.extend([mv(Gimbal::Outer, 90.0), dwell]);
    }
    cycle.extend([
        mv(Gimbal::Inner, 90.0),
        TableLeg::Dwell { dur_s: 60.0 },
        mv(Gimbal::Inner, 90.0),
        dwell,
    ]);
    for _ in 0..3 {
        cycle.extend([mv(Gimbal::Outer, -90.0), dwell]);
    }
    cycle.push(mv(Gimbal::Inner, -180.0));
    let table: Vec<TableLeg> = (0..5).flat_map(|_| cycle.clone()).collect();
    let hold = |temp_c, dur_s| ChamberLeg::Hold { temp_c, dur_s };
    let step = |to_c| ChamberLeg::Ramp {
        to_c,
        rate_k_per_min: 10.0,
    };
    let chambers = [
        vec![hold(10.0, 1200.0), step(30.0)],
        vec![hold(30.0, 1200.0), step(15.0)],
        vec![hold(12.0, 1200.0), step(28.0)],
        vec![hold(20.0, 1e5)],
    ];
    let duration_s = rins_mvm_trials::design::table_length_s(&table);
    d.runs = chambers
        .into_iter()
        .map(|chamber| RunDesign {
            chamber,
            table: table.clone(),
            duration_s,
        })
        .collect();
    d.name = "chamber steps 10→30, 30→15, 12→28 °C and 20 °C; 100 s dwells, 10 °/s moves".into();
    d
}

/// Which of `sf ∝ T` and `sf ∝ T²` explains gyro z's residual better, each alone on the model
/// as given (the single-term ranking the search once followed): both declared with zero
/// coefficients in a probe model, ranked by the catalogue step.
fn square_ranks_first(model: &PlantConfig, design: &Design, hidden: &[HiddenEffect]) -> bool {
    let h = generate(model, design, hidden, 3);
    let mut probe = model.clone();
    for (name, regressor, unit) in [("lin", "temp:block", "K"), ("sq", "temp:block^2", "K^2")] {
        probe.sensor.gyro.custom.push(CustomSpec {
            name: name.into(),
            enabled: true,
            kind: CustomKind::ScaleFactor,
            regressor: regressor.into(),
            unit: unit.into(),
            axes: vec![Axis::Z],
            coef: [0.0; 3],
        });
    }
    let an = analyse(
        &probe,
        &h,
        &Options {
            diagnose: true,
            ..Options::default()
        },
    );
    let r = &an.diagnosis.unwrap().report.ranking;
    let dbic = |e: &str| {
        r.iter()
            .find(|x| x.channel == "gyro_z" && x.effect == e)
            .map(|x| x.delta_bic)
            .unwrap()
    };
    let (lin, sq) = (dbic("custom:lin"), dbic("custom:sq"));
    eprintln!(
        "{}: ΔBIC alone on the model as given: T {lin:.1}, T² {sq:.1}",
        design.name
    );
    sq < lin
}

/// Issue 42: a scale factor 0.8 ppm/K·(T − 25 °C) on gyro z over the model's constant 3 ppm.
/// On the design (10–50 °C) the square alone ranks first on the model as given, on the
/// cooler one (10–30 °C) the linear term does; either way `--iterate` keeps the linear term
/// with its constant, the true slope inside its interval, every gyro at its floor.
#[test]
fn temperature_linear_scale_factor_whatever_ranks_first() {
    let hidden = [HiddenEffect::ScaleFactorTempLinear {
        ppm_per_k: [0.0, 0.0, 0.8],
        ppm: [0.0; 3],
    }];
    let designs = [Design::chamber_steps_four_azimuths(), other_steps()];
    let firsts: Vec<bool> = designs
        .iter()
        .map(|d| square_ranks_first(&d.model_for(&base_model()), d, &hidden))
        .collect();
    assert_eq!(
        firsts,
        [true, false],
        "the two designs rank the square and the linear term first"
    );
    for d in &designs {
        let model = d.model_for(&base_model());
        let it = diagnose(&model, d, &hidden, 3);
        print(&it);
        let kept = kept_terms(&it);
        let regs: Vec<(usize, Option<&str>, &str)> = kept
            .iter()
            .map(|k| (k.channel, k.regressor.as_deref(), k.effect.as_str()))
            .collect();
        assert!(
            kept.iter().all(|k| k.channel == 2
                && (k.regressor.as_deref() == Some("temp:block")
                    || k.effect == "gyro.scale_factor")),
            "{}: kept {regs:?}",
            d.name
        );
        assert!(
            kept.iter()
                .any(|k| k.regressor.as_deref() == Some("temp:block")),
            "{regs:?}"
        );
        let (slope, ci) = written(&it, |k| {
            k.starts_with("sensor.gyro.custom[") && k.ends_with("coef[2]")
        })
        .unwrap();
        eprintln!("slope {slope:.4} [{:.4}, {:.4}] ppm/K", ci[0], ci[1]);
        assert!(ci[0] <= 0.8 && 0.8 <= ci[1], "slope {slope} {ci:?}");
        // The constant with it, on absolute temperature: 3 − 25·0.8 = −17 ppm.
        let (c0, ci0) = written(&it, |k| k == "sensor.gyro.scale_factor.ppm[2]").unwrap();
        eprintln!("constant {c0:.2} [{:.2}, {:.2}] ppm", ci0[0], ci0[1]);
        assert!(ci0[0] <= -17.0 && -17.0 <= ci0[1], "constant {c0} {ci0:?}");
        every_gyro_at_its_floor(&it);
        assert!(it.report.reached_floor, "{}", it.report.stop);
    }
}

/// Issue 42: a bias transient after each table move (0.03 °/h on x, τ = 120 s) and a bias that
/// follows the block temperature through a 25-minute lag (0.002 °/h/K on y): both discovered,
/// each time constant's 95 % interval containing the truth, every gyro at its floor after
/// `--iterate`.
#[test]
fn a_transient_and_a_lagged_temperature_bias_are_discovered_with_their_time_constants() {
    let d = Design::chamber_steps_four_azimuths();
    let model = d.model_for(&base_model());
    let hidden = [
        HiddenEffect::PostMoveTransient {
            dph: [0.03, 0.0, 0.0],
            tau_s: 120.0,
        },
        HiddenEffect::LaggedTempBias {
            dph_per_k: [0.0, 0.002, 0.0],
            tau_s: 1500.0,
        },
    ];
    let it = diagnose(&model, &d, &hidden, 5);
    print(&it);
    let kept = kept_terms(&it);
    let on = |c: usize, prefix: &str| {
        kept.iter()
            .find(|k| {
                k.channel == c
                    && k.regressor
                        .as_deref()
                        .is_some_and(|r| r.starts_with(prefix))
            })
            .unwrap_or_else(|| panic!("{prefix} not kept on channel {c}: {kept:#?}"))
    };
    for (k, truth) in [
        (on(0, "exp(-since_move/"), 120.0),
        (on(1, "lag(temp:block,"), 1500.0),
    ] {
        let tau = k.tau.expect("a time constant");
        eprintln!(
            "{:?}: tau {} {:?} (true {truth})",
            k.regressor, tau.tau_s, tau.ci95_s
        );
        assert!(tau.ci95_s[0] <= truth && truth <= tau.ci95_s[1], "{tau:?}");
    }
    // Nothing else but the constants that came with them.
    for k in &kept {
        assert!(
            k.regressor.is_some() || k.effect == "gyro.bias",
            "{} kept on {}",
            k.effect,
            k.channel
        );
    }
    every_gyro_at_its_floor(&it);
}

/// A 20-trial subset of the randomised benchmark (`rins bench-diagnosis`): 16 single-effect
/// classes, two and three at once, and two controls, each trial drawn from its own seed. What
/// the full benchmark reports per class (docs/model-vs-measurements.md) must hold here in sum:
/// at most 3 trials wrong, no claim on a control, no trial that claims the floor while a
/// channel stays above it, and the 95 % intervals covering the truth in 85 % or more.
#[test]
fn a_benchmark_subset_is_right_and_claims_nothing_on_controls() {
    let classes = [
        Class::GyroAsymmetry,
        Class::GyroMisalignment,
        Class::GyroTemperature,
        Class::GyroGradient,
        Class::GyroGSensitivity,
        Class::GyroPosition,
        Class::GyroDither,
        Class::AccelScaleFactor,
        Class::AccelTemperature,
        Class::SfTempLinear,
        Class::SfTempQuadratic,
        Class::TempRate,
        Class::UpProduct,
        Class::NavField,
        Class::Transient,
        Class::LaggedTemp,
        Class::Two,
        Class::Three,
        Class::Control,
        Class::Control,
    ];
    let specs = plan(20, 42, &classes);
    let report = run(&specs, 42, &|o| {
        eprintln!(
            "{} {}: correct {} missing {:?} extra {:?} ({})",
            o.spec.index,
            o.spec.class.name(),
            o.score.correct,
            o.score.missing,
            o.score.extra,
            o.stop
        )
    });
    eprintln!("{}", rins_mvm_trials::bench::markdown(&report));
    let wrong = report.outcomes.iter().filter(|o| !o.score.correct).count();
    assert!(wrong <= 3, "{wrong} of 20 wrong");
    assert!(
        report
            .outcomes
            .iter()
            .filter(|o| o.spec.class == Class::Control)
            .all(|o| o.score.correct),
        "a control kept something"
    );
    assert!(
        report.outcomes.iter().all(|o| !o.false_floor),
        "a false floor"
    );
    let cov: Vec<bool> = report
        .outcomes
        .iter()
        .flat_map(|o| o.score.coverage.iter().map(|c| c.covers))
        .collect();
    let share = cov.iter().filter(|c| **c).count() as f64 / cov.len() as f64;
    assert!(
        share >= 0.85,
        "coverage {share:.2} over {} coefficients",
        cov.len()
    );
    // The same trial again gives the same outcome (each is drawn from its own seed).
    let again = rins_mvm_trials::bench::run_trial(specs[5]);
    assert_eq!(again.score.correct, report.outcomes[5].score.correct);
    assert_eq!(again.hidden, report.outcomes[5].hidden);
}

/// A paired control is its trial drawn as it is with nothing hidden: the same design, model
/// and noise seed, so the false-claim rate is measured on the effect trials' own designs.
#[test]
fn a_paired_control_is_its_trial_with_nothing_hidden() {
    let specs = rins_mvm_trials::bench::with_paired_controls(plan(
        4,
        7,
        &[Class::GyroBias, Class::Control],
    ));
    // Two effect trials (0, 2) and two drawn controls (1, 3): two paired controls, 4 and 5.
    assert_eq!(specs.len(), 6);
    for (control, of) in [(4, 0), (5, 2)] {
        let (c, t) = (specs[control], specs[of]);
        assert!(c.paired_control && c.is_control() && !t.is_control());
        assert_eq!((c.index, c.seed, c.class), (control, t.seed, t.class));
        let (dc, dt) = (
            rins_mvm_trials::bench::draw_trial(c),
            rins_mvm_trials::bench::draw_trial(t),
        );
        assert!(dc.hidden.is_empty() && !dt.hidden.is_empty());
        assert_eq!(dc.design.name, dt.design.name);
        assert_eq!(dc.noise_seed, dt.noise_seed);
        assert_eq!(format!("{:?}", dc.model), format!("{:?}", dt.model));
    }
}

/// The benchmark's misses at oracle z ≥ 8 of seed 1 (docs/model-vs-measurements.md), replayed:
/// trial 5 keeps the housing temperature's rate for a gradient bias, which the gradient's own
/// ranking row names confusable with it (mutual, so the kept term names the gradient); trial
/// 31's dither bias ∝ u_z² is judged by no fold (its held-out runs are Z-up and Z-down only,
/// where it is the bias) and is kept on ΔBIC, F and resampling; trial 37's quadratic scale
/// factor is z 11 in all but under 6 beyond its linear twin, so it is not a strong trial.
#[test]
fn the_benchmark_misses_at_strong_z_of_seed_1_are_answered() {
    use rins_mvm_trials::bench::{STRONG_Z, run_trial};
    let specs = plan(200, 1, &Class::all());
    for i in [5, 31] {
        let o = run_trial(specs[i]);
        assert!(
            o.score.correct,
            "trial {i}: missing {:?}, extra {:?}; {}",
            o.score.missing, o.score.extra, o.stop
        );
    }
    let o = run_trial(specs[37]);
    assert!(o.z[0] >= STRONG_Z, "drawn z {}", o.z[0]);
    assert!(
        o.z_demanded[0] < 6.0,
        "z beyond the twin {}",
        o.z_demanded[0]
    );
}
