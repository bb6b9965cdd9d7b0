//! Seeds side by side. A Monte Carlo case runs many seeds of one scenario; where the physics
//! does not depend on the seed (the static site, a calm ship or a trajectory, a ship on one
//! sea; with azimuth isolation each seed's table is turned from one reference table,
//! [`crate::carrier::own_table`]), the motion, the temperature field and every deterministic
//! sensor error are computed once per interval and read out for each seed (noise,
//! quantisation, temperature sensors, and the seed's own isolation loop). Otherwise each seed
//! runs its own plant. Either way a seed's samples are the bits [`Plant::step`] gives for that
//! seed alone: every lane, the plant's own included, is read out by the same code on the same
//! interval.

use crate::config::{ConfigError, PlantConfig};
use crate::output::{ImuSample, Truth};
use crate::plant::Plant;
use crate::stages::lane::Lane;

/// Several seeds of one configuration stepped together.
#[derive(Clone, Debug)]
pub struct SeedBatch {
    seeds: Vec<u64>,
    kind: Kind,
    samples: Vec<ImuSample>,
}

#[derive(Clone, Debug)]
enum Kind {
    /// One plant (the first seed) and the other seeds' lanes (readout and own isolation loop).
    Shared { plant: Box<Plant>, lanes: Vec<Lane> },
    /// A plant per seed (the physics depends on the seed).
    Separate(Vec<Plant>),
}

impl SeedBatch {
    /// The configuration `cfg` (its own seed ignored) for each of `seeds`.
    pub fn new(cfg: &PlantConfig, seeds: &[u64]) -> Result<Self, Vec<ConfigError>> {
        let members: Vec<PlantConfig> = seeds.iter().map(|&s| cfg.with_seed(s)).collect();
        Self::of(&members)
    }

    /// One lane per configuration of `members`. They share one plant's physics when the
    /// physics allows it ([`Plant::shares_physics_across_seeds`]) and they differ from the first
    /// only in what the readout alone uses: the seed and the stochastic terms (angle and
    /// velocity random walk, bias instability, rate random walk), so a noise-free member rides
    /// with the seeds of its case; or a member is the first with ideal sensors (every error term
    /// off), which reads the true increments alone. Otherwise each member runs its own plant.
    pub fn of(members: &[PlantConfig]) -> Result<Self, Vec<ConfigError>> {
        let Some(head) = members.first() else {
            return Err(vec![ConfigError {
                path: "seeds".into(),
                expected: "at least one seed".into(),
                got: "none".into(),
            }]);
        };
        let first = Plant::new(head)?;
        let kind = if Self::shared_by(&first, members) {
            for m in &members[1..] {
                m.validate()?;
            }
            let lanes = members[1..].iter().map(|m| first.lane(m)).collect();
            Kind::Shared {
                plant: Box::new(first),
                lanes,
            }
        } else {
            let mut plants = vec![first];
            for m in &members[1..] {
                plants.push(Plant::new(m)?);
            }
            Kind::Separate(plants)
        };
        Ok(Self {
            seeds: members.iter().map(|m| m.seed).collect(),
            kind,
            // Placeholders of the right shape: the first step overwrites every one.
            samples: vec![ImuSample::default(); members.len()],
        })
    }

    /// True when `members` would share one plant's physics in a batch (see [`SeedBatch::of`]);
    /// errors are the first member's configuration errors.
    pub fn shares(members: &[PlantConfig]) -> Result<bool, Vec<ConfigError>> {
        match members.first() {
            None => Ok(true),
            Some(head) => Ok(Self::shared_by(&Plant::new(head)?, members)),
        }
    }

    fn shared_by(first: &Plant, members: &[PlantConfig]) -> bool {
        first.shares_physics_across_seeds()
            && members[1..]
                .iter()
                .all(|m| differs_in_readout_only(first.config(), m))
    }

    /// The seeds, in lane order.
    pub fn seeds(&self) -> &[u64] {
        &self.seeds
    }

    /// True when the seeds share one plant's physics (see the module notes).
    pub fn is_shared(&self) -> bool {
        matches!(self.kind, Kind::Shared { .. })
    }

    /// The plant of the first seed (its configuration, site, schedule, time).
    pub fn first(&self) -> &Plant {
        match &self.kind {
            Kind::Shared { plant, .. } => plant,
            Kind::Separate(p) => &p[0],
        }
    }

