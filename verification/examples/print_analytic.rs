//! Prints the analytic report (development aid; the CLI is `rins verify analytic`).
fn main() {
    print!("{}", rins_verify::report::AnalyticReport::run().to_text());
}
