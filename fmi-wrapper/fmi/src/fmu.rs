//! A model's FMU headers and instantiation tokens, from its [`ModelInfo`] and variable table.

use std::any::TypeId;
use std::sync::Mutex;

use crate::model::Model;
use crate::standard::FmiVersion;
use crate::xml::{Header, model_description};

/// Model identifier (binary and `.fmu` name) of `M`'s FMU for `version`.
pub fn model_identifier<M: Model>(version: FmiVersion) -> &'static str {
    match version {
        FmiVersion::V2 => M::INFO.fmi2_id,
        FmiVersion::V3 => M::INFO.fmi3_id,
    }
}

/// The modelDescription header of `M`'s FMU for `version`.
pub fn header<M: Model>(version: FmiVersion) -> Header {
    Header {
        model_identifier: model_identifier::<M>(version).into(),
        description: M::INFO.description.into(),
        generation_tool: format!("rins-fmi {}", env!("CARGO_PKG_VERSION")),
        stop_time_s: M::INFO.stop_time_s,
        step_size_s: M::INFO.step_size_s,
    }
}

/// modelDescription.xml and token of `M`'s FMU for `version`, computed once per model and
/// version (a pure function of the code; instantiation compares tokens on every call).
///
/// # Panics
/// If `M`'s table cannot be described ([`model_description`]): a bug of the model's code, like
/// a malformed table. The FMI entry points that reach this call it inside `catch_unwind`.
pub fn description<M: Model>(version: FmiVersion) -> &'static (String, String) {
    // A `static` in a generic function is shared by every `M`: key the memo by type. Entries
    // are computed once and never change, so leaking them gives plain `&'static` references.
    type Memo = Vec<(TypeId, FmiVersion, &'static (String, String))>;
    static MEMO: Mutex<Memo> = Mutex::new(Vec::new());
    let key = TypeId::of::<M>();
    let mut memo = MEMO.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, _, d)) = memo.iter().find(|(t, v, _)| *t == key && *v == version) {
        return d;
    }
    let h = header::<M>(version);
    let d = model_description(version, M::table(), &h)
        .unwrap_or_else(|e| panic!("modelDescription of {}: {e}", h.model_identifier));
    let d: &'static (String, String) = Box::leak(Box::new(d));
    memo.push((key, version, d));
    d
}
