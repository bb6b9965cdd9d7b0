//! Rerun recordings of the commands' results (`--rerun DEST`, built with the `rerun` feature):
//! a run as it happens ([`RerunSink`]), a paired paper study ([`record_paired`]) and a
//! model-vs-measurement analysis ([`record_diagnosis`]). The static figures (`rins_report::figures`,
//! [`crate::sinks::RunFigures`]) draw the same results as SVG and PNG.

use anyhow::Result;
use rins_plant::{ImuSample, Truth};
use rins_rerun_sink::{Layout, Recorder, RunOptions, RunRecorder, Target};

use crate::runner::Sink;
use rins_scenario::file::Scenario;

/// A [`Sink`] that records the run to Rerun.
pub struct RerunSink {
    recorder: Option<Recorder>,
    run: RunRecorder,
    layout: Layout,
}

impl RerunSink {
    /// Opens `target` for a run of `scenario` over `samples` output samples.
    pub fn open(
        target: &Target,
        scenario: &Scenario,
        samples: u64,
        bucket_s: Option<f64>,
        navigate: bool,
    ) -> Result<Self> {
        let recorder = Recorder::open(target, &scenario.meta.name)?;
        let plant = rins_scenario::new_plant(&scenario.plant, &scenario.source)?;
        let bucket_samples =
            rins_rerun_sink::bucket::samples_per_bucket(bucket_s, scenario.plant.rate_hz, samples);
        let tracker = navigate.then(|| {
            rins_experiments::Tracker::at_truth(
                &plant,
                bucket_samples as f64 / scenario.plant.rate_hz,
            )
        });
        let run = RunRecorder::new(
            recorder.stream(),
            &scenario.plant,
            &plant.vehicle_to_nav(),
            RunOptions {
                bucket_samples,
                navigate,
            },
            tracker,
        )?;
        let layout = Layout {
            plant: true,
            nav_cases: if navigate {
                vec!["reference".into()]
            } else {
                vec![]
            },
            extra: vec![],
            docs: vec!["/about".into()],
            track: run.moving_carrier(),
        };
        rins_rerun_sink::scene::log_doc(
            recorder.stream(),
            "about",
            &about(scenario, bucket_samples, navigate),
        )?;
        Ok(Self {
            recorder: Some(recorder),
            run,
            layout,
        })
    }

    /// The layout, to extend before the blueprint is sent at [`Sink::finish`].
    pub fn layout_mut(&mut self) -> &mut Layout {
        &mut self.layout
    }

    /// The stream, for further results (paper tables, navigation cases).
    pub fn stream(&self) -> Option<&rerun::RecordingStream> {
        self.recorder.as_ref().map(Recorder::stream)
    }

    /// Rows logged per series.
    pub fn rows(&self) -> u64 {
        self.run.rows()
    }

    /// Sends the blueprint and closes the recording (idempotent).
    pub fn close(&mut self) -> Result<()> {
        if let Some(r) = self.recorder.take() {
            rins_rerun_sink::blueprint::send(r.stream(), &self.layout)?;
            r.finish()?;
        }
        Ok(())
    }
}

impl Sink for RerunSink {
    fn sample(&mut self, s: &ImuSample, truth: &Truth) -> Result<()> {
        self.run.sample(s, truth)
    }

    fn finish(&mut self) -> Result<()> {
        self.run.finish()
    }
}

impl Drop for RerunSink {
    fn drop(&mut self) {
        // An error path still closes the file with its footer.
        let _ = self.close();
    }
}

