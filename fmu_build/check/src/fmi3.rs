//! The FMI 3.0 Co-Simulation calls a host makes, on the same unzipped FMU and loaded binary as FMI 2.0
//! (`fmi::Unpacked`): instantiate with early return allowed, initialize, set and get, step, save and
//! restore a state. fmi3Boolean is C's one-byte `bool`.

use crate::fmi::{check, Status, Unpacked, LAST_MESSAGE};
use std::ffi::{c_char, c_void, CStr, CString};

type Component = *mut c_void;

/// FMI 3.0's logger: not variadic, no instance name.
unsafe extern "C" fn logger(_: *mut c_void, status: Status, category: *const c_char, message: *const c_char) {
    // SAFETY: the FMU passes NUL-terminated strings (FMI 3.0 Sec. 2.3.1).
    let (category, message) = unsafe { (CStr::from_ptr(category).to_string_lossy(), CStr::from_ptr(message).to_string_lossy()) };
    let text = format!("[{category}, status {status}] {message}");
    if status > 0 {
        eprintln!("fmu: {text}");
    }
    *LAST_MESSAGE.lock().unwrap_or_else(|e| e.into_inner()) = text;
}

type Logger = unsafe extern "C" fn(*mut c_void, Status, *const c_char, *const c_char);
type Instantiate = unsafe extern "C" fn(
    *const c_char,
    *const c_char,
    *const c_char,
    bool,
    bool,
    bool,
    bool,
    *const u32,
    usize,
    *mut c_void,
    Option<Logger>,
    *const c_void,
) -> Component;

pub struct Instance3<'a> {
    fmu: &'a Unpacked,
    c: Component,
}

