//! The FMU's variable table: one row per scalar ("slot"). FMI 2 gives every slot its own value
//! reference; FMI 3 groups the slots of one array (`a.b[0..3]`) into one
//! Float64 array variable. Both modelDescriptions and both C APIs are generated from this table.
//!
//! FMI 3 also gets one scalar variable per array element, named as in FMI 2 (`a.b[2]`), after
//! all other variables: masters that read every FMI 3 variable as a scalar (ecos 0.7.2 passes
//! `nValues` 1) can connect, set and read the elements, and one SSP file or `.ssv` set serves
//! both FMI versions. Such an element variable is a view of the array's slot: setting either
//! sets both.

use std::ops::Range;

use rins_message::Num;

use crate::standard::FmiVersion;

/// Type of a scalar.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// 64-bit float (FMI 2 Real, FMI 3 Float64).
    Real,
    /// Non-negative whole number (FMI 2 Integer 0…2³¹−1, FMI 3 UInt64).
    Integer,
    /// Switch (FMI 2/3 Boolean).
    Boolean,
    /// One of named items, numbered from 1 (FMI 2 Integer-valued, FMI 3 Int64-valued).
    Enumeration {
        /// Type name in TypeDefinitions.
        type_name: &'static str,
        /// Item names, value i+1 for item i.
        items: &'static [&'static str],
    },
}

impl Kind {
    /// The type's name in the C API of `version`: what its getter and setter are called after
    /// (`fmi2GetReal`, `fmi3GetFloat64`; FMI 3 Enumerations travel as Int64).
    pub fn accessor(self, version: FmiVersion) -> &'static str {
        match (self, version) {
            (Kind::Real, FmiVersion::V2) => "Real",
            (Kind::Real, FmiVersion::V3) => "Float64",
            (Kind::Integer | Kind::Enumeration { .. }, FmiVersion::V2) => "Integer",
            (Kind::Integer, FmiVersion::V3) => "UInt64",
            (Kind::Enumeration { .. }, FmiVersion::V3) => "Int64",
            (Kind::Boolean, _) => "Boolean",
        }
    }

    /// The type as the modelDescription of `version` declares it, with its article
    /// ("a Float64", "an Enumeration (Colour)"): for messages.
    pub fn described(self, version: FmiVersion) -> String {
        match self {
            Kind::Enumeration { type_name, .. } => format!("an Enumeration ({type_name})"),
            k => with_article(k.accessor(version)),
        }
    }
}

/// `word` with "a" or "an" before it, by its first sound ("an Int32", "a Float64",
/// "a UInt64": U is said "you").
pub fn with_article(word: &str) -> String {
    let an = word.chars().next().is_some_and(|c| "AEIOaeio".contains(c));
    format!("{} {word}", if an { "an" } else { "a" })
}

/// The FMI 3 variable the structured name `name` belongs to: `a.b[2]` and `a.b[1,2]` are
/// elements of the array `a.b`; any other name, `a.b[0].c` (an index inside the name)
/// included, is a scalar variable of its own name, so an array's name is always its
/// elements' names without their trailing index.
pub fn array_name(name: &str) -> &str {
    match name
        .strip_suffix(']')
        .and_then(|n| n.rfind('[').map(|i| (n, i)))
    {
        Some((n, i))
            if !n[i + 1..].is_empty()
                && n[i + 1..].chars().all(|c| c.is_ascii_digit() || c == ',') =>
        {
            &name[..i]
        }
        _ => name,
    }
}

/// Role of a scalar.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    /// Fixed before initialisation ends.
    Parameter,
    /// Set by the master at any communication point.
    Input,
    /// Computed by the FMU.
    Output,
}

/// A value of any [`Kind`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// Real.
    Real(f64),
    /// Integer.
    Integer(u64),
    /// Boolean.
    Boolean(bool),
    /// Enumeration item, 0-based index into the items (FMI value − 1).
    Enumeration(usize),
}

/// One scalar.
#[derive(Clone, Debug, PartialEq)]
pub struct ScalarVar {
    /// FMI 2 name, structured: `a.b[2]`.
    pub name: String,
    /// Name of the FMI 3 variable holding it (the array name without index).
    pub array: String,
    /// Type.
    pub kind: Kind,
    /// Role.
    pub causality: Causality,
    /// Unit symbol (`None` when dimensionless).
    pub unit: Option<&'static str>,
    /// Start value (parameters and inputs; outputs report it before the first step).
    pub start: Value,
    /// Valid range of numbers, inclusive (±∞ for open ends).
    pub range: Option<(f64, f64)>,
    /// One line for the user.
    pub description: String,
}

