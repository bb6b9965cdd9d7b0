//! The one parameter path (issue 27): a scenario is parsed once into a spanned document, the
//! preset is laid in as its TOML fragment and the typed scenario is read once. The reference
//! here is the path it replaced, kept as test code: the text read into a `toml::Table`, the
//! preset struct serialised to a TOML table, the file's `[sensor]` deep-merged over it and read
//! back (struct → TOML → struct). Every built-in scenario, and a file with a partial `[sensor]`
//! over each preset (every leaf key of every preset, in turn), must give exactly its
//! `PlantConfig`; each preset fragment must give exactly the Rust constructor's `SensorSpec`.

use rins_plant::config::SensorSpec;
use rins_plant::{PlantConfig, presets};
use rins_scenario::Override;
use rins_scenario::file::{BUILTIN, Scenario, ScenarioFile};

/// The replaced path, without its validation (the new path validates; both must agree on the
/// configuration of every file the new path accepts).
fn old_path_plant(text: &str) -> PlantConfig {
    let mut table: toml::Table = toml::from_str(text).expect("reference parses");
    let raw: ScenarioFile = table.clone().try_into().expect("reference reads");
    let name = raw.sensor.preset.clone().unwrap_or_else(|| "ideal".into());
    let preset = presets::preset(&name).expect("known preset");
    let mut sensor = toml::Table::try_from(&preset).expect("presets serialise");
    if let Some(toml::Value::Table(mut user)) = table.remove("sensor") {
        user.remove("preset");
        deep_merge(&mut sensor, user);
    }
    let sensor: SensorSpec = sensor.try_into().expect("merged sensor reads");
    PlantConfig {
        rate_hz: raw.run.rate_hz,
        substeps: raw.run.substeps,
        seed: raw.run.seed,
        site: raw.site,
        vehicle: raw.vehicle,
        earth: raw.earth,
        scheme: raw.scheme,
        sensor,
        thermal: raw.thermal,
        carrier: raw.carrier,
    }
}

/// The replaced path's merge: tables merge key by key, anything else replaces.
fn deep_merge(base: &mut toml::Table, over: toml::Table) {
    for (k, v) in over {
        match (base.get_mut(&k), v) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => deep_merge(b, o),
            (_, v) => {
                base.insert(k, v);
            }
        }
    }
}

fn new_path_plant(text: &str) -> PlantConfig {
    Scenario::from_toml(text, "t.toml")
        .unwrap_or_else(|e| panic!("{e}\n--- for ---\n{text}"))
        .plant
}

/// Every leaf of a TOML table as `(dotted key, value)`; arrays are leaves.
fn leaves(prefix: &str, table: &toml::Table, out: &mut Vec<(String, toml::Value)>) {
    for (k, v) in table {
        let key = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            toml::Value::Table(t) => leaves(&key, t, out),
            v => out.push((key, v.clone())),
        }
    }
}

#[test]
fn every_builtin_gives_the_old_paths_configuration() {
    for (name, text) in BUILTIN {
        let new = Scenario::from_toml(text, &format!("builtin:{name}"))
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .plant;
        assert_eq!(new, old_path_plant(text), "{name}");
    }
}

#[test]
fn each_preset_fragment_is_its_rust_constructor() {
    for name in presets::PRESET_NAMES {
        let text = format!("[sensor]\npreset = \"{name}\"\n");
        let plant = new_path_plant(&text);
        let expected = presets::preset(name).expect("listed preset");
        assert_eq!(plant.sensor, expected, "{name}");
        assert_eq!(
            plant,
            PlantConfig {
                sensor: expected,
                ..PlantConfig::default()
            },
            "{name}"
        );
    }
    // The named constructors are the same presets.
    let sensor = |name: &str| new_path_plant(&format!("[sensor]\npreset = \"{name}\"\n")).sensor;
    assert_eq!(sensor("paper-table3"), presets::paper_table3());
    assert_eq!(sensor("nav-grade-full"), presets::nav_grade_full());
    assert_eq!(sensor("ideal"), SensorSpec::default());
    assert_eq!(
        Scenario::from_toml("[scenario]\nname = \"x\"\n", "t.toml")
            .unwrap()
            .plant
            .sensor,
        SensorSpec::default(),
        "no [sensor]: ideal"
    );
}

