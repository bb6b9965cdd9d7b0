//! The measurement reader: a file of the measurement format (docs/measurement-format.md), CSV or
//! Parquet (told apart by the Parquet magic bytes), read whole or handed on in chunks of whole
//! segments. The layers beneath it, each importing only those below: the two parsers
//! ([`csv`], which also reads any stream, and [`parquet`]), the chunks of checked rows, the
//! physical ranges ([`crate::ranges`]), the header checks, the column maps ([`crate::colmap`]),
//! and at the bottom the parsed file, its errors and the documented columns
//! ([`crate::measurement`]).

use std::path::Path;

pub use crate::chunks::ChunkSink;
use crate::colmap::ColumnMap;
use crate::measurement::{Measurement, MeasurementError};
use crate::{csv, parquet};

/// Reads and parses a measurement file, streaming it in [`csv::PIECE`]-byte pieces (a multi-GB
/// file is never held in memory as text).
pub fn read(path: &Path) -> Result<Measurement, MeasurementError> {
    read_with(path, None)
}

/// Reads a measurement file whose columns are named and converted by `map`: CSV, or Parquet
/// when the file starts with the Parquet magic bytes (`PAR1`). The whole file is returned;
/// [`stream_with`] hands it on in chunks instead.
pub fn read_with(path: &Path, map: Option<&ColumnMap>) -> Result<Measurement, MeasurementError> {
    let mut all = Measurement::default();
    stream_with(path, map, usize::MAX, &mut |m| {
        all.append_chunk(m);
        Ok(())
    })?;
    Ok(all)
}

/// Reads a measurement file (CSV or Parquet, columns named and converted by `map`) and hands
/// its rows to `sink` in chunks of whole segments, each of at least `chunk_rows` rows (the
/// last may be shorter), checked as [`read_with`] checks them (error rows count from the
/// file's first). Memory holds one piece of text, the rows of the segment being read and one
/// chunk; a Parquet file is read one row group at a time.
pub fn stream_with(
    path: &Path,
    map: Option<&ColumnMap>,
    chunk_rows: usize,
    sink: &mut ChunkSink<'_>,
) -> Result<(), MeasurementError> {
    if parquet::is_parquet(path) {
        parquet::stream(path, map, chunk_rows, sink)
    } else {
        csv::stream(path, map, chunk_rows, sink)
    }
}

#[cfg(test)]
mod tests {
    use rins_plant::effects::{AccelTerm, GyroTerm};
    use rins_plant::output_columns::{COLUMNS, Group, entries};

    /// Every column `rins run`/`rins measure` writes of a static carrier (the plant's output
    /// table, every term) is one this reader accepts, numeric or label as written: a quantity
    /// added to the table is read back, or this fails until the format names it. (The reader
    /// models a static carrier: a moving carrier's truth columns are refused as unknown,
    /// docs/scenario-format.md, "Carrier truth".)
    #[test]
    fn every_column_of_the_plants_output_table_is_read() {
        let groups = [Group::Measured, Group::Setup, Group::Truth, Group::Effects];
        let all = entries(&groups, &GyroTerm::ALL, &AccelTerm::ALL, true);
        let in_csv = COLUMNS
            .iter()
            .filter(|c| c.in_csv && groups.contains(&c.group));
        assert!(all.len() >= in_csv.count());
        for e in all {
            for name in e.names() {
                let numeric = crate::measurement::classify(&name)
                    .unwrap_or_else(|m| panic!("column {name} of the output table: {m}"));
                let label = matches!(e.column.read, rins_plant::output_columns::Read::Position);
                assert_eq!(numeric, !label, "{name}");
            }
        }
    }
}
