//! `rins.Simulation` and `rins.run`: the plant stepped through a scenario, its samples handed
//! back as numpy arrays, chunk by chunk. Every value is the one `rins run` writes to imu.csv
//! (decimation 1) computed the same way, so the arrays equal the CSV bit for bit.

use std::sync::Mutex;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rins_plant::output_columns::{self, Entry, Group, OverRow, Read, Reading};
use rins_plant::{ImuSample, Plant, Truth};

use crate::memory;
use crate::scenario::PyScenario;

/// Gimbal position labels, indexed by the `position` code of a chunk (the CSV's `position`
/// column: the four 16-position stations, a z-up/z-down dwell elsewhere, or moving).
pub const POSITION_LABELS: [&str; 7] = ["A", "B", "C", "D", "z-up", "z-down", "moving"];

/// Samples gathered while the GIL is released, one vector per column entry
/// ([`rins_plant::output_columns`], in the layout's order).
#[derive(Default)]
struct Columns {
    n: usize,
    sample: Vec<u64>,
    position: Vec<u8>,
    /// The real columns' values, per entry, sample after sample.
    reals: Vec<Vec<f64>>,
    /// One sample's values (scratch).
    values: Vec<f64>,
}

/// What the plant produces besides the samples, fixed for a run.
struct Layout {
    /// The column groups gathered: the measured outputs and the set-up, with `truth` the truth,
    /// the terms' errors and a moving carrier's truth.
    groups: Vec<Group>,
    /// The columns of those groups, the term columns once per enabled term.
    entries: Vec<Entry>,
    /// The mount between the truth's carrier attitude and the table, for q_b^n.
    mount: rins_plant::TruthMount,
    dt_s: f64,
}

impl Layout {
    fn of(cfg: &rins_plant::PlantConfig, truth: bool) -> Self {
        let mut groups = vec![Group::Measured, Group::Setup];
        if truth {
            groups.extend([Group::Truth, Group::Effects]);
            if !cfg.carrier.is_static() {
                groups.push(Group::CarrierTruth);
            }
        }
        let entries = output_columns::entries(
            &groups,
            &cfg.sensor.gyro.enabled_terms(),
            &cfg.sensor.accel.enabled_terms(),
            false,
        );
        Self {
            groups,
            entries,
            mount: rins_plant::TruthMount::of_config(cfg),
            dt_s: 1.0 / cfg.rate_hz,
        }
    }

    /// Bytes of one sample's arrays, as [`Columns::reserve`] reserves them.
    fn bytes_per_sample(&self) -> u128 {
        self.entries
            .iter()
            .map(|e| match e.column.read {
                Read::Index => size_of::<u64>() as u128,
                Read::Position => size_of::<u8>() as u128,
                _ => (size_of::<f64>() * e.width()) as u128,
            })
            .sum()
    }
}

/// Who asked for samples, for the messages of [`Simulation::take`].
#[derive(Clone, Copy)]
enum Caller {
    Run,
    Chunk,
    Step,
}

impl Caller {
    fn name(self) -> &'static str {
        match self {
            Caller::Run => "rins.run",
            Caller::Chunk => "rins.Simulation (a chunk)",
            Caller::Step => "Simulation.step",
        }
    }

    /// What to change when the arrays do not fit.
    fn hint(self) -> &'static str {
        match self {
            Caller::Run => {
                "take the samples in chunks with rins.Simulation(scenario, chunk=N), or run a \
                 shorter span with duration_s="
            }
            Caller::Chunk => "use a smaller chunk (rins.Simulation(scenario, chunk=N))",
            Caller::Step => {
                "step fewer samples at a time, or iterate over rins.Simulation(scenario, chunk=N)"
            }
        }
    }
}

/// Chunks of at most this many samples are stepped without looking for signals (they take
/// well under a second even while a gimbal turns with `truth=True`), and so with no thread of
/// their own and no copy of the plant to go back to.
const UNINTERRUPTED: u64 = 4096;

/// Samples between looks at the stop flag of a longer chunk.
const STOP_EVERY: u64 = 64;

impl Columns {
    /// Empty columns with room for `n` samples of `l`'s entries, or `MemoryError` naming `what`
    /// and the bytes `need` if a reservation fails.
    fn reserve(n: u64, l: &Layout, what: &str, need: u128, hint: &str) -> PyResult<Self> {
        let n = u128::from(n);
        let reals = l
            .entries
            .iter()
            .map(|e| match e.column.read {
                Read::Index | Read::Position => Ok(Vec::new()),
                _ => memory::vec::<f64>(n * e.width() as u128, what, need, hint),
            })
            .collect::<PyResult<_>>()?;
        Ok(Self {
            n: 0,
            sample: memory::vec(n, what, need, hint)?,
            position: memory::vec(n, what, need, hint)?,
            reals,
            values: vec![0.0; l.entries.iter().map(Entry::width).max().unwrap_or(0)],
        })
    }

