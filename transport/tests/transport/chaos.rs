//! Chaos tests of the shared-memory transport (issue 16): kill -9 of either side at each
//! lifecycle stage, a navigator killed during the hello/resend of a restart, repeated kill -9
//! restarts into one session name (iceoryx2 issue #1584, orphaned static configs), two plants
//! and two navigators starting together on one session, and peers that stall without dying.
//! Each case runs `rins-chaos-peer` processes (the library code `rins serve`/`rins nav` run)
//! frozen at a named stage by their probe. Measured: how long the survivor took to notice,
//! samples lost and duplicated against the lockstep contract, and the session's files left in
//! /dev/shm afterwards; after every fault a new run on the same session name must complete.
//! The table (docs/transport.md, Faults) is printed with `--nocapture`.

use crate::peer;

use std::time::Duration;

use crate::peer::{BATCH, Peer, SAMPLES, field, left, now_ms, remove_counter, stage_seq, stamp};

const WAIT: Duration = Duration::from_secs(10);

fn session(tag: &str) -> String {
    format!("c{}{tag}", std::process::id())
}

/// One line of the table.
struct Row {
    stage: &'static str,
    detected_ms: Option<u64>,
    lost: u64,
    duplicated: u64,
    left_after: usize,
}

fn plant(s: &str, extra: &[&str]) -> Peer {
    let n = SAMPLES.to_string();
    let b = BATCH.to_string();
    let mut args = vec!["--samples", &n, "--batch", &b, "--timeout-s", "5"];
    args.extend_from_slice(extra);
    Peer::spawn("plant", s, &args)
}

fn nav(s: &str, extra: &[&str]) -> Peer {
    let mut args = vec!["--timeout-s", "5"];
    args.extend_from_slice(extra);
    Peer::spawn("nav", s, &args)
}

/// A complete new run on session `s`: every sample once. Then the session's files left.
fn next_run(s: &str) -> usize {
    let mut p = plant(s, &[]);
    let mut n = nav(s, &[]);
    let r = n.expect("RESULT", WAIT);
    assert_eq!(
        (
            field(&r, "samples"),
            field(&r, "first_tick"),
            field(&r, "duplicates")
        ),
        (SAMPLES, 0, 0),
        "the next run on {s}: {r}"
    );
    let (p_ok, n_ok) = (p.finish(WAIT), n.finish(WAIT));
    assert!(p_ok && n_ok, "{r}\n{}\n{}", p.said(), n.said());
    let files = left(s);
    assert!(files.is_empty(), "{s} left {files:?}");
    remove_counter(s);
    files.len()
}

/// Lost and duplicated samples (integrated twice, or received twice) of the navigator that
/// finished a run in which batches before `restart` were acknowledged by its killed
/// predecessors.
fn restart_figures(result: &str, restart: u64) -> (u64, u64) {
    let (first, last, samples) = (
        field(result, "first_tick"),
        field(result, "last_tick"),
        field(result, "samples"),
    );
    let from = restart * BATCH;
    let span = last + 1 - first;
    let lost = first.saturating_sub(from) + (SAMPLES - 1 - last) + span.saturating_sub(samples);
    // Also the resent batches it received twice (dropped by their sequence number).
    let dup = from.saturating_sub(first)
        + samples.saturating_sub(span)
        + field(result, "duplicates") * BATCH;
    (lost, dup)
}

/// The navigator is killed frozen at `stall`; with `hello`, its replacement is killed right
/// after its hello too. The plant (waiting for a restart) resends from batch `restart`.
fn navigator_killed(stage: &'static str, tag: &str, stall: &str, restart: u64, hello: bool) -> Row {
    let s = session(tag);
    let mut p = plant(&s, &["--wait"]);
    p.expect("WAITING", WAIT);
    let mut n1 = nav(&s, &["--stall", stall]);
    n1.expect("STALL", WAIT);
    let mut killed = n1.kill9();
    let mut found = p.expect("LOST", WAIT);
    if hello {
        p.expect("WAITING", WAIT); // the wait for the replacement
        let mut n2 = nav(&s, &["--stall", "nav-joined"]);
        n2.expect("STALL", WAIT);
        killed = n2.kill9();
        found = p.expect("LOST", WAIT);
    }
    let mut last = nav(&s, &[]);
    let r = last.expect("RESULT", WAIT);
    let (p_ok, n_ok) = (p.finish(WAIT), last.finish(WAIT));
    assert!(p_ok && n_ok, "{r}\n{}\n{}", p.said(), last.said());
    let (lost, duplicated) = restart_figures(&r, restart);
    let left_after = left(&s).len();
    next_run(&s);
    Row {
        stage,
        detected_ms: Some(stamp(&found).saturating_sub(killed)),
        lost,
        duplicated,
        left_after,
    }
}

