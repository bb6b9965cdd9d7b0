//! The FMI type name of every enumeration parameter of the plant, in one table: an
//! enumeration's `TypeDefinitions` entry (FMI 2 `SimpleType`, FMI 3 `EnumerationType`) is named
//! for the enumeration, not for the model or the first key that uses it.
//!
//! The names are the plant's Rust enum types (`SchemeKind`, `GimbalAxis`, `CarrierKind`), with
//! two spelled out where the Rust name only makes sense inside its module: the gyro's
//! `Transition` is `PositionBiasTransition` and the carrier's `SpectrumKind` is `WaveSpectrum`,
//! the names the FMUs have published since their first release (docs/fmu.md, masters' scripts).

/// `(scenario key, FMI type name)` for every key of [`rins_plant::params::ENUMS`].
pub const ENUM_TYPES: &[(&str, &str)] = &[
    ("scheme.kind", "SchemeKind"),
    ("scheme.axis", "GimbalAxis"),
    (
        "sensor.gyro.position_bias.transition",
        "PositionBiasTransition",
    ),
    ("carrier.kind", "CarrierKind"),
    ("carrier.ship.sea.spectrum", "WaveSpectrum"),
    ("carrier.ship.sea.realisation", "SeaRealisation"),
];

/// The FMI type name of the enumeration at key path `path` (array indices ignored), or `None`
/// when `path` is no enumeration of [`ENUM_TYPES`].
pub fn enum_type_name(path: &str) -> Option<&'static str> {
    let key = rins_plant::params::key_of(path);
    ENUM_TYPES
        .iter()
        .find(|(k, _)| *k == key)
        .map(|(_, name)| *name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rins_plant::params::ENUMS;

    /// A new enumeration in the plant without a type name here would fail when a model's table
    /// is built: this names it first.
    #[test]
    fn every_plant_enumeration_has_one_type_name_and_no_name_is_shared() {
        for (key, _) in ENUMS {
            assert!(
                enum_type_name(key).is_some(),
                "{key} has no FMI type name in ENUM_TYPES"
            );
        }
        assert_eq!(
            ENUM_TYPES.len(),
            ENUMS.len(),
            "ENUM_TYPES lists a key the plant lacks"
        );
        let mut names: Vec<&str> = ENUM_TYPES.iter().map(|(_, n)| *n).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(
            names.len(),
            ENUM_TYPES.len(),
            "two enumerations share a type name"
        );
        assert_eq!(
            enum_type_name("carrier.ship.sea.spectrum"),
            Some("WaveSpectrum")
        );
        assert_eq!(enum_type_name("scheme.rate_dps"), None);
    }

    /// The names are the Rust enums' own where those stand alone.
    #[test]
    fn type_names_follow_the_rust_enums() {
        let last = |full: &'static str| full.rsplit("::").next().unwrap_or(full);
        let cfg = rins_plant::presets::paper_16pos_config();
        assert_eq!(
            enum_type_name("scheme.kind"),
            Some(last(std::any::type_name_of_val(&cfg.scheme.kind)))
        );
        assert_eq!(
            enum_type_name("scheme.axis"),
            Some(last(std::any::type_name_of_val(&cfg.scheme.axis)))
        );
        assert_eq!(
            enum_type_name("carrier.kind"),
            Some(last(std::any::type_name_of_val(&cfg.carrier.kind)))
        );
        assert_eq!(
            enum_type_name("carrier.ship.sea.realisation"),
            Some(last(std::any::type_name_of_val(
                &cfg.carrier.ship.sea.realisation
            )))
        );
    }
}