    /// One sample, computed as the CSV sink computes a row of one sample.
    fn push(&mut self, s: &ImuSample, tr: &Truth, l: &Layout) {
        self.n += 1;
        let r = Reading {
            sample: s,
            truth: tr,
            mount: &l.mount,
        };
        for (e, col) in l.entries.iter().zip(&mut self.reals) {
            match e.column.read {
                Read::Index => self.sample.push(s.index),
                Read::Position => {
                    let label = output_columns::position_of(&r);
                    let code = POSITION_LABELS
                        .iter()
                        .position(|p| *p == label)
                        .unwrap_or(POSITION_LABELS.len() - 1);
                    self.position.push(code as u8);
                }
                _ => {
                    let v = &mut self.values[..e.width()];
                    e.read(&r, v);
                    // The CSV's mean rate over a row of one sample: increment / (1·Δt).
                    if let OverRow::MeanRate { unit_si } = e.column.over_row {
                        v.iter_mut().for_each(|x| *x /= l.dt_s * unit_si);
                    }
                    col.extend_from_slice(v);
                }
            }
        }
    }

    /// The columns as a dict of numpy arrays (moved, not copied): one array per column under
    /// its key (1-D for one element, else one row per sample), a term column as a dict of its
    /// enabled terms' arrays.
    fn into_dict<'py>(self, py: Python<'py>, l: &Layout) -> PyResult<Bound<'py, PyDict>> {
        let n = self.n;
        let d = PyDict::new(py);
        let array = |v: Vec<f64>, k: usize| -> PyResult<Bound<'py, PyAny>> {
            if k == 1 {
                return Ok(PyArray1::from_vec(py, v).into_any());
            }
            let a = Array2::from_shape_vec((n, k), v)
                .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
            Ok(a.into_pyarray(py).into_any())
        };
        let mut reals = l.entries.iter().zip(self.reals).peekable();
        let (mut sample, mut position) = (Some(self.sample), Some(self.position));
        for c in output_columns::COLUMNS {
            if !l.groups.contains(&c.group) {
                continue;
            }
            match c.read {
                Read::Index => {
                    reals.next();
                    let v = sample.take().unwrap_or_default();
                    d.set_item(c.key, PyArray1::from_vec(py, v))?;
                }
                Read::Position => {
                    reals.next();
                    let v = position.take().unwrap_or_default();
                    d.set_item(c.key, PyArray1::from_vec(py, v))?;
                }
                Read::Reals(_) => {
                    let (e, v) = reals.next().expect("an entry per column");
                    d.set_item(c.key, array(v, e.width())?)?;
                }
                Read::GyroTerm | Read::AccelTerm => {
                    // Every enabled term's entry, in order (an empty dict with none enabled).
                    let terms = PyDict::new(py);
                    while let Some((e, v)) = reals.next_if(|(e, _)| e.column.key == c.key) {
                        terms.set_item(e.term.map_or("", |t| t.1), array(v, e.width())?)?;
                    }
                    d.set_item(c.key, terms)?;
                }
            }
        }
        Ok(d)
    }
}

/// Output samples in `duration_s` at `rate_hz`, as the runner counts them; a clear error for a
/// duration that is not a positive, finite number of seconds.
pub fn samples_of(duration_s: f64, rate_hz: f64) -> PyResult<u64> {
    if !(duration_s > 0.0 && duration_s.is_finite() && duration_s <= 1e7) {
        return Err(PyValueError::new_err(format!(
            "duration_s: expected a number in (0, 1e7], got {duration_s}"
        )));
    }
    Ok((duration_s * rate_hz).round() as u64)
}

/// The plant of a scenario, stepped on demand: `Simulation(scenario, duration_s=None,
/// chunk=100000, seed=None, truth=True)`. Iterating yields dicts of numpy arrays of at most `chunk`
/// samples until `duration_s` (default: the scenario's) is covered; `step(n)` takes `n` more.
/// `truth=False` leaves out the truth columns (the measured outputs only). The GIL is released
/// while the plant runs; Ctrl-C stops a call within a fraction of a second and leaves the
/// simulation where it was (the next call gives the same samples).
#[pyclass(module = "rins", name = "Simulation")]
pub struct Simulation {
    plant: Mutex<Plant>,
    layout: Layout,
    total: u64,
    done: u64,
    chunk: u64,
}

