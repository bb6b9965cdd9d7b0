//! `rins fmu build` and `rins fmu run`: package the FMI libraries, and drive a packaged FMU
//! through a scenario with the same sinks as the in-process plant, so the two outputs can be
//! compared byte for byte.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use nalgebra::Vector3;
use rins_fmi::importer::{Fmu2, Instance2};
use rins_fmi::package;
use rins_fmi::xml::FmiVersion;
use rins_plant::effects::{AccelTerm, GyroTerm};
use rins_plant::params::{self, ParamValue};
use rins_plant::table::{GimbalAngles, GimbalState};
use rins_plant::thermal::{Temperatures, node};
use rins_plant::{ImuSample, PlantConfig, Truth};

use crate::file::Scenario;
use crate::progress;
use crate::runner::{RunSummary, Sink};

/// Where the built FMI libraries are looked for when no folder is given: next to the running
/// executable (cargo puts `rins` and the cdylibs in the same target folder).
pub fn default_lib_dir() -> PathBuf {
    std::env::current_exe()
        .ok()
        .and_then(|p| p.parent().map(Path::to_path_buf))
        .unwrap_or_default()
}

/// Writes both FMUs into `out`; returns their paths.
pub fn build(out: &Path, lib_dir: &Path) -> Result<Vec<PathBuf>> {
    let mut made = Vec::new();
    for v in [FmiVersion::V2, FmiVersion::V3] {
        let lib = lib_dir.join(package::library_file(v));
        if !lib.exists() {
            bail!(
                "{} not found: build the FMI libraries first with `cargo build --release -p rins-fmi2 -p rins-fmi3` (or pass --lib-dir)",
                lib.display()
            );
        }
        made.push(
            package::build_fmu(v, &lib, out)
                .with_context(|| format!("packaging {}", lib.display()))?,
        );
    }
    Ok(made)
}

/// Sets every parameter of `cfg` on an instantiated FMU. The chamber profile is replaced by the
/// chamber input (driven by [`run`]); explicit scheme steps cannot be expressed and are refused.
fn set_parameters(fmu: &Fmu2, inst: &Instance2<'_>, cfg: &PlantConfig) -> Result<()> {
    if !cfg.scheme.steps.is_empty() {
        bail!(
            "scheme.steps cannot be FMU parameters; drive the table with the gimbal command inputs instead (docs/fmu.md)"
        );
    }
    let mut fixed = cfg.clone();
    fixed.thermal.chamber.temp_c = cfg.thermal.chamber.temp_at(0.0);
    fixed.thermal.chamber.profile.clear();
    for p in params::flatten(&fixed) {
        let name = p.path.replace("][", ",");
        let vr = fmu.vr(&name).map_err(anyhow::Error::msg)?;
        let r = match &p.value {
            ParamValue::Real(x) => inst.set_real(&[vr], &[*x]),
            ParamValue::Integer(u) => {
                let v = i32::try_from(*u).map_err(|_| {
                    anyhow::anyhow!("{}: {u} does not fit the FMU's 32-bit Integer", p.path)
                })?;
                inst.set_integer(&[vr], &[v])
            }
            ParamValue::Bool(b) => inst.set_boolean(&[vr], &[*b]),
            ParamValue::Enum(e) => {
                let i = params::enum_choices(&p.path)
                    .and_then(|c| c.iter().position(|x| x == e))
                    .context("enumeration item")?;
                inst.set_integer(&[vr], &[i as i32 + 1])
            }
        };
        r.with_context(|| format!("setting {}", p.path))?;
    }
    Ok(())
}

/// Value references of the outputs the sinks need, in one block per call.
struct OutputRefs {
    reals: Vec<u32>,
    moving: u32,
}

const N_FIXED: usize = 3 + 3 + 1 + 4 + node::COUNT + 1 + 3 + 3 + 1;

impl OutputRefs {
    fn new(fmu: &Fmu2) -> Result<Self> {
        let mut names: Vec<String> = Vec::new();
        names.extend((0..3).map(|i| format!("imu.dtheta_rad[{i}]")));
        names.extend((0..3).map(|i| format!("imu.dv_mps[{i}]")));
        names.push("imu.time_s".into());
        names.extend(
            [
                "gimbal.outer_rad",
                "gimbal.inner_rad",
                "gimbal.outer_rate_rps",
                "gimbal.inner_rate_rps",
            ]
            .map(String::from),
        );
        names.extend(node::NAMES.iter().map(|n| format!("thermal.{n}_c")));
        names.push("thermal.chamber_c".into());
        names.extend((0..3).map(|i| format!("truth.dtheta_rad[{i}]")));
        names.extend((0..3).map(|i| format!("truth.dv_mps[{i}]")));
        names.push("effect.position_weight".into());
        for t in GyroTerm::ALL {
            names.extend((0..3).map(|i| format!("effect.gyro.{}_rad[{i}]", t.key())));
        }
        for t in AccelTerm::ALL {
            names.extend((0..3).map(|i| format!("effect.accel.{}_mps[{i}]", t.key())));
        }
        let reals = names
            .iter()
            .map(|n| fmu.vr(n))
            .collect::<Result<Vec<_>, _>>()
            .map_err(anyhow::Error::msg)?;
        Ok(Self {
            reals,
            moving: fmu.vr("gimbal.moving").map_err(anyhow::Error::msg)?,
        })
    }
}