/// Records a paired study (Table 4 / Table 5): the scenario's plant stream over the
/// navigation time (3D table, IMU output, temperatures, effects) and the first seed's
/// navigation errors for both cases, with the report text.
pub fn record_paired(
    target: &Target,
    bucket_s: Option<f64>,
    scenario: &Scenario,
    plant_cfg: &rins_plant::PlantConfig,
    duration_s: f64,
    r: &rins_verification::paper::Table4Report,
    text: &str,
) -> Result<()> {
    let recorder = Recorder::open(target, &scenario.meta.name)?;
    let rec = recorder.stream();
    let mut plant = rins_scenario::new_plant(plant_cfg, &scenario.source)?;
    let n = (duration_s * plant_cfg.rate_hz).round() as u64;
    let bucket_samples =
        rins_rerun_sink::bucket::samples_per_bucket(bucket_s, plant_cfg.rate_hz, n);
    let mut run = RunRecorder::new(
        rec,
        plant_cfg,
        &plant.vehicle_to_nav(),
        RunOptions {
            bucket_samples,
            navigate: false,
        },
        None,
    )?;
    let pb = crate::progress::bar(n, "rerun");
    for k in 0..n {
        if k % (1 << 14) == 0 {
            if crate::interrupt::requested() {
                break;
            }
            pb.set_position(k);
        }
        let s = plant.step();
        run.sample(&s, &plant.truth())?;
    }
    pb.finish_and_clear();
    run.finish()?;
    let dt = 1.0 / plant_cfg.rate_hz;
    let every = "first seed, one record per 60 s";
    rins_rerun_sink::nav::NavSeries::log_all(
        rec,
        "uncompensated",
        every,
        &r.first_seed.uncompensated,
        dt,
    )?;
    rins_rerun_sink::nav::NavSeries::log_all(
        rec,
        "compensated",
        every,
        &r.first_seed.compensated,
        dt,
    )?;
    rins_rerun_sink::nav::NavSeries::log_all(
        rec,
        "noise_free_uncompensated",
        "noise-free",
        &r.noise_free_series.uncompensated,
        dt,
    )?;
    rins_rerun_sink::nav::NavSeries::log_all(
        rec,
        "noise_free_compensated",
        "noise-free",
        &r.noise_free_series.compensated,
        dt,
    )?;
    rins_rerun_sink::scene::log_doc(
        rec,
        "results",
        &format!("# Results\n\n```text\n{text}\n```\n"),
    )?;
    rins_rerun_sink::scene::log_doc(rec, "about", &about(scenario, bucket_samples, false))?;
    let layout = Layout {
        plant: true,
        nav_cases: [
            "uncompensated",
            "compensated",
            "noise_free_uncompensated",
            "noise_free_compensated",
        ]
        .map(String::from)
        .to_vec(),
        extra: vec![],
        docs: vec!["/results".into(), "/about".into()],
        track: run.moving_carrier(),
    };
    rins_rerun_sink::blueprint::send(rec, &layout)?;
    recorder.finish()
}