impl Simulation {
    /// A plant built from `sc` with an optional seed override.
    pub fn new(
        sc: &PyScenario,
        duration_s: Option<f64>,
        chunk: u64,
        seed: Option<u64>,
        truth: bool,
    ) -> PyResult<Self> {
        let mut cfg = sc.inner.plant.clone();
        if let Some(s) = seed {
            cfg.seed = s;
        }
        let total = samples_of(duration_s.unwrap_or(sc.inner.meta.duration_s), cfg.rate_hz)?;
        if chunk == 0 {
            return Err(PyValueError::new_err(
                "chunk: expected at least 1 sample, got 0",
            ));
        }
        // A chunk's arrays must fit (checked again before each chunk is reserved).
        if chunk != u64::MAX {
            let per = Layout::of(&cfg, truth).bytes_per_sample();
            let n = chunk.min(total);
            memory::check(
                &format!(
                    "{}: chunk={chunk}: {n} samples × {per} bytes",
                    Caller::Chunk.name()
                ),
                u128::from(n) * per,
                Caller::Chunk.hint(),
            )?;
        }
        let plant = rins_scenario::new_plant(&cfg, &sc.inner.source)
            .map_err(|e| crate::errors::ScenarioError::new_err(format!("{e:#}")))?;
        Ok(Self {
            layout: Layout::of(&cfg, truth),
            plant: Mutex::new(plant),
            total,
            done: 0,
            chunk,
        })
    }

    /// Steps `n` samples with the GIL released and returns them as a dict of arrays. Their
    /// bytes are checked, then reserved, before the plant steps (`MemoryError` naming them
    /// otherwise); a chunk of more than [`UNINTERRUPTED`] samples stops on Ctrl-C and puts the
    /// plant back as it was.
    fn take<'py>(
        &mut self,
        py: Python<'py>,
        n: u64,
        caller: Caller,
    ) -> PyResult<Bound<'py, PyDict>> {
        let per = self.layout.bytes_per_sample();
        let need = u128::from(n) * per;
        let what = format!("{}: {n} samples × {per} bytes", caller.name());
        memory::check(&what, need, caller.hint())?;
        let layout = &self.layout;
        let mut c = Columns::reserve(n, layout, &what, need, caller.hint())?;
        let plant = self.plant.get_mut().unwrap_or_else(|e| e.into_inner());
        if n <= UNINTERRUPTED {
            py.detach(|| {
                for _ in 0..n {
                    let s = plant.step();
                    c.push(&s, &plant.truth(), layout);
                }
            });
        } else {
            let before = plant.clone();
            let stepped = crate::interrupt::run(py, |stop| {
                for k in 0..n {
                    if k % STOP_EVERY == 0 && stop.requested() {
                        return;
                    }
                    let s = plant.step();
                    c.push(&s, &plant.truth(), layout);
                }
            });
            if let Err(e) = stepped {
                *plant = before;
                return Err(e);
            }
        }
        self.done += n;
        c.into_dict(py, &self.layout)
    }
}

#[pymethods]
impl Simulation {
    #[new]
    #[pyo3(
        signature = (scenario, duration_s = None, chunk = None, seed = None, truth = true),
        text_signature = "(scenario, duration_s=None, chunk=100000, seed=None, truth=True)"
    )]
    fn py_new(
        scenario: &Bound<'_, PyAny>,
        duration_s: Option<f64>,
        chunk: Option<&Bound<'_, PyAny>>,
        seed: Option<&Bound<'_, PyAny>>,
        truth: bool,
    ) -> PyResult<Self> {
        let chunk = crate::args::whole_opt(chunk, "chunk", 1, u64::MAX)?.unwrap_or(100_000);
        let seed = crate::args::seed(seed)?;
        Self::new(
            &PyScenario::resolve(scenario)?,
            duration_s,
            chunk,
            seed,
            truth,
        )
    }

    /// The next `n` samples (beyond `duration_s` too), as a dict of numpy arrays.
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        n: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let n = crate::args::whole(n, "n", 0, u64::MAX)?;
        self.take(py, n, Caller::Step)
    }

    /// Samples stepped so far.
    #[getter]
    fn samples_done(&self) -> u64 {
        self.done
    }

    /// Samples in `duration_s`.
    #[getter]
    fn samples_total(&self) -> u64 {
        self.total
    }

    /// Output sample interval, s.
    #[getter]
    fn dt_s(&self) -> f64 {
        self.layout.dt_s
    }

    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__<'py>(&mut self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let n = self.total.saturating_sub(self.done).min(self.chunk);
        if n == 0 {
            return Ok(None);
        }
        self.take(py, n, Caller::Chunk).map(Some)
    }
}

/// Runs `scenario` for `duration_s` (default: the scenario's) in one call and returns every
/// sample as a dict of numpy arrays (keys: docs/python.md); `truth=False` leaves out the truth
/// columns. The GIL is released while it runs; Ctrl-C stops it. The arrays' bytes are checked
/// first: `MemoryError` where they do not fit (use `Simulation(chunk=…)` or `duration_s=`).
#[pyfunction]
#[pyo3(signature = (scenario, duration_s = None, seed = None, truth = true))]
pub fn run<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    duration_s: Option<f64>,
    seed: Option<&Bound<'py, PyAny>>,
    truth: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let seed = crate::args::seed(seed)?;
    let sc = PyScenario::resolve(scenario)?;
    let mut sim = Simulation::new(&sc, duration_s, u64::MAX, seed, truth)?;
    let n = sim.total;
    sim.take(py, n, Caller::Run)
}
