//! Scenario files: built-ins load, bad input gets an error naming file, line, key and range,
//! and the CSV output is lossless under decimation and bit-identical for the same seed.

use rins_scenario::file::{BUILTIN, OutputSpec, Scenario, ScenarioError};
use rins_scenarios::sinks::CsvSink;
use rins_scenarios::{Sink, run};

fn err_text(toml: &str) -> String {
    match Scenario::from_toml(toml, "bad.toml") {
        Ok(_) => panic!("expected an error for:\n{toml}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn every_builtin_loads_and_validates() {
    for (name, text) in BUILTIN {
        let sc = Scenario::from_toml(text, name).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(sc.samples() > 0);
    }
    let week = Scenario::load(std::path::Path::new("builtin:paper-16pos-week")).unwrap();
    assert_eq!(week.samples(), 60_480_000);
    // Table 3 preset applied.
    assert!(week.plant.sensor.gyro.position_bias.enabled);
    assert_eq!(week.plant.sensor.gyro.position_bias.dph, [0.005; 3]);
    let camp = Scenario::load(std::path::Path::new("builtin:campaign-37")).unwrap();
    let temps = camp.campaign.unwrap().temperatures_c();
    assert_eq!(temps.len(), 37);
    approx::assert_relative_eq!(temps[0], 6.54);
    approx::assert_relative_eq!(temps[36], 58.14, epsilon = 1e-12);
}

#[test]
fn preset_values_are_overridden_key_by_key() {
    let sc = Scenario::from_toml(
        "[sensor]\npreset = \"paper-table3\"\n[sensor.gyro.bias]\ndph = [0.02, 0.0, 0.0]\n",
        "t.toml",
    )
    .unwrap();
    let g = &sc.plant.sensor.gyro;
    assert!(g.bias.enabled, "enabled comes from the preset");
    assert_eq!(g.bias.dph, [0.02, 0.0, 0.0], "dph comes from the file");
    assert_eq!(g.scale_factor.ppm, [5.0; 3]);
}

#[test]
fn unknown_key_names_file_line_and_key() {
    let e = err_text("[scenario]\nname = \"x\"\n\n[site]\nlatitude_deg = 36.6\n");
    assert!(e.contains("bad.toml"), "{e}");
    assert!(e.contains("line 5"), "{e}");
    assert!(e.contains("latitude_deg"), "{e}");
}

#[test]
fn out_of_range_value_names_line_key_and_range() {
    let e = err_text("[site]\nlat_deg = 95.0\n");
    assert!(
        e.contains("line 2")
            && e.contains("site.lat_deg")
            && e.contains("[-89, 89]")
            && e.contains("95"),
        "{e}"
    );
    let e =
        err_text("[sensor.gyro.angle_random_walk]\nenabled = true\ndpsh = [0.003, -1.0, 0.003]\n");
    assert!(
        e.contains("line 3") && e.contains("sensor.gyro.angle_random_walk.dpsh[1]"),
        "{e}"
    );
    let e = err_text("[thermal]\nstep_s = 0.015\n");
    assert!(
        e.contains("thermal.step_s") && e.contains("whole multiple"),
        "{e}"
    );
}

#[test]
fn wrong_type_and_bad_preset_and_bad_campaign() {
    let e = err_text("[run]\nrate_hz = \"fast\"\n");
    assert!(e.contains("line 2") && e.contains("rate_hz"), "{e}");
    let e = err_text("[sensor]\npreset = \"hg9900\"\n");
    assert!(
        e.contains("line 2") && e.contains("paper-table3") && e.contains("hg9900"),
        "{e}"
    );
    let e = err_text("[campaign]\ntemps_c = [20.0, 300.0]\n");
    assert!(e.contains("campaign.temps_c") && e.contains("300"), "{e}");
    assert!(matches!(
        Scenario::load(std::path::Path::new("/nonexistent/x.toml")),
        Err(ScenarioError::Read { .. })
    ));
    let e = Scenario::load(std::path::Path::new("builtin:paper-table9"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("paper-table9") && e.contains("paper-16pos-week"),
        "{e}"
    );
}

fn csv_bytes(sc: &Scenario, decimation: u64) -> Vec<u8> {
    let opts = OutputSpec {
        decimation,
        truth: true,
        effects: true,
        ..OutputSpec::default()
    };
    let mut sink = CsvSink::new(Vec::new(), opts, &sc.plant).unwrap();
    {
        let mut sinks: [&mut dyn Sink; 1] = [&mut sink];
        run(sc, sc.samples(), &mut sinks).unwrap();
    }
    sink.into_inner()
}

fn column_sums(csv: &[u8], cols: &[&str]) -> Vec<f64> {
    let text = std::str::from_utf8(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let idx: Vec<usize> = cols
        .iter()
        .map(|c| header.iter().position(|h| h == c).unwrap())
        .collect();
    let mut sums = vec![0.0; cols.len()];
    for l in lines {
        let f: Vec<&str> = l.split(',').collect();
        for (s, &i) in sums.iter_mut().zip(&idx) {
            *s += f[i].parse::<f64>().unwrap();
        }
    }
    sums
}

#[test]
fn decimated_rows_sum_to_the_full_rate_stream_and_output_is_deterministic() {
    let mut sc = Scenario::load(std::path::Path::new("builtin:paper-16pos-short")).unwrap();
    sc.meta.duration_s = 300.37; // not a multiple of the decimation: the partial row is kept
    let full = csv_bytes(&sc, 1);
    let dec = csv_bytes(&sc, 100);
    let cols = ["dtheta_x_rad", "dtheta_z_rad", "dv_y_mps", "dv_z_mps"];
    let (a, b) = (column_sums(&full, &cols), column_sums(&dec, &cols));
    for (x, y) in a.iter().zip(&b) {
        approx::assert_relative_eq!(x, y, max_relative = 1e-11, epsilon = 1e-15);
    }
    assert_eq!(std::str::from_utf8(&dec).unwrap().lines().count(), 1 + 301);
    assert_eq!(full, csv_bytes(&sc, 1), "same seed, same bytes");
    sc.plant.seed = 7;
    assert_ne!(full, csv_bytes(&sc, 1), "another seed, other bytes");
}

/// Every leaf key of the format (from serialising a scenario with every section present) is
/// documented in docs/scenario-format.md, so the docs cannot fall behind the code.
#[test]
fn every_key_is_documented() {
    let docs = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../docs/scenario-format.md"
    ))
    .unwrap();
    let mut f = rins_scenario::file::ScenarioFile {
        campaign: Some(Default::default()),
        ..Default::default()
    };
    f.sensor.preset = Some("ideal".into());
    let value = toml::Value::try_from(&f).unwrap();
    fn leaves(prefix: &str, v: &toml::Value, out: &mut Vec<String>) {
        if let toml::Value::Table(t) = v {
            for (k, v) in t {
                let is_leaf_table = prefix.ends_with("chamber");
                if matches!(v, toml::Value::Table(_)) && !is_leaf_table {
                    leaves(k, v, out);
                } else {
                    out.push(k.clone());
                }
            }
        }
    }
    let mut keys = Vec::new();
    leaves("", &value, &mut keys);
    assert!(keys.len() > 60, "{}", keys.len());
    for k in keys {
        assert!(
            docs.contains(&format!("`{k}`")),
            "docs/scenario-format.md does not mention `{k}`"
        );
    }
}

#[test]
fn the_headline_scenario_is_the_fmu_default_plant() {
    // The FMU's start values come from `presets::paper_16pos_config`; the scenario file is the
    // user-facing definition. They must not drift apart.
    let s = rins_scenario::file::Scenario::load(std::path::Path::new("builtin:paper-16pos-week"))
        .unwrap();
    assert_eq!(s.plant, rins_plant::presets::paper_16pos_config());
}
