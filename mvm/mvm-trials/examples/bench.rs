//! Runs the randomised benchmark of the diagnosis: `cargo run --release -p rins-mvm-trials
//! --example bench -- TRIALS [SEED] [CLASS,CLASS…] [--json FILE]` (the `rins bench-diagnosis`
//! command is the same with a progress bar and a report).

use rins_mvm_trials::bench::{markdown, plan, run};
use rins_mvm_trials::classes::Class;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(23);
    let seed: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let classes: Vec<Class> = match args.get(3) {
        Some(list) if !list.starts_with("--") => list
            .split(',')
            .map(|c| Class::parse(c).expect("class"))
            .collect(),
        _ => Class::all(),
    };
    let mut specs = plan(n, seed, &classes);
    // `--only I,J`: just those trials of the plan.
    if let Some(i) = args.iter().position(|a| a == "--only") {
        let keep: Vec<usize> = args[i + 1].split(',').map(|x| x.parse().unwrap()).collect();
        specs.retain(|s| keep.contains(&s.index));
        if args.iter().any(|a| a == "--verbose") {
            for s in &specs {
                let t = rins_mvm_trials::bench::draw_trial(*s);
                eprintln!(
                    "trial {}: {}\n  hidden {:?}\n  z {:?}",
                    s.index, t.design.name, t.hidden, t.z_channels
                );
                let h = rins_mvm_trials::generate(&t.model, &t.design, &t.hidden, t.noise_seed);
                let an = rins_mvm::analyse(
                    &t.model,
                    &h,
                    &rins_mvm::Options {
                        diagnose: true,
                        discover: true,
                        ..Default::default()
                    },
                );
                let d = an.diagnosis.as_ref().unwrap();
                for r in &d.report.accepted {
                    eprintln!(
                        "    step0 accepted {} {} dBIC {:.1} p {:.1e} cv {:.2} parents {:?}",
                        r.channel, r.effect, r.delta_bic, r.p_value, r.cv_rmse_gain_pct, r.parents
                    );
                }
                for r in d.report.ranking.iter().take(6) {
                    eprintln!(
                        "    step0 rank {} {} dBIC {:.1} p {:.1e} cv {:.2} gate {}",
                        r.channel,
                        r.effect,
                        r.delta_bic,
                        r.p_value,
                        r.cv_rmse_gain_pct,
                        r.passes_gate
                    );
                }
                let it = rins_mvm::iterate(
                    &t.model,
                    &h,
                    &rins_mvm::Options::default(),
                    &rins_mvm::IterateOptions::default(),
                )
                .unwrap();
                for st in &it.report.steps {
                    let lv: Vec<String> = st
                        .levels
                        .iter()
                        .map(|l| format!("{} {:.2}", l.channel, l.ratio))
                        .collect();
                    eprintln!("  step {}: {}", st.step, lv.join(", "));
                    for a in &st.accepted {
                        eprintln!(
                            "    {} {} ({}) dBIC {:.1} joint {:.1} stab {:.2} kept {} parents {:?}",
                            a.channel,
                            a.effect,
                            a.found_by,
                            a.delta_bic,
                            a.joint_delta_bic,
                            a.stability,
                            a.kept,
                            a.parents
                        );
                    }
                }
                if let Some(d) = it.last.diagnosis.as_ref() {
                    for r in d.report.ranking.iter().take(12) {
                        eprintln!(
                            "    rank {} {} dBIC {:.1} p {:.1e} cv {:.2} gate {}",
                            r.channel,
                            r.effect,
                            r.delta_bic,
                            r.p_value,
                            r.cv_rmse_gain_pct,
                            r.passes_gate
                        );
                    }
                    if let Some(disc) = &d.report.discovery {
                        for r in &disc.refused {
                            eprintln!(
                                "    refused {} {} dBIC {:.1} p {:.1e}",
                                r.channel, r.term, r.delta_bic, r.p_value
                            );
                        }
                    }
                }
            }
        }
    }
    let report = run(&specs, seed, &|o| {
        eprintln!(
            "{:3} {:20} z {:?} correct {} floor {} {:.1} s | missing {:?} extra {:?} | {}",
            o.spec.index,
            o.spec.class.name(),
            o.z.iter()
                .map(|z| (z * 10.0).round() / 10.0)
                .collect::<Vec<_>>(),
            o.score.correct,
            o.floor,
            o.wall_s,
            o.score.missing,
            o.score.extra,
            o.stop
        );
        for c in o.score.coverage.iter().filter(|c| !c.covers) {
            eprintln!(
                "      not covered: {} truth {:.5} ci {:?}",
                c.what, c.truth, c.ci95
            );
        }
    });
    println!("{}", markdown(&report));
    println!("wall {:.0} s", report.wall_s);
    if let Some(i) = args.iter().position(|a| a == "--json") {
        std::fs::write(&args[i + 1], serde_json::to_string_pretty(&report).unwrap()).unwrap();
    }
}
