//! `rins.Simulation` and `rins.run`: the plant stepped through a scenario, its samples handed
//! back as numpy arrays, chunk by chunk. Every value is the one `rins run` writes to imu.csv
//! (decimation 1) computed the same way, so the arrays equal the CSV bit for bit.

use std::sync::Mutex;

use nalgebra::Vector3;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rins_plant::effects::{AccelTerm, GyroTerm};
use rins_plant::thermal::node;
use rins_plant::units::{DPH, UG};
use rins_plant::{ImuSample, Plant, Truth};

use crate::memory;
use crate::scenario::PyScenario;

/// Gimbal position labels, indexed by the `position` code of a chunk (the CSV's `position`
/// column: the four 16-position stations, a z-up/z-down dwell elsewhere, or moving).
pub const POSITION_LABELS: [&str; 7] = ["A", "B", "C", "D", "z-up", "z-down", "moving"];

/// Samples gathered while the GIL is released, one column per quantity.
#[derive(Default)]
struct Columns {
    n: usize,
    sample: Vec<u64>,
    t_s: Vec<f64>,
    dtheta_rad: Vec<f64>,
    dv_mps: Vec<f64>,
    outer_deg: Vec<f64>,
    inner_deg: Vec<f64>,
    position: Vec<u8>,
    temps_c: Vec<f64>,
    temp_chamber_c: Vec<f64>,
    dtheta_true_rad: Vec<f64>,
    dv_true_mps: Vec<f64>,
    q_bn: Vec<f64>,
    gimbal_outer_rad: Vec<f64>,
    gimbal_inner_rad: Vec<f64>,
    gyro_dph: Vec<Vec<f64>>,
    accel_ug: Vec<Vec<f64>>,
    carrier: Vec<f64>,
}

/// What the plant produces besides the samples, fixed for a run.
struct Layout {
    gyro_terms: Vec<GyroTerm>,
    accel_terms: Vec<AccelTerm>,
    /// The mount between the truth's carrier attitude and the table, for q_b^n.
    mount: rins_plant::TruthMount,
    moving_carrier: bool,
    dt_s: f64,
    /// Gather the truth columns too.
    truth: bool,
}

impl Layout {
    fn of(cfg: &rins_plant::PlantConfig, truth: bool) -> Self {
        Self {
            gyro_terms: cfg.sensor.gyro.enabled_terms(),
            accel_terms: cfg.sensor.accel.enabled_terms(),
            mount: rins_plant::TruthMount::of_config(cfg),
            moving_carrier: !cfg.carrier.is_static(),
            dt_s: 1.0 / cfg.rate_hz,
            truth,
        }
    }

