//! Terminal text of the results the commands print. The verification reports render their own
//! text (`AnalyticReport::to_text`, `InsReport::to_text`, `Table4Report::to_text`); the result
//! types of the calibration (rins-nav) and of the diagnosis (rins-verify) get theirs here,
//! through [`RenderText`], since a trait of this crate is how they take a method here.

pub mod calibration;
pub mod diagnosis;

pub use calibration::CalibrationRun;

/// The text a command prints for a result (newline-terminated lines).
pub trait RenderText {
    /// Renders the result as the terminal shows it.
    fn render_text(&self) -> String;
}
