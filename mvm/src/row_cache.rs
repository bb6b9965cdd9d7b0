//! The row cache: a measurement file streamed once into an unnamed temporary file of SI
//! columns, then walked back chunk by chunk by every pass of the analysis ([`Rows`]). Memory
//! holds one chunk at a time (at most [`CHUNK_ROWS`] rows or one segment, whichever is
//! longer), so it does not grow with the file; the cache costs about 110 bytes of disk per
//! row. The file is unlinked as soon as it is created, so nothing is left behind whatever
//! happens to the process.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::os::unix::fs::FileExt;
use std::path::Path;

use crate::colmap::ColumnMap;
use crate::history::{Attitude, History, chunk_to_history};
use crate::measurement::{Measurement, MeasurementError};
use crate::rows::{InfoSums, Rows, RowsInfo};

/// Rows per chunk (whole segments are added until a chunk holds at least this many): about
/// 30 MB of columns, enough for both cores to replay several segments side by side.
pub const CHUNK_ROWS: usize = 1 << 18;

/// One chunk's place in the cache.
#[derive(Clone, Debug)]
struct ChunkEntry {
    /// Byte offset of its first column.
    offset: u64,
    /// Rows.
    rows: usize,
    /// Per segment: rows and run index.
    segments: Vec<(usize, u32)>,
}

/// Which columns a chunk stores, the same for every chunk of a file.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Shape {
    /// Attitude columns: 2 (gimbal) or 4 (quaternion).
    attitude: usize,
    /// A housing temperature column.
    housing: bool,
}

impl Shape {
    fn of(h: &History) -> Self {
        Self {
            attitude: match h.attitude {
                Attitude::Gimbal { .. } => 2,
                Attitude::Quaternion(_) => 4,
            },
            housing: h.housing_temp_c.is_some(),
        }
    }
}

/// Measured rows held in an unlinked temporary file (see the module docs).
pub struct RowCache {
    file: File,
    chunks: Vec<ChunkEntry>,
    shape: Shape,
    info: RowsInfo,
    /// The first row's site columns (lat_deg, lon_deg, height_m) when the file has them.
    first_site: Option<(f64, f64, Option<f64>)>,
}

