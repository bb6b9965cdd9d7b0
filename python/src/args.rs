//! Whole-number arguments, taken as Python ints and checked here, so that every one of them
//! fails the same way, naming the argument and its range: `ValueError: seed: expected a whole
//! number in [0, 18446744073709551615], got -1` (not PyO3's `OverflowError: can't convert
//! negative int to unsigned`), and `TypeError` with the same words for a value that is not a
//! whole number (a float, a string). Python ints, bools and numpy integers (anything with
//! `__index__`) are accepted.

use pyo3::exceptions::{PyOverflowError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyString;

/// What the argument must be, for the messages.
fn expected(lo: u64, hi: u64) -> String {
    format!("expected a whole number in [{lo}, {hi}]")
}

/// `obj` as a whole number in `[lo, hi]`, or a `ValueError` (out of range, whatever the size
/// of the int) or `TypeError` (not a whole number) naming `name` and the range.
pub fn whole(obj: &Bound<'_, PyAny>, name: &str, lo: u64, hi: u64) -> PyResult<u64> {
    let py = obj.py();
    match obj.extract::<i128>() {
        Ok(v) if (i128::from(lo)..=i128::from(hi)).contains(&v) => Ok(v as u64),
        Ok(v) => Err(PyValueError::new_err(format!(
            "{name}: {}, got {v}",
            expected(lo, hi)
        ))),
        Err(e) if e.is_instance_of::<PyOverflowError>(py) => Err(PyValueError::new_err(format!(
            "{name}: {}, got {}",
            expected(lo, hi),
            obj.repr()?
        ))),
        Err(_) => Err(PyTypeError::new_err(format!(
            "{name}: {}, got {} {}",
            expected(lo, hi),
            obj.get_type().name()?,
            obj.repr()?
        ))),
    }
}

/// An optional whole number (`None`: not given).
pub fn whole_opt(
    obj: Option<&Bound<'_, PyAny>>,
    name: &str,
    lo: u64,
    hi: u64,
) -> PyResult<Option<u64>> {
    match obj {
        Some(o) if !o.is_none() => whole(o, name, lo, hi).map(Some),
        _ => Ok(None),
    }
}

/// A seed (`run.seed`): any 64-bit unsigned number.
pub fn seed(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Option<u64>> {
    whole_opt(obj, "seed", 0, u64::MAX)
}

/// A list (any iterable) of seeds: each a whole number in [0, 2^64 - 1], at least one, none
/// twice. The messages name the entry (`seeds[2]`), in the words of a sweep file's
/// `sweep.seeds` (docs/sweeps.md).
pub fn seeds(obj: &Bound<'_, PyAny>) -> PyResult<Vec<u64>> {
    if obj.is_instance_of::<PyString>() {
        return Err(PyTypeError::new_err(format!(
            "seeds: expected a list of whole numbers in [0, {}], got str {}",
            u64::MAX,
            obj.repr()?
        )));
    }
    let it = obj.try_iter().map_err(|_| {
        PyTypeError::new_err(format!(
            "seeds: expected a list of whole numbers in [0, {}], got {}",
            u64::MAX,
            obj.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    })?;
    let mut out: Vec<u64> = Vec::new();
    let mut first_at = std::collections::HashMap::new();
    for (i, s) in it.enumerate() {
        let name = format!("seeds[{i}]");
        let s = whole(&s?, &name, 0, u64::MAX)?;
        if let Some(j) = first_at.insert(s, i) {
            return Err(PyValueError::new_err(format!(
                "{name}: seed {s} is listed twice (also seeds[{j}]); each seed runs once"
            )));
        }
        out.push(s);
    }
    if out.is_empty() {
        return Err(PyValueError::new_err(
            "seeds: expected at least one seed, got none",
        ));
    }
    Ok(out)
}

/// `subsamples`: IMU intervals per navigator update (1 to 4).
pub fn subsamples(obj: &Bound<'_, PyAny>) -> PyResult<rins_navigation::Subsamples> {
    let n = whole(obj, "subsamples", 1, 4).map_err(|e| {
        let py = obj.py();
        let msg = format!(
            "{} (the navigator updates every 1 to 4 IMU intervals)",
            e.value(py)
        );
        if e.is_instance_of::<PyTypeError>(py) {
            PyTypeError::new_err(msg)
        } else {
            PyValueError::new_err(msg)
        }
    })?;
    rins_navigation::Subsamples::new(n as u8).map_err(PyValueError::new_err)
}

/// The Python side's check of a whole-number argument (`rins.montecarlo`'s `seeds_per_task`):
/// [`whole`] exposed as `_rins.whole(value, name, lo, hi)`.
#[pyfunction(name = "whole")]
pub fn py_whole(value: &Bound<'_, PyAny>, name: &str, lo: u64, hi: u64) -> PyResult<u64> {
    whole(value, name, lo, hi)
}

/// The Python side's check of a seed list (`rins.montecarlo`, `rins.sweep`, before any task
/// is sent to a cluster): [`seeds`] exposed as `_rins.check_seeds(seeds)`.
#[pyfunction(name = "check_seeds")]
pub fn py_seeds(seeds: &Bound<'_, PyAny>) -> PyResult<Vec<u64>> {
    self::seeds(seeds)
}
