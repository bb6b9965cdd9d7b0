//! Test helper for the chaos tests (transport/tests/transport/chaos.rs): a plant or a navigator of the
//! 16-position scenario that runs `serve_probed` / `navigate_probed` — the code `rins serve`
//! and `rins nav` run — and can freeze at a named lifecycle stage so the test kills it there.
//!
//! ```text
//! rins-chaos-peer plant SESSION --samples N --batch B [--free] [--pace K] [--wait]
//!                 [--timeout-s T] [--stall STAGE[:SEQ]] [--sleep STAGE[:SEQ]=MS]
//! rins-chaos-peer nav SESSION [--no-ack] [--timeout-s T] [--stall STAGE[:SEQ]]
//!                 [--sleep STAGE[:SEQ]=MS]
//! ```
//!
//! `--sleep` pauses MS milliseconds at the stage and goes on (a slow peer, not a frozen one).
//!
//! Prints `STALL <stage> <unix ms>` when it freezes, `LOST <stage> <unix ms>` when it finds its
//! peer lost, `WAITING <stage> <unix ms>` when the plant waits for a navigator,
//! `END <stage> <unix ms>` when the plant has sent the end of the run, `RESULT key=value …` at a normal end and `ERROR <unix ms> <message>` (exit 1).

use std::io::Write;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use rins_transport::{Mode, NavOptions, ServeOptions, Stage, navigate_probed, serve_probed};

fn now_ms() -> u128 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_millis())
        .unwrap_or(0)
}

fn say(line: String) {
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{line}");
    let _ = out.flush();
}

/// Freezes at `stall`, pauses at `sleep`; reports peer losses as they are found.
fn probe(stall: Option<Stage>, sleep: Option<(Stage, Duration)>) -> impl FnMut(Stage) {
    move |s: Stage| {
        if let Some((at, pause)) = sleep
            && at == s
        {
            std::thread::sleep(pause);
        }
        if matches!(s, Stage::PlantLostNavigator(_) | Stage::NavLostPlant(_)) {
            say(format!("LOST {} {}", s.label(), now_ms()));
        }
        if matches!(s, Stage::PlantWaiting(_)) {
            say(format!("WAITING {} {}", s.label(), now_ms()));
        }
        if matches!(s, Stage::PlantEndSent(_)) {
            say(format!("END {} {}", s.label(), now_ms()));
        }
        if Some(s) == stall {
            say(format!("STALL {} {}", s.label(), now_ms()));
            loop {
                std::thread::sleep(Duration::from_secs(1));
            }
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |f: &str| args.iter().any(|a| a == f);
    let value = |f: &str| {
        args.iter()
            .rposition(|a| a == f)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let num = |f: &str, d: f64| value(f).and_then(|v| v.parse().ok()).unwrap_or(d);
    let (Some(role), Some(session)) = (args.first(), args.get(1)) else {
        eprintln!("usage: rins-chaos-peer plant|nav SESSION [options]");
        std::process::exit(2);
    };
    let stall = match value("--stall") {
        Some(s) => match Stage::parse(&s) {
            Some(st) => Some(st),
            None => {
                eprintln!("--stall {s:?}: unknown stage");
                std::process::exit(2);
            }
        },
        None => None,
    };
    let sleep = value("--sleep").map(|v| {
        let parsed = v.split_once('=').and_then(|(st, ms)| {
            Some((Stage::parse(st)?, Duration::from_millis(ms.parse().ok()?)))
        });
        parsed.unwrap_or_else(|| {
            eprintln!("--sleep {v:?}: expected STAGE[:SEQ]=MS");
            std::process::exit(2);
        })
    });
    let timeout = Duration::from_secs_f64(num("--timeout-s", 10.0));
    let cfg = rins_plant::presets::paper_16pos_config();
    let mut p = probe(stall, sleep);
    let result = if role == "plant" {
        let opts = ServeOptions {
            mode: if flag("--free") {
                Mode::FreeRunning
            } else {
                Mode::Lockstep
            },
            batch: num("--batch", 10.0) as usize,
            pace: value("--pace").and_then(|v| v.parse().ok()),
            peer_timeout: timeout,
            wait_for_restart: flag("--wait"),
        };
        let mut plant = rins_plant::Plant::new(&cfg).expect("valid preset");
        serve_probed(
            session,
            &mut plant,
            num("--samples", 2000.0) as u64,
            &opts,
            &mut |_, _| {},
            &mut p,
        )
        .map(|s| {
            format!(
                "samples={} batches={} restarts={} interrupted={} events={:?}",
                s.samples, s.batches, s.restarts, s.interrupted, s.events
            )
        })
    } else {
        let opts = NavOptions {
            acknowledge: !flag("--no-ack"),
            commands: vec![],
            peer_timeout: timeout,
        };
        navigate_probed(session, &cfg, &opts, &mut p).map(|s| {
            format!(
                "samples={} first_tick={} last_tick={} batches={} duplicates={} interrupted={}",
                s.nav.samples,
                s.nav.first_tick.unwrap_or(0),
                s.nav.last_tick,
                s.batches,
                s.duplicates,
                s.interrupted
            )
        })
    };
    match result {
        Ok(r) => say(format!("RESULT {r}")),
        Err(e) => {
            say(format!("ERROR {} {e}", now_ms()));
            std::process::exit(1);
        }
    }
}