    /// Bytes of one sample's arrays, as [`Columns::reserve`] reserves them.
    fn bytes_per_sample(&self) -> u128 {
        let f = size_of::<f64>() as u128;
        // sample, position; t_s, Δθ, Δv, the encoders, the sensors' and the chamber's
        // temperatures.
        let measured = (size_of::<u64>() + size_of::<u8>()) as u128
            + f * (1 + 3 + 3 + 2 + node::COUNT as u128 + 1);
        if !self.truth {
            return measured;
        }
        // Δθ and Δv true, q_bn, the gimbal angles, each effect's 3 rates, the carrier's 10.
        let effects = 3 * (self.gyro_terms.len() + self.accel_terms.len()) as u128;
        let carrier = if self.moving_carrier { 10 } else { 0 };
        measured + f * (3 + 3 + 4 + 2 + effects + carrier)
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

fn push3(v: &mut Vec<f64>, x: &Vector3<f64>) {
    v.extend_from_slice(&[x.x, x.y, x.z]);
}

impl Columns {
    /// Empty columns with room for `n` samples (the truth columns only with `l.truth`), or
    /// `MemoryError` naming `what` and the bytes `need` if a reservation fails.
    fn reserve(n: u64, l: &Layout, what: &str, need: u128, hint: &str) -> PyResult<Self> {
        let n = u128::from(n);
        let v = |k: usize| memory::vec::<f64>(n * k as u128, what, need, hint);
        let t = |k: usize| if l.truth { v(k) } else { Ok(Vec::new()) };
        Ok(Self {
            n: 0,
            sample: memory::vec(n, what, need, hint)?,
            t_s: v(1)?,
            dtheta_rad: v(3)?,
            dv_mps: v(3)?,
            outer_deg: v(1)?,
            inner_deg: v(1)?,
            position: memory::vec(n, what, need, hint)?,
            temps_c: v(node::COUNT)?,
            temp_chamber_c: v(1)?,
            dtheta_true_rad: t(3)?,
            dv_true_mps: t(3)?,
            q_bn: t(4)?,
            gimbal_outer_rad: t(1)?,
            gimbal_inner_rad: t(1)?,
            gyro_dph: l.gyro_terms.iter().map(|_| t(3)).collect::<PyResult<_>>()?,
            accel_ug: l
                .accel_terms
                .iter()
                .map(|_| t(3))
                .collect::<PyResult<_>>()?,
            carrier: if l.truth && l.moving_carrier {
                v(10)?
            } else {
                Vec::new()
            },
        })
    }

    /// One sample, computed as the CSV sink computes a row of one sample.
    fn push(&mut self, s: &ImuSample, tr: &Truth, l: &Layout) {
        self.n += 1;
        self.sample.push(s.index);
        self.t_s.push(s.t_s);
        push3(&mut self.dtheta_rad, &s.dtheta_rad);
        push3(&mut self.dv_mps, &s.dv_mps);
        self.outer_deg.push(s.encoder.outer_rad.to_degrees());
        self.inner_deg.push(s.encoder.inner_rad.to_degrees());
        let g = &tr.gimbal;
        let label =
            rins_plant::table::position_label(g.angles.outer_rad, g.angles.inner_rad, g.moving);
        let code = POSITION_LABELS
            .iter()
            .position(|p| *p == label)
            .unwrap_or(POSITION_LABELS.len() - 1);
        self.position.push(code as u8);
        self.temps_c.extend_from_slice(&s.temps_c);
        self.temp_chamber_c.push(tr.temps.chamber_c);
        if !l.truth {
            return;
        }
        push3(&mut self.dtheta_true_rad, &tr.dtheta_true_rad);
        push3(&mut self.dv_true_mps, &tr.dv_true_mps);
        // q_b^n = q_c^n·q_v^c·q_z(outer)·q_x(inner) in closed form, the plant's own
        // composition and the CSV's (docs/carrier.md, Frames).
        let q = l.mount.q_bn_of(tr);
        self.q_bn.extend_from_slice(&[q.w, q.i, q.j, q.k]);
        self.gimbal_outer_rad.push(g.angles.outer_rad);
        self.gimbal_inner_rad.push(g.angles.inner_rad);
        // The CSV's mean rate over a row of one sample: increment / (1·Δt), in °/h and µg.
        let span_s = l.dt_s;
        for (col, t) in self.gyro_dph.iter_mut().zip(&l.gyro_terms) {
            push3(col, &(tr.gyro_terms_rad[*t as usize] / (span_s * DPH)));
        }
        for (col, t) in self.accel_ug.iter_mut().zip(&l.accel_terms) {
            push3(col, &(tr.accel_terms_mps[*t as usize] / (span_s * UG)));
        }
        if l.moving_carrier {
            let c = &tr.carrier;
            let q = c.q_cn.quaternion();
            self.carrier.extend_from_slice(&[
                c.lat_rad.to_degrees(),
                c.lon_rad.to_degrees(),
                c.height_m,
                c.v_n.x,
                c.v_n.y,
                c.v_n.z,
                q.w,
                q.i,
                q.j,
                q.k,
            ]);
        }
    }

    /// The columns as a dict of numpy arrays (moved, not copied).
    fn into_dict<'py>(self, py: Python<'py>, l: &Layout) -> PyResult<Bound<'py, PyDict>> {
        let n = self.n;
        let d = PyDict::new(py);
        let mat = |v: Vec<f64>, k: usize| -> PyResult<Bound<'py, PyAny>> {
            let a = Array2::from_shape_vec((n, k), v)
                .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
            Ok(a.into_pyarray(py).into_any())
        };
        let vec = |v: Vec<f64>| PyArray1::from_vec(py, v).into_any();
        d.set_item("sample", PyArray1::from_vec(py, self.sample))?;
        d.set_item("t_s", vec(self.t_s))?;
        d.set_item("dtheta_rad", mat(self.dtheta_rad, 3)?)?;
        d.set_item("dv_mps", mat(self.dv_mps, 3)?)?;
        d.set_item("outer_deg", vec(self.outer_deg))?;
        d.set_item("inner_deg", vec(self.inner_deg))?;
        d.set_item("position", PyArray1::from_vec(py, self.position))?;
        d.set_item("temps_c", mat(self.temps_c, node::COUNT)?)?;
        d.set_item("temp_chamber_c", vec(self.temp_chamber_c))?;
        if !l.truth {
            return Ok(d);
        }
        d.set_item("dtheta_true_rad", mat(self.dtheta_true_rad, 3)?)?;
        d.set_item("dv_true_mps", mat(self.dv_true_mps, 3)?)?;
        d.set_item("q_bn", mat(self.q_bn, 4)?)?;
        d.set_item("gimbal_outer_rad", vec(self.gimbal_outer_rad))?;
        d.set_item("gimbal_inner_rad", vec(self.gimbal_inner_rad))?;
        let gyro = PyDict::new(py);
        for (col, t) in self.gyro_dph.into_iter().zip(&l.gyro_terms) {
            gyro.set_item(t.key(), mat(col, 3)?)?;
        }
        d.set_item("gyro_effects_dph", gyro)?;
        let accel = PyDict::new(py);
        for (col, t) in self.accel_ug.into_iter().zip(&l.accel_terms) {
            accel.set_item(t.key(), mat(col, 3)?)?;
        }
        d.set_item("accel_effects_ug", accel)?;
        if l.moving_carrier {
            d.set_item("carrier", mat(self.carrier, 10)?)?;
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
        let plant = rins_scenarios::runner::new_plant(&cfg, &sc.inner.source)
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
