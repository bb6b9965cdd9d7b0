//! `rins sweep FILE`: a tiny sweep (2 points × 2 seeds, 600 s) checked against references that
//! do not come from it.
//!
//! * Each seed's figures equal a `rins paper table4`-style run of that seed alone through the
//!   Monte Carlo engine (`run_seeds` with one seed, the uncompensated navigator and the one
//!   compensating the plant's own δβ), on a plant built from a scenario file with the swept
//!   value written into its text (not through the parameter table the sweep sets it with), bit
//!   for bit, in the JSON and in the CSV.
//! * The CSV has one row per point × seed × navigator; the Parquet file is one.
//! * The bands are the order statistics of the per-seed figures.
//! * Bad sweep files are refused before anything runs, naming the file, line, field and the
//!   allowed range or names.

use std::path::PathBuf;

use rins_experiments::NavRunConfig;
use rins_scenario::Scenario;
use rins_sweep::{SweepError, SweepPlan};
use rins_verification::paper::EndFigures;
use serde_json::Value;

const RINS: &str = env!("CARGO_BIN_EXE_rins");
const NAV_S: f64 = 600.0;
const DBETA_Z: [f64; 2] = [0.0, 0.02];

fn tmp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rins-sweep-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The built-in Section 3.1 scenario's text.
fn week_text() -> &'static str {
    rins_scenario::file::BUILTIN
        .iter()
        .find(|(n, _)| *n == "paper-16pos-week")
        .unwrap()
        .1
}

const SWEEP: &str = r#"[sweep]
name = "tiny"
scenario = "base.toml"
duration_s = 600.0
seeds = 2
outputs = ["lon_nm", "horizontal_nm"]

[[parameter]]
key = "sensor.gyro.position_bias.dph[2]"
values = [0.0, 0.02]
"#;

/// One seed alone, both navigators, on the week scenario with δβ_z written into the file.
fn reference(dbeta_z: f64, seed: u64) -> [EndFigures; 2] {
    let text = format!(
        "{}\n[sensor.gyro.position_bias]\ndph = [0.005, 0.005, {dbeta_z:?}]\n",
        week_text()
    );
    let sc = Scenario::from_toml(&text, "reference").unwrap();
    assert_eq!(sc.plant.sensor.gyro.position_bias.dph[2], dbeta_z);
    let navs = [
        NavRunConfig::default(),
        NavRunConfig {
            compensation: Some(sc.plant.sensor.gyro.position_bias),
            ..NavRunConfig::default()
        },
    ];
    let runs = rins_experiments::run_seeds(&sc.plant, &[seed], NAV_S, &navs, &|_| {}).unwrap();
    [
        EndFigures::from_run(&runs[0][0]),
        EndFigures::from_run(&runs[0][1]),
    ]
}

fn figures_of(v: &Value) -> [f64; 5] {
    [
        "lat_nm",
        "lon_nm",
        "horizontal_nm",
        "trms_nm",
        "up_att_mean_deg",
    ]
    .map(|k| v[k].as_f64().unwrap())
}

fn end(e: &EndFigures) -> [f64; 5] {
    [
        e.lat_nm,
        e.lon_nm,
        e.horizontal_nm,
        e.trms_nm,
        e.up_att_mean_deg,
    ]
}

