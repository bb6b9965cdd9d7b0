//! The sensor presets in the scenario format: each is the `[sensor]` keys it sets, written as a
//! TOML fragment (`scenarios/scenario/files/presets/NAME.toml`), so that a preset and a file's own
//! `[sensor]` keys meet in one document and are read into the typed configuration once.
//! `rins_plant::presets` keeps the same presets as Rust constructors for callers without a
//! scenario file; the two are tested equal (tests/scenarios/preset_path.rs).

use std::sync::LazyLock;

use toml::de::DeTable;

/// Each preset's name and fragment text, in the order of `rins_plant::presets::PRESET_NAMES`.
const TEXTS: [(&str, &str); 3] = [
    (
        "paper-table3",
        include_str!("../../files/presets/paper-table3.toml"),
    ),
    (
        "nav-grade-full",
        include_str!("../../files/presets/nav-grade-full.toml"),
    ),
    // Every term off: the plant's defaults.
    ("ideal", ""),
];

/// The fragments, parsed once per process.
static FRAGMENTS: LazyLock<Vec<(&'static str, DeTable<'static>)>> = LazyLock::new(|| {
    TEXTS
        .iter()
        .map(|(name, text)| {
            let table = DeTable::parse(text)
                .unwrap_or_else(|e| panic!("preset fragment {name} does not parse: {e}"));
            (*name, table.into_inner())
        })
        .collect()
});

/// The `[sensor]` keys the preset called `name` sets, if there is such a preset.
pub(super) fn fragment(name: &str) -> Option<&'static DeTable<'static>> {
    FRAGMENTS.iter().find(|(n, _)| *n == name).map(|(_, t)| t)
}