    /// The plant lane `k` runs on: the shared one, or the seed's own.
    pub fn plant(&self, k: usize) -> &Plant {
        match &self.kind {
            Kind::Shared { plant, .. } => plant,
            Kind::Separate(p) => &p[k],
        }
    }

    /// Advances every seed by one output interval ([`SeedBatch::samples`] holds the result).
    pub fn step(&mut self) {
        match &mut self.kind {
            Kind::Shared { plant, lanes } => plant.step_lanes(lanes, &mut self.samples),
            Kind::Separate(plants) => {
                for (p, s) in plants.iter_mut().zip(&mut self.samples) {
                    *s = p.step();
                }
            }
        }
    }

    /// The last interval's samples, in lane order.
    pub fn samples(&self) -> &[ImuSample] {
        &self.samples
    }

    /// Lane `k`'s truth over the last interval (see [`Plant::truth`]).
    pub fn truth(&self, k: usize) -> Truth {
        match &self.kind {
            Kind::Shared { plant, lanes } => match k {
                0 => plant.truth(),
                _ => plant.truth_of_lane(&lanes[k - 1]),
            },
            Kind::Separate(p) => p[k].truth(),
        }
    }
}

/// True when `b`'s samples can be read out of `a`'s physics: `b` is `a` but for the seed and
/// the stochastic terms (what only the readout uses), or `a` with ideal sensors (every error
/// term off: its readout takes the true increments alone).
fn differs_in_readout_only(a: &PlantConfig, b: &PlantConfig) -> bool {
    if b.sensor == crate::config::SensorSpec::default() {
        let mut b = b.clone();
        b.seed = a.seed;
        b.sensor = a.sensor.clone();
        return b == *a;
    }
    let mut b = b.clone();
    b.seed = a.seed;
    let (g, ga) = (&mut b.sensor.gyro, &a.sensor.gyro);
    g.angle_random_walk = ga.angle_random_walk;
    g.bias_instability = ga.bias_instability;
    g.rate_random_walk = ga.rate_random_walk;
    b.sensor.accel.velocity_random_walk = a.sensor.accel.velocity_random_walk;
    b == *a
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::carrier::{CarrierKind, SpectrumKind};
    use crate::thermal::ChamberSpec;

    /// Table 3 sensors (noise, quantisation, δβ) with a chamber step, so thermal updates, slow
    /// noise and temperature-sensor noise all happen within the run.
    fn config() -> PlantConfig {
        let mut c = crate::presets::paper_16pos_config();
        c.sensor.temperature.noise.enabled = true;
        c.thermal.enabled = true;
        c.thermal.chamber = ChamberSpec {
            temp_c: 20.0,
            profile: vec![[0.0, 20.0], [200.0, 30.0]],
        };
        c
    }

    /// Every seed's samples and final truth from the batch equal a plant run for that seed
    /// alone, bit for bit; `shared` says which path the batch must have taken.
    fn check(cfg: &PlantConfig, shared: bool, samples: usize) {
        let seeds = [7, 11, 12, 1000];
        let mut batch = SeedBatch::new(cfg, &seeds).unwrap();
        assert_eq!(batch.is_shared(), shared);
        let mut alone: Vec<Plant> = seeds
            .iter()
            .map(|&seed| {
                Plant::new(&PlantConfig {
                    seed,
                    ..cfg.clone()
                })
                .unwrap()
            })
            .collect();
        for k in 0..samples {
            batch.step();
            let got = batch.samples();
            for (lane, p) in alone.iter_mut().enumerate() {
                assert_eq!(got[lane], p.step(), "seed {} sample {k}", seeds[lane]);
            }
        }
        for (lane, p) in alone.iter().enumerate() {
            assert_eq!(
                batch.truth(lane),
                p.truth(),
                "truth of seed {}",
                seeds[lane]
            );
        }
        // The seeds differ: the noise is the seed's.
        batch.step();
        let s = batch.samples();
        assert_ne!(s[0].dtheta_rad, s[1].dtheta_rad);
    }

    /// Every member's samples and final truth from the batch equal its plant run alone.
    fn check_members(members: &[PlantConfig], shared: bool, samples: usize) {
        let mut batch = SeedBatch::of(members).unwrap();
        assert_eq!(batch.is_shared(), shared);
        let mut alone: Vec<Plant> = members.iter().map(|m| Plant::new(m).unwrap()).collect();
        for k in 0..samples {
            batch.step();
            for (lane, p) in alone.iter_mut().enumerate() {
                assert_eq!(batch.samples()[lane], p.step(), "member {lane} sample {k}");
            }
        }
        for (lane, p) in alone.iter().enumerate() {
            assert_eq!(batch.truth(lane), p.truth(), "truth of member {lane}");
        }
    }

    #[test]
    fn a_noise_free_member_rides_with_the_seeds_and_equals_its_run_alone() {
        let c = config();
        let nf = c.noise_free();
        let seeded = |seed| PlantConfig { seed, ..c.clone() };
        check_members(&[seeded(7), nf.clone(), seeded(8)], true, 20_000);
        // The noise-free member first: its plant carries the others' readouts.
        check_members(&[nf.clone(), seeded(3)], true, 5_000);
        // An ideal IMU (every error term off) reads the true increments alone: it rides along,
        // in a lane or carrying the others'.
        let mut ideal = seeded(5);
        ideal.sensor = Default::default();
        check_members(&[seeded(7), ideal.clone(), seeded(8)], true, 20_000);
        check_members(&[ideal.clone(), seeded(3)], false, 2_000);
        // Another deterministic error is other physics: a plant per member.
        let mut biased = seeded(9);
        biased.sensor.gyro.bias.dph[2] += 0.01;
        check_members(&[seeded(7), biased, nf], false, 3_000);
    }

    #[test]
    fn static_seeds_share_the_physics_and_equal_their_runs_alone() {
        // 300 s at 100 Hz: a turn of the scheme, 300 thermal updates, the chamber step.
        check(&config(), true, 30_000);
    }

    #[test]
    fn a_calm_ship_shares_and_a_ship_at_sea_runs_a_plant_per_seed() {
        let mut c = config();
        c.carrier.kind = CarrierKind::Ship;
        check(&c, true, 3_000);
        c.carrier.ship.sea.spectrum = SpectrumKind::Jonswap;
        c.carrier.ship.sea.sea_state = 4;
        check(&c, false, 3_000);
    }

    /// With azimuth isolation on one sea the seeds' own tables are turned from one reference
    /// table ([`crate::carrier::own_table`]): they share its physics, and each seed (and the
    /// noise-free member) equals its run alone, truth included.
    #[test]
    fn isolated_seeds_on_one_sea_share_the_reference_table_and_equal_their_runs_alone() {
        let mut c = config();
        c.carrier.kind = CarrierKind::Ship;
        c.carrier.ship.sea.spectrum = SpectrumKind::Jonswap;
        c.carrier.ship.sea.sea_state = 4;
        c.carrier.ship.sea.realisation = crate::carrier::SeaRealisation::Fixed;
        c.carrier.azimuth_isolation = true;
        check(&c, true, 3_000);
        let seeded = |seed| PlantConfig { seed, ..c.clone() };
        check_members(&[seeded(7), c.noise_free(), seeded(8)], true, 2_000);
        // An ideal IMU rides along too, with its own loop.
        let mut ideal = seeded(4);
        ideal.sensor = Default::default();
        check_members(&[seeded(7), ideal, seeded(8)], true, 2_000);
        // Each seed moving its own table shares nothing.
        let mut own = Plant::new(&c).unwrap();
        own.set_isolation_reference(false).unwrap();
        assert!(!own.shares_physics_across_seeds());
    }

    /// A sea drawn from its own seed is the same for every run seed: the seeds share the
    /// ship's motion, and each still equals its run alone. The realisation is the one a run
    /// whose own seed is that seed sails.
    #[test]
    fn a_fixed_sea_is_shared_by_the_seeds_and_is_the_sea_of_its_seed() {
        let mut c = config();
        c.carrier.kind = CarrierKind::Ship;
        c.carrier.ship.sea.spectrum = SpectrumKind::Jonswap;
        c.carrier.ship.sea.sea_state = 4;
        let per_run = c.clone();
        c.carrier.ship.sea.realisation = crate::carrier::SeaRealisation::Fixed;
        c.carrier.ship.sea.seed = 11;
        check(&c, true, 3_000);
        // Seed 11's own sea (per run) and the fixed sea 11 under another run seed move the
        // ship the same way; another sea does not.
        let truth = |cfg: &PlantConfig, seed: u64| {
            let mut p = Plant::new(&PlantConfig {
                seed,
                ..cfg.clone()
            })
            .unwrap();
            (0..500).for_each(|_| {
                p.step();
            });
            p.truth().dtheta_true_rad
        };
        assert_eq!(truth(&c, 5), truth(&per_run, 11));
        assert_ne!(truth(&per_run, 5), truth(&per_run, 11));
    }
}
