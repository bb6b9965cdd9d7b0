//! `rins nav`: the reference navigator as a separate process, consuming a served IMU stream. It
//! starts from the state the plant sends with the first batch it receives (the run's start, or
//! the batch a replacement navigator joins at), prints its solution in degrees, and its final
//! error when the plant publishes its truth.

use std::path::PathBuf;

use anyhow::Result;
use rins_transport::{NavAction, ScheduledCommand};

use super::args::{Overrides, load};
use super::serve::peer_timeout;

/// Arguments of `rins nav`.
#[derive(clap::Args, Debug)]
pub struct NavArgs {
    /// Session to connect to (1-64 letters, digits, '-', '_').
    #[arg(long)]
    pub connect: String,
    /// The scenario being served (its run.rate_hz; the start state comes from the plant).
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
    rins_transport::session::check_name(&a.connect)?;
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
    let out = summary_json(&s);
    eprintln!("{}", summary_line(&s));
    println!("{out}");
    Ok(())
}

/// Longitude wrapped to (−π, π], rad. The navigator integrates longitude without wrapping it
/// (a ship crossing the antimeridian eastwards goes beyond π), so the output wraps it; one
/// already within the range keeps its bits.
fn lon_wrapped_rad(lon_rad: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    if lon_rad > -PI && lon_rad <= PI {
        return lon_rad;
    }
    let w = PI - (PI - lon_rad).rem_euclid(TAU);
    // Rounding may land on −π itself, which the range leaves out.
    if w <= -PI { w + TAU } else { w }
}

/// Longitude in degrees, of [`lon_wrapped_rad`]: (−180°, 180°], the same longitude as the
/// JSON's `lon_rad`.
fn lon_deg(lon_rad: f64) -> f64 {
    lon_wrapped_rad(lon_rad).to_degrees()
}

/// The result as one JSON object: degrees and SI units in the names; `lat_rad`/`lon_rad` keep
/// the exact bits for comparisons (the longitude wrapped to (−π, π] as `lon_deg` is, its bits
/// kept when the navigator's is already there); the error figures when the plant published
/// its truth.
fn summary_json(s: &rins_transport::NavSummary) -> serde_json::Value {
    let st = s.nav.state().copied();
    let q = st.map(|s| s.q_bn.into_inner());
    let fe = s.final_error();
    serde_json::json!({
        "samples": s.nav.samples,
        "batches": s.batches,
        "duplicates": s.duplicates,
        "first_tick": s.nav.first_tick,
        "last_tick": s.nav.last_tick,
        "digest": format!("{:016x}", s.nav.digest),
        "interrupted": s.interrupted,
        "start": s.nav.start.map(|b| serde_json::json!({
            "tick": b.tick,
            "lat_deg": b.lat_rad.to_degrees(),
            "lon_deg": lon_deg(b.lon_rad),
            "height_m": b.height_m,
            "v_enu_mps": b.v_enu_mps,
        })),
        "lat_deg": st.map(|s| s.lat_rad.to_degrees()),
        "lon_deg": st.map(|s| lon_deg(s.lon_rad)),
        "height_m": st.map(|s| s.height_m),
        "v_enu_mps": st.map(|s| [s.v_n.x, s.v_n.y, s.v_n.z]),
        "q_bn": q.map(|q| [q.w, q.i, q.j, q.k]),
        "lat_rad": st.map(|s| s.lat_rad),
        "lon_rad": st.map(|s| lon_wrapped_rad(s.lon_rad)),
        "north_error_m": fe.map(|e| e.north_m),
        "east_error_m": fe.map(|e| e.east_m),
        "horizontal_error_m": fe.map(|e| e.horizontal_m),
        "velocity_error_mps": fe.map(|e| e.velocity_mps),
    })
}

