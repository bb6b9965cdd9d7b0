//! Column buffers: rows are collected per entity and sent as one chunk per [`FLUSH_ROWS`] rows
//! (`send_columns`), which costs a small fraction of logging each row on its own.

use anyhow::Result;
use rerun::{RecordingStream, Scalars, SeriesLines, TimeColumn};

/// Rows buffered per entity before they are sent.
pub const FLUSH_ROWS: usize = 4096;

/// Name of the simulated-time timeline (a duration since the start of the run).
pub const SIM_TIME: &str = "sim_time";
/// Name of the step timeline (the output sample number of the row's last sample).
pub const STEP: &str = "step";

/// One scalar series entity with `names.len()` lines per row.
pub struct Series {
    path: String,
    width: usize,
    steps: Vec<i64>,
    nanos: Vec<i64>,
    values: Vec<f64>,
    rows_sent: u64,
}

impl Series {
    /// Declares the entity at `path`, logging its line names and colours once (static).
    pub fn new(
        rec: &RecordingStream,
        path: impl Into<String>,
        names: &[String],
        colors: &[[u8; 3]],
    ) -> Result<Self> {
        let path = path.into();
        let mut lines = SeriesLines::new().with_names(names.iter().map(String::as_str));
        if colors.len() == names.len() {
            lines = lines.with_colors(
                colors
                    .iter()
                    .map(|c| rerun::Color::from_rgb(c[0], c[1], c[2])),
            );
        }
        rec.log_static(path.as_str(), &lines)?;
        Ok(Self {
            path,
            width: names.len(),
            steps: Vec::new(),
            nanos: Vec::new(),
            values: Vec::new(),
            rows_sent: 0,
        })
    }

    /// Adds a row at output sample `step`, time `t_ns`.
    pub fn push(&mut self, rec: &RecordingStream, step: u64, t_ns: i64, row: &[f64]) -> Result<()> {
        debug_assert_eq!(row.len(), self.width);
        self.steps.push(step as i64);
        self.nanos.push(t_ns);
        self.values.extend_from_slice(row);
        if self.steps.len() >= FLUSH_ROWS {
            self.flush(rec)?;
        }
        Ok(())
    }

    /// Sends the buffered rows.
    pub fn flush(&mut self, rec: &RecordingStream) -> Result<()> {
        let n = self.steps.len();
        if n == 0 {
            return Ok(());
        }
        let indexes = [
            TimeColumn::new_sequence(STEP, self.steps.drain(..)),
            TimeColumn::new_duration_nanos(SIM_TIME, self.nanos.drain(..)),
        ];
        let columns =
            Scalars::new(self.values.drain(..)).columns(std::iter::repeat_n(self.width, n))?;
        rec.send_columns(self.path.as_str(), indexes, columns)?;
        self.rows_sent += n as u64;
        Ok(())
    }

    /// Rows logged so far (sent or buffered).
    pub fn rows(&self) -> u64 {
        self.rows_sent + self.steps.len() as u64
    }

    /// The entity path.
    pub fn path(&self) -> &str {
        &self.path
    }
}

/// Seconds to the integer nanoseconds of the duration timeline.
pub fn nanos(t_s: f64) -> i64 {
    (t_s * 1e9).round() as i64
}

/// Logs a finished table as one series entity: rows of (step, time s, values).
pub fn log_rows(
    rec: &RecordingStream,
    path: &str,
    names: &[String],
    colors: &[[u8; 3]],
    rows: impl IntoIterator<Item = (u64, f64, Vec<f64>)>,
) -> Result<u64> {
    let mut s = Series::new(rec, path, names, colors)?;
    for (step, t_s, v) in rows {
        s.push(rec, step, nanos(t_s), &v)?;
    }
    s.flush(rec)?;
    Ok(s.rows())
}
