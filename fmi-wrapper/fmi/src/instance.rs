//! The FMI instance state machine, generic over the [`Model`]: instantiated → initialization
//! mode → step mode → terminated. Calls in the wrong state, unknown value references and bad
//! values are rejected with an [`FmiError`] that the C glue logs; nothing here touches C.

use crate::model::Model;
use crate::state::{StateReader, StateWriter};
use crate::vars::{Causality, Value, VariableTable};

/// FMI status codes (the same numbers in FMI 2 and 3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
#[repr(i32)]
pub enum Status {
    /// Success.
    Ok = 0,
    /// Success with a remark.
    Warning = 1,
    /// The call was ignored; the instance is unchanged.
    Discard = 2,
    /// The call failed; the instance may be reset.
    Error = 3,
    /// The instance is unusable.
    Fatal = 4,
}

/// A refused call: status, log category and the reason.
#[derive(Clone, Debug, PartialEq)]
pub struct FmiError {
    /// Status to return.
    pub status: Status,
    /// Log category (`logStatusError`, …).
    pub category: &'static str,
    /// Why.
    pub message: String,
}

impl FmiError {
    /// An error-status refusal.
    pub fn error(message: impl Into<String>) -> Self {
        Self {
            status: Status::Error,
            category: "logStatusError",
            message: message.into(),
        }
    }
}

/// Where the instance is in its life.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// After instantiate: parameters may be set.
    Instantiated,
    /// Between enter/exit initialization mode.
    Initialization,
    /// Stepping.
    Step,
    /// After terminate.
    Terminated,
    /// After a failed call; only reset, free, get and state restore are allowed.
    Error,
}

impl Mode {
    /// How messages name the mode.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Instantiated => "Instantiated mode",
            Mode::Initialization => "Initialization mode",
            Mode::Step => "Step mode",
            Mode::Terminated => "Terminated mode",
            Mode::Error => "the error state",
        }
    }
}

/// What the standards allow in [`Mode::Error`], said in every call refused there.
pub const ALLOWED_IN_ERROR: &str = "only reset, free, reading values and getting, setting or \
serializing the FMU state are allowed until reset or a state restore";

/// One FMU instance.
#[derive(Clone, Debug)]
pub struct Instance<M: Model> {
    model: M,
    mode: Mode,
    start_time_s: f64,
    /// Internal steps per second, fixed at the end of initialisation.
    rate_hz: f64,
    /// Internal steps done since initialisation: the FMU's time is `start + steps / rate`.
    steps_done: u64,
    /// The first call setting a value before the end of initialisation that was refused, and
    /// why. FMI 2 masters may carry on after the error status (ecos does): leaving
    /// initialization mode is then refused with this reason ([`Instance::note_refused_set`]),
    /// so the model never runs with a start value in place of the one the master asked for.
    refused_set: Option<String>,
}

/// Tolerance, relative to the step, for "whole number of internal steps" and "at the current time".
const STEP_TOL: f64 = 1e-9;

impl<M: Model> Default for Instance<M> {
    fn default() -> Self {
        Self::new()
    }
}

impl<M: Model> Instance<M> {
    /// A fresh instance in [`Mode::Instantiated`].
    pub fn new() -> Self {
        Self {
            model: M::new(),
            mode: Mode::Instantiated,
            start_time_s: 0.0,
            rate_hz: 1.0,
            steps_done: 0,
            refused_set: None,
        }
    }

