//! Runs one hand-made trial through `rins diagnose --iterate` (in process) and prints what it
//! kept: `cargo run --release -p rins-mvm-trials --example trial -- CASE [SEED]`.

use rins_mvm::{IterateOptions, Options, iterate};
use rins_mvm_trials::{Design, HiddenEffect, generate};
use rins_plant::PlantConfig;

fn base_model() -> PlantConfig {
    let mut m = PlantConfig::default();
    let g = &mut m.sensor.gyro;
    g.bias.enabled = true;
    g.bias.dph = [0.01, -0.02, 0.015];
    g.scale_factor.enabled = true;
    g.scale_factor.ppm = [3.0, -2.0, 3.0];
    g.angle_random_walk.enabled = true;
    g.angle_random_walk.dpsh = [0.003; 3];
    let a = &mut m.sensor.accel;
    a.bias.enabled = true;
    a.bias.ug = [50.0, -30.0, 20.0];
    a.scale_factor.enabled = true;
    a.scale_factor.ppm = [50.0, 40.0, -30.0];
    a.velocity_random_walk.enabled = true;
    a.velocity_random_walk.ug_per_sqrthz = [10.0; 3];
    m
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let case = args.get(1).map_or("sf", |s| s.as_str());
    let seed: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let (design, hidden) = match case {
        "sf" => (
            Design::chamber_steps_four_azimuths(),
            vec![HiddenEffect::ScaleFactorTempLinear {
                ppm_per_k: [0.0, 0.0, 0.8],
                ppm: [0.0, 0.0, -20.0],
            }],
        ),
        "field" => (
            Design::field_four_azimuths(),
            vec![HiddenEffect::NavFieldBias {
                dph: [0.006, 0.005, 0.0],
                inclination_deg: 55.0,
                declination_deg: -8.0,
            }],
        ),
        "transient" => (
            Design::chamber_steps_four_azimuths(),
            vec![HiddenEffect::PostMoveTransient {
                dph: [0.03, 0.0, 0.0],
                tau_s: 120.0,
            }],
        ),
        "lag" => (
            Design::chamber_steps_four_azimuths(),
            vec![HiddenEffect::LaggedTempBias {
                dph_per_k: [0.0, 0.002, 0.0],
                tau_s: 1500.0,
            }],
        ),
        _ => (Design::chamber_steps_four_azimuths(), vec![]),
    };
    let model = design.model_for(&base_model());
    let z_target: Option<f64> = args.get(3).and_then(|s| s.parse().ok());
    let hidden: Vec<HiddenEffect> = hidden
        .into_iter()
        .map(|e| match z_target {
            Some(z) => rins_mvm_trials::scale_to_z(&model, &design, &e, z).expect("visible"),
            None => e,
        })
        .collect();
    for e in &hidden {
        eprintln!(
            "{e:?}: oracle z per channel {:?}",
            rins_mvm_trials::oracle_z_per_channel(&model, &design, e)
        );
    }
    let t0 = std::time::Instant::now();
    let h = generate(&model, &design, &hidden, seed);
    eprintln!("{} rows in {:.2} s", h.len(), t0.elapsed().as_secs_f64());
    let t0 = std::time::Instant::now();
    let it = iterate(&model, &h, &Options::default(), &IterateOptions::default()).unwrap();
    eprintln!("iterate {:.2} s", t0.elapsed().as_secs_f64());
    let r = &it.report;
    for s in &r.steps {
        let lv: Vec<String> = s
            .levels
            .iter()
            .map(|l| format!("{} {:.2}", l.channel, l.ratio))
            .collect();
        println!(
            "step {}: {} | cells {}",
            s.step,
            lv.join(", "),
            s.flagged_cells
        );
        for a in &s.accepted {
            println!(
                "  {} {} ({}) dBIC {:.1} joint {:.1} stab {:.2} kept {} parents {:?} replaces {:?}",
                a.channel,
                a.effect,
                a.found_by,
                a.delta_bic,
                a.joint_delta_bic,
                a.stability,
                a.kept,
                a.parents,
                a.replaces
            );
        }
        for c in &s.coefficients {
            println!("    {:?}", c);
        }
    }
    println!("stop: {} (floor {})", r.stop, r.reached_floor);
    for u in &r.unexplained {
        println!("  {u}");
    }
    if let Some(d) = it
        .last
        .diagnosis
        .as_ref()
        .and_then(|d| d.report.discovery.as_ref())
    {
        for p in &d.proposals {
            for t in &p.terms {
                println!(
                    "  proposal {} {} {} {:.5} {:?} tau {:?} parent_of {:?} dBIC {:.1} p {:.2e} cv {:.2} boot {:.2} on {}",
                    p.name,
                    t.channel,
                    t.term,
                    t.coefficient,
                    t.ci95,
                    t.tau,
                    t.parent_of,
                    t.delta_bic,
                    t.p_value,
                    t.cv_rmse_gain_pct,
                    t.bootstrap_frequency,
                    t.searched_on
                );
            }
        }
    }
}
