//! The Python and C mirrors of the wire types (`transport/wire/rins_wire.py`,
//! `transport/wire/rins_wire.h`) checked against the Rust definitions, the single source of
//! truth: every type's iceoryx2 type name, size and alignment, every field's name, order, type
//! and offset, and the constants (layout version, capacities, flags, command kinds). The mirrors
//! state their numbers in asserts (Python `assert`, C `_Static_assert`), one per line with
//! literal numbers; this test reads those lines with `include_str!`, so a change on any of the
//! three sides fails here until all agree. It also compiles the header (C11 and C++17) when a
//! compiler is on PATH, so the static asserts are known to hold for this machine's ABI.
//!
//! Included by `layout.rs` as its test module `layout::wire`.

use super::*;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

const PY: &str = include_str!("../../wire/rins_wire.py");
const H: &str = include_str!("../../wire/rins_wire.h");

/// One field as a language states it: name, offset (bytes) and type in Rust spelling
/// (`u64`, `[f64; 3]`, `[ImuRecord; 64]`).
#[derive(Debug, Clone, PartialEq)]
struct Field {
    name: String,
    offset: usize,
    ty: String,
}

/// One wire type as a language states it. Keyed by the Rust struct name (`ImuBatch`).
#[derive(Debug, Clone, Default, PartialEq)]
struct TypeLayout {
    type_name: String,
    size: usize,
    align: usize,
    /// Declaration order, with their types (offsets are not in declarations, so 0 here when
    /// parsed from a mirror; the asserts give them).
    fields: Vec<Field>,
    /// Offsets the asserts state, by field name.
    offsets: BTreeMap<String, usize>,
}

/// Rust's type name of a field, without the crate path (`[rins_transport::layout::ImuRecord; 64]`
/// becomes `[ImuRecord; 64]`).
fn short(ty: &str) -> String {
    ty.replace("rins_transport::layout::", "")
}

/// A wire type's Rust layout. The struct pattern without `..` makes a field added to the Rust
/// type a compile error here until it is listed (and so compared with the mirrors).
macro_rules! rust_layout {
    ($t:ident { $($f:ident),+ $(,)? }) => {{
        let v = <$t>::default();
        let $t { $($f),+ } = &v;
        let fields = vec![$(Field {
            name: stringify!($f).to_string(),
            offset: std::mem::offset_of!($t, $f),
            ty: short(std::any::type_name_of_val($f)),
        }),+];
        let sizes = vec![$(std::mem::size_of_val($f)),+];
        // SAFETY: type_name only returns the name given in #[type_name(...)]; the layouts it
        // vouches for are exactly what this test compares.
        let type_name = unsafe { <$t as ZeroCopySend>::type_name() }.to_string();
        let offsets = fields.iter().map(|f| (f.name.clone(), f.offset)).collect();
        (
            stringify!($t).to_string(),
            TypeLayout {
                type_name,
                size: std::mem::size_of::<$t>(),
                align: std::mem::align_of::<$t>(),
                fields,
                offsets,
            },
            sizes,
        )
    }};
}

/// The six wire types as Rust lays them out, with each field's size.
fn rust_layouts() -> Vec<(String, TypeLayout, Vec<usize>)> {
    vec![
        rust_layout!(ImuRecord {
            tick,
            t_s,
            dtheta_rad,
            dv_mps,
            outer_rad,
            inner_rad,
            temps_c
        }),
        rust_layout!(TruthRecord {
            lat_rad,
            lon_rad,
            height_m,
            v_enu_mps,
            q_cn,
            q_bn
        }),
        rust_layout!(StartRecord {
            tick,
            t_s,
            lat_rad,
            lon_rad,
            height_m,
            v_enu_mps,
            q_bn
        }),
        rust_layout!(ImuBatch {
            layout_version,
            record_size,
            seq,
            count,
            flags,
            records,
            truth,
            start,
            reason
        }),
        rust_layout!(NavCommand {
            layout_version,
            kind,
            ack_seq,
            outer_rad,
            inner_rad,
            rate_rps
        }),
        rust_layout!(NavSolution {
            seq,
            tick,
            lat_rad,
            lon_rad,
            height_m,
            v_n,
            q_bn
        }),
    ]
}

