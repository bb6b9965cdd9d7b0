//! `rins schemes analyse` as users run it: every built-in scheme (5) × every effect (the
//! nav-grade-full catalogue, the general b(u) basis and the per-axis δβ), one scheme per task
//! on every core. Issue target: ≤ 10 s on this machine.

use criterion::Criterion;
use rayon::prelude::*;
use rins_schemes::effects::EffectSet;
use rins_schemes::response::StaticResponse;
use rins_schemes::{AnalyseOptions, analyse_scheme, library};

fn five_schemes_every_effect(c: &mut Criterion) {
    let sensor = rins_plant::presets::nav_grade_full();
    let set = EffectSet::empty(9.8)
        .with_catalogue(&sensor)
        .with_general()
        .with_delta_beta_axes(&sensor.gyro.position_bias);
    let schemes = library::all_built_in();
    let opt = AnalyseOptions::default();
    c.bench_function(
        "analyse 5 schemes x every effect (incl. week response)",
        |b| {
            b.iter(|| {
                let resp = StaticResponse::new(opt.lat_rad, opt.days);
                let n: usize = schemes
                    .par_iter()
                    .map(|s| analyse_scheme(s, &set, &opt, &resp).unwrap().effects.len())
                    .sum();
                assert_eq!(n, 5 * set.channels().len());
            })
        },
    );
}

fn main() {
    let mut c = Criterion::default().sample_size(10).configure_from_args();
    five_schemes_every_effect(&mut c);
    c.final_summary();
}