    /// The variable table.
    pub fn table(&self) -> &'static VariableTable {
        M::table()
    }

    /// Current mode.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The wrapped model.
    pub fn model(&self) -> &M {
        &self.model
    }

    /// Current communication time, s.
    pub fn time_s(&self) -> f64 {
        self.start_time_s + self.steps_done as f64 / self.rate_hz
    }

    fn expect(&self, allowed: &[Mode], what: &str) -> Result<(), FmiError> {
        if allowed.contains(&self.mode) {
            Ok(())
        } else if self.mode == Mode::Error {
            Err(FmiError::error(format!(
                "{what} is refused: the instance is in the error state after an earlier call failed (its reason was logged then); {ALLOWED_IN_ERROR}"
            )))
        } else {
            let names: Vec<&str> = allowed.iter().map(|m| m.name()).collect();
            Err(FmiError::error(format!(
                "{what} is not allowed in {} (allowed in {})",
                self.mode.name(),
                names.join(", ")
            )))
        }
    }

    /// Records that a call setting a value was refused before the end of initialisation
    /// (`what`: the function and its reason); the first such refusal is kept and makes
    /// [`Instance::exit_initialization`] fail. Later modes keep nothing: a refused input in
    /// step mode leaves the previous input, as the status says.
    pub fn note_refused_set(&mut self, what: String) {
        if matches!(self.mode, Mode::Instantiated | Mode::Initialization)
            && self.refused_set.is_none()
        {
            self.refused_set = Some(what);
        }
    }

    /// The refused set [`Instance::note_refused_set`] kept, if any.
    pub fn refused_set(&self) -> Option<&str> {
        self.refused_set.as_deref()
    }

    /// Records the start time (FMI 2 setupExperiment / FMI 3 enterInitializationMode). Only
    /// right after instantiation: both standards fix the start time before initialisation.
    pub fn setup(&mut self, start_time_s: f64) -> Result<(), FmiError> {
        self.expect(&[Mode::Instantiated], "setting the start time")?;
        if !start_time_s.is_finite() {
            return Err(FmiError::error(format!(
                "start time must be finite, got {start_time_s}"
            )));
        }
        self.start_time_s = start_time_s;
        Ok(())
    }

    /// Records the start time and enters initialization mode (FMI 3 enterInitializationMode,
    /// whose refusals name that call, not the start time).
    pub fn enter_initialization_at(&mut self, start_time_s: f64) -> Result<(), FmiError> {
        self.expect(&[Mode::Instantiated], "entering initialization mode")?;
        self.setup(start_time_s)?;
        self.enter_initialization()
    }

    /// Enters initialization mode.
    pub fn enter_initialization(&mut self) -> Result<(), FmiError> {
        self.expect(&[Mode::Instantiated], "entering initialization mode")?;
        self.mode = Mode::Initialization;
        Ok(())
    }

    /// Leaves initialization mode: the model is built from its parameters.
    pub fn exit_initialization(&mut self) -> Result<(), FmiError> {
        self.expect(&[Mode::Initialization], "exiting initialization mode")?;
        if let Some(why) = &self.refused_set {
            let e = FmiError::error(format!(
                "cannot leave initialization mode: an earlier call setting a value was refused ({why}), so the model would run with a value the master did not ask for; reset the instance and set valid values"
            ));
            self.mode = Mode::Error;
            return Err(e);
        }
        match self.model.initialize() {
            Ok(()) => {
                self.mode = Mode::Step;
                self.rate_hz = self.model.internal_rate_hz();
                self.steps_done = 0;
                Ok(())
            }
            Err(e) => {
                self.mode = Mode::Error;
                Err(FmiError::error(format!("initialization failed: {e}")))
            }
        }
    }

    /// Terminates.
    pub fn terminate(&mut self) -> Result<(), FmiError> {
        self.expect(&[Mode::Step, Mode::Initialization], "terminate")?;
        self.mode = Mode::Terminated;
        Ok(())
    }

    /// Puts the instance in [`Mode::Error`] after a failed call: the standards allow only
    /// reset, free, state restore and reads from there, so a master that ignores the error
    /// status cannot step on with an instance whose last call was not carried out.
    pub fn fail(&mut self) {
        self.mode = Mode::Error;
    }

    /// Back to a fresh instance with start values.
    pub fn reset(&mut self) {
        *self = Self::new();
    }

    fn slot_of(&self, vr: u32) -> Result<usize, FmiError> {
        let n = M::table().scalars.len();
        let slot = vr as usize;
        if slot < n {
            Ok(slot)
        } else {
            Err(FmiError::error(format!(
                "unknown value reference {vr} (valid: 0…{})",
                n - 1
            )))
        }
    }

    /// Whether the scalar at value reference `vr` may be set to `v` now ([`Self::check_set`]).
    pub fn check_vr(&self, vr: u32, v: Value) -> Result<(), FmiError> {
        let slot = self.slot_of(vr)?;
        self.check_set(slot, v)
    }

    /// Sets the scalar at value reference `vr` (its slot).
    pub fn set(&mut self, vr: u32, v: Value) -> Result<(), FmiError> {
        let slot = self.slot_of(vr)?;
        self.set_slot(slot, v)
    }

    /// Sets slot `slot`, checking causality against the mode, then type and range. An
    /// enumeration's Integer code sets the enumeration.
    pub fn set_slot(&mut self, slot: usize, v: Value) -> Result<(), FmiError> {
        if let Some(target) = M::table().code_target(slot) {
            M::table().check(slot, v).map_err(FmiError::error)?;
            // The check passed: an Integer in 1…n.
            let code = if let Value::Integer(c) = v { c } else { 1 };
            return self.set_slot(target, Value::Enumeration(code as usize - 1));
        }
        self.check_set(slot, v)?;
        self.model.set(slot, v).map_err(FmiError::error)
    }

    /// Whether slot `slot` may be set to `v` now (causality against the mode, type, range),
    /// without setting it: callers setting several values check them all first.
    pub fn check_set(&self, slot: usize, v: Value) -> Result<(), FmiError> {
        if let Some(target) = M::table().code_target(slot) {
            M::table().check(slot, v).map_err(FmiError::error)?;
            return self.check_set(target, M::table().scalars[target].start);
        }
        let s = &M::table().scalars[slot];
        match s.causality {
            Causality::Output => {
                return Err(FmiError::error(format!(
                    "{} is an output and cannot be set",
                    s.name
                )));
            }
            Causality::Parameter => self.expect(
                &[Mode::Instantiated, Mode::Initialization],
                &format!("setting parameter {}", s.name),
            )?,
            Causality::Input => self.expect(
                &[Mode::Instantiated, Mode::Initialization, Mode::Step],
                &format!("setting input {}", s.name),
            )?,
        }
        M::table().check(slot, v).map_err(FmiError::error)
    }

    /// Value at value reference `vr`.
    pub fn get(&self, vr: u32) -> Result<Value, FmiError> {
        let slot = self.slot_of(vr)?;
        Ok(self.get_slot(slot))
    }

    /// Value of slot `slot`.
    pub fn get_slot(&self, slot: usize) -> Value {
        if let Some(target) = M::table().code_target(slot) {
            return match self.model.get(target) {
                Value::Enumeration(i) => Value::Integer(i as u64 + 1),
                v => v,
            };
        }
        self.model.get(slot)
    }

    /// Advances from `t_s` by `h_s`, which must be a whole number of internal steps.
    ///
    /// This runs once per communication step, so the accepted path is kept to a few compares;
    /// the refusals are built out of line.
    ///
    /// A refused step (after initialisation) tells the model ([`Model::step_refused`]), so
    /// that outputs summed over a communication step read NaN instead of the last step's
    /// values a master ignoring the status would take again.
    pub fn do_step(&mut self, t_s: f64, h_s: f64) -> Result<(), FmiError> {
        let r = self.try_step(t_s, h_s);
        if r.is_err() && matches!(self.mode, Mode::Step | Mode::Error | Mode::Terminated) {
            self.model.step_refused();
        }
        r
    }

    fn try_step(&mut self, t_s: f64, h_s: f64) -> Result<(), FmiError> {
        if self.mode != Mode::Step {
            return Err(self.do_step_refused_mode());
        }
        let rate = self.rate_hz;
        let now = self.start_time_s + self.steps_done as f64 / rate;
        // Within a millionth of an internal step, or 1e-9 relative: masters that accumulate
        // `t += h` drift by rounding over a week of steps; a skipped step is still refused.
        if !((t_s - now).abs() <= (1e-6 / rate).max(now.abs() * 1e-9)) {
            return Err(Self::do_step_refused_time(t_s, now));
        }
        let n = h_s * rate;
        // Truncation after +0.5 is round-half-up for positive n without a libm call.
        let whole = if (0.5..1e15).contains(&n) {
            (n + 0.5) as u64
        } else {
            0
        };
        if whole == 0 || !((n - whole as f64).abs() <= STEP_TOL * whole as f64) {
            return Err(Self::do_step_refused_size(h_s, n, rate));
        }
        if let Err(e) = self.model.advance(whole) {
            self.mode = Mode::Error;
            return Err(FmiError::error(e));
        }
        self.steps_done += whole;
        Ok(())
    }

    #[cold]
    fn do_step_refused_mode(&self) -> FmiError {
        self.expect(&[Mode::Step], "doStep")
            .expect_err("not in step mode")
    }

    #[cold]
    fn do_step_refused_time(t_s: f64, now: f64) -> FmiError {
        FmiError::error(format!(
            "doStep from t = {t_s} s, but the FMU is at t = {now} s"
        ))
    }

    #[cold]
    fn do_step_refused_size(h_s: f64, n: f64, rate: f64) -> FmiError {
        FmiError::error(format!(
            "communication step {h_s} s is not a whole positive number of internal steps of {} s (ratio {n})",
            1.0 / rate
        ))
    }

    /// A copy of the whole instance (FMU state by value).
    pub fn snapshot(&self) -> Self {
        self.clone()
    }

    /// Restores a snapshot.
    pub fn restore_snapshot(&mut self, s: &Self) {
        *self = s.clone();
    }

    /// The state as bytes: magic, model identifier, mode, start time, rate, steps done, then
    /// the model's own fields.
    pub fn serialize(&self) -> Vec<u8> {
        let mut w = StateWriter(MAGIC.to_vec());
        w.bytes(M::INFO.fmi2_id.as_bytes());
        w.u64(self.mode as u64);
        w.f64(self.start_time_s);
        w.f64(self.rate_hz);
        w.u64(self.steps_done);
        self.model.save(&mut w);
        w.0
    }

    /// An instance from [`Instance::serialize`] bytes.
    pub fn deserialize(bytes: &[u8]) -> Result<Self, FmiError> {
        let bad = |e: String| FmiError::error(format!("cannot restore the serialized state: {e}"));
        if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
            return Err(FmiError::error(
                "not a serialized state of this FMU (bad header)",
            ));
        }
        let mut r = StateReader::new(&bytes[MAGIC.len()..]);
        let model_id = r.bytes().map_err(bad)?;
        if model_id != M::INFO.fmi2_id.as_bytes() {
            return Err(bad(format!(
                "the state is of model {:?}, this FMU is {:?}",
                String::from_utf8_lossy(model_id),
                M::INFO.fmi2_id
            )));
        }
        let mode = match r.u64().map_err(bad)? {
            0 => Mode::Instantiated,
            1 => Mode::Initialization,
            2 => Mode::Step,
            3 => Mode::Terminated,
            _ => Mode::Error,
        };
        let start_time_s = r.f64().map_err(bad)?;
        let rate_hz = r.f64().map_err(bad)?;
        let steps_done = r.u64().map_err(bad)?;
        let mut model = M::new();
        model.restore(&mut r).map_err(bad)?;
        r.finish().map_err(bad)?;
        Ok(Self {
            model,
            mode,
            start_time_s,
            rate_hz,
            steps_done,
            refused_set: None,
        })
    }
}

/// First bytes of a serialized FMU state (layout version 2: model identifier, codec fields).
const MAGIC: &[u8; 8] = b"RINSFMU2";