/// The plant is killed frozen at `stall`, having sent batches before `sent`; the navigator
/// must have every one of them and report the plant dead.
fn plant_killed(stage: &'static str, tag: &str, stall: &str, sent: u64) -> Row {
    let s = session(tag);
    let mut p = plant(&s, &["--stall", stall]);
    let mut n = nav(&s, &[]);
    p.expect("STALL", WAIT);
    let killed = p.kill9();
    let found = n.expect("LOST", WAIT);
    let err = n.expect("ERROR", WAIT);
    assert!(err.contains("plant process died"), "{err}");
    assert!(!n.finish(WAIT));
    let next = stage_seq(&found);
    let left_after = left(&s).len();
    next_run(&s);
    Row {
        stage,
        detected_ms: Some(stamp(&found).saturating_sub(killed)),
        lost: sent.saturating_sub(next) * BATCH,
        duplicated: next.saturating_sub(sent) * BATCH,
        left_after,
    }
}

fn table(rows: &[Row]) -> String {
    let mut t = String::from(
        "| stage | detected after (ms) | samples lost | samples duplicated | files left in /dev/shm |\n|---|---|---|---|---|\n",
    );
    for r in rows {
        t += &format!(
            "| {} | {} | {} | {} | {} |\n",
            r.stage,
            r.detected_ms.map_or("—".into(), |d| d.to_string()),
            r.lost,
            r.duplicated,
            r.left_after
        );
    }
    t
}

#[test]
fn kill9_at_each_lifecycle_stage() {
    let last = SAMPLES / BATCH - 1;
    let mut rows = vec![
        navigator_killed(
            "navigator killed before its first batch",
            "n0",
            "nav-joined",
            0,
            false,
        ),
        navigator_killed(
            "navigator killed mid-run, plant waiting for its acknowledgement",
            "n1",
            "nav-received:100",
            100,
            false,
        ),
        navigator_killed(
            "replacement navigator killed after its hello, during the resend",
            "n2",
            "nav-received:100",
            100,
            true,
        ),
        navigator_killed(
            "navigator killed at shutdown, holding the end-of-run batch",
            "n3",
            &format!("nav-end-received:{last}"),
            last,
            false,
        ),
        plant_killed(
            "plant killed before the first batch",
            "p0",
            "plant-connected",
            0,
        ),
        plant_killed(
            "plant killed mid-run, waiting for an acknowledgement",
            "p1",
            "plant-awaiting-ack:100",
            101,
        ),
    ];
    // The plant killed about to resend to a replacement navigator.
    {
        let s = session("p2");
        let mut p = plant(&s, &["--wait", "--stall", "plant-resending:100"]);
        let mut n1 = nav(&s, &["--stall", "nav-received:100"]);
        n1.expect("STALL", WAIT);
        n1.kill9();
        p.expect("LOST", WAIT);
        let mut n2 = nav(&s, &[]);
        p.expect("STALL", WAIT);
        let killed = p.kill9();
        let found = n2.expect("LOST", WAIT);
        assert!(!n2.finish(WAIT));
        let left_after = left(&s).len();
        next_run(&s);
        rows.push(Row {
            stage: "plant killed during the resend to a replacement navigator",
            detected_ms: Some(stamp(&found).saturating_sub(killed)),
            // The replacement received nothing: the plant died before resending.
            lost: stage_seq(&found) * BATCH,
            duplicated: 0,
            left_after,
        });
    }
    // The plant killed at shutdown, after the end-of-run batch: the navigator has the whole run.
    {
        let s = session("p3");
        let mut p = plant(&s, &["--stall", &format!("plant-end-sent:{last}")]);
        let mut n = nav(&s, &[]);
        let r = n.expect("RESULT", WAIT);
        p.expect("STALL", WAIT);
        p.kill9();
        assert!(n.finish(WAIT));
        // Nobody survived the plant: its files stay until the next process joins the session.
        let left_after = left(&s).len();
        next_run(&s);
        rows.push(Row {
            stage: "plant killed at shutdown, end-of-run batch sent (files: until the next run)",
            detected_ms: None,
            lost: SAMPLES - field(&r, "samples"),
            duplicated: field(&r, "duplicates") * BATCH,
            left_after,
        });
    }
    println!("{}", table(&rows));
    for r in &rows {
        assert_eq!((r.lost, r.duplicated), (0, 0), "{}", r.stage);
        if let Some(d) = r.detected_ms {
            assert!(d < 1000, "{}: detected after {d} ms", r.stage);
        }
    }
    assert!(
        rows.iter()
            .filter(|r| r.detected_ms.is_some())
            .all(|r| r.left_after == 0)
    );
}

