//! `rins fmu build|run`: package the FMI libraries as FMUs, or drive an FMU through a scenario.
//! The packaging and the FMU driver are in `crate::fmu`; this module finds (or builds) the
//! libraries and reads the arguments.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use anyhow::{Context, Result};

use super::args::{Overrides, load};
use crate::sinks::CsvSink;
use crate::sinks::RunFigures;

/// The FMU commands.
#[derive(clap::Subcommand, Debug)]
pub enum FmuCommand {
    /// Write RinsImu.fmu and RinsCarrier.fmu (FMI 2.0), RinsImu3.fmu and RinsCarrier3.fmu
    /// (FMI 3.0).
    Build(BuildArgs),
    /// Run an FMI 2.0 FMU through a scenario, one communication step per IMU sample, writing
    /// the same imu.csv as `rins run`.
    Run(FmuRunArgs),
}

/// Arguments of `rins fmu build`.
#[derive(clap::Args, Debug)]
pub struct BuildArgs {
    /// Output folder.
    #[arg(long, default_value = "out/fmu")]
    pub out: PathBuf,
    /// Folder holding librins_imu_fmi2.so, librins_imu_fmi3.so, librins_carrier_fmi2.so and
    /// librins_carrier_fmi3.so (default: next to this executable,
    /// where they are built first when missing and rins runs from its cargo workspace).
    #[arg(long)]
    pub lib_dir: Option<PathBuf>,
}

/// Arguments of `rins fmu run`.
#[derive(clap::Args, Debug)]
pub struct FmuRunArgs {
    /// The .fmu file.
    pub fmu: PathBuf,
    /// Scenario file, or `builtin:NAME`.
    pub scenario: PathBuf,
    /// Output folder.
    #[arg(long, default_value = "out/fmu-run")]
    pub out: PathBuf,
    /// Also write the run's figures (SVG and PNG) into the output folder.
    #[arg(long)]
    pub figures: bool,
    /// `--seed`, `--duration-s`, `--rate-hz`.
    #[command(flatten)]
    pub overrides: Overrides,
}

/// Runs an FMU command.
pub fn run(cmd: &FmuCommand) -> Result<()> {
    match cmd {
        FmuCommand::Build(a) => build(a),
        FmuCommand::Run(a) => fmu_run(a),
    }
}

fn build(a: &BuildArgs) -> Result<()> {
    let lib_dir = match &a.lib_dir {
        Some(d) => d.clone(),
        None => {
            let d = crate::fmu::default_lib_dir();
            ensure_libraries(&d)?;
            d
        }
    };
    for p in crate::fmu::build(&a.out, &lib_dir)? {
        println!("{}", p.display());
    }
    Ok(())
}

pub use crate::fmu::{FMI_PACKAGES, FMI_VERSIONS};

/// File names of every library of [`FMI_PACKAGES`] (each FMI version, each model of
/// [`crate::fmu::MODELS`]).
pub fn library_files() -> Vec<&'static str> {
    FMI_VERSIONS
        .iter()
        .flat_map(|v| crate::fmu::MODELS.iter().map(|m| (m.library_file)(*v)))
        .collect()
}

/// Makes sure the FMI libraries are in `lib_dir`, the folder of this executable. When one is
/// missing and this `rins` is a cargo build inside its workspace (a fresh clone running
/// `cargo run --release -- fmu build`), builds them into the same target folder with cargo,
/// saying so on stderr; otherwise fails naming what to build.
pub fn ensure_libraries(lib_dir: &Path) -> Result<()> {
    let missing: Vec<&str> = library_files()
        .into_iter()
        .filter(|f| !lib_dir.join(f).exists())
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    let what = crate::fmu::build_command();
    // Built by cargo: the executable sits in <target>/<profile>/ and its workspace still exists.
    let profile = lib_dir.file_name().and_then(|n| n.to_str());
    let (Some(profile @ ("release" | "debug")), Some(target), Some(root)) =
        (profile, lib_dir.parent(), workspace_root())
    else {
        anyhow::bail!(
            "{} not found in {}: build the FMI libraries in the rins workspace with `{what}` and pass their folder (target/release) with --lib-dir",
            missing.join(", "),
            lib_dir.display()
        );
    };
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    eprintln!(
        "{} not found beside rins: building the FMI libraries with `{what}` in {}",
        missing.join(", "),
        root.display()
    );
    let mut cmd = Command::new(&cargo);
    cmd.arg("build");
    if profile == "release" {
        cmd.arg("--release");
    }
    for p in FMI_PACKAGES {
        cmd.args(["-p", p]);
    }
    // stdout is the FMU paths; cargo's own output goes to stderr.
    let status = cmd
        .arg("--target-dir")
        .arg(target)
        .current_dir(&root)
        .stdout(Stdio::from(std::io::stderr()))
        .status()
        .with_context(|| format!("cannot run {}", Path::new(&cargo).display()))?;
    if !status.success() {
        anyhow::bail!("`{what}` in {} failed ({status})", root.display());
    }
    Ok(())
}

/// The cargo workspace this binary was built from, if it is still there: the parent of the
/// scenarios crate (`CARGO_MANIFEST_DIR` as `cargo run` sets it, else as at compile time).
fn workspace_root() -> Option<PathBuf> {
    let manifest = std::env::var_os("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")));
    let root = manifest.parent()?.to_path_buf();
    let toml = std::fs::read_to_string(root.join("Cargo.toml")).ok()?;
    toml.contains("[workspace]").then_some(root)
}

fn fmu_run(a: &FmuRunArgs) -> Result<()> {
    let sc = load(&a.scenario, &a.overrides)?;
    super::create_dir(&a.out)?;
    let mut csv = CsvSink::create(&a.out.join("imu.csv"), sc.outputs, &sc.plant)?;
    let mut figs = RunFigures::new(&sc.plant, sc.samples());
    let summary = if a.figures {
        crate::fmu::run(&a.fmu, &sc, sc.samples(), &mut [&mut csv, &mut figs])?
    } else {
        crate::fmu::run(&a.fmu, &sc, sc.samples(), &mut [&mut csv])?
    };
    if a.figures {
        for p in figs.write(&a.out, &sc.meta.name)? {
            eprintln!("wrote {}", p.display());
        }
    }
    eprintln!(
        "{} via {}: {} samples in {:.2} s, {:.1} ns/sample -> {}",
        sc.meta.name,
        a.fmu.display(),
        summary.samples,
        summary.wall_s,
        summary.wall_s * 1e9 / summary.samples.max(1) as f64,
        a.out.display()
    );
    Ok(())
}