/// The Rust constants the mirrors repeat, under the mirrors' names (`kind::ACK` is `KIND_ACK`).
fn rust_constants() -> BTreeMap<String, u64> {
    [
        ("LAYOUT_VERSION", u64::from(LAYOUT_VERSION)),
        ("BATCH_CAPACITY", BATCH_CAPACITY as u64),
        ("REASON_BYTES", REASON_BYTES as u64),
        ("FLAG_END", u64::from(FLAG_END)),
        ("FLAG_INTERRUPTED", u64::from(FLAG_INTERRUPTED)),
        ("FLAG_REFUSED", u64::from(FLAG_REFUSED)),
        ("FLAG_TRUTH", u64::from(FLAG_TRUTH)),
        ("KIND_ACK", u64::from(kind::ACK)),
        ("KIND_MOVE_TO", u64::from(kind::MOVE_TO)),
        ("KIND_STOP", u64::from(kind::STOP)),
        ("KIND_HELLO", u64::from(kind::HELLO)),
        (
            "KIND_AZIMUTH_ISOLATION_ON",
            u64::from(kind::AZIMUTH_ISOLATION_ON),
        ),
        (
            "KIND_AZIMUTH_ISOLATION_OFF",
            u64::from(kind::AZIMUTH_ISOLATION_OFF),
        ),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect()
}

/// What a mirror file states: its types (by Rust struct name) and its constants.
#[derive(Debug, Default)]
struct Mirror {
    types: BTreeMap<String, TypeLayout>,
    constants: BTreeMap<String, u64>,
}

/// A number in a mirror, or a constant of the same file (array lengths).
fn number(text: &str, constants: &BTreeMap<String, u64>, at: &str) -> Result<usize, String> {
    let text = text.trim();
    text.parse::<usize>()
        .ok()
        .or_else(|| constants.get(text).map(|&v| v as usize))
        .ok_or_else(|| format!("{at}: {text:?} is neither a number nor a constant of the file"))
}

/// `text` between `open` and the last `close` after it (`sizeof(X) == 3, "m"` → `X`).
fn between<'a>(text: &'a str, open: &str, close: &str) -> Option<&'a str> {
    let rest = text.strip_prefix(open)?;
    Some(&rest[..rest.find(close)?])
}

/// A Python field type in Rust spelling: `ctypes.c_double * 3` → `[f64; 3]`. `c_char` is one
/// byte, Rust's u8 (the module uses it so that `reason` reads as `bytes`).
fn python_type(text: &str, constants: &BTreeMap<String, u64>, at: &str) -> Result<String, String> {
    if let Some((element, n)) = text.split_once('*') {
        let element = python_type(element.trim(), constants, at)?;
        return Ok(format!("[{element}; {}]", number(n, constants, at)?));
    }
    Ok(match text.trim() {
        "ctypes.c_uint64" => "u64".to_string(),
        "ctypes.c_uint32" => "u32".to_string(),
        "ctypes.c_uint8" | "ctypes.c_char" => "u8".to_string(),
        "ctypes.c_double" => "f64".to_string(),
        other if other.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') => other.to_string(),
        other => {
            return Err(format!(
                "{at}: field type {other:?} is not one this test reads"
            ));
        }
    })
}