/// Records a model-vs-measurement analysis: per channel the window residual (measured −
/// model, as a rate) with the fitted effects' prediction, and static navigation on the
/// measured vs the model's increments, with the report text. With `history` (`--iterate`)
/// the analysis is the final model's, and the error falling is recorded too: per channel the
/// residual over the noise floor at each step (`diagnosis/iteration/CHANNEL`, one row per
/// step; the time axis counts steps, 1 s each) beside the floor bound.
pub fn record_diagnosis(
    target: &Target,
    an: &rins_mvm::Analysis,
    pred: Option<&[Vec<f64>]>,
    history: Option<&rins_mvm::IterationReport>,
    source: &str,
    text: &str,
) -> Result<()> {
    use rins_mvm::CHANNELS;
    let recorder = Recorder::open(target, &format!("diagnosis of {source}"))?;
    let rec = recorder.stream();
    let ws = &an.replay.windows;
    let mut roots = Vec::new();
    for (c, ch) in CHANNELS.iter().enumerate() {
        let (unit, scale) = if c < 3 {
            ("deg/h", rins_plant::units::DPH)
        } else {
            ("µg", rins_plant::units::UG)
        };
        let mut names = vec![format!("residual (measured − model), window mean, {unit}")];
        if pred.is_some() {
            names.push(format!("fitted effects, window mean, {unit}"));
        }
        names.push("up_z of the window (+1 Z-up, −1 Z-down)".into());
        let rows = ws.iter().enumerate().map(|(i, w)| {
            let mut v = vec![an.data[c].y[i] / w.duration_s / scale];
            if let Some(p) = pred {
                v.push(p[c][i] / w.duration_s / scale);
            }
            v.push(w.up_z);
            (i as u64, w.t_mid_s, v)
        });
        let path = format!("diagnosis/residual/{ch}");
        rins_rerun_sink::series::log_rows(rec, &path, &names, &[], rows)?;
        roots.push(format!("/{path}"));
    }
    let mut nav_roots = Vec::new();
    for t in an.replay.nav.iter().filter(|t| !t.t_s.is_empty()) {
        let run = an
            .run_names
            .get(t.run as usize)
            .cloned()
            .unwrap_or_else(|| format!("run{}", t.run));
        let path = format!("diagnosis/navigation/{}", sanitize(&run));
        let rows = t
            .t_s
            .iter()
            .enumerate()
            .map(|(i, ts)| (i as u64, *ts, vec![t.measured_m[i], t.model_m[i]]));
        rins_rerun_sink::series::log_rows(
            rec,
            &path,
            &[
                "horizontal error on the measured increments, m".into(),
                "on the model's increments, m".into(),
            ],
            &[[120, 120, 120], [31, 119, 180]],
            rows,
        )?;
        nav_roots.push(format!("/{path}"));
    }
    rins_rerun_sink::scene::log_doc(
        rec,
        "results",
        &format!(
            "# {source}\n\nWindows are the diagnosis windows (one row each, time = window mid time).\n\n```text\n{text}\n```\n"
        ),
    )?;
    let mut iteration_roots = Vec::new();
    if let Some(hist) = history {
        // The ratio at which `--iterate` calls a channel at its floor, drawn beside it.
        let bound = rins_mvm::IterateOptions::default().floor_ratio;
        for (c, ch) in CHANNELS.iter().enumerate() {
            let rows = hist.steps.iter().map(|st| {
                let ratio = st.levels.get(c).map_or(f64::NAN, |l| l.ratio);
                (st.step as u64, st.step as f64, vec![ratio, bound])
            });
            let path = format!("diagnosis/iteration/{ch}");
            rins_rerun_sink::series::log_rows(
                rec,
                &path,
                &[
                    "residual RMS / noise floor".into(),
                    "at the floor below".into(),
                ],
                &[[31, 119, 180], [120, 120, 120]],
                rows,
            )?;
            iteration_roots.push(format!("/{path}"));
        }
    }
    let mut extra = vec![("Residuals".to_string(), roots)];
    if !iteration_roots.is_empty() {
        extra.insert(
            0,
            (
                "Iteration: residual / floor per step".to_string(),
                iteration_roots,
            ),
        );
    }
    if !nav_roots.is_empty() {
        nav_roots.truncate(8);
        extra.push(("Navigation: measured vs model".to_string(), nav_roots));
    }
    rins_rerun_sink::blueprint::send(
        rec,
        &Layout {
            plant: false,
            nav_cases: vec![],
            extra,
            docs: vec!["/results".into()],
            track: false,
        },
    )?;
    recorder.finish()
}

/// An entity-path component from a run name.
fn sanitize(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn about(sc: &Scenario, bucket: u64, navigate: bool) -> String {
    let span = bucket as f64 / sc.plant.rate_hz;
    format!(
        "# {name}\n\n{desc}\n\nSource: `{src}`, {rate} Hz, {dur} s simulated, seed {seed}.\n\n\
         **Decimation.** Every series has one row per bucket of {bucket} samples ({span} s). \
         `imu/*` and `gimbal/*` rows hold the bucket's mean, minimum and maximum (Δθ and Δv per \
         sample, rad and m/s); `thermal/temps_c` and `effects/*` rows hold the bucket mean \
         over up to 64 evenly spaced samples (one in {stride}; effects as rates, deg/h and \
         µg). The 3D pose is logged at each dwell change and at the \
         end of each bucket; `status/position` logs every dwell change.{nav}\n\n\
         Timelines: `sim_time` (simulated time) and `step` (output sample number of the row's \
         last sample). Entities: docs/visualization.md.\n",
        name = sc.meta.name,
        desc = sc.meta.description,
        src = sc.source,
        rate = sc.plant.rate_hz,
        dur = sc.meta.duration_s,
        seed = sc.plant.seed,
        stride = (bucket / rins_rerun_sink::run::SLOW_SAMPLES).max(1),
        nav = if navigate {
            "\n\n`nav/reference/*`: the reference navigator, aligned to the truth, its errors instantaneous at each bucket end."
        } else {
            ""
        },
    )
}
