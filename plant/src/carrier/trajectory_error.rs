//! The error of a trajectory file, beneath the parser (`trajectory`) and the line reader
//! (`trajectory_text`) that both raise it.

/// An error in a trajectory file; `row` counts data rows from 1 (the header is row 0). The
/// message says where ([`crate::message::file_location`]): the whole file (row 0 without a
/// column), the header's column, the row, or the row's column.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{source_name}: {}: {message}", crate::message::file_location(*.row, .column))]
pub struct TrajectoryError {
    /// File name.
    pub source_name: String,
    /// Data row (1-based; 0 = header).
    pub row: usize,
    /// Column name.
    pub column: String,
    /// What is wrong and what was expected.
    pub message: String,
}