/// Reads rins_wire.py: `NAME = N` constants, `class X(ctypes.Structure)` bodies (`_fields_`
/// entries `("name", TYPE),` and the `type_name()` return value) and the layout asserts.
fn parse_python(text: &str) -> Result<Mirror, String> {
    let mut m = Mirror::default();
    let mut class: Option<String> = None;
    for (k, raw) in text.lines().enumerate() {
        let at = format!("rins_wire.py line {}", k + 1);
        let line = raw.trim();
        if !raw.starts_with(' ') && !raw.is_empty() {
            class = None;
        }
        if let Some((name, value)) = line.split_once(" = ")
            && !raw.starts_with(' ')
            && name.chars().all(|c| c.is_ascii_uppercase() || c == '_')
        {
            let v = value.parse::<u64>().map_err(|e| format!("{at}: {e}"))?;
            m.constants.insert(name.to_string(), v);
        } else if let Some(name) = between(line, "class ", "(ctypes.Structure):") {
            class = Some(name.to_string());
            m.types.entry(name.to_string()).or_default();
        } else if let (Some(c), Some(entry)) = (&class, line.strip_prefix("(\"")) {
            let (name, ty) = entry
                .strip_suffix("),")
                .and_then(|e| e.split_once("\", "))
                .ok_or_else(|| format!("{at}: a field entry is (\"name\", TYPE),"))?;
            let ty = python_type(ty, &m.constants, &at)?;
            let t = m.types.get_mut(c).expect("class entered");
            t.fields.push(Field {
                name: name.to_string(),
                offset: 0,
                ty,
            });
        } else if let (Some(c), Some(name)) = (&class, between(line, "return \"", "\"")) {
            m.types.get_mut(c).expect("class entered").type_name = name.to_string();
        } else if let Some(assertion) = line.strip_prefix("assert ") {
            let (lhs, rhs) = assertion
                .split_once(" == ")
                .ok_or_else(|| format!("{at}: a layout assert is `assert LHS == N`"))?;
            let n = number(rhs.split(',').next().unwrap_or(rhs), &BTreeMap::new(), &at)?;
            if let Some(t) = between(lhs, "ctypes.sizeof(", ")") {
                m.types.entry(t.to_string()).or_default().size = n;
            } else if let Some(t) = between(lhs, "ctypes.alignment(", ")") {
                m.types.entry(t.to_string()).or_default().align = n;
            } else if let Some(path) = lhs.strip_suffix(".offset")
                && let Some((t, f)) = path.split_once('.')
            {
                let t = m.types.entry(t.to_string()).or_default();
                if t.offsets.insert(f.to_string(), n).is_some() {
                    return Err(format!("{at}: a second offset assert for {path}"));
                }
            } else {
                return Err(format!("{at}: assert {lhs:?} is not one this test reads"));
            }
        }
    }
    Ok(m)
}

/// A C field type in Rust spelling: `double` → `f64`, `rins_ImuRecord` → `ImuRecord`.
fn c_type(text: &str, at: &str) -> Result<String, String> {
    Ok(match text {
        "uint64_t" => "u64".to_string(),
        "uint32_t" => "u32".to_string(),
        "uint8_t" => "u8".to_string(),
        "double" => "f64".to_string(),
        other => match other.strip_prefix("rins_") {
            Some(t) => t.to_string(),
            None => {
                return Err(format!(
                    "{at}: field type {other:?} is not one this test reads"
                ));
            }
        },
    })
}