#[test]
fn repeated_kill9_restarts_into_one_session() {
    // Both sides killed mid-run five times: stale nodes, ports and static configs stay behind
    // (iceoryx2 #1584) until the next process cleans them up.
    let s = session("rr");
    let mut stale = 0;
    for _ in 0..5 {
        let mut p = plant(&s, &[]);
        let mut n = nav(&s, &["--stall", "nav-received:50"]);
        n.expect("STALL", WAIT);
        n.kill9();
        p.kill9();
        stale = stale.max(left(&s).len());
    }
    assert!(
        stale > 0,
        "kill -9 of both sides leaves files until the next run"
    );
    let left_after = next_run(&s);
    println!(
        "| 5 × kill -9 of both sides, restarted into the same session | — | 0 | 0 | {left_after} (up to {stale} before the next run) |"
    );
}

#[test]
fn two_plants_and_two_navigators_at_once() {
    let s = session("two");
    // Paced so that the runs overlap (0.3 s each).
    let mut peers = [
        plant(&s, &["--pace", "100"]),
        plant(&s, &["--pace", "100"]),
        nav(&s, &[]),
        nav(&s, &[]),
    ];
    let t0 = now_ms();
    let mut outcome = Vec::new();
    for p in peers.iter_mut() {
        let ok = p.finish(WAIT);
        let line = p
            .wait_for("RESULT", Duration::ZERO)
            .or_else(|| p.wait_for("ERROR", Duration::ZERO))
            .unwrap_or_default();
        outcome.push((ok, line));
    }
    let refused_after = now_ms() - t0;
    let served: Vec<_> = outcome[..2].iter().filter(|o| o.0).collect();
    let navigated: Vec<_> = outcome[2..].iter().filter(|o| o.0).collect();
    assert_eq!(served.len(), 1, "one plant serves: {outcome:?}");
    assert_eq!(navigated.len(), 1, "one navigator: {outcome:?}");
    assert!(
        outcome[..2]
            .iter()
            .any(|o| !o.0 && o.1.contains("already has a plant")),
        "{outcome:?}"
    );
    assert!(
        outcome[2..]
            .iter()
            .any(|o| !o.0 && o.1.contains("already has a navigator")),
        "{outcome:?}"
    );
    let r = &navigated[0].1;
    assert_eq!((field(r, "samples"), field(r, "duplicates")), (SAMPLES, 0));
    let files = left(&s);
    assert!(files.is_empty(), "{files:?}");
    remove_counter(&s);
    println!(
        "| two plants and two navigators started together on one session: one of each runs, the others are refused | {refused_after} (all done) | 0 | 0 | {} |",
        files.len()
    );
}

