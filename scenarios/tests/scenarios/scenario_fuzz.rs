//! Property test of the scenario reader (issue 16): arbitrary bytes and mutated copies of the
//! built-in scenario files never panic, and every refusal names the file and where: a parse
//! error carries toml's line and column (a line of the text), a range error names the line and
//! column of the key (or says the value came from a default or preset) and the dotted key.
//!
//! Fixed seeds (ChaCha8): a failure prints the seed and case number to replay.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rins_scenario::Scenario;
use rins_scenario::file::{BUILTIN, ScenarioError};

const SEED: u64 = 0x5eed_0016;
/// Mutated copies of the built-in files.
const MUTATED_CASES: usize = 20_000;
/// Random byte strings (raw, and made of TOML punctuation and words).
const RANDOM_CASES: usize = 10_000;

/// Values that stress range checks: non-finite, huge, tiny, negative, wrong type.
const NASTY: [&str; 16] = [
    "nan",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "1e-320",
    "0",
    "-1",
    "0.0",
    "18446744073709551616",
    "9223372036854775807",
    "-9223372036854775808",
    "\"x\"",
    "true",
    "[]",
    "{}",
];

/// The line number in toml's "line N, column M" (the first occurrence).
fn line_of(text: &str) -> Option<usize> {
    let i = text.find("line ")?;
    let digits: String = text[i + 5..]
        .chars()
        .take_while(|c| c.is_ascii_digit())
        .collect();
    digits.parse().ok()
}

/// The dotted key in serde's "… in `a.b.c`" (an error without a span).
fn key_of(message: &str) -> Option<&str> {
    let (_, rest) = message.trim_end().rsplit_once("in `")?;
    rest.strip_suffix('`')
}

/// Checks the refusal names the file and where; `source` is the text read.
fn check_refusal(e: &ScenarioError, name: &str, source: &str, ctx: &str) {
    let lines = source.lines().count();
    let text = e.to_string();
    assert!(text.starts_with(&format!("{name}: ")), "{ctx}: {text}");
    match e {
        ScenarioError::Parse { message, .. } => {
            if let Some(key) = key_of(message) {
                // An error that names a dotted key instead of a line (a value the preset laid
                // into the document, which has no place in the text): its last part is
                // written in the file. Since the one parse, type errors inside [sensor] carry
                // their line like any other.
                let last = key.rsplit('.').next().unwrap_or(key);
                let last = last.split('[').next().unwrap_or(last);
                assert!(
                    key.starts_with("sensor.") && source.contains(last),
                    "{ctx}: key {key:?} is not in the text: {text}"
                );
                return;
            }
            let line = line_of(message).unwrap_or_else(|| panic!("{ctx}: no line in {text}"));
            assert!(
                (1..=lines.max(1) + 1).contains(&line),
                "{ctx}: line {line} of {lines}: {text}"
            );
            assert!(message.contains("column "), "{ctx}: {text}");
        }
        ScenarioError::Invalid { problems, .. } => {
            assert!(!problems.is_empty(), "{ctx}");
            for p in problems {
                if p.contains("no keys") {
                    continue;
                }
                let rest =
                    if let Some(r) = p.trim_start().strip_prefix("(default or preset value) ") {
                        r
                    } else {
                        let line = line_of(p).unwrap_or_else(|| panic!("{ctx}: no line in {p:?}"));
                        assert!((1..=lines).contains(&line), "{ctx}: line {line}: {p}");
                        p.split_once(": ")
                            .map(|(_, r)| r)
                            .unwrap_or_else(|| panic!("{ctx}: {p:?}"))
                    };
                // Then the dotted key and what was expected.
                let (key, why) = rest
                    .split_once(": ")
                    .unwrap_or_else(|| panic!("{ctx}: no key in {p:?}"));
                assert!(
                    !key.is_empty() && !key.contains(' ') && key.contains('.'),
                    "{ctx}: key {key:?} in {p:?}"
                );
                assert!(why.contains("expected"), "{ctx}: {p:?}");
            }
        }
        ScenarioError::Read { .. } => panic!("{ctx}: nothing is read from disk here"),
    }
}