/// Reads rins_wire.h: `#define RINS_NAME N` constants, `#define RINS_X_TYPE_NAME "…"`,
/// `typedef struct rins_X { … } rins_X;` bodies and the `_Static_assert` lines.
fn parse_header(text: &str) -> Result<Mirror, String> {
    let mut m = Mirror::default();
    let mut names: BTreeMap<String, String> = BTreeMap::new();
    let mut current: Option<String> = None;
    for (k, raw) in text.lines().enumerate() {
        let at = format!("rins_wire.h line {}", k + 1);
        let line = raw.trim();
        if let Some(def) = line.strip_prefix("#define RINS_") {
            let Some((name, value)) = def.split_once(' ') else {
                continue;
            };
            if let Some(s) = value.strip_prefix('"').and_then(|v| v.strip_suffix('"')) {
                names.insert(format!("RINS_{name}"), s.to_string());
            } else if let Ok(v) = value.parse::<u64>() {
                m.constants.insert(name.to_string(), v);
            }
        } else if let Some(t) = between(line, "typedef struct rins_", " {") {
            current = Some(t.to_string());
            m.types.entry(t.to_string()).or_default();
        } else if line.starts_with('}') {
            current = None;
        } else if let Some(t) = &current {
            if line.starts_with("/*") || line.starts_with('*') || line.is_empty() {
                continue;
            }
            if let Some(macro_name) = between(line, "RINS_WIRE_TYPE_NAME(", ")") {
                let name = names
                    .get(macro_name)
                    .ok_or_else(|| format!("{at}: {macro_name} is not defined above"))?;
                m.types.get_mut(t).expect("struct entered").type_name = name.clone();
                continue;
            }
            let decl = line
                .strip_suffix(';')
                .ok_or_else(|| format!("{at}: a field is `TYPE NAME;` or `TYPE NAME[N];`"))?;
            let (ty, name) = decl
                .split_once(' ')
                .ok_or_else(|| format!("{at}: a field is `TYPE NAME;`"))?;
            let mut ty = c_type(ty, &at)?;
            let mut name = name.to_string();
            if let Some((n, dim)) = name.clone().split_once('[') {
                let dim = dim.strip_suffix(']').unwrap_or(dim);
                let dim = dim.strip_prefix("RINS_").unwrap_or(dim);
                ty = format!("[{ty}; {}]", number(dim, &m.constants, &at)?);
                name = n.to_string();
            }
            let t = m.types.get_mut(t).expect("struct entered");
            t.fields.push(Field {
                name,
                offset: 0,
                ty,
            });
        } else if let Some(assertion) = between(line, "_Static_assert(", ", \"") {
            let (lhs, rhs) = assertion.split_once(" == ").ok_or_else(|| {
                format!("{at}: a layout assert is `_Static_assert(LHS == N, \"…\");`")
            })?;
            let n = number(rhs, &BTreeMap::new(), &at)?;
            if let Some(t) = between(lhs, "sizeof(rins_", ")") {
                m.types.entry(t.to_string()).or_default().size = n;
            } else if let Some(t) = between(lhs, "_Alignof(rins_", ")") {
                m.types.entry(t.to_string()).or_default().align = n;
            } else if let Some((t, f)) =
                between(lhs, "offsetof(rins_", ")").and_then(|p| p.split_once(", "))
            {
                let layout = m.types.entry(t.to_string()).or_default();
                if layout.offsets.insert(f.to_string(), n).is_some() {
                    return Err(format!("{at}: a second offset assert for rins_{t}.{f}"));
                }
            } else {
                return Err(format!(
                    "{at}: _Static_assert of {lhs:?} is not one this test reads"
                ));
            }
        }
    }
    Ok(m)
}