/// An FMI 3 variable: a scalar or a 1-D array of consecutive slots.
#[derive(Clone, Debug, PartialEq)]
pub struct ArrayVar {
    /// Name.
    pub name: String,
    /// Slots it covers.
    pub slots: Range<usize>,
    /// Whether it is declared as an array (with a Dimension), even of length 1.
    pub is_array: bool,
    /// Array dimensions, row-major (empty for scalars).
    pub dims: Vec<usize>,
    /// For a scalar view of one array element: index (in [`VariableTable::arrays`]) of the
    /// array it belongs to; `None` for every other variable.
    pub element_of: Option<usize>,
}

/// Indices of a structured name: `a.b[1,2]` → `[1, 2]`.
fn indices(name: &str) -> Vec<usize> {
    name.rfind('[').map_or_else(Vec::new, |i| {
        name[i + 1..name.len() - 1]
            .split(',')
            .filter_map(|x| x.trim().parse().ok())
            .collect()
    })
}

/// All scalars, with their FMI 3 grouping.
#[derive(Clone, Debug, PartialEq)]
pub struct VariableTable {
    /// Scalars in value-reference order (FMI 2 value reference = index).
    pub scalars: Vec<ScalarVar>,
    /// FMI 3 variables in order (FMI 3 value reference = index + 1; 0 is `time`): the
    /// variables proper, then the scalar views of every array element (`element_of`).
    pub arrays: Vec<ArrayVar>,
    /// Integer codes of enumeration parameters, `(code slot, enumeration slot)`: masters
    /// without FMI 2 enumerations (libcosim, ecos) set the code; the instance routes it to
    /// the enumeration, so both always read the same item ([`VariableTable::with_enum_codes`]).
    pub enum_codes: Vec<(usize, usize)>,
    /// Per slot, the slots of the knowns (parameters, inputs) an output's value during
    /// initialization mode depends on (empty: none; the modelDescription's InitialUnknowns).
    pub initial_dependencies: Vec<Vec<usize>>,
}

impl VariableTable {
    /// Builds the table and its FMI 3 grouping: consecutive scalars sharing an array name form
    /// one array variable.
    ///
    /// Panics if a scalar's array name is not its name without a trailing index
    /// ([`array_name`]): an FMI 3 array must be named as its elements are.
    pub fn new(scalars: Vec<ScalarVar>) -> Self {
        let mut arrays: Vec<ArrayVar> = Vec::new();
        for (i, s) in scalars.iter().enumerate() {
            assert!(
                s.array == s.name || s.array == array_name(&s.name),
                "{}: array name {:?} is not the name without its trailing index ({:?})",
                s.name,
                s.array,
                array_name(&s.name)
            );
            match arrays.last_mut() {
                Some(a) if a.name == s.array && a.slots.end == i && a.is_array => {
                    a.slots.end = i + 1
                }
                _ => arrays.push(ArrayVar {
                    name: s.array.clone(),
                    slots: i..i + 1,
                    is_array: s.name != s.array,
                    dims: Vec::new(),
                    element_of: None,
                }),
            }
        }
        for a in arrays.iter_mut().filter(|a| a.is_array) {
            a.dims = indices(&scalars[a.slots.end - 1].name)
                .iter()
                .map(|i| i + 1)
                .collect();
            assert_eq!(
                a.dims.iter().product::<usize>(),
                a.slots.len(),
                "{}: elements must be complete and row-major",
                a.name
            );
        }
        let views: Vec<ArrayVar> = arrays
            .iter()
            .enumerate()
            .filter(|(_, a)| a.is_array)
            .flat_map(|(i, a)| a.slots.clone().map(move |k| (i, k)))
            .map(|(i, k)| ArrayVar {
                name: scalars[k].name.clone(),
                slots: k..k + 1,
                is_array: false,
                dims: Vec::new(),
                element_of: Some(i),
            })
            .collect();
        arrays.extend(views);
        let initial_dependencies = vec![Vec::new(); scalars.len()];
        Self {
            scalars,
            arrays,
            enum_codes: Vec::new(),
            initial_dependencies,
        }
    }

