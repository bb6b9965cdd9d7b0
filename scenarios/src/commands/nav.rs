//! `rins nav`: the reference navigator as a separate process, consuming a served IMU stream.

use std::path::PathBuf;

use anyhow::Result;
use rins_transport::{NavAction, ScheduledCommand};

use super::args::{Overrides, load};
use super::serve::peer_timeout;

/// Arguments of `rins nav`.
#[derive(clap::Args, Debug)]
pub struct NavArgs {
    /// Session to connect to.
    #[arg(long)]
    pub connect: String,
    /// The scenario being served (site, mount and rate of the plant).
    pub scenario: PathBuf,
    /// Do not acknowledge batches (for a free-running plant).
    #[arg(long)]
    pub no_ack: bool,
    /// Command the table after batch SEQ: SEQ:OUTER_DEG:INNER_DEG:RATE_DPS (repeatable).
    #[arg(long)]
    pub command_after: Vec<String>,
    /// Switch azimuth isolation after batch SEQ: SEQ:on or SEQ:off (repeatable; a moving
    /// carrier only, docs/carrier.md).
    #[arg(long)]
    pub isolation_after: Vec<String>,
    /// Seconds without a plant before giving up.
    #[arg(long, default_value_t = 30.0, allow_negative_numbers = true)]
    pub peer_timeout_s: f64,
    /// `--seed`, `--duration-s`, `--rate-hz`.
    #[command(flatten)]
    pub overrides: Overrides,
}

/// Navigates on the served stream to its end and prints the final state as one JSON line.
pub fn run(a: &NavArgs) -> Result<()> {
    let sc = load(&a.scenario, &a.overrides)?;
    let mut commands = a
        .command_after
        .iter()
        .map(|c| parse_command(c))
        .chain(a.isolation_after.iter().map(|c| parse_isolation(c)))
        .collect::<Result<Vec<_>>>()?;
    commands.sort_by_key(|c| c.after_seq);
    if let Some(w) = commands
        .windows(2)
        .find(|w| w[0].after_seq == w[1].after_seq)
    {
        anyhow::bail!(
            "two commands after batch {}: one command per acknowledgement (docs/transport.md)",
            w[0].after_seq
        );
    }
    let opts = rins_transport::NavOptions {
        acknowledge: !a.no_ack,
        commands,
        peer_timeout: peer_timeout(a.peer_timeout_s)?,
    };
    let s = rins_transport::navigate(&a.connect, &sc.plant, &opts)?;
    let st = s.nav.state().copied();
    let q = st.map(|s| s.q_bn.into_inner());
    let out = serde_json::json!({
        "samples": s.nav.samples,
        "batches": s.batches,
        "duplicates": s.duplicates,
        "first_tick": s.nav.first_tick,
        "last_tick": s.nav.last_tick,
        "digest": format!("{:016x}", s.nav.digest),
        "interrupted": s.interrupted,
        "lat_rad": st.map(|s| s.lat_rad),
        "lon_rad": st.map(|s| s.lon_rad),
        "v_n": st.map(|s| [s.v_n.x, s.v_n.y, s.v_n.z]),
        "q_bn": q.map(|q| [q.w, q.i, q.j, q.k]),
    });
    println!("{out}");
    Ok(())
}

/// One `--command-after SEQ:OUTER_DEG:INNER_DEG:RATE_DPS`.
fn parse_command(c: &str) -> Result<ScheduledCommand> {
    let p: Vec<&str> = c.split(':').collect();
    let bad =
        || anyhow::anyhow!("--command-after {c:?}: expected SEQ:OUTER_DEG:INNER_DEG:RATE_DPS");
    if p.len() != 4 {
        return Err(bad());
    }
    let f = |s: &str| s.parse::<f64>().map_err(|_| bad());
    Ok(ScheduledCommand {
        after_seq: p[0].parse().map_err(|_| bad())?,
        action: NavAction::MoveTo {
            outer_rad: f(p[1])?.to_radians(),
            inner_rad: f(p[2])?.to_radians(),
            rate_rps: f(p[3])?.to_radians(),
        },
    })
}

/// One `--isolation-after SEQ:on|off`.
fn parse_isolation(c: &str) -> Result<ScheduledCommand> {
    let bad = || anyhow::anyhow!("--isolation-after {c:?}: expected SEQ:on or SEQ:off");
    let (seq, state) = c.split_once(':').ok_or_else(bad)?;
    let on = match state {
        "on" => true,
        "off" => false,
        _ => return Err(bad()),
    };
    Ok(ScheduledCommand {
        after_seq: seq.parse().map_err(|_| bad())?,
        action: NavAction::AzimuthIsolation(on),
    })
}