/// Opens an unlinked temporary file in the system's temporary folder (`TMPDIR`).
fn anonymous_file() -> std::io::Result<File> {
    let dir = std::env::temp_dir();
    for attempt in 0..100u32 {
        let path = dir.join(format!(
            ".rins-rows-{}-{}-{attempt}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.subsec_nanos())
        ));
        match std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create_new(true)
            .open(&path)
        {
            Ok(f) => {
                std::fs::remove_file(&path)?;
                return Ok(f);
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    Err(std::io::Error::other("no free temporary file name"))
}

/// Builds a cache from measurement chunks fed in file order.
struct Builder {
    out: BufWriter<File>,
    offset: u64,
    chunks: Vec<ChunkEntry>,
    shape: Option<Shape>,
    sums: InfoSums,
    run_names: Vec<String>,
    first_site: Option<(f64, f64, Option<f64>)>,
    source: String,
}

impl Builder {
    fn add(&mut self, m: Measurement) -> Result<(), MeasurementError> {
        if self.chunks.is_empty() {
            let first = |c: &str| m.col(c).and_then(|v| v.first().copied());
            if let (Some(lat), Some(lon)) = (first("lat_deg"), first("lon_deg")) {
                self.first_site = Some((lat, lon, first("height_m")));
            }
        }
        let h = chunk_to_history(m, &self.source, &mut self.run_names)?;
        let shape = Shape::of(&h);
        if *self.shape.get_or_insert(shape) != shape {
            unreachable!("every chunk of a file has the file's columns");
        }
        self.sums.add(&h);
        let io = |e: std::io::Error| MeasurementError {
            source_name: self.source.clone(),
            row: 0,
            column: String::new(),
            message: format!(
                "cannot write the row cache in {}: {e}",
                std::env::temp_dir().display()
            ),
        };
        let n = h.len();
        let mut columns: Vec<&[f64]> = vec![&h.t_s];
        columns.extend(h.dtheta_rad.iter().map(Vec::as_slice));
        columns.extend(h.dv_mps.iter().map(Vec::as_slice));
        let quaternion: Vec<Vec<f64>>;
        match &h.attitude {
            Attitude::Gimbal {
                outer_rad,
                inner_rad,
            } => columns.extend([outer_rad.as_slice(), inner_rad.as_slice()]),
            Attitude::Quaternion(q) => {
                quaternion = (0..4).map(|i| q.iter().map(|r| r[i]).collect()).collect();
                columns.extend(quaternion.iter().map(Vec::as_slice));
            }
        }
        columns.extend(h.gyro_temp_c.iter().map(Vec::as_slice));
        columns.push(&h.accel_temp_c);
        if let Some(t) = &h.housing_temp_c {
            columns.push(t);
        }
        for c in &columns {
            for v in c.iter() {
                self.out.write_all(&v.to_le_bytes()).map_err(io)?;
            }
        }
        self.chunks.push(ChunkEntry {
            offset: self.offset,
            rows: n,
            segments: h
                .segments
                .iter()
                .map(|s| (s.len(), h.run[s.start]))
                .collect(),
        });
        self.offset += (columns.len() * n * 8) as u64;
        Ok(())
    }
}

impl RowCache {
    /// Streams measurement file `path` (CSV or Parquet, read with `map`) into a cache, checking
    /// every row as [`crate::reader::read_with`] does. `chunk_rows` sets the chunk length
    /// ([`CHUNK_ROWS`] in the commands; tests use small chunks to walk many).
    pub fn read(
        path: &Path,
        map: Option<&ColumnMap>,
        chunk_rows: usize,
    ) -> Result<Self, MeasurementError> {
        let source = path.display().to_string();
        let file = anonymous_file().map_err(|e| MeasurementError {
            source_name: source.clone(),
            row: 0,
            column: String::new(),
            message: format!(
                "cannot create the row cache in {}: {e}",
                std::env::temp_dir().display()
            ),
        })?;
        let mut b = Builder {
            out: BufWriter::with_capacity(1 << 20, file.try_clone().expect("a file handle")),
            offset: 0,
            chunks: Vec::new(),
            shape: None,
            sums: InfoSums::default(),
            run_names: Vec::new(),
            first_site: None,
            source: source.clone(),
        };
        crate::reader::stream_with(path, map, chunk_rows, &mut |m| b.add(m))?;
        b.out.flush().map_err(|e| MeasurementError {
            source_name: source.clone(),
            row: 0,
            column: String::new(),
            message: format!("cannot write the row cache: {e}"),
        })?;
        let shape = b.shape.expect("the reader hands on at least two rows");
        let info = b
            .sums
            .info(&source, &b.run_names, shape.attitude == 2, shape.housing);
        Ok(Self {
            file,
            chunks: b.chunks,
            shape,
            info,
            first_site: b.first_site,
        })
    }

    /// The first row's site columns (lat_deg, lon_deg, height_m), when the file has them.
    pub fn first_site(&self) -> Option<(f64, f64, Option<f64>)> {
        self.first_site
    }

    /// Chunks in the cache.
    pub fn chunks(&self) -> usize {
        self.chunks.len()
    }

    /// Reads chunk `c` back.
    fn chunk(&self, c: &ChunkEntry) -> std::io::Result<History> {
        let n = c.rows;
        let mut bytes = vec![0u8; n * 8];
        let mut at = c.offset;
        let mut column = || -> std::io::Result<Vec<f64>> {
            self.file.read_exact_at(&mut bytes, at)?;
            at += (n * 8) as u64;
            Ok(bytes
                .chunks_exact(8)
                .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
                .collect())
        };
        let t_s = column()?;
        let dtheta_rad = [column()?, column()?, column()?];
        let dv_mps = [column()?, column()?, column()?];
        let attitude = if self.shape.attitude == 2 {
            Attitude::Gimbal {
                outer_rad: column()?,
                inner_rad: column()?,
            }
        } else {
            let q = [column()?, column()?, column()?, column()?];
            Attitude::Quaternion(
                (0..n)
                    .map(|k| [q[0][k], q[1][k], q[2][k], q[3][k]])
                    .collect(),
            )
        };
        let gyro_temp_c = [column()?, column()?, column()?];
        let accel_temp_c = column()?;
        let housing_temp_c = if self.shape.housing {
            Some(column()?)
        } else {
            None
        };
        let mut run = Vec::with_capacity(n);
        let mut segments = Vec::with_capacity(c.segments.len());
        for &(len, r) in &c.segments {
            segments.push(run.len()..run.len() + len);
            run.extend(std::iter::repeat_n(r, len));
        }
        Ok(History {
            t_s,
            dtheta_rad,
            dv_mps,
            attitude,
            gyro_temp_c,
            housing_temp_c,
            accel_temp_c,
            run,
            run_names: self.info.run_names.clone(),
            segments,
            source: self.info.source.clone(),
        })
    }
}

impl Rows for RowCache {
    fn info(&self) -> RowsInfo {
        self.info.clone()
    }

    fn for_each_chunk(&self, f: &mut dyn FnMut(&History)) {
        for c in &self.chunks {
            // The cache was written by this process into a file only it holds: a read error
            // is a failing disk, not a data problem the analysis could report.
            let h = self.chunk(c).unwrap_or_else(|e| {
                panic!(
                    "the row cache of {} cannot be read back: {e}",
                    self.info.source
                )
            });
            f(&h);
        }
    }
}
