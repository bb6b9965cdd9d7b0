//! A file's rows handed on in chunks of whole segments: the reader (CSV piece by piece, Parquet
//! row group by row group) pushes the rows it parses, and every chunk of at least the asked
//! number of rows whose last segment is complete leaves, checked, to the sink. A segment is never
//! split, because the replay starts each segment afresh (docs/measurement-format.md, "Memory").
//! The rows parsed so far are an [`Acc`]; each chunk is built and checked by [`finish`].

use rins_plant::message::num;

use crate::header::{Kind, Layout};
use crate::measurement::{LabelColumn, Measurement, MeasurementError};
use crate::ranges;

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

/// Columns filled so far.
pub(crate) struct Acc {
    /// Numeric columns (empty for labels and ignored ones).
    pub nums: Vec<Vec<f64>>,
    /// Label columns.
    pub labs: Vec<LabelColumn>,
    /// Rows.
    pub rows: usize,
}

impl Acc {
    pub(crate) fn new(l: &Layout) -> Self {
        Self {
            nums: vec![Vec::new(); l.header.len()],
            labs: vec![LabelColumn::default(); l.header.len()],
            rows: 0,
        }
    }

    /// The first `k` rows, which leave `self`.
    pub(crate) fn split_front(&mut self, k: usize) -> Acc {
        let front = |v: &mut Vec<f64>| {
            if v.is_empty() {
                return Vec::new();
            }
            let back = v.split_off(k);
            std::mem::replace(v, back)
        };
        let nums = self.nums.iter_mut().map(front).collect();
        let labs = self
            .labs
            .iter_mut()
            .map(|l| {
                if l.index.is_empty() {
                    return LabelColumn::default();
                }
                let back = l.index.split_off(k);
                LabelColumn {
                    names: l.names.clone(),
                    index: std::mem::replace(&mut l.index, back),
                }
            })
            .collect();
        self.rows -= k;
        Acc {
            nums,
            labs,
            rows: k,
        }
    }

    /// Appends the rows of `other`.
    pub(crate) fn append(&mut self, other: Acc) {
        for (x, y) in self.nums.iter_mut().zip(other.nums) {
            x.extend(y);
        }
        for (x, y) in self.labs.iter_mut().zip(other.labs) {
            x.append(y);
        }
        self.rows += other.rows;
    }
}

/// Builds the measurement from the parsed columns of whole segments and checks segments, time
/// and the physical ranges ([`ranges`]); `t0_ns` is the origin of a `t_s` read from a Parquet
/// time type; the rows follow `row0` rows of the file (for error rows).
pub(crate) fn finish(
    layout: &Layout,
    acc: Acc,
    t0_ns: Option<i64>,
    row0: usize,
) -> Result<Measurement, MeasurementError> {
    let err = |row: usize, column: &str, message: String| layout.err(row0 + row, column, message);
    let mut m = Measurement {
        rows: acc.rows,
        t0_ns,
        ..Measurement::default()
    };
    for (i, (n, l)) in acc.nums.into_iter().zip(acc.labs).enumerate() {
        let h = layout.header[i].clone();
        match layout.kind[i] {
            Kind::Skip => m.ignored.push(layout.raw[i].clone()),
            Kind::Label => {
                m.labels.insert(h, l);
            }
            Kind::Num => {
                let mut n = n;
                let (f, o) = layout.conv[i];
                if (f, o) != (1.0, 0.0) {
                    for (k, v) in n.iter_mut().enumerate() {
                        *v = *v * f + o;
                        if !v.is_finite() {
                            return Err(err(
                                k + 1,
                                &layout.raw[i],
                                format!(
                                    "not finite after the column map's conversion (x {f} + {o})"
                                ),
                            ));
                        }
                    }
                }
                m.columns.insert(h, n);
            }
        }
    }
    // Values out of their physical range, before time is looked at (a t_s of 1e30 is a unit
    // mistake, not a gap).
    ranges::check_values(&m, layout, row0)?;
    // Segments: consecutive rows with the same (run, segment) labels.
    let label = |name: &str, i: usize| m.labels.get(name).map_or(u32::MAX, |c| c.index[i]);
    let name = |col: &str, i: usize| {
        m.labels
            .get(col)
            .map_or(String::new(), |c| c.get(i).to_string())
    };
    let mut start = 0;
    let mut segments = Vec::new();
    for i in 1..=m.rows {
        if i == m.rows
            || label("run", i) != label("run", start)
            || label("segment", i) != label("segment", start)
        {
            segments.push((name("run", start), name("segment", start), start, i));
            start = i;
        }
    }
    m.segments = segments;
    // Time strictly increasing within a segment, and evenly spaced (a gap means lost samples).
    let t_col = ranges::source_of(layout, "t_s").0;
    let t = &m.columns["t_s"];
    // Each row's interval; a segment's first row takes the segment's median interval (a
    // one-row segment the longest interval accepted).
    let mut dt_s = vec![ranges::ROW_INTERVAL_S[1]; m.rows];
    for &(_, _, a, b) in &m.segments {
        if b - a < 2 {
            continue;
        }
        let mut d: Vec<f64> = t[a..b].windows(2).map(|w| w[1] - w[0]).collect();
        for (k, dt) in d.iter().enumerate() {
            if *dt <= 0.0 {
                return Err(err(
                    a + k + 2,
                    &t_col,
                    format!(
                        "time not increasing: {} after {}",
                        num(t[a + k + 1]),
                        num(t[a + k])
                    ),
                ));
            }
        }
        dt_s[a + 1..b].copy_from_slice(&d);
        d.sort_by(f64::total_cmp);
        let median = d[d.len() / 2];
        dt_s[a] = median;
        for k in a + 1..b {
            let dt = t[k] - t[k - 1];
            // The last row of a decimated file may be shorter; a longer step is a gap.
            if dt > median * 1.01 + 1e-9 {
                return Err(err(
                    k + 1,
                    &t_col,
                    format!(
                        "gap: {} s since the previous row, the segment's interval is {} s (start a new segment or run after a gap)",
                        num(dt),
                        num(median)
                    ),
                ));
            }
        }
    }
    ranges::check_rows(&m, layout, &dt_s, row0)?;
    Ok(m)
}
