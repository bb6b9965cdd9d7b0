//! Driving `rins-chaos-peer` processes: spawn, read their report lines as they come, kill -9
//! or SIGSTOP them, and list what a session left in /dev/shm.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

const PEER: &str = env!("CARGO_BIN_EXE_rins-chaos-peer");

/// Samples per run and per batch: 300 batches.
pub const SAMPLES: u64 = 3000;
pub const BATCH: u64 = 10;

pub fn now_ms() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_millis() as u64)
        .unwrap_or(0)
}

/// A running peer and its report lines.
pub struct Peer {
    pub name: String,
    child: Child,
    lines: Receiver<String>,
    seen: Vec<String>,
}

impl Peer {
    /// `rins-chaos-peer ROLE SESSION ARGS…`.
    pub fn spawn(role: &str, session: &str, args: &[&str]) -> Self {
        let mut child = Command::new(PEER)
            .arg(role)
            .arg(session)
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("rins-chaos-peer runs");
        let out = child.stdout.take().expect("piped");
        let (tx, rx) = channel();
        std::thread::spawn(move || {
            for l in BufReader::new(out).lines().map_while(Result::ok) {
                if tx.send(l).is_err() {
                    break;
                }
            }
        });
        Self {
            name: format!("{role} {}", args.join(" ")),
            child,
            lines: rx,
            seen: Vec::new(),
        }
    }

    /// The next report line starting with `prefix` (also among those read but not taken yet),
    /// within `timeout`; it is taken (a second call waits for the next one).
    pub fn wait_for(&mut self, prefix: &str, timeout: Duration) -> Option<String> {
        if let Some(i) = self.seen.iter().position(|l| l.starts_with(prefix)) {
            return Some(self.seen.remove(i));
        }
        let t = Instant::now();
        while let Some(left) = timeout.checked_sub(t.elapsed()) {
            match self.lines.recv_timeout(left) {
                Ok(l) => {
                    if l.starts_with(prefix) {
                        return Some(l);
                    }
                    self.seen.push(l);
                }
                Err(_) => return None,
            }
        }
        None
    }

    /// Like [`Peer::wait_for`], panicking with what the peer said when the line does not come.
    pub fn expect(&mut self, prefix: &str, timeout: Duration) -> String {
        match self.wait_for(prefix, timeout) {
            Some(l) => l,
            None => panic!(
                "{}: no {prefix:?} line within {timeout:?}; said {:?}",
                self.name, self.seen
            ),
        }
    }

    /// kill -9; returns the wall time of the kill, ms since the epoch.
    pub fn kill9(&mut self) -> u64 {
        let t = now_ms();
        let _ = self.child.kill();
        let _ = self.child.wait();
        t
    }

    /// Waits for the process to end (killing it after `timeout`); whether it exited with 0.
    pub fn finish(&mut self, timeout: Duration) -> bool {
        let t = Instant::now();
        loop {
            if let Ok(Some(st)) = self.child.try_wait() {
                // Collect the remaining lines.
                while let Ok(l) = self.lines.recv_timeout(Duration::from_millis(200)) {
                    self.seen.push(l);
                }
                return st.success();
            }
            if t.elapsed() > timeout {
                self.kill9();
                return false;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Everything the peer printed that was not taken by [`Peer::expect`]: its name and lines,
    /// for failure messages.
    pub fn said(&self) -> String {
        format!("{}: {:?}", self.name, self.seen)
    }

    pub fn pid(&self) -> u32 {
        self.child.id()
    }
}

impl Drop for Peer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The unix-ms stamp of a `LOST`/`STALL`/`ERROR` line (its third field; second for ERROR).
pub fn stamp(line: &str) -> u64 {
    let f: Vec<&str> = line.split_whitespace().collect();
    let i = if line.starts_with("ERROR") { 1 } else { 2 };
    f.get(i).and_then(|v| v.parse().ok()).unwrap_or(0)
}

/// `key=value` from a `RESULT` line.
pub fn field(line: &str, key: &str) -> u64 {
    line.split_whitespace()
        .find_map(|kv| kv.strip_prefix(&format!("{key}=")))
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no {key} in {line}"))
}

/// The batch number of a `… stage:seq …` line.
pub fn stage_seq(line: &str) -> u64 {
    line.split_whitespace()
        .nth(1)
        .and_then(|s| s.rsplit(':').next())
        .and_then(|v| v.parse().ok())
        .unwrap_or(0)
}

/// Files of `session` in /dev/shm and /tmp/iceoryx2, but iceoryx2's persistent 16-byte node
/// counter of the session name (`…node.<version>.global_mgmt`), kept by design.
pub fn left(session: &str) -> Vec<String> {
    let prefix = format!("rins_{session}_");
    let mut out = Vec::new();
    let mut walk = vec![std::path::PathBuf::from("/dev/shm"), "/tmp/iceoryx2".into()];
    while let Some(dir) = walk.pop() {
        let Ok(rd) = std::fs::read_dir(&dir) else {
            continue;
        };
        for e in rd.flatten() {
            let p = e.path();
            if p.is_dir() {
                walk.push(p);
                continue;
            }
            let n = e.file_name().to_string_lossy().to_string();
            if n.contains(&prefix) && !n.ends_with(".global_mgmt") {
                out.push(p.display().to_string());
            }
        }
    }
    out
}

/// Removes the node counter of a finished test session (no process of it is running).
pub fn remove_counter(session: &str) {
    let prefix = format!("rins_{session}_");
    if let Ok(rd) = std::fs::read_dir("/dev/shm") {
        for e in rd.flatten() {
            let n = e.file_name().to_string_lossy().to_string();
            if n.starts_with(&prefix) && n.ends_with(".global_mgmt") {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
}

/// Sends `sig` (e.g. "STOP", "CONT", "TERM") with kill(1).
pub fn signal(pid: u32, sig: &str) {
    let ok = Command::new("kill")
        .arg(format!("-{sig}"))
        .arg(pid.to_string())
        .status()
        .map(|s| s.success())
        .unwrap_or(false);
    assert!(ok, "kill -{sig} {pid}");
}