/// Every difference between a mirror and the Rust layouts, each naming the file, type, field
/// and both values; empty when they agree.
fn differences(file: &str, mirror: &Mirror) -> Vec<String> {
    let mut out = Vec::new();
    let rust: BTreeMap<String, TypeLayout> = rust_layouts()
        .into_iter()
        .map(|(name, layout, _)| (name, layout))
        .collect();
    for name in mirror.types.keys().filter(|n| !rust.contains_key(*n)) {
        out.push(format!("{file}: type {name} is not a Rust wire type"));
    }
    for (name, want) in &rust {
        let Some(got) = mirror.types.get(name) else {
            out.push(format!("{file}: type {name} is missing"));
            continue;
        };
        for (what, g, w) in [
            ("size", got.size, want.size),
            ("alignment", got.align, want.align),
        ] {
            if g != w {
                out.push(format!("{file}: {name} {what} is {g}, Rust's is {w}"));
            }
        }
        if got.type_name != want.type_name {
            out.push(format!(
                "{file}: {name} type name is {:?}, Rust's is {:?}",
                got.type_name, want.type_name
            ));
        }
        let declared: Vec<(&str, &str)> = got
            .fields
            .iter()
            .map(|f| (f.name.as_str(), f.ty.as_str()))
            .collect();
        let rust_declared: Vec<(&str, &str)> = want
            .fields
            .iter()
            .map(|f| (f.name.as_str(), f.ty.as_str()))
            .collect();
        // The first declaration that differs (name, type or position), or a missing or extra
        // field at the end.
        let n = declared.len().max(rust_declared.len());
        if let Some(k) = (0..n).find(|&k| declared.get(k) != rust_declared.get(k)) {
            let show = |f: Option<&(&str, &str)>| match f {
                Some((field, ty)) => format!("`{field}: {ty}`"),
                None => "nothing".to_string(),
            };
            out.push(format!(
                "{file}: {name} field {k} is {}, Rust's is {} (names, types and order must match)",
                show(declared.get(k)),
                show(rust_declared.get(k))
            ));
        }
        for (field, w) in &want.offsets {
            match got.offsets.get(field) {
                Some(g) if g == w => {}
                Some(g) => out.push(format!(
                    "{file}: {name}.{field} offset is {g}, Rust's is {w}"
                )),
                None => out.push(format!(
                    "{file}: {name}.{field} has no offset assert (Rust's offset is {w})"
                )),
            }
        }
        for field in got
            .offsets
            .keys()
            .filter(|f| !want.offsets.contains_key(*f))
        {
            out.push(format!(
                "{file}: {name}.{field} is asserted but Rust has no such field"
            ));
        }
    }
    let want = rust_constants();
    for (k, w) in &want {
        match mirror.constants.get(k) {
            Some(g) if g == w => {}
            Some(g) => out.push(format!("{file}: constant {k} is {g}, Rust's is {w}")),
            None => out.push(format!("{file}: constant {k} is missing (Rust's is {w})")),
        }
    }
    for k in mirror.constants.keys().filter(|k| !want.contains_key(*k)) {
        out.push(format!("{file}: constant {k} has no Rust counterpart"));
    }
    out
}

/// Both mirrors against Rust.
fn all_differences(py: &str, h: &str) -> Vec<String> {
    let mut out = Vec::new();
    match parse_python(py) {
        Ok(m) => out.extend(differences("rins_wire.py", &m)),
        Err(e) => out.push(e),
    }
    match parse_header(h) {
        Ok(m) => out.extend(differences("rins_wire.h", &m)),
        Err(e) => out.push(e),
    }
    out
}

#[test]
fn the_rust_fields_tile_each_type_without_padding() {
    // With no gaps, the fields listed in rust_layouts() account for every byte, so none is
    // left out of the comparison (the struct patterns make that a compile error too).
    for (name, t, sizes) in rust_layouts() {
        let mut end = 0;
        for (f, size) in t.fields.iter().zip(&sizes) {
            assert_eq!(
                f.offset, end,
                "{name}.{} does not follow the field before it",
                f.name
            );
            end += size;
        }
        assert_eq!(
            end, t.size,
            "{name}: its fields end at {end}, the type at {}",
            t.size
        );
        assert_eq!(t.align, 8, "{name}");
    }
}

#[test]
fn the_python_and_c_mirrors_state_the_rust_layout() {
    let py = parse_python(PY).expect("rins_wire.py parses");
    let h = parse_header(H).expect("rins_wire.h parses");
    // Six types, 7 + 6 + 7 + 9 + 6 + 7 = 42 fields, in both files.
    for m in [&py, &h] {
        assert_eq!(m.types.len(), 6);
        let fields: usize = m.types.values().map(|t| t.offsets.len()).sum();
        assert_eq!(fields, 42);
    }
    let diffs = all_differences(PY, H);
    assert!(
        diffs.is_empty(),
        "the mirrors differ from transport/src/layout.rs:\n{}",
        diffs.join("\n")
    );
}

