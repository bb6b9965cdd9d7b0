//! The integration tests of rins-mvm in one test binary (one link instead of one per file): one
//! module per former test file; `common` is what the replay tests share.

mod common;

mod analyse;
mod column_map;
mod conditioning;
mod correlations;
mod measurement_bytes;
mod reader;
mod reader_fuzz;
mod row_cache;
