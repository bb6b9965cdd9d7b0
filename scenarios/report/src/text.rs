//! Terminal text of the results the commands print. The verification reports render their own
//! text (`AnalyticReport::to_text`, `InsReport::to_text`, Table 5's `to_text_table5`); the
//! result types of the calibration (rins-navigation), of the diagnosis (rins-verification), of Table 4
//! ([`table4_text`]) and of the at-sea study ([`sea_text`]) get theirs here, through [`RenderText`],
//! since a trait of this crate is how they take a method here.

pub mod calibration_text;
pub mod diagnosis_text;
pub mod sea_text;
pub mod sweep_text;
pub mod table4_text;

pub use calibration_text::CalibrationRun;

/// The text a command prints for a result (newline-terminated lines).
pub trait RenderText {
    /// Renders the result as the terminal shows it.
    fn render_text(&self) -> String;
}