    /// The table of `scalars` plus, after them, an Integer parameter `<name>_code` for every
    /// Enumeration parameter, with values 1…n in item order (the enumeration's own values).
    /// libcosim and ecos skip FMI 2/3 enumerations, so without the code such a parameter
    /// could not be set from them; tools with enumerations keep using the enumeration.
    pub fn with_enum_codes(mut scalars: Vec<ScalarVar>) -> Self {
        let mut codes = Vec::new();
        let n = scalars.len();
        for slot in 0..n {
            let s = &scalars[slot];
            if let (Kind::Enumeration { items, type_name }, Causality::Parameter) =
                (s.kind, s.causality)
            {
                let Value::Enumeration(start) = s.start else {
                    continue;
                };
                let values: Vec<String> = items
                    .iter()
                    .enumerate()
                    .map(|(i, it)| format!("{}={it}", i + 1))
                    .collect();
                let name = format!("{}_code", s.name);
                codes.push((scalars.len(), slot));
                scalars.push(ScalarVar {
                    array: name.clone(),
                    name,
                    kind: Kind::Integer,
                    causality: Causality::Parameter,
                    unit: None,
                    start: Value::Integer(start as u64 + 1),
                    range: Some((1.0, items.len() as f64)),
                    description: format!(
                        "{} ({type_name}) as an Integer for masters without enumerations: {}; setting either sets both",
                        s.name,
                        values.join(", ")
                    ),
                });
            }
        }
        let mut t = Self::new(scalars);
        t.enum_codes = codes;
        t
    }

    /// The enumeration slot whose Integer code is slot `slot`, if it is a code.
    pub fn code_target(&self, slot: usize) -> Option<usize> {
        // Codes follow every other slot: one compare on the output-reading path.
        match self.enum_codes.first() {
            Some((first, _)) if slot >= *first => {}
            _ => return None,
        }
        self.enum_codes
            .iter()
            .find(|(c, _)| *c == slot)
            .map(|(_, e)| *e)
    }

    /// The FMI 3 variables proper: arrays and scalars, without the element views.
    pub fn variables(&self) -> impl Iterator<Item = &ArrayVar> {
        self.arrays.iter().filter(|a| a.element_of.is_none())
    }

    /// Slot of the scalar called `name`.
    pub fn slot(&self, name: &str) -> Option<usize> {
        self.scalars.iter().position(|s| s.name == name)
    }

    /// Checks `v` against slot `slot`'s kind and range; the error says what was expected, its
    /// numbers as the rest of rins echoes them ([`rins_message::Num`]: 1e-300, not 300 digits).
    pub fn check(&self, slot: usize, v: Value) -> Result<(), String> {
        let s = &self.scalars[slot];
        let range = |x: f64, shown: String| match s.range {
            // An infinite value of a finite range is not read as too large a number.
            Some((lo, hi)) if !x.is_finite() && lo.is_finite() && hi.is_finite() => Err(format!(
                "{} = {shown} is not finite: expected {}",
                s.name,
                rins_message::expected_in(x, lo, hi)
            )),
            Some((lo, hi)) if !(x >= lo && x <= hi) => Err(format!(
                "{} = {shown} is outside its range {}",
                s.name,
                rins_message::range(lo, hi)
            )),
            _ => Ok(()),
        };
        match (s.kind, v) {
            (Kind::Real, Value::Real(x)) if x.is_nan() => {
                Err(format!("{} = NaN is not a number", s.name))
            }
            (Kind::Real, Value::Real(x)) => range(x, Num(x).to_string()),
            // A whole number is echoed exactly (its digits are its value).
            (Kind::Integer, Value::Integer(u)) => range(u as f64, u.to_string()),
            (Kind::Boolean, Value::Boolean(_)) => Ok(()),
            (Kind::Enumeration { items, type_name }, Value::Enumeration(i)) if i >= items.len() => {
                // FMI values below 1 arrive as `usize::MAX` (no item): no overflow here.
                let value = i
                    .checked_add(1)
                    .map_or("a value below 1".to_string(), |n| n.to_string());
                Err(format!(
                    "{} = {value} is not an item of {type_name} (1…{}: {})",
                    s.name,
                    items.len(),
                    items.join(", ")
                ))
            }
            (Kind::Enumeration { .. }, Value::Enumeration(_)) => Ok(()),
            (k, v) => {
                let got = match v {
                    Value::Real(x) => format!("the Real {}", Num(x)),
                    Value::Integer(u) => format!("the Integer {u}"),
                    Value::Boolean(b) => format!("the Boolean {b}"),
                    Value::Enumeration(i) => format!("enumeration item {}", i.wrapping_add(1)),
                };
                Err(format!(
                    "{} is {} variable (FMI 3: {}), got {got}",
                    s.name,
                    k.described(FmiVersion::V2),
                    k.accessor(FmiVersion::V3)
                ))
            }
        }
    }
}

