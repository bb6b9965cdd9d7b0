//! The paper's week-long simulation (Section 3.1, Table 4, Figures 2–3): uncompensated and
//! compensated navigation of the 16-position RINS over several seeds, side by side with the paper.

use rins_experiments::{NavRecord, NavRunConfig};
use rins_plant::PlantConfig;
use serde::Serialize;

/// Table 4 of the paper and the up-axis mean attitude errors quoted with Figure 2.
pub mod published {
    /// Latitude error at the end, uncompensated / compensated, nmi.
    pub const LAT_NM: [f64; 2] = [2.7088, 2.6382];
    /// Longitude error at the end, uncompensated / compensated, nmi.
    pub const LON_NM: [f64; 2] = [6.6784, 2.6241];
    /// Up-axis mean attitude error, uncompensated / compensated, degrees.
    pub const UP_ATT_MEAN_DEG: [f64; 2] = [0.0338, 0.0302];
}

/// Median and 5–95 % band over the seeds.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Band {
    /// Median.
    pub median: f64,
    /// 5th percentile.
    pub p05: f64,
    /// 95th percentile.
    pub p95: f64,
}

impl Band {
    /// Band of `xs` (linear interpolation between order statistics).
    pub fn of(xs: &[f64]) -> Self {
        let mut v = xs.to_vec();
        v.sort_by(f64::total_cmp);
        let q = |p: f64| {
            if v.is_empty() {
                return f64::NAN;
            }
            let x = p * (v.len() - 1) as f64;
            let (i, f) = (x.floor() as usize, x - x.floor());
            if i + 1 < v.len() {
                v[i] * (1.0 - f) + v[i + 1] * f
            } else {
                v[i]
            }
        };
        Self {
            median: q(0.5),
            p05: q(0.05),
            p95: q(0.95),
        }
    }
}

/// End-of-run figures of one navigation run.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct EndFigures {
    /// Latitude error at the end (signed, north positive), nmi.
    pub lat_nm: f64,
    /// Longitude error at the end (signed, east positive), nmi.
    pub lon_nm: f64,
    /// Horizontal error at the end, nmi.
    pub horizontal_nm: f64,
    /// tRMS at the end (Eq. 20), nmi.
    pub trms_nm: f64,
    /// Mean |φ_U| over the run, degrees.
    pub up_att_mean_deg: f64,
}

impl EndFigures {
    /// The end figures of a finished navigation run.
    pub fn from_run(r: &rins_experiments::NavRun) -> Self {
        let e = r.end();
        let nm = rins_navigation::errors::nmi;
        Self {
            lat_nm: nm(e.north_m),
            lon_nm: nm(e.east_m),
            horizontal_nm: nm(e.horizontal_m),
            trms_nm: nm(e.trms_m),
            up_att_mean_deg: r.up_att_mean_abs_rad.to_degrees(),
        }
    }
}

/// Statistics of one case over the seeds.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct CaseStats {
    /// Signed latitude error.
    pub lat_nm: Band,
    /// Signed longitude error.
    pub lon_nm: Band,
    /// |latitude error| (the paper prints magnitudes).
    pub abs_lat_nm: Band,
    /// |longitude error|.
    pub abs_lon_nm: Band,
    /// Horizontal error.
    pub horizontal_nm: Band,
    /// tRMS.
    pub trms_nm: Band,
    /// Mean |φ_U|.
    pub up_att_mean_deg: Band,
}

impl CaseStats {
    fn of(runs: &[EndFigures]) -> Self {
        let b = |f: &dyn Fn(&EndFigures) -> f64| Band::of(&runs.iter().map(f).collect::<Vec<_>>());
        Self {
            lat_nm: b(&|r| r.lat_nm),
            lon_nm: b(&|r| r.lon_nm),
            abs_lat_nm: b(&|r| r.lat_nm.abs()),
            abs_lon_nm: b(&|r| r.lon_nm.abs()),
            horizontal_nm: b(&|r| r.horizontal_nm),
            trms_nm: b(&|r| r.trms_nm),
            up_att_mean_deg: b(&|r| r.up_att_mean_deg),
        }
    }
}

