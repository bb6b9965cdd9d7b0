//! A file's rows handed on in chunks of whole segments: the reader (CSV piece by piece, Parquet
//! row group by row group) pushes the rows it parses, and every chunk of at least the asked
//! number of rows whose last segment is complete leaves, checked, to the sink. A segment is never
//! split, because the replay starts each segment afresh (docs/measurement-format.md, "Memory").

use crate::header::{Kind, Layout};
use crate::measurement::{Measurement, MeasurementError};
use crate::reader::{Acc, finish};

/// What receives a file's rows, chunk after chunk in file order: each chunk a checked
/// measurement of whole segments.
pub type ChunkSink<'a> = dyn FnMut(Measurement) -> Result<(), MeasurementError> + 'a;

/// Rows parsed but not yet handed on: whole segments leave in chunks of at least `chunk_rows`
/// rows (the last may be shorter), each checked by [`finish`]; the rows of the segment that
/// may go on in the next piece stay.
pub(crate) struct Chunker<'s, 'a> {
    layout: Layout,
    pending: Acc,
    /// Rows handed on so far (error rows count across chunks).
    row0: usize,
    chunk_rows: usize,
    t0_ns: Option<i64>,
    sink: &'s mut ChunkSink<'a>,
    /// Columns of the run and segment labels.
    keys: [Option<usize>; 2],
    /// Start of the last segment among the pending rows.
    last_start: usize,
}

impl<'s, 'a> Chunker<'s, 'a> {
    pub(crate) fn new(layout: Layout, chunk_rows: usize, sink: &'s mut ChunkSink<'a>) -> Self {
        let key = |name: &str| {
            layout
                .header
                .iter()
                .zip(&layout.kind)
                .position(|(h, k)| h == name && *k == Kind::Label)
        };
        let keys = [key("run"), key("segment")];
        Self {
            pending: Acc::new(&layout),
            layout,
            row0: 0,
            chunk_rows: chunk_rows.max(1),
            t0_ns: None,
            sink,
            keys,
            last_start: 0,
        }
    }

    /// The layout the rows are read with.
    pub(crate) fn layout(&self) -> &Layout {
        &self.layout
    }

    /// Sets the origin of a `t_s` read from a Parquet time type.
    pub(crate) fn set_t0_ns(&mut self, t0_ns: Option<i64>) {
        self.t0_ns = self.t0_ns.or(t0_ns);
    }

    /// Whether rows `i − 1` and `i` of the pending rows belong to different segments.
    fn boundary(&self, i: usize) -> bool {
        self.keys
            .iter()
            .flatten()
            .any(|&c| self.pending.labs[c].index[i] != self.pending.labs[c].index[i - 1])
    }

    /// Adds parsed rows and hands on every whole chunk.
    pub(crate) fn push(&mut self, rows: Acc) -> Result<(), MeasurementError> {
        let old = self.pending.rows;
        self.pending.append(rows);
        // Rows before the start of the last segment are complete (it may go on in the next
        // piece); only the new rows are scanned.
        for i in old.max(1)..self.pending.rows {
            if self.boundary(i) {
                self.last_start = i;
            }
        }
        while self.last_start >= self.chunk_rows {
            let cut = (self.chunk_rows..=self.last_start)
                .find(|&i| self.boundary(i))
                .expect("the last segment's start is a boundary");
            self.hand_on(cut)?;
            self.last_start -= cut;
        }
        Ok(())
    }

    /// Hands on the first `k` pending rows.
    fn hand_on(&mut self, k: usize) -> Result<(), MeasurementError> {
        let front = self.pending.split_front(k);
        let m = finish(&self.layout, front, self.t0_ns, self.row0)?;
        self.row0 += k;
        (self.sink)(m)
    }

    /// Hands on the rest at the end of the file; the total rows handed on.
    pub(crate) fn end(mut self) -> Result<usize, MeasurementError> {
        if self.pending.rows > 0 {
            self.hand_on(self.pending.rows)?;
        }
        if self.row0 < 2 {
            let got = format!("need at least two data rows, got {}", self.row0);
            return Err(self.layout.err(0, "", got));
        }
        Ok(self.row0)
    }
}
