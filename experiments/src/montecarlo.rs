//! The Monte Carlo engine: many seeds of one case, each seed's samples feeding several
//! navigators (uncompensated and compensated, say) from one plant run. Seeds whose physics is
//! the same share it ([`rins_plant::SeedBatch`]): the motion, the temperature field and the
//! deterministic sensor errors are computed once per interval for a whole batch, the readout
//! and the navigators once per seed. The members' navigators are split into one batch per core
//! (a member whose navigators fall in two batches is read out in both).
//!
//! A seed's runs are bit-identical to [`crate::run`] of that seed alone with each navigator:
//! the samples are (the batch's guarantee) and each navigator sees them in the same order.

use nalgebra::Vector3;
use rayon::prelude::*;
use rins_navigation::errors::NavRecord;
use rins_navigation::strapdown::Strapdown;
use rins_navigation::strapdown_lanes::{LANES, StrapdownLanes};
use rins_plant::{PlantConfig, SeedBatch};

use crate::session::{
    Alignment, NavRun, NavRunConfig, PROGRESS_EVERY, SessionError, run_with_progress, tracker_for,
};
use crate::tracker::initial_state;

/// Runs `seeds` of `cfg` for `nav_s` seconds; each seed's samples feed one navigator per
/// entry of `navs`. Returns, per seed in order, one run per navigator. `progress` receives
/// samples done (summed over seeds and navigators, like separate runs would report).
/// Self-alignment steps each navigator's plant through its own alignment, so those runs are
/// made one by one ([`crate::run`]).
pub fn run_seeds(
    cfg: &PlantConfig,
    seeds: &[u64],
    nav_s: f64,
    navs: &[NavRunConfig],
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<Vec<NavRun>>, SessionError> {
    let members: Vec<PlantConfig> = seeds.iter().map(|&s| cfg.with_seed(s)).collect();
    run_members(&members, nav_s, navs, progress)
}

/// [`run_seeds`] over whole configurations: each member of `members` (a seed of a case, or the
/// case with its noise off) feeds one navigator per entry of `navs`. Members that differ only
/// in their seed and stochastic terms share one plant's physics ([`SeedBatch::of`]), so Table
/// 4's noise-free pair rides in a batch with the seeds. Returns, per member in order, one run
/// per navigator.
pub fn run_members(
    members: &[PlantConfig],
    nav_s: f64,
    navs: &[NavRunConfig],
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<Vec<NavRun>>, SessionError> {
    run_members_split(members, nav_s, navs, Split::PerCore, progress)
}

/// How [`run_members_split`] divides a case that shares its physics into batches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Split {
    /// One batch per core, with equal runs of navigators: the case alone uses every core.
    PerCore,
    /// One batch: for a caller that runs as many cases side by side as there are cores. The
    /// plant's physics is then computed once rather than once per core, and the navigators
    /// fill whole lane groups.
    Whole,
}

/// [`run_members`] with the batches chosen by `split` (members that do not share the physics
/// are split per core either way).
pub fn run_members_split(
    members: &[PlantConfig],
    nav_s: f64,
    navs: &[NavRunConfig],
    split: Split,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<Vec<NavRun>>, SessionError> {
    if !(nav_s > 0.0 && navs.iter().all(|n| n.record_every_s > 0.0)) {
        return Err(SessionError::BadTimes(format!(
            "navigation time {nav_s} s and record intervals must be > 0"
        )));
    }
    // The configurations are checked here, once (every plant below is built from them).
    for m in members {
        m.validate().map_err(invalid_config)?;
    }
    if navs
        .iter()
        .any(|n| matches!(n.alignment, Alignment::SelfAlign { .. }))
    {
        return members
            .par_iter()
            .map(|m| {
                navs.iter()
                    .map(|n| {
                        let mut p = rins_plant::Plant::new(m).expect("validated configuration");
                        run_with_progress(&mut p, nav_s, n, progress)
                    })
                    .collect()
            })
            .collect();
    }
    let shared = SeedBatch::shares(members).map_err(invalid_config)?;
    // The work is one slot per member and navigator, member-major. Members that share the
    // physics: the slots split into one equal run of slots per core, so a member at a boundary
    // has its navigators in two batches (each batch reads that member out, and runs only its own
    // navigators): Table 4's 33 members × 2 navigators give each core 33 navigators, where whole
    // members gave one core 34 and the other 32. Members that do not share (a ship with
    // azimuth isolation, say) each run their own plant, and whole members go to a batch: enough
    // of them that their navigators fill a lane group, in a number of batches the cores divide.
    let slots: Vec<Slot> = (0..members.len())
        .flat_map(|m| (0..navs.len()).map(move |n| Slot { member: m, nav: n }))
        .collect();
    let cores = rayon::current_num_threads().max(1);
    let batches: Vec<std::ops::Range<usize>> = if shared {
        match split {
            Split::PerCore => even_split(slots.len(), cores),
            Split::Whole => even_split(slots.len(), 1),
        }
    } else {
        let per_group = (LANES / navs.len().max(1)).max(1);
        let parts = members.len().div_ceil(per_group).div_ceil(cores) * cores;
        even_split(members.len(), parts)
            .into_iter()
            .map(|m| m.start * navs.len()..m.end * navs.len())
            .collect()
    };
    let batches: Vec<Vec<(Slot, NavRun)>> = batches
        .into_par_iter()
        .map(|range| run_batch(members, &slots[range], nav_s, navs, progress))
        .collect::<Result<_, _>>()?;
    let mut runs: Vec<Vec<Option<NavRun>>> = members
        .iter()
        .map(|_| navs.iter().map(|_| None).collect())
        .collect();
    for (slot, run) in batches.into_iter().flatten() {
        runs[slot.member][slot.nav] = Some(run);
    }
    Ok(runs
        .into_iter()
        .map(|r| r.into_iter().map(|x| x.expect("every slot ran")).collect())
        .collect())
}

/// `0..len` in `parts` consecutive ranges whose lengths differ by at most one (the longer
/// first), none empty.
fn even_split(len: usize, parts: usize) -> Vec<std::ops::Range<usize>> {
    let parts = parts.clamp(1, len.max(1));
    let (base, extra) = (len / parts, len % parts);
    let mut start = 0;
    (0..parts)
        .map(|k| {
            let n = base + usize::from(k < extra);
            start += n;
            start - n..start
        })
        .filter(|r| !r.is_empty())
        .collect()
}

/// One member's run with one navigator: indices into the members and the navigators.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Slot {
    member: usize,
    nav: usize,
}

/// One batch: the members named by `slots` stepped together, each slot's member feeding that
/// slot's navigator. The navigators of all slots run side by side in vector lanes
/// ([`StrapdownLanes`]); each keeps its own compensation and error records
/// ([`crate::tracker::Bookkeeping`]). Returns each slot's run.
fn run_batch(
    members: &[PlantConfig],
    slots: &[Slot],
    nav_s: f64,
    navs: &[NavRunConfig],
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<(Slot, NavRun)>, SessionError> {
    // The batch's members in slot order, each once; `lane_of[i]` is slot i's member's lane.
    let mut in_batch: Vec<usize> = Vec::new();
    let lane_of: Vec<usize> = slots
        .iter()
        .map(|s| match in_batch.iter().position(|&m| m == s.member) {
            Some(lane) => lane,
            None => {
                in_batch.push(s.member);
                in_batch.len() - 1
            }
        })
        .collect();
    let chunk: Vec<PlantConfig> = in_batch.iter().map(|&m| members[m].clone()).collect();
    let mut batch = SeedBatch::of(&chunk).map_err(invalid_config)?;
    // The navigators start aligned from truth, which is the same for every lane when they
    // share the physics; a plant per member starts each from its own.
    // Each navigator's bookkeeping goes into its lane group below: the sample loop walks a
    // group's books in lane order with no index into batch-wide lists.
    let samples = (nav_s / batch.first().dt_s()).round() as u64;
    let mut books = Vec::new();
    let mut navigators = Vec::new();
    for (i, (s, &lane)) in slots.iter().zip(&lane_of).enumerate() {
        let plant = batch.plant(lane);
        let init = initial_state(plant);
        let (nav, book) = tracker_for(plant, init, init.height_m, &navs[s.nav]).into_parts();
        let records = Vec::with_capacity((samples / book.record_interval() + 1) as usize);
        books.push(Some(LaneBook {
            slot: i,
            member: lane,
            book,
            records,
        }));
        navigators.push(nav);
    }
    let mut groups: Vec<(StrapdownLanes, Vec<LaneBook>)> = lane_groups(&navigators)
        .into_iter()
        .map(|group| {
            let members: Vec<Strapdown> = group.iter().map(|&i| navigators[i].clone()).collect();
            let lanes = StrapdownLanes::new(&members).expect("grouped alike");
            let books = group
                .iter()
                .map(|&i| books[i].take().expect("one group per navigator"))
                .collect();
            (lanes, books)
        })
        .collect();
    let (mut dth, mut dv) = ([Vector3::zeros(); LANES], [Vector3::zeros(); LANES]);
    let mut reported = 0;
    for k in 1..=samples {
        batch.step();
        let out = batch.samples();
        for (g, lanes) in &mut groups {
            for (j, l) in lanes.iter_mut().enumerate() {
                let s = &out[l.member];
                dth[j] = l.book.dtheta(s, || g.up_b(j));
                dv[j] = s.dv_mps;
            }
            g.update(&dth[..lanes.len()], &dv[..lanes.len()]);
            for (j, l) in lanes.iter_mut().enumerate() {
                if l.book.advance(&out[l.member]) || k == samples {
                    let record = l.book.record(&g.state(j), &batch.truth(l.member));
                    l.records.push(record);
                }
            }
        }
        if k % PROGRESS_EVERY == 0 || k == samples {
            progress((k - reported) * slots.len() as u64);
            reported = k;
        }
    }
    let mut done: Vec<LaneBook> = groups.into_iter().flat_map(|(_, l)| l).collect();
    done.sort_by_key(|l| l.slot);
    Ok(done
        .into_iter()
        .map(|l| {
            let run = NavRun {
                up_att_mean_abs_rad: l.book.up_att_mean_abs_rad(),
                records: l.records,
                alignment: None,
            };
            (slots[l.slot], run)
        })
        .collect())
}

/// A navigator's bookkeeping in its lane group: its slot in the batch, its member's lane in
/// the batch's samples, its compensation and error records ([`crate::tracker::Bookkeeping`]).
struct LaneBook {
    slot: usize,
    member: usize,
    book: crate::tracker::Bookkeeping,
    records: Vec<NavRecord>,
}

/// The plant's configuration errors as the engine's error, in one line.
fn invalid_config(e: Vec<rins_plant::ConfigError>) -> SessionError {
    SessionError::InvalidConfig(
        e.iter()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join("; "),
    )
}

/// The navigators' indices in groups of at most [`LANES`] that can share lanes (the same
/// update interval, vertical channel and intervals per update; none has an update under way
/// here), in order.
fn lane_groups(navigators: &[Strapdown]) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for (i, n) in navigators.iter().enumerate() {
        let alike = |g: &&mut Vec<usize>| {
            let first = &navigators[g[0]];
            g.len() < LANES
                && first.dt_s() == n.dt_s()
                && first.vertical() == n.vertical()
                && first.subsamples() == n.subsamples()
        };
        match groups.iter_mut().find(alike) {
            Some(g) => g.push(i),
            None => groups.push(vec![i]),
        }
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::session::run;
    use rins_navigation::VerticalChannel;
    use rins_plant::Plant;
    use rins_plant::carrier::{CarrierKind, SpectrumKind};

    /// Each seed's runs through the engine equal `run` of that seed alone with each navigator,
    /// record for record, bit for bit.
    fn check(cfg: &PlantConfig, nav_s: f64) {
        let navs = [
            NavRunConfig {
                record_every_s: 20.0,
                ..NavRunConfig::default()
            },
            NavRunConfig {
                record_every_s: 30.0,
                compensation: Some(cfg.sensor.gyro.position_bias),
                ..NavRunConfig::default()
            },
        ];
        check_with(cfg, &[3, 4, 9], &navs, nav_s);
    }

    fn check_with(cfg: &PlantConfig, seeds: &[u64], navs: &[NavRunConfig], nav_s: f64) {
        let got = run_seeds(cfg, seeds, nav_s, navs, &|_| {}).unwrap();
        assert_eq!(got.len(), seeds.len());
        for (seed, runs) in seeds.iter().zip(&got) {
            for (n, r) in navs.iter().zip(runs) {
                let mut p = Plant::new(&PlantConfig {
                    seed: *seed,
                    ..cfg.clone()
                })
                .unwrap();
                let alone = run(&mut p, nav_s, n).unwrap();
                assert_eq!(r.records, alone.records, "seed {seed}");
                assert_eq!(r.up_att_mean_abs_rad, alone.up_att_mean_abs_rad);
                assert!(!r.records.is_empty());
            }
        }
        // Different seeds, different errors.
        assert_ne!(got[0][0].end(), got[1][0].end());
    }

    #[test]
    fn an_invalid_configuration_is_refused_naming_the_field() {
        let mut c = rins_plant::presets::paper_16pos_config();
        c.rate_hz = -5.0;
        let e = run_seeds(&c, &[1, 2], 10.0, &[NavRunConfig::default()], &|_| {}).unwrap_err();
        assert!(matches!(e, SessionError::InvalidConfig(_)), "{e:?}");
        assert!(e.to_string().contains("rate_hz"), "{e}");
    }

    /// One batch of nine seeds with four navigators each, one of them with a damped vertical
    /// channel and one compensating and updating every 4 intervals: 36 navigators in several
    /// lane groups, some of them partly filled.
    #[test]
    fn navigators_in_several_lane_groups_equal_their_runs_alone() {
        let cfg = rins_plant::presets::paper_16pos_config();
        let navs = [
            NavRunConfig::default(),
            NavRunConfig {
                compensation: Some(cfg.sensor.gyro.position_bias),
                ..NavRunConfig::default()
            },
            NavRunConfig {
                vertical: VerticalChannel::Damped {
                    ref_height_m: 0.0,
                    tau_s: 50.0,
                },
                record_every_s: 10.0,
                ..NavRunConfig::default()
            },
            NavRunConfig {
                compensation: Some(cfg.sensor.gyro.position_bias),
                subsamples: rins_navigation::Subsamples::new(4).unwrap(),
                record_every_s: 30.0,
                ..NavRunConfig::default()
            },
        ];
        let one_batch = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        one_batch.install(|| check_with(&cfg, &[1, 2, 3, 4, 5, 6, 7, 8, 9], &navs, 200.0));
        let at = rins_navigation::NavState {
            q_bn: nalgebra::UnitQuaternion::identity(),
            v_n: Vector3::zeros(),
            lat_rad: 0.6,
            lon_rad: 2.0,
            height_m: 0.0,
        };
        let held: Vec<Strapdown> = (0..10)
            .map(|_| Strapdown::new(at, 0.01, VerticalChannel::Hold { ref_height_m: 0.0 }))
            .collect();
        let mut mixed = held.clone();
        mixed.insert(
            3,
            Strapdown::new(
                at,
                0.01,
                VerticalChannel::Damped {
                    ref_height_m: 0.0,
                    tau_s: 50.0,
                },
            ),
        );
        let mut held_slots: Vec<usize> = (0..11).filter(|&i| i != 3).collect();
        let rest = held_slots.split_off(LANES.min(held_slots.len()));
        let mut want = vec![held_slots, vec![3]];
        if !rest.is_empty() {
            want.push(rest);
        }
        assert_eq!(lane_groups(&mixed), want);
        // More navigators than one group holds: the groups fill in order.
        let many = vec![held[0].clone(); LANES + 3];
        let groups = lane_groups(&many);
        assert_eq!(groups.len(), 2);
        assert_eq!(groups[1], (LANES..LANES + 3).collect::<Vec<_>>());
    }

    /// A noise-free member rides in a batch with the seeds (Table 4's pair), and a member's
    /// navigators may fall in two batches: every member's runs equal `run` of its
    /// configuration alone, and the noise-free one's differ from the seeds'.
    #[test]
    fn a_noise_free_member_in_a_batch_equals_its_run_alone() {
        let cfg = rins_plant::presets::paper_16pos_config();
        let quiet = cfg.noise_free();
        let members = [
            PlantConfig {
                seed: 5,
                ..cfg.clone()
            },
            PlantConfig {
                seed: 6,
                ..cfg.clone()
            },
            quiet,
        ];
        assert!(SeedBatch::shares(&members).unwrap());
        let navs = [
            NavRunConfig::default(),
            NavRunConfig {
                compensation: Some(cfg.sensor.gyro.position_bias),
                ..NavRunConfig::default()
            },
        ];
        // One batch; then two, where the six slots split three and three, so the middle
        // member's two navigators run in different batches (each reading that member out).
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let got = pool
                .install(|| run_members(&members, 300.0, &navs, &|_| {}))
                .unwrap();
            for (m, runs) in members.iter().zip(&got) {
                for (n, r) in navs.iter().zip(runs) {
                    let alone = run(&mut Plant::new(m).unwrap(), 300.0, n).unwrap();
                    assert_eq!(
                        r.records, alone.records,
                        "seed {} ({threads} threads)",
                        m.seed
                    );
                }
            }
            assert_ne!(got[2][0].end(), got[0][0].end());
        }
    }

    #[test]
    fn static_seeds_equal_their_runs_alone() {
        check(&rins_plant::presets::paper_16pos_config(), 400.0);
    }

    #[test]
    fn ship_seeds_equal_their_runs_alone_in_calm_water_and_at_sea() {
        let mut c = rins_plant::presets::paper_16pos_config();
        c.carrier.kind = CarrierKind::Ship;
        check(&c, 120.0);
        c.carrier.ship.sea.spectrum = SpectrumKind::Jonswap;
        c.carrier.ship.sea.sea_state = 4;
        check(&c, 120.0);
        // Each seed's sea and isolation loop: a plant per seed, several seeds' navigators side
        // by side in one lane group.
        c.carrier.azimuth_isolation = true;
        assert!(!SeedBatch::shares(&[c.clone()]).unwrap());
        check(&c, 120.0);
        // One sea for every seed: the seeds' own tables are turned from one reference table,
        // so they share its physics.
        c.carrier.ship.sea.realisation = rins_plant::carrier::SeaRealisation::Fixed;
        assert!(SeedBatch::shares(&[c.clone()]).unwrap());
        check(&c, 120.0);
    }

    /// The batches cover every index once, in order, with lengths at most one apart.
    #[test]
    fn an_even_split_covers_every_index_once_in_balanced_ranges() {
        for len in 0..40 {
            for parts in 1..12 {
                let r = even_split(len, parts);
                let flat: Vec<usize> = r.iter().cloned().flatten().collect();
                assert_eq!(flat, (0..len).collect::<Vec<_>>(), "{len} in {parts}");
                assert!(r.len() <= parts && r.iter().all(|x| !x.is_empty()));
                let (lo, hi) = (
                    r.iter().map(|x| x.len()).min(),
                    r.iter().map(|x| x.len()).max(),
                );
                assert!(
                    hi.unwrap_or(0) - lo.unwrap_or(0) <= 1,
                    "{len} in {parts}: {r:?}"
                );
            }
        }
    }
}
