//! `rins`: run scenarios of the rotating RLG INS plant and verify them. Each command is a module
//! of `rins_scenarios::commands`; this file lists them.

use clap::{Parser, Subcommand};
use rins_scenarios::commands::{
    self, bench_diagnosis, calibrate, campaign, compare, diagnose, fmu, measure, paper, run,
    scenarios, schemes, sweep, verify,
};
#[cfg(feature = "transport")]
use rins_scenarios::commands::{nav, serve};

#[derive(Parser)]
#[command(
    name = "rins",
    version,
    about = "Co-simulation plant model of a dual-axis rotating RLG inertial navigation system"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scenario and write the IMU stream as CSV.
    Run(run::RunArgs),
    /// Verification reports.
    #[command(subcommand)]
    Verify(verify::VerifyCommand),
    /// The paper's experiments. Without a subcommand: the headline job, the analytic
    /// verification plus Table 4 with the paper's 32 seeds (`--runs N` for fewer).
    Paper(paper::PaperArgs),
    /// Section 3.2: Z-up and Z-down system-level indirect calibration (Fig. 4-5, Eq. 16-19),
    /// estimating beta at each position and delta-beta = beta_down - beta_up.
    Calibrate(calibrate::CalibrateArgs),
    /// Section 4.1 / Figure 8: calibrations over the scenario's [campaign] temperatures, a
    /// third-order fit of delta-beta(T) per axis, saved as a compensation file.
    Campaign(campaign::CampaignArgs),
    /// The plant as FMI 2.0 / 3.0 co-simulation FMUs: package them, or run one through a scenario.
    #[command(subcommand)]
    Fmu(fmu::FmuCommand),
    /// Model vs measurements: replay MODEL on the measured history and show where it fails (a
    /// map of channel x position x temperature x time, each cell in units of its noise floor).
    Compare(compare::CompareArgs),
    /// Rank the plant's candidate effects that explain the residual of MODEL on DATA; with
    /// --apply EFFECT, write MODEL with that effect added and fitted.
    Diagnose(diagnose::DiagnoseArgs),
    /// Simulate a measurement log from a scenario (one run per [campaign] temperature when the
    /// scenario has one), in the measurement format: test data with known effects.
    Measure(measure::MeasureArgs),
    /// The randomised benchmark of `diagnose --iterate`: trials of every effect class, run
    /// design and magnitude from an independent generator; identification, interval coverage,
    /// floor and false-claim rates per class.
    BenchDiagnosis(bench_diagnosis::BenchDiagnosisArgs),
    /// Serve the plant over iceoryx2 shared memory to navigation software (docs/transport.md).
    #[cfg(feature = "transport")]
    Serve(serve::ServeArgs),
    /// The reference navigator as a separate process, consuming a served IMU stream.
    #[cfg(feature = "transport")]
    Nav(nav::NavArgs),
    /// Rotation schemes as a design space: what each scheme leaves of each effect, worst cases
    /// over a class of position-dependent biases, scheme search, simulation (docs/schemes.md).
    #[command(subcommand)]
    Schemes(schemes::SchemesCommand),
    /// List the built-in scenarios, or print one.
    Scenarios(scenarios::ScenariosArgs),
    /// Sweep scenario keys over a list or a grid, each point x seeds through the Monte Carlo
    /// engine (uncompensated and compensated): table, CSV/Parquet, figures, report (docs/sweeps.md).
    Sweep(sweep::SweepArgs),
}

fn main() -> std::process::ExitCode {
    commands::default_sigpipe();
    commands::exit_code(match Cli::parse().command {
        Command::Run(a) => run::run(&a),
        Command::Verify(c) => verify::run(&c),
        Command::Schemes(c) => schemes::run(&c),
        Command::Paper(a) => paper::run(&a),
        Command::Calibrate(a) => calibrate::run(&a),
        Command::Campaign(a) => campaign::run(&a),
        Command::Fmu(c) => fmu::run(&c),
        Command::Compare(a) => compare::run(&a),
        Command::Diagnose(a) => diagnose::run(&a),
        Command::Measure(a) => measure::run(&a),
        Command::BenchDiagnosis(a) => bench_diagnosis::run(&a),
        #[cfg(feature = "transport")]
        Command::Serve(a) => serve::run(&a),
        #[cfg(feature = "transport")]
        Command::Nav(a) => nav::run(&a),
        Command::Scenarios(a) => scenarios::run(&a),
        Command::Sweep(a) => sweep::run(&a),
    })
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;
    use clap::builder::ValueParser;

    use super::Cli;

    /// Every option with a numeric value takes a negative number, so that `-5` reaches the
    /// command's range check instead of clap's "use `-- -5`" tip.
    #[test]
    fn every_numeric_option_takes_negative_numbers() {
        let numeric = [
            ValueParser::from(clap::value_parser!(f64)).type_id(),
            ValueParser::from(clap::value_parser!(i64)).type_id(),
            ValueParser::from(clap::value_parser!(u64)).type_id(),
            ValueParser::from(clap::value_parser!(usize)).type_id(),
        ];
        fn walk(
            cmd: &clap::Command,
            path: &str,
            is_numeric: &dyn Fn(&clap::Arg) -> bool,
            seen: &mut Vec<String>,
            refused: &mut Vec<String>,
        ) {
            for arg in cmd.get_arguments() {
                if is_numeric(arg) {
                    let name = format!("{path} --{}", arg.get_id());
                    if !arg.is_allow_negative_numbers_set() {
                        refused.push(name.clone());
                    }
                    seen.push(name);
                }
            }
            for sub in cmd.get_subcommands() {
                walk(
                    sub,
                    &format!("{path} {}", sub.get_name()),
                    is_numeric,
                    seen,
                    refused,
                );
            }
        }
        let (mut seen, mut refused) = (Vec::new(), Vec::new());
        let is_numeric = |a: &clap::Arg| numeric.contains(&a.get_value_parser().type_id());
        walk(
            &Cli::command(),
            "rins",
            &is_numeric,
            &mut seen,
            &mut refused,
        );
        assert!(seen.len() >= 20, "numeric options found: {seen:?}");
        assert!(refused.is_empty(), "refuse negative numbers: {refused:?}");
    }
}
