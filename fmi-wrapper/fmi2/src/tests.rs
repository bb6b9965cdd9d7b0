//! The generic functions driven for a model that is not the rins plant: a counter whose output
//! grows by a parameter each internal step. What a second model needs is the `Model` impl only.

use std::ffi::{CString, c_void};

use rins_fmi::model::{Model, ModelInfo};
use rins_fmi::state::{StateReader, StateWriter};
use rins_fmi::vars::{Causality, Kind, OutputDecl, ScalarVar, Value, VariableTable};

use crate::{lifecycle, state, values};

#[derive(Clone, Debug)]
struct Counter {
    gain: f64,
    steps: u64,
}

fn table() -> &'static VariableTable {
    static T: std::sync::OnceLock<VariableTable> = std::sync::OnceLock::new();
    T.get_or_init(|| {
        let gain = ScalarVar {
            name: "gain".into(),
            array: "gain".into(),
            kind: Kind::Real,
            causality: Causality::Parameter,
            unit: None,
            start: Value::Real(1.0),
            range: Some((0.0, 10.0)),
            description: "added per step".into(),
        };
        let out = OutputDecl {
            name: "total".into(),
            len: None,
            kind: Kind::Real,
            unit: None,
            start: vec![Value::Real(0.0)],
            description: "sum".into(),
        };
        VariableTable::new(std::iter::once(gain).chain(out.scalars()).collect())
    })
}

impl Model for Counter {
    const INFO: ModelInfo = ModelInfo {
        fmi2_id: "Counter",
        fmi3_id: "Counter3",
        description: "a counter",
        stop_time_s: 1.0,
        step_size_s: 0.1,
    };
    fn table() -> &'static VariableTable {
        table()
    }
    fn new() -> Self {
        Self {
            gain: 1.0,
            steps: 0,
        }
    }
    fn set(&mut self, _slot: usize, v: Value) -> Result<(), String> {
        if let Value::Real(x) = v {
            self.gain = x;
        }
        Ok(())
    }
    fn get(&self, slot: usize) -> Value {
        Value::Real(if slot == 0 {
            self.gain
        } else {
            self.gain * self.steps as f64
        })
    }
    fn initialize(&mut self) -> Result<(), String> {
        Ok(())
    }
    fn internal_rate_hz(&self) -> f64 {
        10.0
    }
    fn advance(&mut self, n: u64) -> Result<(), String> {
        self.steps += n;
        Ok(())
    }
    fn save(&self, w: &mut StateWriter) {
        w.f64(self.gain);
        w.u64(self.steps);
    }
    fn restore(&mut self, r: &mut StateReader<'_>) -> Result<(), String> {
        (self.gain, self.steps) = (r.f64()?, r.u64()?);
        Ok(())
    }
}

#[test]
fn a_second_model_runs_through_the_generic_fmi2_functions() {
    let token = CString::new(
        rins_fmi::fmu::description::<Counter>(rins_fmi::standard::FmiVersion::V2)
            .1
            .clone(),
    )
    .unwrap();
    let name = c"c".as_ptr();
    // SAFETY: arguments as the FMI 2.0 standard gives them; NULL callbacks are allowed.
    unsafe {
        let bad = lifecycle::instantiate::<Counter>(
            name,
            1,
            c"{x}".as_ptr(),
            std::ptr::null(),
            std::ptr::null(),
            0,
            0,
        );
        assert!(bad.is_null(), "a foreign GUID is refused");
        let c = lifecycle::instantiate::<Counter>(
            name,
            1,
            token.as_ptr(),
            std::ptr::null(),
            std::ptr::null(),
            0,
            0,
        );
        assert!(!c.is_null());
        assert_eq!(
            values::set_real::<Counter>(c, [0].as_ptr(), 1, [2.5].as_ptr()),
            0
        );
        assert_eq!(
            values::set_real::<Counter>(c, [0].as_ptr(), 1, [11.0].as_ptr()),
            3,
            "out of range"
        );
        assert_eq!(
            lifecycle::setup_experiment::<Counter>(c, 0, 0.0, 0.0, 0, 0.0),
            0
        );
        assert_eq!(lifecycle::enter_initialization_mode::<Counter>(c), 0);
        // The refused set blocks the end of initialisation (a master that carried on would
        // run with the start value), and the error state blocks steps, until reset.
        assert_eq!(lifecycle::exit_initialization_mode::<Counter>(c), 3);
        assert_eq!(lifecycle::do_step::<Counter>(c, 0.0, 0.3, 1), 3);
        assert_eq!(lifecycle::reset::<Counter>(c), 0);
        assert_eq!(
            values::set_real::<Counter>(c, [0].as_ptr(), 1, [2.5].as_ptr()),
            0
        );
        assert_eq!(
            lifecycle::setup_experiment::<Counter>(c, 0, 0.0, 0.0, 0, 0.0),
            0
        );
        assert_eq!(lifecycle::enter_initialization_mode::<Counter>(c), 0);
        assert_eq!(lifecycle::exit_initialization_mode::<Counter>(c), 0);
        assert_eq!(lifecycle::do_step::<Counter>(c, 0.0, 0.3, 1), 0);
        let mut s: *mut c_void = std::ptr::null_mut();
        assert_eq!(state::get_fmu_state::<Counter>(c, &mut s), 0);
        assert_eq!(lifecycle::do_step::<Counter>(c, 0.3, 0.2, 1), 0);
        let mut total = [0.0];
        assert_eq!(
            values::get_real::<Counter>(c, [1].as_ptr(), 1, total.as_mut_ptr()),
            0
        );
        assert_eq!(total[0], 2.5 * 5.0);
        assert_eq!(state::set_fmu_state::<Counter>(c, s), 0);
        assert_eq!(
            values::get_real::<Counter>(c, [1].as_ptr(), 1, total.as_mut_ptr()),
            0
        );
        assert_eq!(total[0], 2.5 * 3.0);
        assert_eq!(
            lifecycle::do_step::<Counter>(c, 0.0, 0.1, 1),
            3,
            "not at the FMU's time"
        );
        assert_eq!(state::free_fmu_state::<Counter>(c, &mut s), 0);
        assert!(s.is_null());
        lifecycle::free_instance::<Counter>(c);
    }
}

#[test]
fn a_freed_instance_or_a_foreign_pointer_is_refused_without_touching_memory() {
    let token = CString::new(
        rins_fmi::fmu::description::<Counter>(rins_fmi::standard::FmiVersion::V2)
            .1
            .clone(),
    )
    .unwrap();
    // SAFETY: arguments as the FMI 2.0 standard gives them; the misuse under test is handing
    // back pointers that are not live instances, which the functions must not dereference.
    unsafe {
        let c = lifecycle::instantiate::<Counter>(
            c"c".as_ptr(),
            1,
            token.as_ptr(),
            std::ptr::null(),
            std::ptr::null(),
            0,
            0,
        );
        assert!(!c.is_null());
        lifecycle::free_instance::<Counter>(c);
        // A second free is a no-op, and every call on the freed handle returns fmi2Error.
        lifecycle::free_instance::<Counter>(c);
        assert_eq!(lifecycle::do_step::<Counter>(c, 0.0, 0.1, 1), 3);
        assert_eq!(lifecycle::reset::<Counter>(c), 3);
        // A pointer that never was an instance (here a local variable) is not read either.
        let mut not_an_instance = [0u64; 4];
        let p = not_an_instance.as_mut_ptr() as *mut c_void;
        assert_eq!(lifecycle::terminate::<Counter>(p), 3);
        lifecycle::free_instance::<Counter>(p);
        assert_eq!(not_an_instance, [0; 4]);
    }
}
