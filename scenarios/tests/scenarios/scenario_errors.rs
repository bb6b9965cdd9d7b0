//! Scenario errors name where the bad value was written: line and column from the TOML parser
//! (inline tables and arrays included), or the command-line flag that set it.

use rins_scenario::{Override, Scenario};

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

/// Issue 44: a bad number is echoed as it reads, not as hundreds of digits (1e300 was printed
/// with 301, 1e-300 with 302 characters) nor as digits that look exact (2^63 - 1 given to a
/// real-valued key read "9223372036854776000"); an infinite value is said to need to be finite,
/// and a sea height or period outside its range is reported by its range alone (it also gave
/// "tp_s above inf s … (steepness inf)").
#[test]
fn huge_tiny_and_infinite_numbers_are_echoed_readably() {
    let e = err(
        "[scenario]\nname = \"x\"\n[site]\nlat_deg = 9223372036854775807\n\
         [sensor]\ngyro.bias = { enabled = true, dph = [1e300, -1e-300, 0.0] }\n\
         [carrier]\nkind = \"ship\"\n[carrier.ship.sea]\nspectrum = \"jonswap\"\nhs_m = inf\ntp_s = 1e-300\n",
    );
    let want = "t.toml: invalid scenario:\n\
        \x20 line 4, column 11: site.lat_deg: expected a number in [-89, 89], got 9.223372036854776e18\n\
        \x20 line 6, column 38: sensor.gyro.bias.dph[0]: expected a number in [-100, 100], got 1e300\n\
        \x20 line 11, column 8: carrier.ship.sea.hs_m: expected a finite number in [0, 20], got inf\n\
        \x20 line 12, column 8: carrier.ship.sea.tp_s: expected a number in [2, 30], got 1e-300";
    assert_eq!(e, want);
    // In range, too steep: the limits are finite numbers, written short.
    let e = err(
        "[scenario]\nname = \"x\"\n[carrier]\nkind = \"ship\"\n[carrier.ship.sea]\n\
         spectrum = \"jonswap\"\nhs_m = 20\ntp_s = 2\n",
    );
    assert_eq!(
        e,
        "t.toml: invalid scenario:\n\
         \x20 line 7, column 8: carrier.ship.sea.hs_m: expected a significant wave height below \
         λp/7 = 0.892 m for tp_s = 2 s (significant steepness Hs/λp < 1/7, λp = g·Tp²/(2π) = \
         6.243 m: steeper waves break), or tp_s above 9.471 s for this height, got hs_m = 20 \
         (steepness 3.204)"
    );
}