/// The sample and truth of the last communication step, rebuilt from the FMU's outputs.
fn read_outputs(
    inst: &Instance2<'_>,
    refs: &OutputRefs,
    buf: &mut [f64],
    index: u64,
) -> Result<(ImuSample, Truth)> {
    inst.get_real(&refs.reals, buf)?;
    let mut moving = [0];
    inst.get_boolean(&[refs.moving], &mut moving)?;
    let v3 = |k: usize| Vector3::new(buf[k], buf[k + 1], buf[k + 2]);
    let mut nodes_c = [0.0; node::COUNT];
    nodes_c.copy_from_slice(&buf[11..11 + node::COUNT]);
    // Interim: the FMU reports the true angles and temperatures until its measured outputs land.
    let sample = ImuSample {
        index,
        t_s: buf[6],
        dtheta_rad: v3(0),
        dv_mps: v3(3),
        encoder: GimbalAngles::new(buf[7], buf[8]),
        temps_c: nodes_c,
    };
    let k = 11 + node::COUNT;
    let mut gyro = [Vector3::zeros(); GyroTerm::ALL.len()];
    for (t, g) in gyro.iter_mut().enumerate() {
        *g = v3(N_FIXED + 3 * t);
    }
    let mut accel = [Vector3::zeros(); AccelTerm::ALL.len()];
    let a0 = N_FIXED + 3 * GyroTerm::ALL.len();
    for (t, a) in accel.iter_mut().enumerate() {
        *a = v3(a0 + 3 * t);
    }
    let truth = Truth {
        gimbal: GimbalState {
            angles: GimbalAngles::new(buf[7], buf[8]),
            outer_rate_rps: buf[9],
            inner_rate_rps: buf[10],
            step_index: 0,
            moving: moving[0] != 0,
        },
        dtheta_true_rad: v3(k + 1),
        dv_true_mps: v3(k + 4),
        temps: Temperatures {
            nodes_c,
            chamber_c: buf[k],
        },
        gyro_terms_rad: gyro,
        accel_terms_mps: accel,
        position_weight: buf[k + 7],
    };
    Ok((sample, truth))
}

/// Runs `scenario` through the FMI 2 FMU at `fmu_path` for `samples` IMU samples, one
/// communication step per sample, feeding `sinks` exactly as [`crate::runner::run`] does.
pub fn run(
    fmu_path: &Path,
    scenario: &Scenario,
    samples: u64,
    sinks: &mut [&mut dyn Sink],
) -> Result<RunSummary> {
    let fmu = Fmu2::open(fmu_path).map_err(anyhow::Error::msg)?;
    let inst = fmu.instantiate(&scenario.meta.name, false)?;
    inst.setup_experiment(0.0, None)?;
    set_parameters(&fmu, &inst, &scenario.plant)?;
    let chamber = &scenario.plant.thermal.chamber;
    let profile = !chamber.profile.is_empty();
    let (override_vr, chamber_vr) = (
        fmu.vr("input.chamber_override")
            .map_err(anyhow::Error::msg)?,
        fmu.vr("input.chamber_temp_c").map_err(anyhow::Error::msg)?,
    );
    if profile {
        inst.set_boolean(&[override_vr], &[true])?;
        inst.set_real(&[chamber_vr], &[chamber.temp_at(0.0)])?;
    }
    inst.enter_initialization_mode()?;
    inst.exit_initialization_mode()?;
    let refs = OutputRefs::new(&fmu)?;
    let mut buf = vec![0.0; refs.reals.len()];
    let dt = 1.0 / scenario.plant.rate_hz;
    let pb = progress::bar(samples, &scenario.meta.name);
    let t0 = std::time::Instant::now();
    let mut t = 0.0;
    for k in 0..samples {
        if profile {
            // The plant reads the chamber at thermal steps, which start at communication points:
            // the input set here is the profile value the in-process plant would use.
            inst.set_real(&[chamber_vr], &[chamber.temp_at(t)])?;
        }
        inst.do_step(t, dt)?;
        let (s, tr) = read_outputs(&inst, &refs, &mut buf, k)?;
        t = s.t_s;
        for sink in sinks.iter_mut() {
            sink.sample(&s, &tr)?;
        }
        if k % (1 << 16) == 0 {
            pb.set_position(k);
        }
    }
    for sink in sinks.iter_mut() {
        sink.finish()?;
    }
    pb.finish_and_clear();
    inst.terminate()?;
    Ok(RunSummary {
        samples,
        wall_s: t0.elapsed().as_secs_f64(),
        interrupted: false,
    })
}
