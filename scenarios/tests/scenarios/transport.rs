//! The plant and the navigator as separate processes (`rins serve`, `rins nav`) over iceoryx2:
//! lockstep over one simulated hour equals the in-process run bit for bit; a navigator killed
//! with SIGKILL is detected and replaced with no sample lost or duplicated from the restart
//! point; a killed plant is detected by the navigator, and a new session on the same name works.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const RINS: &str = env!("CARGO_BIN_EXE_rins");

fn session(tag: &str) -> String {
    format!("p{}{tag}", std::process::id())
}

fn json(out: &std::process::Output) -> serde_json::Value {
    let text = String::from_utf8_lossy(&out.stdout);
    serde_json::from_str(text.trim())
        .unwrap_or_else(|e| panic!("{e}: {text} / {}", String::from_utf8_lossy(&out.stderr)))
}

#[test]
fn lockstep_processes_over_one_hour_equal_the_in_process_run() {
    let name = session("hour");
    let serve = Command::new(RINS)
        .args([
            "serve",
            "builtin:paper-16pos-week",
            "--session",
            &name,
            "--duration-s",
            "3600",
            "--batch",
            "50",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let nav = Command::new(RINS)
        .args([
            "nav",
            "--connect",
            &name,
            "builtin:paper-16pos-week",
            "--duration-s",
            "3600",
            "--command-after",
            "3000:90:180:5",
        ])
        .output()
        .unwrap();
    let served = serve.wait_with_output().unwrap();
    assert!(
        nav.status.success(),
        "{}",
        String::from_utf8_lossy(&nav.stderr)
    );
    assert!(
        served.status.success(),
        "{}",
        String::from_utf8_lossy(&served.stderr)
    );
    let got = json(&nav);
    let cfg = rins_plant::presets::paper_16pos_config();
    let cmd = [rins_transport::ScheduledCommand {
        after_seq: 3000,
        action: rins_transport::NavAction::MoveTo {
            outer_rad: 90f64.to_radians(),
            inner_rad: 180f64.to_radians(),
            rate_rps: 5f64.to_radians(),
        },
    }];
    let want = rins_transport::reference(&cfg, 360_000, 50, &cmd);
    assert_eq!(got["samples"], 360_000);
    assert_eq!(got["last_tick"], 359_999);
    assert_eq!(
        got["digest"],
        format!("{:016x}", want.digest),
        "every navigation state equal to the last bit"
    );
    let s = want.state().unwrap();
    assert_eq!(
        got["lat_rad"].as_f64().unwrap().to_bits(),
        s.lat_rad.to_bits()
    );
    assert_eq!(
        got["lon_rad"].as_f64().unwrap().to_bits(),
        s.lon_rad.to_bits()
    );
}

#[test]
fn a_killed_navigator_is_detected_and_a_new_one_resumes_without_loss() {
    let name = session("navkill");
    let serve = Command::new(RINS)
        .args([
            "serve",
            "builtin:paper-16pos-week",
            "--session",
            &name,
            "--duration-s",
            "60",
            "--batch",
            "10",
            "--pace",
            "15",
            "--wait-for-restart",
            "--peer-timeout-s",
            "20",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // A navigator killed mid-run (the lockstep plant is paced at 15x real time: 4 s).
    let mut first = Command::new(RINS)
        .args(["nav", "--connect", &name, "builtin:paper-16pos-week"])
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1000));
    first.kill().unwrap(); // SIGKILL
    first.wait().unwrap();
    let killed = Instant::now();
    let second = Command::new(RINS)
        .args(["nav", "--connect", &name, "builtin:paper-16pos-week"])
        .output()
        .unwrap();
    let served = serve.wait_with_output().unwrap();
    let log = String::from_utf8_lossy(&served.stderr);
    assert!(served.status.success(), "{log}");
    // Either the plant found the navigator dead, or the new navigator cleaned up its dead
    // predecessor first and announced itself; both resend the unacknowledged batch.
    assert!(
        log.contains("navigator died")
            || log.contains("navigator gone")
            || log.contains("a navigator joined"),
        "{log}"
    );
    let restarts: u32 = log
        .split(" navigator restarts")
        .next()
        .and_then(|h| h.rsplit(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    assert!(restarts >= 1, "{log}");
    assert!(killed.elapsed() < Duration::from_secs(30));
    let got = json(&second);
    // From the restart point to the end: every sample once.
    let (first_tick, last_tick, samples) = (
        got["first_tick"].as_u64().unwrap(),
        got["last_tick"].as_u64().unwrap(),
        got["samples"].as_u64().unwrap(),
    );
    assert!(first_tick > 0, "the restart point is mid-run");
    assert_eq!(last_tick, 5_999);
    assert_eq!(
        samples,
        last_tick - first_tick + 1,
        "no sample lost or duplicated from the restart point"
    );
}

#[test]
fn a_killed_plant_is_detected_and_the_session_restarts() {
    let name = session("plantkill");
    let mut plant = Command::new(RINS)
        .args([
            "serve",
            "builtin:paper-16pos-week",
            "--session",
            &name,
            "--mode",
            "free",
            "--pace",
            "1",
        ])
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let nav = Command::new(RINS)
        .args([
            "nav",
            "--connect",
            &name,
            "builtin:paper-16pos-week",
            "--no-ack",
        ])
        .stderr(Stdio::piped())
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(500));
    plant.kill().unwrap();
    plant.wait().unwrap();
    let killed = Instant::now();
    let out = nav.wait_with_output().unwrap();
    let detected = killed.elapsed();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("plant process died"), "{err}");
    assert!(
        detected < Duration::from_secs(2),
        "detected after {detected:?}"
    );
    // Restart on the same session: dead nodes are cleaned up at start, and the run completes.
    let serve = Command::new(RINS)
        .args([
            "serve",
            "builtin:paper-16pos-week",
            "--session",
            &name,
            "--duration-s",
            "60",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let nav = Command::new(RINS)
        .args([
            "nav",
            "--connect",
            &name,
            "builtin:paper-16pos-week",
            "--duration-s",
            "60",
        ])
        .output()
        .unwrap();
    assert!(serve.wait_with_output().unwrap().status.success());
    assert_eq!(json(&nav)["samples"], 6000);
}

#[test]
fn sigint_stops_the_plant_cleanly() {
    let name = session("sigint");
    let serve = Command::new(RINS)
        .args([
            "serve",
            "builtin:paper-16pos-week",
            "--session",
            &name,
            "--peer-timeout-s",
            "30",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(300));
    let rc = unsafe_kill(serve.id(), libc::SIGINT);
    assert_eq!(rc, 0);
    let out = serve.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("interrupted"), "{err}");
    // Nothing stale: the same session serves again.
    let serve = Command::new(RINS)
        .args([
            "serve",
            "builtin:paper-16pos-week",
            "--session",
            &name,
            "--duration-s",
            "10",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let nav = Command::new(RINS)
        .args([
            "nav",
            "--connect",
            &name,
            "builtin:paper-16pos-week",
            "--duration-s",
            "10",
        ])
        .output()
        .unwrap();
    assert!(serve.wait_with_output().unwrap().status.success());
    assert_eq!(json(&nav)["samples"], 1000);
}

#[allow(unsafe_code)]
fn unsafe_kill(pid: u32, sig: i32) -> i32 {
    // SAFETY: sending a signal to our own child process.
    unsafe { libc::kill(pid as i32, sig) }
}