/// An output as a model declares it: one FMI 3 variable, a scalar or a 1-D array, whose
/// elements become consecutive slots (`name[0]`, `name[1]`, … in FMI 2).
#[derive(Clone, Debug, PartialEq)]
pub struct OutputDecl {
    /// Variable name (FMI 3 name; the FMI 2 names add `[i]` for arrays).
    pub name: String,
    /// Number of elements for an array, `None` for a scalar.
    pub len: Option<usize>,
    /// Type of every element.
    pub kind: Kind,
    /// Unit symbol (`None` when dimensionless).
    pub unit: Option<&'static str>,
    /// Value of each element before the first step.
    pub start: Vec<Value>,
    /// One line for the user.
    pub description: String,
}

impl OutputDecl {
    /// Number of scalars (slots) it covers.
    pub fn count(&self) -> usize {
        self.len.unwrap_or(1)
    }

    /// FMI 2 (scalar) name of element `i`.
    pub fn element_name(&self, i: usize) -> String {
        match self.len {
            Some(_) => format!("{}[{i}]", self.name),
            None => self.name.clone(),
        }
    }

    /// Its rows of the variable table.
    pub fn scalars(&self) -> impl Iterator<Item = ScalarVar> + '_ {
        (0..self.count()).map(|i| ScalarVar {
            name: self.element_name(i),
            array: self.name.clone(),
            kind: self.kind,
            causality: Causality::Output,
            unit: self.unit,
            start: self.start[i.min(self.start.len() - 1)],
            range: None,
            description: self.description.clone(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn real(name: &str, array: &str) -> ScalarVar {
        ScalarVar {
            name: name.into(),
            array: array.into(),
            kind: Kind::Real,
            causality: Causality::Parameter,
            unit: None,
            start: Value::Real(0.0),
            range: Some((-1.0, 1.0)),
            description: String::new(),
        }
    }

    #[test]
    fn consecutive_elements_group_into_arrays_and_checks_name_the_variable() {
        let t = VariableTable::new(vec![
            real("a[0]", "a"),
            real("a[1]", "a"),
            real("b", "b"),
            real("c[0]", "c"),
        ]);
        let m = VariableTable::new(
            (0..6)
                .map(|k| real(&format!("m[{},{}]", k / 3, k % 3), "m"))
                .collect(),
        );
        assert_eq!(m.arrays[0].dims, [2, 3]);
        assert_eq!(
            t.arrays
                .iter()
                .map(|a| (a.name.as_str(), a.slots.clone(), a.is_array, a.element_of))
                .collect::<Vec<_>>(),
            [
                ("a", 0..2, true, None),
                ("b", 2..3, false, None),
                ("c", 3..4, true, None),
                // Scalar views of the array elements, after every variable proper.
                ("a[0]", 0..1, false, Some(0)),
                ("a[1]", 1..2, false, Some(0)),
                ("c[0]", 3..4, false, Some(2)),
            ]
        );
        assert_eq!(t.variables().count(), 3);
        assert_eq!(m.arrays.len(), 1 + 6);
        assert!(
            t.check(1, Value::Real(2.0))
                .unwrap_err()
                .contains("a[1] = 2 is outside its range [-1, 1]")
        );
        assert!(
            t.check(1, Value::Real(f64::NAN))
                .unwrap_err()
                .contains("NaN")
        );
        assert_eq!(
            t.check(2, Value::Integer(0)).unwrap_err(),
            "b is a Real variable (FMI 3: Float64), got the Integer 0"
        );
        let e = VariableTable::new(vec![ScalarVar {
            kind: Kind::Enumeration {
                type_name: "T",
                items: &["a", "b"],
            },
            start: Value::Enumeration(0),
            range: None,
            ..real("e", "e")
        }]);
        assert_eq!(
            e.check(0, Value::Enumeration(usize::MAX)).unwrap_err(),
            "e = a value below 1 is not an item of T (1…2: a, b)"
        );
        assert!(
            e.check(0, Value::Enumeration(2))
                .unwrap_err()
                .contains("e = 3 is not")
        );
        assert!(t.check(2, Value::Real(-1.0)).is_ok());
    }

    #[test]
    fn array_names_are_element_names_without_the_trailing_index() {
        for (name, array) in [
            ("a.b[2]", "a.b"),
            ("m[1,2]", "m"),
            ("a.legs[0].heading_deg", "a.legs[0].heading_deg"),
            ("a.legs[0].v[1]", "a.legs[0].v"),
            ("a.b", "a.b"),
            ("a.b[]", "a.b[]"),
            ("a.b[x]", "a.b[x]"),
        ] {
            assert_eq!(array_name(name), array, "{name}");
        }
        // An element whose array is named otherwise is a table bug, refused on construction.
        let r = std::panic::catch_unwind(|| {
            VariableTable::new(vec![real("s.legs[0].heading_deg", "s.legs.heading_deg")])
        });
        let msg = *r.unwrap_err().downcast::<String>().unwrap();
        assert!(msg.contains("s.legs[0].heading_deg: array name"), "{msg}");
    }

    #[test]
    fn type_names_follow_the_fmi_version() {
        let e = Kind::Enumeration {
            type_name: "Colour",
            items: &["a"],
        };
        assert_eq!(Kind::Real.described(FmiVersion::V3), "a Float64");
        assert_eq!(Kind::Integer.described(FmiVersion::V3), "a UInt64");
        assert_eq!(Kind::Integer.described(FmiVersion::V2), "an Integer");
        assert_eq!(e.described(FmiVersion::V3), "an Enumeration (Colour)");
        assert_eq!(e.accessor(FmiVersion::V3), "Int64");
        assert_eq!(e.accessor(FmiVersion::V2), "Integer");
        assert_eq!(with_article("Int32"), "an Int32");
    }

    #[test]
    fn output_declarations_expand_to_named_elements() {
        let d = OutputDecl {
            name: "q".into(),
            len: Some(2),
            kind: Kind::Real,
            unit: None,
            start: vec![Value::Real(1.0), Value::Real(0.0)],
            description: "d".into(),
        };
        let t = VariableTable::new(d.scalars().collect());
        assert_eq!(t.slot("q[1]"), Some(1));
        assert_eq!(t.scalars[0].start, Value::Real(1.0));
        assert_eq!(t.arrays[0].dims, [2]);
        assert_eq!(t.scalars[1].causality, Causality::Output);
    }

    /// Issue 44: range messages echoed numbers raw (1e-300 as 300 digits, 1e300 as 301, 2^63
    /// as "9223372036854775808" for a Real); they go through the one formatter of rins'
    /// messages, and an infinite value is asked to be finite.
    #[test]
    fn range_messages_echo_numbers_short_and_exact() {
        let two63 = 9_223_372_036_854_775_808.0_f64;
        let t = VariableTable::new(vec![
            real("a", "a"),
            ScalarVar {
                range: Some((1e-3, 1e300)),
                ..real("w", "w")
            },
            ScalarVar {
                kind: Kind::Integer,
                start: Value::Integer(0),
                range: Some((0.0, 2_147_483_647.0)),
                ..real("n", "n")
            },
        ]);
        let cases: [(usize, Value, &str); 9] = [
            (
                0,
                Value::Real(1e300),
                "a = 1e300 is outside its range [-1, 1]",
            ),
            (
                0,
                Value::Real(-1e300),
                "a = -1e300 is outside its range [-1, 1]",
            ),
            (
                1,
                Value::Real(1e-300),
                "w = 1e-300 is outside its range [0.001, 1e300]",
            ),
            (
                0,
                Value::Real(two63),
                "a = 9.223372036854776e18 is outside its range [-1, 1]",
            ),
            (
                0,
                Value::Real(f64::INFINITY),
                "a = inf is not finite: expected a finite number in [-1, 1]",
            ),
            (
                0,
                Value::Real(f64::NEG_INFINITY),
                "a = -inf is not finite: expected a finite number in [-1, 1]",
            ),
            (0, Value::Real(f64::NAN), "a = NaN is not a number"),
            (
                2,
                Value::Integer(1 << 63),
                "n = 9223372036854775808 is outside its range [0, 2147483647]",
            ),
            (
                2,
                Value::Real(1e300),
                "n is an Integer variable (FMI 3: UInt64), got the Real 1e300",
            ),
        ];
        for (slot, v, want) in cases {
            assert_eq!(t.check(slot, v).unwrap_err(), want);
        }
    }
}