impl<'a> Instance3<'a> {
    /// A Co-Simulation instance; `early_return`: earlyReturnAllowed (Event Mode is not used).
    pub fn new(fmu: &'a Unpacked, early_return: bool) -> Result<Instance3<'a>, String> {
        let name = CString::new("fmu_check").expect("no NUL");
        let token = CString::new(fmu.model_description.guid.clone()).map_err(|e| e.to_string())?;
        // FMI 3.0 passes the resources folder as a path with a trailing separator.
        let mut path = fmu.dir.join("resources").to_string_lossy().into_owned();
        path.push(std::path::MAIN_SEPARATOR);
        let resources = CString::new(path).map_err(|e| e.to_string())?;
        let instantiate: Instantiate = fmu.symbol("fmi3InstantiateCoSimulation")?;
        // SAFETY: valid NUL-terminated strings, no intermediate variables, a logger that outlives the instance.
        let c = unsafe {
            instantiate(
                name.as_ptr(),
                token.as_ptr(),
                resources.as_ptr(),
                false,
                false,
                false,
                early_return,
                std::ptr::null(),
                0,
                std::ptr::null_mut(),
                Some(logger),
                std::ptr::null(),
            )
        };
        if c.is_null() {
            return Err(format!("fmi3InstantiateCoSimulation failed: {}", LAST_MESSAGE.lock().unwrap_or_else(|e| e.into_inner())));
        }
        Ok(Instance3 { fmu, c })
    }

    pub fn call(&self, function: &str) -> Result<(), String> {
        let f: unsafe extern "C" fn(Component) -> Status = self.fmu.symbol(function)?;
        // SAFETY: a live instance.
        check(function, unsafe { f(self.c) })
    }

    pub fn enter_initialization(&self, start: f64) -> Result<(), String> {
        let f: unsafe extern "C" fn(Component, bool, f64, f64, bool, f64) -> Status = self.fmu.symbol("fmi3EnterInitializationMode")?;
        // SAFETY: a live instance.
        check("fmi3EnterInitializationMode", unsafe { f(self.c, false, 0.0, start, false, 0.0) })
    }

    pub fn set_real(&self, name: &str, value: f64) -> Result<(), String> {
        let vr = self.fmu.model_description.vr(name)?;
        let f: unsafe extern "C" fn(Component, *const u32, usize, *const f64, usize) -> Status = self.fmu.symbol("fmi3SetFloat64")?;
        // SAFETY: one value reference, one value.
        check(&format!("fmi3SetFloat64({name})"), unsafe { f(self.c, &vr, 1, &value, 1) })
    }

    pub fn set_string(&self, name: &str, value: &str) -> Result<(), String> {
        let vr = self.fmu.model_description.vr(name)?;
        let text = CString::new(value).map_err(|e| e.to_string())?;
        let f: unsafe extern "C" fn(Component, *const u32, usize, *const *const c_char, usize) -> Status = self.fmu.symbol("fmi3SetString")?;
        // SAFETY: one value reference, one string.
        check(&format!("fmi3SetString({name})"), unsafe { f(self.c, &vr, 1, &text.as_ptr(), 1) })
    }

    pub fn real(&self, name: &str) -> Result<f64, String> {
        let vr = self.fmu.model_description.vr(name)?;
        let mut v = f64::NAN;
        let f: unsafe extern "C" fn(Component, *const u32, usize, *mut f64, usize) -> Status = self.fmu.symbol("fmi3GetFloat64")?;
        // SAFETY: one value reference, room for one value.
        check(&format!("fmi3GetFloat64({name})"), unsafe { f(self.c, &vr, 1, &mut v, 1) })?;
        Ok(v)
    }

    pub fn integer(&self, name: &str) -> Result<i32, String> {
        let vr = self.fmu.model_description.vr(name)?;
        let mut v = 0i32;
        let f: unsafe extern "C" fn(Component, *const u32, usize, *mut i32, usize) -> Status = self.fmu.symbol("fmi3GetInt32")?;
        // SAFETY: one value reference, room for one value.
        check(&format!("fmi3GetInt32({name})"), unsafe { f(self.c, &vr, 1, &mut v, 1) })?;
        Ok(v)
    }

    /// fmi3DoStep: (earlyReturn, lastSuccessfulTime).
    pub fn do_step(&self, t: f64, h: f64) -> Result<(bool, f64), String> {
        type DoStep = unsafe extern "C" fn(Component, f64, f64, bool, *mut bool, *mut bool, *mut bool, *mut f64) -> Status;
        let f: DoStep = self.fmu.symbol("fmi3DoStep")?;
        let (mut event, mut terminate, mut early, mut last) = (false, false, false, f64::NAN);
        // SAFETY: four out-parameters.
        check("fmi3DoStep", unsafe { f(self.c, t, h, true, &mut event, &mut terminate, &mut early, &mut last) })?;
        Ok((early, last))
    }

    /// The state serialized to bytes (fmi3GetFMUState, fmi3SerializeFMUState).
    pub fn serialize_state(&self) -> Result<Vec<u8>, String> {
        let get: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.fmu.symbol("fmi3GetFMUState")?;
        let size: unsafe extern "C" fn(Component, *mut c_void, *mut usize) -> Status = self.fmu.symbol("fmi3SerializedFMUStateSize")?;
        let ser: unsafe extern "C" fn(Component, *mut c_void, *mut u8, usize) -> Status = self.fmu.symbol("fmi3SerializeFMUState")?;
        let free: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.fmu.symbol("fmi3FreeFMUState")?;
        let mut state = std::ptr::null_mut();
        let mut n = 0usize;
        // SAFETY: the standard's calling sequence with buffers of the size the FMU gives.
        unsafe {
            check("fmi3GetFMUState", get(self.c, &mut state))?;
            check("fmi3SerializedFMUStateSize", size(self.c, state, &mut n))?;
            let mut bytes = vec![0u8; n];
            check("fmi3SerializeFMUState", ser(self.c, state, bytes.as_mut_ptr(), n))?;
            check("fmi3FreeFMUState", free(self.c, &mut state))?;
            Ok(bytes)
        }
    }

    /// Sets the state from bytes (fmi3DeserializeFMUState, fmi3SetFMUState).
    pub fn restore_state(&self, bytes: &[u8]) -> Result<(), String> {
        let de: unsafe extern "C" fn(Component, *const u8, usize, *mut *mut c_void) -> Status = self.fmu.symbol("fmi3DeserializeFMUState")?;
        let set: unsafe extern "C" fn(Component, *mut c_void) -> Status = self.fmu.symbol("fmi3SetFMUState")?;
        let free: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.fmu.symbol("fmi3FreeFMUState")?;
        let mut state = std::ptr::null_mut();
        // SAFETY: bytes of the given length; the state is freed after use.
        unsafe {
            check("fmi3DeserializeFMUState", de(self.c, bytes.as_ptr(), bytes.len(), &mut state))?;
            check("fmi3SetFMUState", set(self.c, state))?;
            check("fmi3FreeFMUState", free(self.c, &mut state))
        }
    }
}

impl Drop for Instance3<'_> {
    fn drop(&mut self) {
        if let Ok(f) = self.fmu.symbol::<unsafe extern "C" fn(Component)>("fmi3FreeInstance") {
            // SAFETY: the instance is freed once, here.
            unsafe { f(self.c) }
        }
    }
}