/// Improvement of compensated over uncompensated, 100·(1 − comp/uncomp), on medians of magnitudes.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Improvement {
    /// |latitude|.
    pub lat: f64,
    /// |longitude|.
    pub lon: f64,
    /// Horizontal.
    pub horizontal: f64,
    /// tRMS.
    pub trms: f64,
    /// Mean |φ_U|.
    pub up_att_mean: f64,
}

fn improvement(u: &CaseStats, c: &CaseStats) -> Improvement {
    let pct = |a: f64, b: f64| 100.0 * (1.0 - b / a);
    Improvement {
        lat: pct(u.abs_lat_nm.median, c.abs_lat_nm.median),
        lon: pct(u.abs_lon_nm.median, c.abs_lon_nm.median),
        horizontal: pct(u.horizontal_nm.median, c.horizontal_nm.median),
        trms: pct(u.trms_nm.median, c.trms_nm.median),
        up_att_mean: pct(u.up_att_mean_deg.median, c.up_att_mean_deg.median),
    }
}

/// The noise-free pair that isolates δβ.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct NoiseFree {
    /// Uncompensated.
    pub uncompensated: EndFigures,
    /// Compensated.
    pub compensated: EndFigures,
}

/// Time series of one run, for the figures.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Series {
    /// Uncompensated records.
    pub uncompensated: Vec<NavRecord>,
    /// Compensated records.
    pub compensated: Vec<NavRecord>,
}

/// `rins paper table4`.
#[derive(Clone, Debug, Serialize)]
pub struct Table4Report {
    /// Seeds.
    pub runs: usize,
    /// Simulated days.
    pub days: f64,
    /// IMU intervals per navigator update ([`rins_navigation::Subsamples`]).
    pub nav_subsamples: u8,
    /// Uncompensated statistics.
    pub uncompensated: CaseStats,
    /// Compensated statistics.
    pub compensated: CaseStats,
    /// Improvements, %.
    pub improvement_pct: Improvement,
    /// The deterministic pair with every stochastic term off.
    pub noise_free: NoiseFree,
    /// Per-seed end figures (uncompensated, compensated).
    pub per_seed: Vec<(u64, EndFigures, EndFigures)>,
    /// Records of the first seed (both cases).
    #[serde(skip)]
    pub first_seed: Series,
    /// Records of the noise-free pair.
    #[serde(skip)]
    pub noise_free_series: Series,
    /// Wall time, s.
    pub wall_s: f64,
}

/// Options of the reproduction.
#[derive(Clone, Debug)]
pub struct Table4Options {
    /// Plant configuration (the Section 3.1 scenario).
    pub plant: PlantConfig,
    /// Seeds run (seed = plant.seed + k).
    pub runs: usize,
    /// Navigation time, s.
    pub duration_s: f64,
    /// Navigator options (alignment, vertical channel, record interval). Compensation is set per case.
    pub nav: NavRunConfig,
    /// What the compensated case subtracts: `None` = the plant's own δβ (known exactly, Table 4);
    /// `Some` = a fitted δβ(T) (Table 5).
    pub compensation: Option<rins_plant::effects::gyro::PositionBiasSpec>,
}

/// The navigators of the study: uncompensated, then compensated with `opt`'s δβ (or the
/// plant's own).
pub fn paired_navs(
    opt: &Table4Options,
    plant_cfg: &PlantConfig,
) -> [rins_experiments::NavRunConfig; 2] {
    [false, true].map(|compensated| {
        let mut cfg = opt.nav.clone();
        cfg.compensation = compensated.then(|| {
            opt.compensation
                .unwrap_or(plant_cfg.sensor.gyro.position_bias)
        });
        cfg
    })
}

/// Runs the reproduction on every core: `runs` seeds × {uncompensated, compensated} with common
/// random numbers (each seed's samples feed both navigators), plus the noise-free pair, through
/// the Monte Carlo engine ([`rins_experiments::run_members`]). `progress` receives samples done.
pub fn table4(opt: &Table4Options, progress: &(dyn Fn(u64) + Sync)) -> Table4Report {
    table4_with(opt, &[], rins_experiments::Split::PerCore, progress).0
}