#[test]
fn a_changed_number_on_either_side_is_reported() {
    let cases = [
        (
            PY.replace(
                "ImuBatch.truth.offset == 8216",
                "ImuBatch.truth.offset == 8224",
            ),
            H.to_string(),
            "rins_wire.py: ImuBatch.truth offset is 8224, Rust's is 8216",
        ),
        (
            PY.to_string(),
            H.replace(
                "offsetof(rins_NavCommand, kind) == 4",
                "offsetof(rins_NavCommand, kind) == 8",
            ),
            "rins_wire.h: NavCommand.kind offset is 8, Rust's is 4",
        ),
        (
            PY.replace(
                "ctypes.sizeof(StartRecord) == 96",
                "ctypes.sizeof(StartRecord) == 88",
            ),
            H.to_string(),
            "rins_wire.py: StartRecord size is 88, Rust's is 96",
        ),
        (
            PY.to_string(),
            H.replace(
                "#define RINS_LAYOUT_VERSION 3",
                "#define RINS_LAYOUT_VERSION 4",
            ),
            "rins_wire.h: constant LAYOUT_VERSION is 4, Rust's is 3",
        ),
        (
            PY.replace("return \"rins::NavSolution\"", "return \"NavSolution\""),
            H.to_string(),
            "rins_wire.py: NavSolution type name is \"NavSolution\", Rust's is \"rins::NavSolution\"",
        ),
        (
            PY.replace(
                "(\"tick\", ctypes.c_uint64),\n        # Time of",
                "(\"tick\", ctypes.c_double),\n        # Time of",
            ),
            H.to_string(),
            "rins_wire.py: StartRecord field 0 is `tick: f64`, Rust's is `tick: u64`",
        ),
        (
            PY.to_string(),
            H.replace("    double v_n[3];", "    double v_n[4];"),
            "rins_wire.h: NavSolution field 5 is `v_n: [f64; 4]`, Rust's is `v_n: [f64; 3]`",
        ),
        (
            PY.replace("assert NavSolution.q_bn.offset == 64\n", ""),
            H.to_string(),
            "rins_wire.py: NavSolution.q_bn has no offset assert (Rust's offset is 64)",
        ),
    ];
    for (py, h, want) in cases {
        assert_ne!(
            (py.as_str(), h.as_str()),
            (PY, H),
            "the case must change a file: {want}"
        );
        let diffs = all_differences(&py, &h);
        assert!(
            diffs.iter().any(|d| d.starts_with(want)),
            "expected a difference starting {want:?}, got {diffs:?}"
        );
    }
}

/// Compiles `header` with `compiler` and `args`; None when the compiler is not installed.
fn compile(compiler: &str, args: &[&str], header: &Path) -> Option<std::process::Output> {
    match Command::new(compiler).args(args).arg(header).output() {
        Ok(out) => Some(out),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
        Err(e) => panic!("running {compiler}: {e}"),
    }
}

#[test]
fn the_header_compiles_and_its_static_asserts_hold() {
    let header = Path::new(env!("CARGO_MANIFEST_DIR")).join("wire/rins_wire.h");
    // A header with one wrong offset must fail on this ABI: the asserts are really evaluated.
    let bad = std::env::temp_dir().join(format!("rins_wire_bad_{}.h", std::process::id()));
    std::fs::write(
        &bad,
        H.replace(
            "offsetof(rins_ImuBatch, start) == 15384",
            "offsetof(rins_ImuBatch, start) == 15392",
        ),
    )
    .expect("write the temporary header");
    for (compiler, lang) in [
        ("cc", ["-std=c11", "-x", "c"]),
        ("c++", ["-std=c++17", "-x", "c++"]),
    ] {
        let args = [
            &lang[..],
            &["-Wall", "-Wextra", "-pedantic", "-Werror", "-fsyntax-only"],
        ]
        .concat();
        let Some(out) = compile(compiler, &args, &header) else {
            println!(
                "note: {compiler} is not installed; rins_wire.h not compiled as {}",
                lang[2]
            );
            continue;
        };
        assert!(
            out.status.success(),
            "{compiler} {args:?} rins_wire.h failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let out = compile(compiler, &args, &bad).expect("the compiler ran a moment ago");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{compiler} accepted a wrong offset");
        assert!(
            err.contains("rins_ImuBatch.start"),
            "{compiler} said: {err}"
        );
        println!(
            "{compiler} {}: rins_wire.h compiles, a wrong offset is refused",
            args.join(" ")
        );
    }
    std::fs::remove_file(&bad).ok();
}
