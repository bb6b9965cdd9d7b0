//! `rins scenarios`: list the built-in scenarios, or print one.

use anyhow::{Context, Result};

use rins_scenario::file::{BUILTIN, Scenario};

/// Arguments of `rins scenarios`.
#[derive(clap::Args, Debug)]
pub struct ScenariosArgs {
    /// Print this built-in scenario's TOML.
    pub name: Option<String>,
}

/// Lists every built-in scenario with its description, or prints the named one's TOML.
pub fn run(a: &ScenariosArgs) -> Result<()> {
    match &a.name {
        None => {
            for (n, text) in BUILTIN {
                let sc = Scenario::from_toml(text, n)?;
                println!("builtin:{n:<22} {}", sc.meta.description);
            }
        }
        Some(n) => {
            let n = n.strip_prefix("builtin:").unwrap_or(n);
            let (_, text) = BUILTIN
                .iter()
                .find(|(b, _)| *b == n)
                .with_context(|| format!("no built-in scenario {n:?}; see `rins scenarios`"))?;
            print!("{text}");
        }
    }
    Ok(())
}