/// [`table4`] with `extra` members in the same run (each fed to the study's navigators, after
/// the seeds and the noise-free pair): a member that shares the case's physics, such as the
/// case with ideal sensors, rides in its batches. Returns the report and, per extra member,
/// its runs (uncompensated, compensated). `split` divides the case into batches
/// ([`rins_experiments::Split`]).
pub fn table4_with(
    opt: &Table4Options,
    extra: &[PlantConfig],
    split: rins_experiments::Split,
    progress: &(dyn Fn(u64) + Sync),
) -> (Table4Report, Vec<Vec<rins_experiments::NavRun>>) {
    let t0 = std::time::Instant::now();
    let seeds: Vec<u64> = (0..opt.runs as u64).map(|k| opt.plant.seed + k).collect();
    // The noise-free pair is one more member of the case: it shares the seeds' physics, so it
    // rides in a batch with them. It goes in the middle: the engine splits the members'
    // navigators evenly over the cores, so with two cores the member at the boundary is read
    // out in both batches, and the noise-free one's readout draws no normals.
    let mid = seeds.len() / 2;
    let seeded_cfg = |&seed: &u64| opt.plant.with_seed(seed);
    let members: Vec<PlantConfig> = seeds[..mid]
        .iter()
        .map(seeded_cfg)
        .chain(std::iter::once(opt.plant.noise_free()))
        .chain(seeds[mid..].iter().map(seeded_cfg))
        .chain(extra.iter().cloned())
        .collect();
    let mut seeded = rins_experiments::run_members_split(
        &members,
        opt.duration_s,
        &paired_navs(opt, &opt.plant),
        split,
        progress,
    )
    .expect("navigation runs");
    let extra_runs = seeded.split_off(seeded.len() - extra.len());
    let nf_runs = vec![seeded.remove(mid)];
    let mut results: Vec<((Option<u64>, bool), rins_experiments::NavRun)> = Vec::new();
    for (seed, pair) in seeds.iter().zip(seeded) {
        for (comp, r) in [false, true].into_iter().zip(pair) {
            results.push(((Some(*seed), comp), r));
        }
    }
    for pair in nf_runs {
        for (comp, r) in [false, true].into_iter().zip(pair) {
            results.push(((None, comp), r));
        }
    }
    let mut per_seed = Vec::new();
    let mut first = Series::default();
    let mut nf = NoiseFree::default();
    let mut nf_series = Series::default();
    for k in 0..opt.runs as u64 {
        let seed = opt.plant.seed + k;
        let get = |c: bool| {
            results
                .iter()
                .find(|((s, cc), _)| *s == Some(seed) && *cc == c)
                .map(|(_, r)| r)
                .expect("task ran")
        };
        let (u, c) = (get(false), get(true));
        if k == 0 {
            first = Series {
                uncompensated: u.records.clone(),
                compensated: c.records.clone(),
            };
        }
        per_seed.push((seed, EndFigures::from_run(u), EndFigures::from_run(c)));
    }
    for ((s, c), r) in &results {
        if s.is_none() {
            if *c {
                nf.compensated = EndFigures::from_run(r);
                nf_series.compensated = r.records.clone();
            } else {
                nf.uncompensated = EndFigures::from_run(r);
                nf_series.uncompensated = r.records.clone();
            }
        }
    }
    let u: Vec<EndFigures> = per_seed.iter().map(|p| p.1).collect();
    let c: Vec<EndFigures> = per_seed.iter().map(|p| p.2).collect();
    let (us, cs) = (CaseStats::of(&u), CaseStats::of(&c));
    let report = Table4Report {
        runs: opt.runs,
        days: opt.duration_s / 86_400.0,
        nav_subsamples: opt.nav.subsamples.into(),
        improvement_pct: improvement(&us, &cs),
        uncompensated: us,
        compensated: cs,
        noise_free: nf,
        per_seed,
        first_seed: first,
        noise_free_series: nf_series,
        wall_s: t0.elapsed().as_secs_f64(),
    };
    (report, extra_runs)
}