#[test]
fn sweep_figures_equal_single_runs_bit_for_bit_and_the_csv_has_a_row_per_seed_and_navigator() {
    let dir = tmp("tiny");
    std::fs::write(dir.join("base.toml"), week_text()).unwrap();
    std::fs::write(dir.join("tiny.toml"), SWEEP).unwrap();
    let out = dir.join("out");
    let p = std::process::Command::new(RINS)
        .args(["sweep", "tiny.toml", "--json", "--out"])
        .arg(&out)
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(p.status.success(), "{}", String::from_utf8_lossy(&p.stderr));
    let r: Value = serde_json::from_slice(&p.stdout).unwrap();
    assert_eq!(r["seeds"], serde_json::json!([1, 2]));
    let points = r["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "point,sensor.gyro.position_bias.dph[2],seed,navigator,lat_nm,lon_nm,horizontal_nm,trms_nm,up_att_mean_deg"
    );
    assert_eq!(lines.len() - 1, 2 * 2 * 2, "{csv}");
    // The same sweep in-process: the engine's figures themselves.
    let plan = SweepPlan::load(&dir.join("tiny.toml")).unwrap();
    let lib = rins_sweep::run(&plan, &|_| {}).unwrap();
    let mut row = 1;
    for (k, (point, dbeta)) in points.iter().zip(DBETA_Z).enumerate() {
        assert_eq!(point["values"][0].as_f64(), Some(dbeta));
        for (j, seed) in [1u64, 2].into_iter().enumerate() {
            let got = &point["per_seed"][j];
            assert_eq!(got["seed"].as_u64(), Some(seed));
            assert_eq!(lib.points[k].per_seed[j].seed, seed);
            let want = reference(dbeta, seed);
            for (n, nav) in ["uncompensated", "compensated"].into_iter().enumerate() {
                let want = end(&want[n]).map(f64::to_bits);
                assert_eq!(
                    end(lib.points[k].per_seed[j].figures(n)).map(f64::to_bits),
                    want,
                    "point {k} seed {seed} {nav}"
                );
                let cells: Vec<&str> = lines[row].split(',').collect();
                assert_eq!(
                    cells[..4],
                    [&k.to_string(), &dbeta.to_string(), &seed.to_string(), nav]
                );
                let from_csv: Vec<u64> = cells[4..]
                    .iter()
                    .map(|c| c.parse::<f64>().unwrap().to_bits())
                    .collect();
                assert_eq!(from_csv, want, "CSV row {row}");
                // serde_json's default parser may round the last bit (its exact parser is a
                // feature this workspace does not turn on); the JSON's text is exact (the
                // browser test reads it with Python's parser).
                let json = figures_of(&got[nav]);
                for (a, b) in json.iter().zip(want) {
                    assert!(
                        a.to_bits().abs_diff(b) <= 1,
                        "point {k} seed {seed} {nav}: {json:?}"
                    );
                }
                row += 1;
            }
        }
        // The bands of two seeds: the median is their mean, 5 % and 95 % interpolate.
        let lp = &lib.points[k];
        let lon: Vec<f64> = lp.per_seed.iter().map(|s| s.uncompensated.lon_nm).collect();
        let (lo, hi) = (lon[0].min(lon[1]), lon[0].max(lon[1]));
        let band = lp.band(0, "lon_nm");
        assert_eq!(band.median, 0.5 * lo + 0.5 * hi);
        assert!((band.p05 - (lo + 0.05 * (hi - lo))).abs() < 1e-15);
        assert!((band.p95 - (lo + 0.95 * (hi - lo))).abs() < 1e-15);
    }
    // δβ_z acts on the uncompensated navigator; the seeds differ.
    let lon = |k: usize, j: usize| points[k]["per_seed"][j]["uncompensated"]["lon_nm"].as_f64();
    assert_ne!(lon(0, 0), lon(1, 0));
    assert_ne!(lon(0, 0), lon(0, 1));
    let parquet = std::fs::read(out.join("sweep.parquet")).unwrap();
    assert!(parquet.starts_with(b"PAR1") && parquet.ends_with(b"PAR1"));
    for f in ["sweep_lon_nm", "sweep_horizontal_nm"] {
        assert!(out.join(format!("{f}.svg")).exists() && out.join(format!("{f}.png")).exists());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The problems of a refused sweep text.
fn refused(text: &str) -> String {
    match SweepPlan::from_toml(text, "bad.toml", None) {
        Err(e @ SweepError::Invalid { .. }) => e.to_string(),
        Err(e) => panic!("refused for another reason: {e}"),
        Ok(_) => panic!("accepted:\n{text}"),
    }
}

/// `SWEEP` on the built-in scenario with its parameter block replaced by `parameter`.
fn with(parameter: &str, outputs: &str) -> String {
    format!(
        "[sweep]\nscenario = \"builtin:paper-16pos-week\"\nduration_s = 600.0\nseeds = 2\noutputs = {outputs}\n\n[[parameter]]\n{parameter}"
    )
}

#[test]
fn sweep_errors_name_file_line_field_and_the_allowed_values() {
    // The [[parameter]] header is line 7: its key is on line 8, its values on line 9.
    let e = refused(&with(
        "key = \"sensor.gyro.position_bias.dhp[2]\"\nvalues = [0.0]\n",
        "[\"lon_nm\"]",
    ));
    assert!(e.starts_with("bad.toml: invalid sweep:"), "{e}");
    assert!(
        e.contains("line 8, column 7: parameter[0].key: unknown scenario key \"sensor.gyro.position_bias.dhp[2]\"; the nearest keys are sensor.gyro.position_bias.dph[2]"),
        "{e}"
    );
    let e = refused(&with(
        "key = \"sensor.gyro.position_bias.dph[2]\"\nvalues = [0.0, 200.0]\n",
        "[\"lon_nm\"]",
    ));
    assert!(
        e.contains("line 9, column 16: parameter[0].values[1]: sensor.gyro.position_bias.dph[2]: expected a number in [-100, 100] deg/h, got 200"),
        "{e}"
    );
    let e = refused(&with(
        "key = \"scheme.dwell_s\"\nvalues = []\n",
        "[\"lon_nm\"]",
    ));
    assert!(
        e.contains("line 9, column 10: parameter[0].values: expected at least one value of scheme.dwell_s, got an empty list"),
        "{e}"
    );
    let e = refused(&with(
        "key = \"scheme.dwell_s\"\nvalues = [180.0]\n",
        "[\"lon_nm\", \"longitude\"]",
    ));
    assert!(
        e.contains("line 5, column 22: sweep.outputs[1]: unknown output \"longitude\"; outputs are [\"lat_nm\", \"lon_nm\", \"abs_lat_nm\", \"abs_lon_nm\", \"horizontal_nm\", \"trms_nm\", \"up_att_mean_deg\"]"),
        "{e}"
    );
    let e = refused(&with(
        "key = \"scheme.dwell_s\"\nlinspace = { start = 60.0, stop = 2e7, count = 3 }\n",
        "[\"lon_nm\"]",
    ));
    assert!(
        e.contains(
            "parameter[0].linspace.stop: scheme.dwell_s: expected a number in [0, 1e7] s, got 2e7"
        ),
        "{e}"
    );
    let e = refused(
        &with(
            "key = \"scheme.dwell_s\"\nvalues = [180.0]\n",
            "[\"lon_nm\"]",
        )
        .replace("seeds = 2", "seeds = [3, 3]"),
    );
    assert!(
        e.contains("line 4, column 13: sweep.seeds[1]: seed 3 is listed twice"),
        "{e}"
    );
    let e = refused(&with("key = \"run.seed\"\nvalues = [1]\n", "[\"lon_nm\"]"));
    assert!(
        e.contains("parameter[0].key: the seeds are given by sweep.seeds"),
        "{e}"
    );
    // The command refuses the file before running anything, naming it.
    let dir = tmp("bad");
    let file = dir.join("bad.toml");
    std::fs::write(
        &file,
        with(
            "key = \"scheme.kind\"\nvalues = [\"twelve-position\"]\n",
            "[\"lon_nm\"]",
        ),
    )
    .unwrap();
    let p = std::process::Command::new(RINS)
        .args(["sweep"])
        .arg(&file)
        .arg("--out")
        .arg(dir.join("out"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&p.stderr);
    assert!(!p.status.success());
    assert!(
        err.contains(&format!("{}: invalid sweep", file.display())),
        "{err}"
    );
    assert!(
        err.contains("line 9, column 11: parameter[0].values[0]: scheme.kind: expected one of [\"sixteen-position\""),
        "{err}"
    );
    assert!(!dir.join("out").join("sweep.csv").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sweep_linspace_and_zip_make_the_points_the_docs_say() {
    let text = |combine: &str, second: &str| {
        format!(
            "[sweep]\nscenario = \"builtin:paper-16pos-week\"\ndays = 0.01\nseeds = [4, 9]\noutputs = [\"trms_nm\"]\ncombine = \"{combine}\"\n\n[[parameter]]\nkey = \"sensor.gyro.position_bias.dph[2]\"\nlinspace = {{ start = 0.0, stop = 0.02, count = 3 }}\n\n[[parameter]]\nkey = \"scheme.dwell_s\"\nvalues = {second}\n"
        )
    };
    let grid = SweepPlan::from_toml(&text("grid", "[120.0, 240.0]"), "g.toml", None).unwrap();
    assert_eq!(grid.points.len(), 6);
    assert_eq!(grid.seeds, [4, 9]);
    assert_eq!(grid.duration_s, 864.0);
    let dbeta: Vec<f64> = grid
        .points
        .iter()
        .map(|p| p.plant.sensor.gyro.position_bias.dph[2])
        .collect();
    assert_eq!(dbeta, [0.0, 0.0, 0.01, 0.01, 0.02, 0.02]);
    let dwell: Vec<f64> = grid.points.iter().map(|p| p.plant.scheme.dwell_s).collect();
    assert_eq!(dwell, [120.0, 240.0, 120.0, 240.0, 120.0, 240.0]);
    let zip = SweepPlan::from_toml(&text("zip", "[120.0, 240.0, 360.0]"), "z.toml", None).unwrap();
    let pairs: Vec<(f64, f64)> = zip
        .points
        .iter()
        .map(|p| {
            (
                p.plant.sensor.gyro.position_bias.dph[2],
                p.plant.scheme.dwell_s,
            )
        })
        .collect();
    assert_eq!(pairs, [(0.0, 120.0), (0.01, 240.0), (0.02, 360.0)]);
    // Self-alignment starts the scheme after its 900 s, as `rins paper table4 --align self`.
    let aligned = text("grid", "[120.0]").replace("combine", "alignment = \"self\"\ncombine");
    let aligned = SweepPlan::from_toml(&aligned, "a.toml", None).unwrap();
    assert_eq!(
        aligned.points[0].plant.scheme.lead_dwell_s,
        grid.points[0].plant.scheme.lead_dwell_s + 900.0
    );
    let e = refused(&text("zip", "[120.0, 240.0]"));
    assert!(
        e.contains("line 13, column 7: parameter[1].key: combine = \"zip\""),
        "{e}"
    );
}

#[test]
fn sweep_figures_put_names_on_a_categorical_axis_one_line_per_other_value_clear_of_the_legend() {
    use rins_report::figures::rules::HEADROOM_PX;
    let text = "[sweep]\nscenario = \"builtin:paper-16pos-week\"\nduration_s = 300.0\nseeds = 2\noutputs = [\"lon_nm\"]\n\n[[parameter]]\nkey = \"scheme.kind\"\nvalues = [\"sixteen-position\", \"eight-position\"]\n\n[[parameter]]\nkey = \"sensor.gyro.position_bias.dph[2]\"\nvalues = [0.0, 0.02]\n";
    let plan = SweepPlan::from_toml(text, "f.toml", None).unwrap();
    let r = rins_sweep::run(&plan, &|_| {}).unwrap();
    let figs = rins_report::figures::sweep::sweep_figures(&r);
    assert_eq!(figs.len(), 1);
    let f = &figs[0];
    assert_eq!(f.stem, "sweep_lon_nm");
    assert_eq!(f.categories, ["sixteen-position", "eight-position"]);
    // Grid order: scheme.kind slowest; the line of δβ_z = 0 holds points 0 and 2.
    for nav in 0..2 {
        assert_eq!(f.lines[nav].len(), 2);
        for (j, (label, pts)) in f.lines[nav].iter().enumerate() {
            assert!(
                label.ends_with(&format!("dph[2] = {} deg/h", [0.0, 0.02][j])),
                "{label}"
            );
            for (i, p) in pts.iter().enumerate() {
                let b = r.points[2 * i + j].band(nav, "lon_nm");
                assert_eq!([p[1], p[2], p[3]], [b.p05, b.median, b.p95]);
                assert!(
                    (p[0] - i as f64).abs() < 0.05,
                    "category {i} drawn at {}",
                    p[0]
                );
            }
        }
    }
    let (_, geometry) = f.render().unwrap();
    assert_eq!(geometry.len(), 2);
    for (k, g) in geometry.iter().enumerate() {
        assert_eq!(g.categories.len(), 2, "panel {k}");
        let e = g.extent.expect("marks");
        let h = HEADROOM_PX - 1;
        assert!(
            e.y0 >= g.plot.y0 + h
                && e.y1 <= g.plot.y1 - h
                && e.x0 >= g.plot.x0 + h
                && e.x1 <= g.plot.x1 - h,
            "panel {k}: marks {e:?} within {HEADROOM_PX} px of the frame {:?}",
            g.plot
        );
        if let Some(l) = g.legend {
            for &(a, b) in &g.marks {
                assert!(
                    !l.touches_segment(a, b),
                    "panel {k}: legend {l:?} covers {a:?}-{b:?}"
                );
            }
        }
    }
}

/// A sweep point's plant travels to a Dask worker as TOML text (`SweepPlan.point_plants`), and
/// the worker must compute exactly what `run_json` computes in-process: the text must give back
/// the same plant, bit for bit. Checked here for every built-in scenario with random values of
/// random parameters of its table (any value the sweep's range check lets through, whole
/// numbers up to 2^64 − 1, every enumeration name), so the client need not parse each text
/// back at run time.
#[test]
fn every_sweepable_plant_survives_toml_text_bit_for_bit() {
    use rand::{Rng, SeedableRng};
    use rins_plant::PlantConfig;
    use rins_plant::params::{self, ParamValue};

    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x7011_5eed);
    const TRIALS: usize = 60;
    let mut checked = 0usize;
    // Which kinds of value travelled in a checked plant (real, whole number, switch, name).
    let mut kinds = [false; 4];
    for (name, text) in rins_scenario::file::BUILTIN {
        let sc = Scenario::from_toml(text, name).unwrap();
        let table = params::flatten(&sc.plant);
        for trial in 0..TRIALS {
            let mut values = Vec::new();
            for _ in 0..6 {
                let p = &table[rng.random_range(0..table.len())];
                let v = match &p.value {
                    ParamValue::Real(_) => {
                        // An open side of the range is drawn up to 1e30 (uniform over
                        // ±inf would give NaN, which no check lets through).
                        let (lo, hi) = p.range.unwrap_or((-1e6, 1e6));
                        let (lo, hi) = (lo.max(-1e30), hi.min(1e30));
                        // Uniform over the range has 53 random bits; also the range's edges,
                        // a negative zero and tiny values where the range allows them.
                        ParamValue::Real(match rng.random_range(0..8) {
                            0 => lo,
                            1 => hi,
                            2 if lo <= 0.0 => -0.0,
                            3 if lo <= 0.0 && hi >= 1e-300 => 1e-300 * rng.random::<f64>(),
                            _ => lo + (hi - lo) * rng.random::<f64>(),
                        })
                    }
                    ParamValue::Integer(_) => {
                        let (lo, hi) = p.range.unwrap_or((0.0, u64::MAX as f64));
                        ParamValue::Integer(if hi >= u64::MAX as f64 {
                            rng.random::<u64>()
                        } else {
                            rng.random_range(lo as u64..=hi as u64)
                        })
                    }
                    ParamValue::Bool(_) => ParamValue::Bool(rng.random()),
                    ParamValue::Enum(e) => ParamValue::Enum(match params::enum_choices(&p.path) {
                        Some(c) => c[rng.random_range(0..c.len())].to_string(),
                        None => e.clone(),
                    }),
                };
                values.push((p.path.as_str(), v));
            }
            // As the sweep makes a point: the values set, then the whole scenario checked
            // (a profile's times out of order, a period below the step, … are refused there
            // and never travel).
            let Ok(plant) = params::apply(&sc.plant, values.clone()) else {
                continue;
            };
            let point = Scenario {
                plant: plant.clone(),
                ..sc.clone()
            };
            if point.validate(None).is_err() {
                continue;
            }
            for (_, v) in &values {
                kinds[match v {
                    ParamValue::Real(_) => 0,
                    ParamValue::Integer(_) => 1,
                    ParamValue::Bool(_) => 2,
                    ParamValue::Enum(_) => 3,
                }] = true;
            }
            let text = toml::to_string(&plant).unwrap();
            let back: PlantConfig = toml::from_str(&text)
                .unwrap_or_else(|e| panic!("{name} trial {trial} ({values:?}): {e}"));
            // `==` on the plant compares numbers by value; the texts written again compare
            // the bits too (a negative zero, the last digit of a real).
            assert_eq!(back, plant, "{name} trial {trial}: {values:?}");
            assert_eq!(
                toml::to_string(&back).unwrap(),
                text,
                "{name} trial {trial}"
            );
            checked += 1;
        }
    }
    // Most draws are accepted, with every kind of value among them: the check is not passing
    // on an empty or one-sided set.
    let trials = rins_scenario::file::BUILTIN.len() * TRIALS;
    assert!(
        checked >= trials * 3 / 4,
        "only {checked} of {trials} trials gave a plant"
    );
    assert_eq!(
        kinds, [true; 4],
        "kinds of value checked: real, whole, switch, name"
    );
}