/// Runs one case: 0 accepted, 1 refused with a parse error, 2 refused with range errors.
fn run_case(bytes: &[u8], ctx: &str) -> usize {
    let text = String::from_utf8_lossy(bytes);
    let name = "fuzz.toml";
    match std::panic::catch_unwind(|| Scenario::from_toml(&text, name)) {
        Ok(Ok(_)) => 0,
        Ok(Err(e)) => {
            check_refusal(&e, name, &text, ctx);
            if matches!(e, ScenarioError::Parse { .. }) {
                1
            } else {
                2
            }
        }
        Err(_) => panic!("{ctx}: the reader panicked on {text:?}"),
    }
}

fn mutate(rng: &mut ChaCha8Rng, good: &str) -> Vec<u8> {
    let mut lines: Vec<String> = good.lines().map(str::to_string).collect();
    for _ in 0..rng.random_range(1..4) {
        let k = rng.random_range(0..lines.len());
        match rng.random_range(0..7) {
            // A value replaced with a nasty one.
            0 | 1 => {
                if let Some((key, _)) = lines[k].split_once('=') {
                    lines[k] = format!("{key}= {}", NASTY[rng.random_range(0..NASTY.len())]);
                }
            }
            2 => {
                lines.remove(k);
                if lines.is_empty() {
                    lines.push(String::new());
                }
            }
            3 => {
                let l = lines[k].clone();
                lines.insert(rng.random_range(0..lines.len()), l);
            }
            4 => {
                let j = rng.random_range(0..lines.len());
                lines.swap(k, j);
            }
            5 => {
                // A byte of the line changed to TOML punctuation or a random byte.
                let mut b = lines[k].clone().into_bytes();
                if !b.is_empty() {
                    let i = rng.random_range(0..b.len());
                    b[i] = *b"=[]\"'.,#{}\n\\ 0e-"
                        .get(rng.random_range(0..20))
                        .unwrap_or(&rng.random::<u8>());
                }
                lines[k] = String::from_utf8_lossy(&b).into_owned();
            }
            _ => {
                let cut = rng.random_range(0..=lines[k].len());
                lines[k] = String::from_utf8_lossy(&lines[k].as_bytes()[..cut]).into_owned();
            }
        }
    }
    lines.join("\n").into_bytes()
}

#[test]
fn mutated_builtin_scenarios_never_panic_and_refusals_name_where() {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let mut outcomes = [0usize; 3];
    for case in 0..MUTATED_CASES {
        let (builtin, good) = BUILTIN[case % BUILTIN.len()];
        let bytes = mutate(&mut rng, good);
        let ctx = format!("seed {SEED:#x}, case {case} (from {builtin})");
        outcomes[run_case(&bytes, &ctx)] += 1;
    }
    // Every outcome occurs (harmless mutations such as a moved comment are accepted), so both
    // kinds of refusal were checked.
    println!("accepted, parse errors, range errors: {outcomes:?}");
    assert!(outcomes.iter().all(|n| *n > 100), "{outcomes:?}");
}

#[test]
fn random_bytes_never_panic_and_refusals_name_where() {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED ^ 1);
    const WORDS: [&str; 14] = [
        "[scenario]",
        "[sensor]",
        "[scheme]",
        "name",
        " = ",
        "\n",
        "\"",
        "[",
        "]",
        "{",
        "}",
        "1.5",
        "preset",
        "duration_s",
    ];
    for case in 0..RANDOM_CASES {
        let n = rng.random_range(0..300);
        let bytes: Vec<u8> = if case % 2 == 0 {
            (0..n).map(|_| rng.random()).collect()
        } else {
            (0..n / 4)
                .flat_map(|_| WORDS[rng.random_range(0..WORDS.len())].bytes())
                .collect()
        };
        run_case(&bytes, &format!("seed {:#x}, case {case}", SEED ^ 1));
    }
}