/// Each leaf key of every preset (values of each preset, the defaults included), written alone
/// over each preset as a dotted key and as a one-key section, gives the old path's
/// configuration: the file's key wins, every other key stays the preset's.
#[test]
fn one_key_over_each_preset_gives_the_old_paths_configuration() {
    let mut checked = 0;
    for over in presets::PRESET_NAMES {
        let table = toml::Table::try_from(presets::preset(over).unwrap()).unwrap();
        let mut keys = Vec::new();
        leaves("", &table, &mut keys);
        assert!(keys.len() > 60, "{}", keys.len());
        for base in presets::PRESET_NAMES {
            for (key, value) in &keys {
                let (section, last) = key.rsplit_once('.').unwrap();
                for text in [
                    format!("[sensor]\npreset = \"{base}\"\n{key} = {value}\n"),
                    format!(
                        "[sensor]\npreset = \"{base}\"\n[sensor.{section}]\n{last} = {value}\n"
                    ),
                ] {
                    assert_eq!(new_path_plant(&text), old_path_plant(&text), "{text}");
                    checked += 1;
                }
            }
        }
    }
    println!("{checked} one-key files compared with the old path");
    assert!(checked > 1000, "{checked}");
}

/// Partial sections as people write them: inline tables, several terms, declared effects
/// (arrays of tables), sections beside `[sensor]`, and every preset under them.
#[test]
fn partial_sensor_sections_over_each_preset_give_the_old_paths_configuration() {
    const PARTIALS: [&str; 5] = [
        r#"gyro.bias = { dph = [0.02, 0.0, -0.01] }
accel.scale_factor = { enabled = false }
"#,
        r#"[sensor.gyro.position_bias]
dph_per_k = [1e-4, 2e-4, 3e-4]
transition = "step"
[sensor.accel.bias]
ug = [1.0, 2.0, 3.0]
"#,
        r#"gyro.misalignment.arcsec = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
gyro.g_sensitivity = { enabled = true }
[sensor.temperature.noise]
enabled = true
sigma_k = [0.1, 0.1, 0.1, 0.1, 0.1, 0.1]
"#,
        r#"[sensor.encoder.offset]
enabled = true
arcsec = [10.0, -5.0]
[[sensor.gyro.custom]]
name = "trate"
regressor = "dtemp_dt:block"
unit = "K/s"
axes = ["x", "z"]
coef = [2.0, 0.0, -1.5]
[[sensor.gyro.custom]]
name = "sq"
kind = "scale-factor"
regressor = "temp:block^2"
unit = "K^2"
axes = ["y"]
coef = [0.0, 0.5, 0.0]
"#,
        r#"gyro = {}
accel = { quantization = { enabled = false, pulse = [2e-5, 2e-5, 2e-5] } }
"#,
    ];
    for base in presets::PRESET_NAMES {
        for partial in PARTIALS {
            let text = format!(
                "[scenario]\nname = \"p\"\nduration_s = 60.0\n[run]\nseed = 3\n\
                 [sensor]\npreset = \"{base}\"\n{partial}[site]\nlat_deg = 30.0\n"
            );
            let new = new_path_plant(&text);
            assert_eq!(new, old_path_plant(&text), "{text}");
            assert_eq!(new.site.lat_deg, 30.0);
        }
    }
    // A figure checked by hand: Table 3's bias is on with 0.01 °/h; the file changes only dph.
    let p = new_path_plant(
        "[sensor]\npreset = \"paper-table3\"\ngyro.bias = { dph = [0.02, 0.0, -0.01] }\n",
    );
    assert!(p.sensor.gyro.bias.enabled);
    assert_eq!(p.sensor.gyro.bias.dph, [0.02, 0.0, -0.01]);
    assert_eq!(p.sensor.accel.bias.ug, [50.0; 3]);
}