/// One line for people: where the navigator ended and, with the plant's truth, how far off.
fn summary_line(s: &rins_transport::NavSummary) -> String {
    let Some(st) = s.nav.state() else {
        return format!("navigated {} samples: no solution", s.nav.samples);
    };
    let mut line = format!(
        "navigated {} samples (ticks {}-{}): {:.6}° {}, {:.6}° {}, v_e {:.3} m/s, v_n {:.3} m/s",
        s.nav.samples,
        s.nav.first_tick.unwrap_or(0),
        s.nav.last_tick,
        st.lat_rad.to_degrees().abs(),
        if st.lat_rad < 0.0 { "S" } else { "N" },
        lon_deg(st.lon_rad).abs(),
        if lon_deg(st.lon_rad) < 0.0 { "W" } else { "E" },
        st.v_n.x,
        st.v_n.y,
    );
    match s.final_error() {
        Some(e) => line.push_str(&format!(
            "; error against the plant's truth: horizontal {:.3} m (north {:.3} m, east {:.3} m), velocity {:.4} m/s",
            e.horizontal_m, e.north_m, e.east_m, e.velocity_mps
        )),
        None => line.push_str("; the plant published no truth: no error figure"),
    }
    line
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

#[cfg(test)]
mod tests {
    use super::*;
    use rins_transport::layout::{ImuRecord, StartRecord, TruthRecord};

    /// A summary as `navigate` returns it: the reference navigator over `samples` of `cfg`,
    /// started like the transport starts it, with the plant's truth at the end if `truth`.
    fn summary(
        cfg: &rins_plant::PlantConfig,
        samples: u64,
        truth: bool,
    ) -> rins_transport::NavSummary {
        let mut plant = rins_plant::Plant::new(cfg).unwrap();
        let mut nav = rins_transport::NavProcessor::new(cfg);
        nav.begin(&StartRecord::from_plant(&plant));
        for _ in 0..samples {
            nav.push(&ImuRecord::from_sample(&plant.step()));
        }
        rins_transport::NavSummary {
            nav,
            batches: 1,
            duplicates: 0,
            interrupted: false,
            truth: truth.then(|| TruthRecord::from_plant(&plant)),
        }
    }

    /// (−π, π]: within it the bits are kept, beyond it whole turns come off, and both ends
    /// map into it (π stays, −π becomes π).
    #[test]
    fn longitude_is_wrapped_to_minus_pi_exclusive_pi_inclusive() {
        use std::f64::consts::{PI, TAU};
        for lon in [0.0, -0.0, 1.0, -3.0, PI, -PI + 1e-15, 3.1] {
            assert_eq!(lon_wrapped_rad(lon).to_bits(), lon.to_bits(), "{lon}");
        }
        assert_eq!(lon_wrapped_rad(-PI), PI);
        let w = lon_wrapped_rad(PI + TAU);
        assert!(w <= PI && PI - w < 1e-15, "{w}");
        // The figure: 3.14287 rad is −179.93°.
        let w = lon_wrapped_rad(3.14287);
        assert!((w - (3.14287 - TAU)).abs() < 1e-15, "{w}");
        assert!(
            (lon_deg(3.14287) - (-179.93)).abs() < 5e-3,
            "{}",
            lon_deg(3.14287)
        );
        assert_eq!(lon_deg(3.14287), w.to_degrees());
        for k in -3..=3 {
            for lon in [0.5, -2.0, 3.0, -3.05] {
                let w = lon_wrapped_rad(lon + k as f64 * TAU);
                assert!(w > -PI && w <= PI, "{k}, {lon}: {w}");
                assert!((w - lon).abs() < 1e-14, "{k}, {lon}: {w}");
            }
        }
        let big = lon_wrapped_rad(-1e6);
        assert!(big > -PI && big <= PI, "{big}");
    }

    #[test]
    fn the_output_is_in_degrees_with_the_error_against_the_truth() {
        // Issue 29's ship: 0° N 179.99° E, east at 30 kn; it crosses the antimeridian at ~72 s.
        let mut cfg = rins_plant::presets::paper_16pos_config();
        cfg.carrier.kind = rins_plant::carrier::CarrierKind::Ship;
        (cfg.carrier.ship.lat_deg, cfg.carrier.ship.lon_deg) = (0.0, 179.99);
        cfg.carrier.ship.legs = vec![rins_plant::carrier::LegSpec {
            heading_deg: 90.0,
            speed_kn: 30.0,
            duration_s: 3600.0,
        }];
        let s = summary(&cfg, 10_000, true);
        let j = summary_json(&s);
        let st = s.nav.state().unwrap();
        assert_eq!(j["lat_deg"].as_f64().unwrap(), st.lat_rad.to_degrees());
        // East of the antimeridian: printed as west longitude, within ±180°, in degrees and
        // in radians alike (the navigator's own longitude is beyond π).
        let lon = j["lon_deg"].as_f64().unwrap();
        assert!((-180.0..-179.9).contains(&lon), "{lon}");
        assert!(
            (st.lon_rad.to_degrees() - 360.0 - lon).abs() < 1e-9,
            "{lon}"
        );
        assert!(st.lon_rad > std::f64::consts::PI, "{}", st.lon_rad);
        let lon_rad = j["lon_rad"].as_f64().unwrap();
        assert!((lon_rad - (st.lon_rad - std::f64::consts::TAU)).abs() < 1e-15);
        assert_eq!(lon_rad.to_degrees(), lon);
        let start_lon = j["start"]["lon_deg"].as_f64().unwrap();
        assert!(
            (start_lon - 179.99).abs() < 1e-9,
            "starts at the ship: {start_lon}"
        );
        let v_e = j["v_enu_mps"][0].as_f64().unwrap();
        assert!((v_e - 15.43).abs() < 0.5, "v_e {v_e} m/s at 30 kn");
        // The error against the truth, computed here from the truth record independently.
        let t = s.truth.unwrap();
        let (rm, rn) = rins_plant::earth::radii_of_curvature(t.lat_rad);
        let dlon = st.lon_rad
            - t.lon_rad
            - (st.lon_rad - t.lon_rad + std::f64::consts::PI).div_euclid(std::f64::consts::TAU)
                * std::f64::consts::TAU;
        let north = (st.lat_rad - t.lat_rad) * (rm + t.height_m);
        let east = dlon * (rn + t.height_m) * t.lat_rad.cos();
        let h = j["horizontal_error_m"].as_f64().unwrap();
        assert!((h - north.hypot(east)).abs() < 1e-9, "{h} m");
        assert!(h < 50.0, "the navigator follows the ship: {h} m");
        assert!(
            summary_line(&s).contains("horizontal"),
            "{}",
            summary_line(&s)
        );
        // Without the plant's truth: no error figure, and the line says so.
        let s = summary(&cfg, 100, false);
        assert!(summary_json(&s)["horizontal_error_m"].is_null());
        assert!(
            summary_line(&s).contains("no truth"),
            "{}",
            summary_line(&s)
        );
    }
}
