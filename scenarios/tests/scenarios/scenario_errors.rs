//! Scenario errors name where the bad value was written: line and column from the TOML parser
//! (inline tables and arrays included), or the command-line flag that set it.

use rins_scenarios::{Override, Scenario};

fn err(text: &str) -> String {
    Scenario::from_toml(text, "t.toml").unwrap_err().to_string()
}

#[test]
fn an_inline_table_value_out_of_range_names_its_line_and_column() {
    let e = err(
        "[scenario]\nname = \"x\"\n[sensor]\ngyro.bias = { enabled = true, dph = [500.0, 0.0, 0.0] }\n",
    );
    assert!(
        e.contains("line 4, column 38: sensor.gyro.bias.dph[0]"),
        "{e}"
    );
    assert!(e.contains("500"), "{e}");
}

#[test]
fn nan_is_reported_as_nan() {
    let e = err("[scenario]\nname = \"x\"\n[site]\nlat_deg = nan\n");
    assert!(e.contains("line 4, column 11: site.lat_deg"), "{e}");
    assert!(e.contains("got NaN"), "{e}");
    assert!(!e.contains("inf"), "{e}");
}

#[test]
fn an_empty_or_comment_only_file_is_refused() {
    for text in ["", "  \n", "# only a comment\n"] {
        let e = err(text);
        assert!(e.contains("t.toml") && e.contains("no keys"), "{e}");
    }
}

#[test]
fn a_bad_override_names_its_flag_and_is_validated_once_with_the_file() {
    let o = [Override {
        flag: "--duration-s",
        path: "scenario.duration_s",
        value: toml::Value::Float(-5.0),
    }];
    let e = Scenario::from_toml_with("[scenario]\nname = \"x\"\n", "t.toml", &o)
        .unwrap_err()
        .to_string();
    assert!(e.contains("--duration-s: scenario.duration_s"), "{e}");
    let ok = [Override {
        flag: "--seed",
        path: "run.seed",
        value: toml::Value::Integer(42),
    }];
    let sc = Scenario::from_toml_with("[scenario]\nname = \"x\"\n", "t.toml", &ok).unwrap();
    assert_eq!(sc.plant.seed, 42);
}

#[test]
fn encoder_and_temperature_sensor_keys_are_scenario_keys() {
    let sc = Scenario::from_toml(
        "[scenario]\nname = \"x\"\n[sensor.encoder.offset]\nenabled = true\narcsec = [10.0, -5.0]\n[sensor.temperature.noise]\nenabled = true\nsigma_k = [0.1, 0.1, 0.1, 0.1, 0.1, 0.1]\n",
        "t.toml",
    )
    .unwrap();
    assert_eq!(sc.plant.sensor.encoder.offset.arcsec, [10.0, -5.0]);
    let e = err(
        "[scenario]\nname = \"x\"\n[sensor.temperature.noise]\nsigma_k = [0.1, 0.1, 99.0, 0.1, 0.1, 0.1]\n",
    );
    assert!(
        e.contains("line 4, column 22: sensor.temperature.noise.sigma_k[2]"),
        "{e}"
    );
}