/// A wrong type inside `[sensor]` now names its line and column (the preset is laid into the
/// file's own document, so the file's spans survive the merge); an unknown key too.
#[test]
fn errors_inside_a_partial_sensor_section_name_the_line() {
    let err = |text: &str| Scenario::from_toml(text, "t.toml").unwrap_err().to_string();
    let e = err("[sensor]\npreset = \"nav-grade-full\"\n[sensor.gyro.bias]\ndph = \"x\"\n");
    assert!(
        e.contains("line 4, column 7") && e.contains("invalid type"),
        "{e}"
    );
    let e = err("[sensor]\npreset = \"paper-table3\"\ngyro.bias.dps = [1.0, 2.0, 3.0]\n");
    assert!(e.contains("line 3") && e.contains("dps"), "{e}");
    // A range error on a declared effect's element names the element's line and column.
    let e = err(r#"[sensor]
preset = "paper-table3"
[[sensor.gyro.custom]]
name = "a"
regressor = "u_x"
unit = "1"
axes = ["x"]
coef = [1.0, 0.0, 0.0]
[[sensor.gyro.custom]]
name = "b"
regressor = "u_y"
unit = "1"
axes = ["y"]
coef = [0.0,
  2e9, 0.0]
"#);
    assert!(
        e.contains("line 15, column 3: sensor.gyro.custom[1].coef[1]"),
        "{e}"
    );
    // An array longer than its type holds is refused (toml's spanned reader alone would drop
    // the extra elements), now with the array's line and column.
    let e = err(
        "[sensor]\npreset = \"paper-table3\"\n[sensor.accel.bias]\nug = [1.0, 2.0, 3.0, 4.0]\n",
    );
    assert!(
        e.contains("line 4, column 6")
            && e.contains("invalid length 4, expected fewer elements in array"),
        "{e}"
    );
    let sc = Scenario::from_toml("[campaign]\ntemps_c = [20.0, 25.0, 30.0, 35.0]\n", "t.toml");
    assert_eq!(
        sc.unwrap().campaign.unwrap().temps_c.len(),
        4,
        "a list takes any length"
    );
    // An integer beyond TOML's 64-bit range is refused where it is written, before any key.
    let e = err("[scenario]\nname = 1.0\n[run]\nseed = 18446744073709551615\n");
    assert!(
        e.contains("line 4, column 8") && e.contains("u64 value was too large"),
        "{e}"
    );
    // An unknown preset is reported after the file's own errors, with its line.
    let e = err("[sensor]\npreset = \"hg9900\"\n");
    assert!(
        e.contains("line 2, column 10: sensor.preset: expected one of"),
        "{e}"
    );
}

/// Overrides join the same document: a range error names the flag (as before), a wrong type
/// names the flag too, and an override cannot hide a file whose section is not a table.
#[test]
fn overrides_are_laid_into_the_document() {
    let o = |flag, path, value| [Override { flag, path, value }];
    let over = o(
        "--rate-hz",
        "run.rate_hz",
        toml::Value::String("fast".into()),
    );
    let e = Scenario::from_toml_with("[scenario]\nname = \"x\"\n", "t.toml", &over)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("t.toml: --rate-hz: invalid type: string \"fast\"") && !e.contains("line"),
        "{e}"
    );
    let over = o(
        "--duration-s",
        "scenario.duration_s",
        toml::Value::Float(7.5),
    );
    let e = Scenario::from_toml_with("scenario = 3\n", "t.toml", &over)
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 1, column 12"), "{e}");
    // A wrong type in the file is not hidden by the flag that replaces the value.
    let e = Scenario::from_toml_with("[scenario]\nduration_s = []\n", "t.toml", &over)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("line 2, column 14") && e.contains("expected f64"),
        "{e}"
    );
    let sc = Scenario::from_toml_with(
        "[scenario]\nname = \"x\"\nduration_s = 99.0\n",
        "t.toml",
        &over,
    )
    .unwrap();
    assert_eq!(sc.meta.duration_s, 7.5);
    // The override on a key the file does not write creates its table.
    let over = o("--rate-hz", "run.rate_hz", toml::Value::Float(200.0));
    let sc = Scenario::from_toml_with("[scenario]\nname = \"x\"\n", "t.toml", &over).unwrap();
    assert_eq!(sc.plant.rate_hz, 200.0);
    let over = o("--rate-hz", "run.rate_hz", toml::Value::Float(1e6));
    let e = Scenario::from_toml_with("[run]\nrate_hz = 100.0\n", "t.toml", &over)
        .unwrap_err()
        .to_string();
    assert!(e.contains("  --rate-hz: run.rate_hz: expected"), "{e}");
}