/// Table 5 of the paper (long-term static test): uncompensated / compensated.
pub mod published_table5 {
    /// Latitude error, nmi.
    pub const LAT_NM: [f64; 2] = [0.3241, 0.3319];
    /// Longitude error, nmi.
    pub const LON_NM: [f64; 2] = [-3.5077, -0.6271];
    /// Horizontal error, nmi.
    pub const HORIZONTAL_NM: [f64; 2] = [3.5227, 0.7096];
    /// tRMS, nmi.
    pub const TRMS_NM: [f64; 2] = [2.4603, 1.2921];
}

/// The column header of the Table 4 and Table 5 text: an empty quantity column `label_w`
/// characters wide (its two-space indent included), the paper's two columns and our two bands.
/// One definition, so the two tables (and `rins paper table4`, which prints Table 4 from
/// rins-scenarios) cannot drift apart.
pub fn paired_table_header(label_w: usize) -> String {
    format!(
        "{:<label_w$} {:>9} {:>9}   {:>27}   {:>27}\n",
        "", "paper unc", "paper comp", "ours uncompensated median [5%, 95%]", "ours compensated"
    )
}

impl Table4Report {
    /// The Table 5 side-by-side table (same runner, fitted compensation).
    pub fn to_text_table5(&self) -> String {
        use published_table5 as p;
        let (u, c) = (&self.uncompensated, &self.compensated);
        let row = |name: &str, paper: [f64; 2], bu: &Band, bc: &Band| {
            format!(
                "  {:<24} {:>9.4} {:>9.4}   {:>8.4} [{:>7.4}, {:>7.4}]   {:>8.4} [{:>7.4}, {:>7.4}]\n",
                name, paper[0], paper[1], bu.median, bu.p05, bu.p95, bc.median, bc.p05, bc.p95
            )
        };
        let mut s = format!(
            "Table 5: {} seeds x {:.2} days, 16-position RINS, compensation from the fitted dbeta(T) (wall {:.1} s)\n",
            self.runs, self.days, self.wall_s,
        );
        s += &paired_table_header(26);
        s += &row("latitude error (nmi)", p::LAT_NM, &u.lat_nm, &c.lat_nm);
        s += &row("longitude error (nmi)", p::LON_NM, &u.lon_nm, &c.lon_nm);
        s += &row(
            "horizontal error (nmi)",
            p::HORIZONTAL_NM,
            &u.horizontal_nm,
            &c.horizontal_nm,
        );
        s += &row("tRMS (nmi)", p::TRMS_NM, &u.trms_nm, &c.trms_nm);
        let i = &self.improvement_pct;
        s += &format!(
            "  improvement (medians):  horizontal {:.2} % (paper 79.86 %), tRMS {:.2} % (paper 47.48 %), longitude {:.2} % (paper 82.12 %)\n",
            i.horizontal, i.trms, i.lon
        );
        let (nu, nc) = (&self.noise_free.uncompensated, &self.noise_free.compensated);
        s += &format!(
            "  noise-free pair:        uncompensated lat {:+.4} lon {:+.4} hor {:.4} tRMS {:.4} nmi; compensated lat {:+.4} lon {:+.4} hor {:.4} tRMS {:.4} nmi\n",
            nu.lat_nm,
            nu.lon_nm,
            nu.horizontal_nm,
            nu.trms_nm,
            nc.lat_nm,
            nc.lon_nm,
            nc.horizontal_nm,
            nc.trms_nm
        );
        s
    }
}

/// Largest errors of one ideal-IMU run (every sensor error off), for the at-sea study.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct IdealFigures {
    /// Largest horizontal error over the records, m.
    pub max_horizontal_m: f64,
    /// Largest attitude error (norm of φ) over the records, rad.
    pub max_attitude_rad: f64,
}

impl IdealFigures {
    fn of(r: &rins_experiments::NavRun) -> Self {
        let mut f = Self::default();
        for x in &r.records {
            f.max_horizontal_m = f.max_horizontal_m.max(x.horizontal_m);
            let a = nalgebra::Vector3::from(x.att_err_rad).norm();
            f.max_attitude_rad = f.max_attitude_rad.max(a);
        }
        f
    }
}

