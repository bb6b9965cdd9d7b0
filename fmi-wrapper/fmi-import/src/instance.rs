//! One instance of a loaded FMU: the FMI 2.0 calls, each returning what the FMU logged when it
//! refuses.

#![allow(unsafe_code)] // calling into a shared library; see each SAFETY note

use std::ffi::{c_char, c_int, c_void};
use std::sync::Mutex;

use libloading::Symbol;

use crate::{CallError, Callbacks, Component, Fmu2, Vr};

/// One instance of an [`Fmu2`].
pub struct Instance2<'a> {
    pub(crate) fmu: &'a Fmu2,
    pub(crate) c: Component,
    pub(crate) log: Box<Mutex<Vec<String>>>,
    pub(crate) _callbacks: Box<Callbacks>,
}

/// An FMU state handle (free it with [`Instance2::free_state`]).
#[derive(Debug)]
pub struct StateHandle(*mut c_void);

impl Instance2<'_> {
    fn check(&self, function: &'static str, status: c_int) -> Result<(), CallError> {
        let log = std::mem::take(&mut *self.log.lock().expect("log lock"));
        if status == 0 {
            Ok(())
        } else {
            Err(CallError {
                function,
                status,
                log,
            })
        }
    }

    /// Messages logged since the last call that returned them.
    pub fn take_log(&self) -> Vec<String> {
        std::mem::take(&mut *self.log.lock().expect("log lock"))
    }

    fn call<F: Copy>(&self, name: &'static str) -> Result<Symbol<'_, F>, CallError> {
        self.fmu.sym(name).map_err(|e| CallError {
            function: name,
            status: -1,
            log: vec![e],
        })
    }

    /// fmi2SetupExperiment.
    pub fn setup_experiment(&self, start_s: f64, stop_s: Option<f64>) -> Result<(), CallError> {
        let f = self
            .call::<unsafe extern "C" fn(Component, c_int, f64, f64, c_int, f64) -> c_int>(
                "fmi2SetupExperiment",
            )?;
        // SAFETY: FMI 2.0 signature, live instance.
        self.check("fmi2SetupExperiment", unsafe {
            f(
                self.c,
                0,
                0.0,
                start_s,
                stop_s.is_some() as c_int,
                stop_s.unwrap_or(0.0),
            )
        })
    }

    fn unit_call(&self, name: &'static str) -> Result<(), CallError> {
        let f = self.call::<unsafe extern "C" fn(Component) -> c_int>(name)?;
        // SAFETY: FMI 2.0 signature, live instance.
        self.check(name, unsafe { f(self.c) })
    }

    /// fmi2EnterInitializationMode.
    pub fn enter_initialization_mode(&self) -> Result<(), CallError> {
        self.unit_call("fmi2EnterInitializationMode")
    }

    /// fmi2ExitInitializationMode.
    pub fn exit_initialization_mode(&self) -> Result<(), CallError> {
        self.unit_call("fmi2ExitInitializationMode")
    }

    /// fmi2Terminate.
    pub fn terminate(&self) -> Result<(), CallError> {
        self.unit_call("fmi2Terminate")
    }

    /// fmi2Reset.
    pub fn reset(&self) -> Result<(), CallError> {
        self.unit_call("fmi2Reset")
    }

    /// fmi2DoStep.
    pub fn do_step(&self, t_s: f64, h_s: f64) -> Result<(), CallError> {
        // SAFETY: FMI 2.0 signature, live instance.
        let status = unsafe { (self.fmu.hot.do_step)(self.c, t_s, h_s, 1) };
        if status == 0 {
            Ok(())
        } else {
            self.check("fmi2DoStep", status)
        }
    }

    /// fmi2GetReal.
    pub fn get_real(&self, vrs: &[Vr], out: &mut [f64]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), out.len());
        // SAFETY: arrays of equal length.
        let status =
            unsafe { (self.fmu.hot.get_real)(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr()) };
        if status == 0 {
            Ok(())
        } else {
            self.check("fmi2GetReal", status)
        }
    }

    /// fmi2GetInteger.
    pub fn get_integer(&self, vrs: &[Vr], out: &mut [i32]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), out.len());
        let f = self
            .call::<unsafe extern "C" fn(Component, *const Vr, usize, *mut c_int) -> c_int>(
                "fmi2GetInteger",
            )?;
        // SAFETY: arrays of equal length.
        self.check("fmi2GetInteger", unsafe {
            f(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr())
        })
    }

    /// fmi2GetBoolean.
    pub fn get_boolean(&self, vrs: &[Vr], out: &mut [i32]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), out.len());
        let f = self
            .call::<unsafe extern "C" fn(Component, *const Vr, usize, *mut c_int) -> c_int>(
                "fmi2GetBoolean",
            )?;
        // SAFETY: arrays of equal length.
        self.check("fmi2GetBoolean", unsafe {
            f(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr())
        })
    }

    /// fmi2GetString into `out` (the pointers the FMU returns, NULL where it wrote none).
    pub fn get_string(&self, vrs: &[Vr], out: &mut [*const c_char]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), out.len());
        let f = self.call::<unsafe extern "C" fn(
            Component,
            *const Vr,
            usize,
            *mut *const c_char,
        ) -> c_int>("fmi2GetString")?;
        // SAFETY: arrays of equal length.
        self.check("fmi2GetString", unsafe {
            f(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr())
        })
    }

    /// fmi2GetRealStatus(fmi2LastSuccessfulTime): the FMU's current time.
    pub fn last_successful_time(&self) -> Result<f64, CallError> {
        let f = self.call::<unsafe extern "C" fn(Component, c_int, *mut f64) -> c_int>(
            "fmi2GetRealStatus",
        )?;
        let mut t = f64::NAN;
        // SAFETY: valid out-pointer; 2 is fmi2LastSuccessfulTime.
        self.check("fmi2GetRealStatus", unsafe { f(self.c, 2, &mut t) })?;
        Ok(t)
    }

    /// fmi2SetReal.
    pub fn set_real(&self, vrs: &[Vr], values: &[f64]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), values.len());
        // SAFETY: arrays of equal length.
        let status =
            unsafe { (self.fmu.hot.set_real)(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr()) };
        if status == 0 {
            Ok(())
        } else {
            self.check("fmi2SetReal", status)
        }
    }

    /// fmi2SetInteger.
    pub fn set_integer(&self, vrs: &[Vr], values: &[i32]) -> Result<(), CallError> {
        assert_eq!(vrs.len(), values.len());
        let f = self
            .call::<unsafe extern "C" fn(Component, *const Vr, usize, *const c_int) -> c_int>(
                "fmi2SetInteger",
            )?;
        // SAFETY: arrays of equal length.
        self.check("fmi2SetInteger", unsafe {
            f(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr())
        })
    }

    /// fmi2SetBoolean.
    pub fn set_boolean(&self, vrs: &[Vr], values: &[bool]) -> Result<(), CallError> {
        let v: Vec<c_int> = values.iter().map(|b| *b as c_int).collect();
        let f = self
            .call::<unsafe extern "C" fn(Component, *const Vr, usize, *const c_int) -> c_int>(
                "fmi2SetBoolean",
            )?;
        // SAFETY: arrays of equal length.
        self.check("fmi2SetBoolean", unsafe {
            f(self.c, vrs.as_ptr(), vrs.len().min(v.len()), v.as_ptr())
        })
    }

    /// fmi2GetFMUstate (a new handle).
    pub fn get_state(&self) -> Result<StateHandle, CallError> {
        let f = self.call::<unsafe extern "C" fn(Component, *mut *mut c_void) -> c_int>(
            "fmi2GetFMUstate",
        )?;
        let mut s: *mut c_void = std::ptr::null_mut();
        // SAFETY: valid out-pointer.
        self.check("fmi2GetFMUstate", unsafe { f(self.c, &mut s) })?;
        Ok(StateHandle(s))
    }

    /// fmi2SetFMUstate.
    pub fn set_state(&self, s: &StateHandle) -> Result<(), CallError> {
        let f =
            self.call::<unsafe extern "C" fn(Component, *mut c_void) -> c_int>("fmi2SetFMUstate")?;
        // SAFETY: handle from this FMU.
        self.check("fmi2SetFMUstate", unsafe { f(self.c, s.0) })
    }

    /// fmi2FreeFMUstate.
    pub fn free_state(&self, mut s: StateHandle) -> Result<(), CallError> {
        let f = self.call::<unsafe extern "C" fn(Component, *mut *mut c_void) -> c_int>(
            "fmi2FreeFMUstate",
        )?;
        // SAFETY: handle from this FMU.
        self.check("fmi2FreeFMUstate", unsafe { f(self.c, &mut s.0) })
    }

    /// fmi2SerializedFMUstateSize + fmi2SerializeFMUstate.
    pub fn serialize_state(&self, s: &StateHandle) -> Result<Vec<u8>, CallError> {
        let size_f = self
            .call::<unsafe extern "C" fn(Component, *mut c_void, *mut usize) -> c_int>(
                "fmi2SerializedFMUstateSize",
            )?;
        let mut n = 0usize;
        // SAFETY: handle from this FMU, valid out-pointer.
        self.check("fmi2SerializedFMUstateSize", unsafe {
            size_f(self.c, s.0, &mut n)
        })?;
        let mut buf = vec![0u8; n];
        let f = self
            .call::<unsafe extern "C" fn(Component, *mut c_void, *mut c_char, usize) -> c_int>(
                "fmi2SerializeFMUstate",
            )?;
        // SAFETY: buffer of the size the FMU asked for.
        self.check("fmi2SerializeFMUstate", unsafe {
            f(self.c, s.0, buf.as_mut_ptr() as *mut c_char, n)
        })?;
        Ok(buf)
    }

    /// fmi2DeSerializeFMUstate.
    pub fn deserialize_state(&self, bytes: &[u8]) -> Result<StateHandle, CallError> {
        let f = self.call::<unsafe extern "C" fn(
            Component,
            *const c_char,
            usize,
            *mut *mut c_void,
        ) -> c_int>("fmi2DeSerializeFMUstate")?;
        let mut s: *mut c_void = std::ptr::null_mut();
        // SAFETY: byte buffer and out-pointer.
        self.check("fmi2DeSerializeFMUstate", unsafe {
            f(self.c, bytes.as_ptr() as *const c_char, bytes.len(), &mut s)
        })?;
        Ok(StateHandle(s))
    }
}

impl Drop for Instance2<'_> {
    fn drop(&mut self) {
        if let Ok(f) = self
            .fmu
            .sym::<unsafe extern "C" fn(Component)>("fmi2FreeInstance")
        {
            // SAFETY: the instance is freed exactly once, here.
            unsafe { f(self.c) };
        }
    }
}
