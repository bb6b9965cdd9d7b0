//! The built-in scheme files.

use rins_schemes::library::{self, BUILT_IN};

#[test]
fn every_built_in_file_parses_and_round_trips() {
    for (name, _) in BUILT_IN {
        let s = library::built_in(name).unwrap();
        assert_eq!(s.name, name);
        let back = rins_schemes::SchemeFile::parse(&s.to_toml(), "round trip").unwrap();
        assert_eq!(back, s);
    }
}

/// mirror-32 and mirror-64 are what their descriptions say: built from the 16-position
/// scheme by the library's constructions.
#[test]
fn mirror_files_are_their_constructions() {
    let s16 = rins_plant::table::SchemeSpec::default().resolve();
    let steps: Vec<rins_plant::table::RotationStep> = s16
        .steps
        .iter()
        .map(|s| rins_plant::table::RotationStep {
            axis: s.axis,
            angle_deg: s.angle_rad.to_degrees().round(),
            rate_dps: 2.0,
            dwell_s: 180.0,
        })
        .collect();
    let m32 = library::mirrored(&steps);
    assert_eq!(library::built_in("mirror-32").unwrap().scheme.steps, m32);
    let mut m64 = m32.clone();
    m64.extend(library::azimuth_reversed(&m32));
    assert_eq!(library::built_in("mirror-64").unwrap().scheme.steps, m64);
}

#[test]
fn a_bad_scheme_file_names_the_file_and_the_field() {
    let text = "name = \"x\"\n[scheme]\nkind = \"steps\"\nrepeat = true\n[[scheme.steps]]\naxis = \"inner\"\nangle_deg = 0.0\nrate_dps = 2.0\ndwell_s = 10.0\n";
    let err = rins_schemes::SchemeFile::parse(text, "my.toml")
        .unwrap_err()
        .to_string();
    assert!(err.starts_with("my.toml: "), "{err}");
    assert!(err.contains("scheme.steps[0].angle_deg"), "{err}");
    let err =
        rins_schemes::SchemeFile::parse("name = \"x\"\n[scheme]\nkind = \"sideways\"\n", "my.toml")
            .unwrap_err()
            .to_string();
    assert!(err.contains("my.toml") && err.contains("line 3"), "{err}");
}
