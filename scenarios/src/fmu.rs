//! `rins fmu build` and `rins fmu run`: package the FMI libraries, and drive a packaged FMU
//! through a scenario with the same sinks as the in-process plant, so the two outputs can be
//! compared byte for byte.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use rins_carrier_fmu::RinsCarrier;
use rins_fmi::package;
use rins_fmi::standard::FmiVersion;
use rins_fmi::vars::{Kind, Value};
use rins_fmi_import::{Fmu2, Instance2};
use rins_imu_fmu::RinsImu;
use rins_imu_fmu::outputs::{Output, Record, outputs};
use rins_plant::PlantConfig;
use rins_plant::params::{self, ParamValue};

use crate::progress;
use crate::runner::{RunSummary, Sink};
use rins_scenario::file::Scenario;

/// Where the built FMI libraries are looked for when no folder is given: next to the running
/// executable (cargo puts `rins` and the cdylibs in the same target folder).
pub fn default_lib_dir() -> PathBuf {
    std::env::current_exe()
        .ok()
        .and_then(|p| p.parent().map(Path::to_path_buf))
        .unwrap_or_default()
}

/// One exported FMU model: what `rins fmu build` builds and packages for it. A new model is
/// one row of [`MODELS`] (beside its own crates).
pub struct FmuModel {
    /// Cargo packages of its FMI 2 and FMI 3 libraries (the one-line cdylib crates).
    pub packages: [&'static str; 2],
    /// File name of the library cargo builds for an FMI version.
    pub library_file: fn(FmiVersion) -> &'static str,
    /// Its reference results as `(file suffix, text)`, written beside each of its FMUs as
    /// modelica/Reference-FMUs ship them (`<Model>_ref.opt`, `<Model>_in.csv` when it has
    /// inputs, `<Model>_ref.csv`).
    pub reference: fn() -> Result<Vec<(&'static str, String)>>,
    /// Packages its library for an FMI version into a folder with the reference files
    /// ([`package_one`]).
    pub package: fn(FmiVersion, &Path, &Path, &[(&'static str, String)]) -> Result<PathBuf>,
}

/// Every model `rins fmu build` packages, in the order it lists them.
pub const MODELS: [FmuModel; 2] = [
    FmuModel {
        packages: ["rins-imu-fmi2", "rins-imu-fmi3"],
        library_file: rins_imu_fmu::library_file,
        reference: || {
            let (opt, input, reference) =
                rins_imu_fmu::reference::reference_results().map_err(anyhow::Error::msg)?;
            Ok(vec![
                ("_ref.opt", opt),
                ("_in.csv", input),
                ("_ref.csv", reference),
            ])
        },
        package: package_one::<RinsImu>,
    },
    FmuModel {
        packages: ["rins-carrier-fmi2", "rins-carrier-fmi3"],
        library_file: rins_carrier_fmu::library_file,
        reference: || {
            let (opt, reference) =
                rins_carrier_fmu::reference::reference_results().map_err(anyhow::Error::msg)?;
            Ok(vec![("_ref.opt", opt), ("_ref.csv", reference)])
        },
        package: package_one::<RinsCarrier>,
    },
];

/// The FMI versions packaged, in the order of [`FmuModel::packages`].
pub const FMI_VERSIONS: [FmiVersion; 2] = [FmiVersion::V2, FmiVersion::V3];

/// The cargo packages of every model's libraries ([`MODELS`], each FMI version).
pub const FMI_PACKAGES: [&str; 2 * MODELS.len()] = {
    let mut out = [""; 2 * MODELS.len()];
    let mut i = 0;
    while i < MODELS.len() {
        out[2 * i] = MODELS[i].packages[0];
        out[2 * i + 1] = MODELS[i].packages[1];
        i += 1;
    }
    out
};

/// The cargo command that builds every library of [`FMI_PACKAGES`].
pub fn build_command() -> String {
    let packages: Vec<String> = FMI_PACKAGES.iter().map(|p| format!("-p {p}")).collect();
    format!("cargo build --release {}", packages.join(" "))
}

/// Writes the FMUs of every model of [`MODELS`] (FMI 2 and FMI 3 each) into `out`, each with
/// its reference results beside it ([`rins_imu_fmu::reference`],
/// [`rins_carrier_fmu::reference`]); returns the FMU paths.
pub fn build(out: &Path, lib_dir: &Path) -> Result<Vec<PathBuf>> {
    let references = MODELS
        .iter()
        .map(|m| (m.reference)())
        .collect::<Result<Vec<_>>>()?;
    let mut made = Vec::new();
    for v in FMI_VERSIONS {
        for (m, files) in MODELS.iter().zip(&references) {
            made.push((m.package)(
                v,
                &lib_dir.join((m.library_file)(v)),
                out,
                files,
            )?);
        }
    }
    Ok(made)
}

/// Packages the library `lib` of model `M` as the FMU of version `v` in `out` and writes the
/// reference files `files` (suffix, text) beside it.
fn package_one<M: rins_fmi::model::Model>(
    v: FmiVersion,
    lib: &Path,
    out: &Path,
    files: &[(&str, String)],
) -> Result<PathBuf> {
    if !lib.exists() {
        bail!(
            "{} not found: build the FMI libraries first with `{}` (or pass --lib-dir)",
            lib.display(),
            build_command()
        );
    }
    let made = package::build_fmu::<M>(v, lib, out)
        .with_context(|| format!("packaging {}", lib.display()))?;
    let id = rins_fmi::fmu::model_identifier::<M>(v);
    for (suffix, text) in files {
        let path = out.join(format!("{id}{suffix}"));
        std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))?;
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
        // Declared effects go into the FMU's slots (below), not parameters of their own.
        if p.path.starts_with("sensor.gyro.custom[") || p.path.starts_with("sensor.accel.custom[") {
            continue;
        }
        // The FMU's own naming of a parameter path (one definition, shared with the models).
        let name = rins_fmi_plant::parameter::variable_name(&p.path);
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
    set_declared_slots(fmu, inst, cfg)
}

/// Puts the scenario's declared effects (`[[sensor.gyro.custom]]`, `[[sensor.accel.custom]]`)
/// into the FMU's declared-effect slots, so a declared effect is simulated through the FMU as
/// in process; more effects than slots is an error, never a silent drop.
fn set_declared_slots(fmu: &Fmu2, inst: &Instance2<'_>, cfg: &PlantConfig) -> Result<()> {
    let slots =
        rins_imu_fmu::declared::slot_values(&cfg.sensor.gyro.custom, &cfg.sensor.accel.custom)
            .map_err(|e| anyhow::anyhow!("declared effects (sensor.*.custom) as FMU slots: {e}"))?;
    for (name, value) in slots {
        let vr = fmu.vr(&name).map_err(anyhow::Error::msg)?;
        let r = match value {
            Value::Real(x) => inst.set_real(&[vr], &[x]),
            Value::Integer(i) => {
                let v = i32::try_from(i).map_err(|_| {
                    anyhow::anyhow!("{name}: {i} does not fit the FMU's 32-bit Integer")
                })?;
                inst.set_integer(&[vr], &[v])
            }
            Value::Boolean(b) => inst.set_boolean(&[vr], &[b]),
            Value::Enumeration(_) => bail!("{name}: slots have no enumerations"),
        };
        r.with_context(|| format!("setting {name}"))?;
    }
    Ok(())
}

/// The outputs the sinks take, by the output table: value references grouped by type, each
/// with the row and element it stores (the names come from the table, not typed here).
struct OutputRefs {
    reals: Vec<u32>,
    real_rows: Vec<(&'static Output, usize)>,
    integers: Vec<u32>,
    integer_rows: Vec<(&'static Output, usize)>,
    booleans: Vec<u32>,
    boolean_rows: Vec<(&'static Output, usize)>,
}

impl OutputRefs {
    fn new(fmu: &Fmu2) -> Result<Self> {
        let mut r = Self {
            reals: Vec::new(),
            real_rows: Vec::new(),
            integers: Vec::new(),
            integer_rows: Vec::new(),
            booleans: Vec::new(),
            boolean_rows: Vec::new(),
        };
        for o in outputs().iter().filter(|o| o.store.is_some()) {
            for i in 0..o.decl.count() {
                let vr = fmu
                    .vr(&o.decl.element_name(i))
                    .map_err(anyhow::Error::msg)?;
                let (vrs, rows) = match o.decl.kind {
                    Kind::Real => (&mut r.reals, &mut r.real_rows),
                    Kind::Boolean => (&mut r.booleans, &mut r.boolean_rows),
                    _ => (&mut r.integers, &mut r.integer_rows),
                };
                vrs.push(vr);
                rows.push((o, i));
            }
        }
        Ok(r)
    }

    /// Reads the outputs of the last communication step into `rec`.
    fn read(&self, inst: &Instance2<'_>, rec: &mut Record, buf: &mut Vec<f64>) -> Result<()> {
        let store = |rec: &mut Record, (o, i): &(&Output, usize), v: Value| {
            if let Some(s) = &o.store {
                s(rec, *i, v);
            }
        };
        buf.resize(self.reals.len(), 0.0);
        inst.get_real(&self.reals, buf)?;
        for (row, x) in self.real_rows.iter().zip(buf.iter()) {
            store(rec, row, Value::Real(*x));
        }
        let mut ints = vec![0; self.integers.len().max(self.booleans.len())];
        inst.get_integer(&self.integers, &mut ints[..self.integers.len()])?;
        for (row, n) in self.integer_rows.iter().zip(&ints) {
            store(rec, row, Value::Integer(*n as u64));
        }
        inst.get_boolean(&self.booleans, &mut ints[..self.booleans.len()])?;
        for (row, b) in self.boolean_rows.iter().zip(&ints) {
            store(rec, row, Value::Boolean(*b != 0));
        }
        Ok(())
    }
}

/// Runs `scenario` through the FMI 2 FMU at `fmu_path` for `samples` IMU samples, one
/// communication step per sample, feeding `sinks` exactly as [`crate::runner::run`] does.
pub fn run(
    fmu_path: &Path,
    scenario: &Scenario,
    samples: u64,
    sinks: &mut [&mut dyn Sink],
) -> Result<RunSummary> {
    if !scenario.plant.carrier.is_static() {
        // The IMU FMU has no carrier-truth outputs, so the sinks' carrier columns could not be
        // filled: refuse rather than write a wrong track. The scenario file is named, as every
        // other refusal of its contents is.
        bail!(
            "{}: carrier.kind: `rins fmu run` drives the static carrier only (the FMU outputs no carrier truth); connect the RinsCarrier FMU to the IMU FMU's carrier inputs instead (docs/cosimulation.md)",
            scenario.source
        );
    }
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
    let mut buf = Vec::new();
    let mut rec = Record::template(&scenario.plant).map_err(anyhow::Error::msg)?;
    let dt = 1.0 / scenario.plant.rate_hz;
    let pb = progress::bar(samples, &scenario.meta.name);
    let t0 = std::time::Instant::now();
    let mut t = 0.0;
    // The in-process plant reads its chamber profile at the thermal updates (every
    // `thermal.step_s`, on a grid from the start). A changed chamber input ends a thermal step
    // early (docs/fmu.md), so the profile is set only at those grid points: the FMU then takes
    // the same updates with the same chamber values as the in-process plant.
    let thermal_every =
        ((scenario.plant.thermal.step_s * scenario.plant.rate_hz).round() as u64).max(1);
    for k in 0..samples {
        if profile && k % thermal_every == 0 {
            inst.set_real(&[chamber_vr], &[chamber.temp_at(t)])?;
        }
        inst.do_step(t, dt)?;
        refs.read(&inst, &mut rec, &mut buf)?;
        t = rec.sample.t_s;
        for sink in sinks.iter_mut() {
            sink.sample(&rec.sample, &rec.truth)?;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sinks::CsvSink;

    const SCENARIO: &str = r#"
[scenario]
name = "deflate-check"
duration_s = 3.0
[run]
rate_hz = 100.0
seed = 11
[sensor]
preset = "paper-table3"
gyro.bias_instability.enabled = true
[thermal.chamber]
temp_c = 25.0
profile = [[0.0, 25.0], [2.0, 35.0]]
[outputs]
decimation = 1
truth = true
"#;

    /// imu.csv of `scenario` through the FMU at `fmu` (`None`: in process, `rins run`).
    fn imu_csv(scenario: &Scenario, fmu: Option<&Path>, out: &Path) -> Vec<u8> {
        std::fs::create_dir_all(out).unwrap();
        let path = out.join("imu.csv");
        let mut csv = CsvSink::create(&path, scenario.outputs, &scenario.plant).unwrap();
        match fmu {
            Some(f) => run(f, scenario, scenario.samples(), &mut [&mut csv]).unwrap(),
            None => crate::runner::run(scenario, scenario.samples(), &mut [&mut csv]).unwrap(),
        };
        drop(csv);
        std::fs::read(&path).unwrap()
    }

    /// Issue 27: the IMU FMU packaged the usual way (deflated entries, as `zip`, 7-Zip and FMI
    /// tools write it) runs in `rins fmu run` and gives the imu.csv of the same FMU with stored
    /// entries, byte for byte, which is also the in-process plant's. `rins fmu build` packages
    /// deflated archives with fixed timestamps: two builds are byte-identical.
    ///
    /// Needs the FMI 2 library beside the test binary's folder (`cargo build -p rins-imu-fmi2`).
    #[test]
    fn a_deflated_fmu_runs_bit_identical_to_a_stored_one_and_to_the_plant() {
        let lib_dir = std::env::current_exe()
            .unwrap()
            .parent()
            .and_then(Path::parent)
            .unwrap()
            .to_path_buf();
        let lib = lib_dir.join(rins_imu_fmu::library_file(FmiVersion::V2));
        assert!(
            lib.exists(),
            "{} missing: run `cargo build -p rins-imu-fmi2` first",
            lib.display()
        );
        let dir = std::env::temp_dir().join(format!("rins-deflate-{}", std::process::id()));
        let deflated = package::build_fmu::<RinsImu>(FmiVersion::V2, &lib, &dir.join("a")).unwrap();
        let again = package::build_fmu::<RinsImu>(FmiVersion::V2, &lib, &dir.join("b")).unwrap();
        let bytes = std::fs::read(&deflated).unwrap();
        assert_eq!(bytes, std::fs::read(&again).unwrap(), "two builds differ");
        // Every local header says method 8 (deflate).
        let mut methods = Vec::new();
        let mut p = 0;
        while p + 30 <= bytes.len() && bytes[p..p + 4] == [0x50, 0x4b, 0x03, 0x04] {
            methods.push(u16::from_le_bytes([bytes[p + 8], bytes[p + 9]]));
            let csize = u32::from_le_bytes(bytes[p + 18..p + 22].try_into().unwrap()) as usize;
            let (n, x) = (
                u16::from_le_bytes([bytes[p + 26], bytes[p + 27]]) as usize,
                u16::from_le_bytes([bytes[p + 28], bytes[p + 29]]) as usize,
            );
            p += 30 + n + x + csize;
        }
        assert_eq!(methods, [8, 8, 8, 8], "four deflated entries");
        // The same entries stored (method 0): the archive the old writer made.
        let entries = rins_fmi::zip::read(&bytes).unwrap();
        let stored = dir.join("RinsImu-stored.fmu");
        std::fs::write(
            &stored,
            rins_fmi::zip::write(&entries, rins_fmi::zip::Compression::Stored).unwrap(),
        )
        .unwrap();
        let stored_len = std::fs::metadata(&stored).unwrap().len() as usize;
        assert!(
            bytes.len() * 2 < stored_len,
            "deflated {} bytes, stored {stored_len}",
            bytes.len()
        );

        let sc = Scenario::from_toml(SCENARIO, "deflate-check").unwrap();
        assert_eq!(sc.samples(), 300);
        let from_deflated = imu_csv(&sc, Some(&deflated), &dir.join("run-deflated"));
        let from_stored = imu_csv(&sc, Some(&stored), &dir.join("run-stored"));
        let in_process = imu_csv(&sc, None, &dir.join("run-plant"));
        assert!(from_stored.len() > 300 * 100, "{} bytes", from_stored.len());
        assert!(
            from_deflated == from_stored,
            "deflated and stored FMUs differ"
        );
        assert!(from_stored == in_process, "the FMU differs from the plant");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