/// A peer frozen without dying (it stops reading or sending): the other side waits
/// `--timeout-s` (1 s here), then reports it stalled.
fn stalled(stage: &str, tag: &str, plant_args: &[&str], nav_args: &[&str], frozen_is_plant: bool) {
    let s = session(tag);
    let mut p = plant(&s, plant_args);
    let mut n = nav(&s, nav_args);
    let (frozen, other) = if frozen_is_plant {
        (&mut p, &mut n)
    } else {
        (&mut n, &mut p)
    };
    let st = frozen.expect("STALL", WAIT);
    let err = other.expect("ERROR", WAIT);
    assert!(err.contains("stalled"), "{err}");
    let after = stamp(&err).saturating_sub(stamp(&st));
    assert!((900..3000).contains(&after), "{stage}: {after} ms");
    frozen.kill9();
    assert!(!other.finish(WAIT));
    next_run(&s);
    println!("| {stage} | {after} | — | — | 0 |");
}

#[test]
fn peers_that_stall_without_dying_are_reported() {
    stalled(
        "navigator stops reading without dying (lockstep, --timeout-s 1)",
        "sl",
        &["--timeout-s", "1"],
        &["--stall", "nav-received:100"],
        false,
    );
    stalled(
        "navigator stops reading without dying (free-running: its buffer fills, --timeout-s 1)",
        "sf",
        &["--free", "--timeout-s", "1"],
        &["--no-ack", "--stall", "nav-received:5"],
        false,
    );
    stalled(
        "plant stops sending without dying (--timeout-s 1)",
        "sp",
        &["--stall", "plant-awaiting-ack:100"],
        &["--timeout-s", "1"],
        true,
    );
}

#[test]
fn a2_sigterm_stops_a_slowly_paced_plant_within_one_batch() {
    // 0.5 x real time, 64 samples per batch: one batch every 1.28 s. Before the fix the signal
    // was looked at every 256 batches (5.5 min here); the pacing sleep was not cut short.
    let s = session("term");
    let mut p = Peer::spawn(
        "plant",
        &s,
        &["--samples", "100000", "--batch", "64", "--pace", "0.5"],
    );
    let mut n = nav(&s, &[]);
    std::thread::sleep(Duration::from_millis(700));
    let sent = now_ms();
    peer::signal(p.pid(), "TERM");
    let end = p.expect("END", WAIT);
    let after = stamp(&end).saturating_sub(sent);
    let r = n.expect("RESULT", WAIT);
    assert!(field_str(&r, "interrupted") == "true", "{r}");
    assert!(p.finish(WAIT) && n.finish(WAIT));
    assert!(after <= 100, "end of run sent {after} ms after SIGTERM");
    assert!(left(&s).is_empty());
    remove_counter(&s);
    println!(
        "| SIGTERM to a plant paced at 0.5 × real time, 64-sample batches | {after} (end of run sent) | 0 | 0 | 0 |"
    );
}

fn field_str<'a>(line: &'a str, key: &str) -> &'a str {
    line.split_whitespace()
        .find_map(|kv| kv.strip_prefix(key).and_then(|v| v.strip_prefix('=')))
        .unwrap_or("")
}

#[test]
fn a_plant_slow_to_read_the_end_acknowledgement_still_gets_it() {
    // iceoryx2 drops the samples of a publisher that is gone before the subscriber has
    // connected to it (iceoryx2 issue #39). A replacement navigator that acknowledged the resent
    // end of the run and exited at once lost that acknowledgement when the plant had not read
    // its commands since the navigator joined: the plant waited for a navigator that never came
    // (seen under CI load). The navigator now stays until the plant has left; here the plant
    // pauses 500 ms after sending the end to make the race certain.
    let s = session("slowend");
    let end = SAMPLES / BATCH - 1;
    let sleep = format!("plant-end-sent:{end}=500");
    let mut p = plant(&s, &["--wait", "--sleep", &sleep]);
    let mut n1 = nav(&s, &["--stall", &format!("nav-end-received:{end}")]);
    n1.expect("STALL", WAIT);
    n1.kill9();
    p.expect("LOST", WAIT);
    let mut n2 = nav(&s, &[]);
    let r = n2.expect("RESULT", WAIT);
    let (p_ok, n_ok) = (p.finish(WAIT), n2.finish(WAIT));
    assert!(p_ok && n_ok, "{r}\n{}\n{}", p.said(), n2.said());
    assert_eq!(restart_figures(&r, end), (0, 0), "{r}");
    assert!(left(&s).is_empty());
    remove_counter(&s);
}