/// `rins paper sea`: the paired study (Table 4's machinery) on the static reference, on the ship
/// without azimuth isolation and on the ship with it, plus ideal-IMU runs on the ship.
#[derive(Clone, Debug, Serialize)]
pub struct SeaReport {
    /// Seeds.
    pub runs: usize,
    /// Simulated days.
    pub days: f64,
    /// The static reference (the paper's Section 3.1 site and sensors, no carrier).
    pub static_reference: Table4Report,
    /// The ship, azimuth isolation off.
    pub ship: Table4Report,
    /// The ship, azimuth isolation on.
    pub ship_isolated: Table4Report,
    /// Ideal IMU on the ship (isolation off, on), uncompensated.
    pub ideal: [IdealFigures; 2],
    /// The seed of the one sea every seed sails (`carrier.ship.sea.realisation = "fixed"`), or
    /// `None` when each seed draws its own from its run seed.
    pub sea_seed: Option<u64>,
    /// Wall time, s.
    pub wall_s: f64,
}

/// Options of the at-sea study.
#[derive(Clone, Debug)]
pub struct SeaOptions {
    /// The ship scenario's plant (a moving carrier); the isolated case sets
    /// `carrier.azimuth_isolation`.
    pub ship: PlantConfig,
    /// Seeds, navigation time and navigator options (its `plant` is the static reference).
    pub paired: Table4Options,
}

/// Runs the at-sea study: [`table4`] on the static reference and on the ship without and with
/// azimuth isolation (same seeds, common random numbers), and the ship with every sensor error
/// off. `progress` receives samples done.
pub fn sea(opt: &SeaOptions, progress: &(dyn Fn(u64) + Sync)) -> SeaReport {
    let t0 = std::time::Instant::now();
    let with = |iso: bool| {
        let mut plant = opt.ship.clone();
        plant.carrier.azimuth_isolation = iso;
        Table4Options {
            plant,
            ..opt.paired.clone()
        }
    };
    // The ideal IMU on the ship (every sensor error off) shares each ship case's physics: it
    // rides in that case's batches as one more member (its uncompensated run is the figure).
    let ideal_of = |o: &Table4Options| {
        let mut m = o.plant.clone();
        m.sensor = PlantConfig::default().sensor;
        m
    };
    // With fewer cores than cases each case is one batch (its physics computed once, its
    // navigators in whole lane groups), the isolated case, the longest, started first so that
    // the other core takes the other two in turn; with more cores each case is split per core.
    let split = if rayon::current_num_threads() < 3 {
        rins_experiments::Split::Whole
    } else {
        rins_experiments::Split::PerCore
    };
    let ship_case = |iso: bool| {
        let o = with(iso);
        let (report, extra) = table4_with(&o, &[ideal_of(&o)], split, progress);
        (report, IdealFigures::of(&extra[0][0]))
    };
    let ((ship_isolated, ideal_on), ((ship, ideal_off), static_reference)) = rayon::join(
        || ship_case(true),
        || {
            rayon::join(
                || ship_case(false),
                || table4_with(&opt.paired, &[], split, progress).0,
            )
        },
    );
    let ideal = (ideal_off, ideal_on);
    SeaReport {
        runs: opt.paired.runs,
        days: opt.paired.duration_s / 86_400.0,
        static_reference,
        ship,
        ship_isolated,
        ideal: [ideal.0, ideal.1],
        sea_seed: {
            let sea = &opt.ship.carrier.ship.sea;
            (sea.realisation == rins_plant::carrier::SeaRealisation::Fixed).then_some(sea.seed)
        },
        wall_s: t0.elapsed().as_secs_f64(),
    }
}

impl SeaReport {
    /// The cases in order (static, ship, ship isolated) with their names.
    pub fn cases(&self) -> [(&'static str, &Table4Report); 3] {
        [
            ("static reference", &self.static_reference),
            ("ship", &self.ship),
            ("ship, azimuth isolation", &self.ship_isolated),
        ]
    }
}
