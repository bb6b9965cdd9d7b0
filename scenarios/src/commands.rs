//! The `rins` commands, one module each: its clap arguments and a `run` that does the job. The
//! binary (`src/bin/rins.rs`) only lists them and dispatches.

pub mod args;
pub mod bench_diagnosis;
pub mod calibrate;
pub mod campaign;
pub mod compare;
pub mod diagnose;
pub mod fmu;
pub mod measure;
#[cfg(feature = "transport")]
pub mod nav;
pub mod paired_runs;
pub mod paper;
pub mod run;
pub mod scenarios;
pub mod schemes;
pub mod sea;
#[cfg(feature = "transport")]
pub mod serve;
pub mod sweep;
pub mod table4;
pub mod table5;
pub mod verify;

use std::process::ExitCode;

use anyhow::Result;

/// Ctrl-C stopped a run after this many samples; its outputs were closed cleanly.
#[derive(Debug, thiserror::Error)]
#[error("interrupted after {0} samples; the outputs are complete up to there")]
pub struct Interrupted(pub u64);

/// The process exit of a command: 0, 130 after Ctrl-C (as a shell reports SIGINT), 1 on an
/// error, which is printed with its chain of causes.
pub fn exit_code(result: Result<()>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.downcast_ref::<Interrupted>().is_some() => {
            eprintln!("{e}");
            ExitCode::from(130)
        }
        Err(e) => {
            // The chain, without the backtrace anyhow adds when RUST_BACKTRACE is set.
            eprintln!("error: {e}");
            for cause in e.chain().skip(1) {
                eprintln!("  caused by: {cause}");
            }
            ExitCode::FAILURE
        }
    }
}

/// Restores the default SIGPIPE action so `rins … | head` ends quietly, as Unix tools do,
/// instead of panicking on the closed pipe (Rust ignores SIGPIPE by default). Call once at
/// start-up, before any other thread exists.
#[allow(unsafe_code)]
pub fn default_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called once at start-up, before any other thread exists; SIG_DFL is a valid action.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// Prints a report as JSON or as its text, and fails when a check failed.
pub fn emit_report<T: serde::Serialize>(
    report: &T,
    json: bool,
    text: &str,
    passed: bool,
    what: &str,
) -> Result<()> {
    if json {
        println!("{}", serde_json::to_string_pretty(report)?);
    } else {
        print!("{text}");
    }
    if !passed {
        anyhow::bail!("{what} failed");
    }
    Ok(())
}

/// Creates `dir` and its parents, naming it on failure.
pub fn create_dir(dir: &std::path::Path) -> Result<()> {
    use anyhow::Context;
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))
}
