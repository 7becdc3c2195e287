//! What both C ABIs do at the boundary: registries of live pointers (a freed or foreign pointer is refused,
//! not followed), C arrays and strings turned into slices with their NULLs and lengths checked, and the one
//! `catch_unwind` boundary (`call_on`), so that no panic crosses into the host.

use super::instance::{error, Call, Failure, Instance, Kind, Mode};
use super::Status;
use std::collections::BTreeSet;
use std::ffi::{c_void, CStr};
use std::os::raw::c_char;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Mutex;

/// Arrays longer than this are refused (a garbage length must not become a huge allocation).
const MAX_ARRAY: usize = 1 << 24;

/// Addresses handed to the host and not yet freed.
pub struct Registry(Mutex<BTreeSet<usize>>);

impl Registry {
    /// An empty registry; `const`, so that it can be a `static`.
    pub const fn new() -> Registry {
        Registry(Mutex::new(BTreeSet::new()))
    }

    /// Whether `p` is registered (false also if the lock is poisoned).
    pub fn live(&self, p: usize) -> bool {
        self.0.lock().map(|s| s.contains(&p)).unwrap_or(false)
    }

    /// Records `p` as live (nothing happens if the lock is poisoned).
    pub fn register(&self, p: usize) {
        if let Ok(mut s) = self.0.lock() {
            s.insert(p);
        }
    }

    /// Removes `p`; whether it was live (false also if the lock is poisoned).
    pub fn unregister(&self, p: usize) -> bool {
        self.0.lock().map(|mut s| s.remove(&p)).unwrap_or(false)
    }
}

impl Default for Registry {
    fn default() -> Registry {
        Registry::new()
    }
}

/// The FMU state behind a pointer handed to the host (fmi2FMUstate, fmi3FMUState): the bytes of
/// `state_format`.
pub struct FmuState {
    /// The saved instance, in the byte format of `state_format`.
    pub bytes: Vec<u8>,
}

/// The saved state behind a host's pointer, if it is a live one of `states`.
pub fn saved<'a>(states: &Registry, state: *mut c_void, function: &str) -> Call<&'a FmuState> {
    if state.is_null() {
        return error(format!("{function}: argument `FMUState` is NULL"));
    }
    if !states.live(state as usize) {
        return error(format!("{function}: the FMU state is not a live state of this library (freed, or made by another FMU)"));
    }
    // SAFETY: live state pointers come from Box::into_raw of a FmuState and are not yet freed.
    Ok(unsafe { &*(state as *const FmuState) })
}

/// fmi2FreeFMUstate and fmi3FreeFMUState: frees the state at `*p` and sets `*p` to NULL (NULL: nothing to
/// free). A host that passes the state itself instead of its address (fmusim 0.0.39 does) gets that
/// state freed too, and the message returned names the mistake for the log: the pointer is then a live
/// state of this library, which the address of a host's variable cannot be, so it is recognised before
/// it is read. The call succeeds: fmusim ends its run at any status other than OK, before simulating when
/// it restores a state from a file.
///
/// # Safety
/// `p` is the host's argument: NULL, a live state of `states`, or the address of a variable holding NULL
/// or a state pointer.
pub unsafe fn free_state(states: &Registry, p: *mut *mut c_void, function: &str, arg: &str) -> Call<Option<String>> {
    if p.is_null() {
        return error(format!("{function}: argument `{arg}` is NULL"));
    }
    if states.unregister(p as usize) {
        // SAFETY: just unregistered; live states come from Box::into_raw of a FmuState.
        drop(unsafe { Box::from_raw(p as *mut FmuState) });
        return Ok(Some(format!(
            "{function}: `{arg}` is the FMU state itself, not the address of the host's pointer to it (FMI passes the address, so that the pointer can be set to NULL); the state is freed, and the host's pointer still holds it"
        )));
    }
    // SAFETY: not a state, so by the contract the address of the host's variable.
    let s = unsafe { *p };
    if s.is_null() {
        return Ok(None);
    }
    if !states.unregister(s as usize) {
        return error(format!("{function}: `*{arg}` is not a live state of this library (already freed?)"));
    }
    // SAFETY: just unregistered; it came from Box::into_raw of a FmuState.
    drop(unsafe { Box::from_raw(s as *mut FmuState) });
    // SAFETY: the address of the host's variable, checked non-NULL above.
    unsafe { *p = std::ptr::null_mut() };
    Ok(None)
}

/// Runs `f` on the instance behind `c` if `c` is live in `instances`, of interface `kind` (None: either),
/// and in a mode of `modes`. A failure is logged; one that says so puts the instance in the Error state;
/// a panic puts it in the Fatal state.
pub fn call_on(
    instances: &Registry,
    c: *mut c_void,
    function: &'static str,
    kind: Option<Kind>,
    modes: u32,
    f: impl FnOnce(&mut Instance) -> Call,
) -> Status {
    if c.is_null() || !instances.live(c as usize) {
        return Status::Error;
    }
    // SAFETY: `c` was made by an instantiate function from a Box<Instance> and has not been freed (it is live).
    let inst = unsafe { &mut *(c as *mut Instance) };
    let result = catch_unwind(AssertUnwindSafe(|| {
        if inst.mode == Mode::Fatal {
            return error(format!("{function}: the instance is in the Fatal state after an earlier internal error; free it"));
        }
        if let Some(kind) = kind {
            inst.check_kind(function, kind)?;
        }
        inst.check_mode(function, modes)?;
        if inst.logger.enabled("logAll") {
            inst.log(Status::Ok, "logAll", function);
        }
        f(inst)
    }));
    let status = match result {
        Ok(Ok(())) => Status::Ok,
        Ok(Err(Failure { status, message, enters_error_state })) => {
            let category = match status {
                Status::Fatal => "logStatusFatal",
                Status::Warning => "logStatusWarning",
                _ => "logStatusError",
            };
            if status == Status::Fatal {
                inst.mode = Mode::Fatal;
                inst.log(status, category, &message);
            } else if enters_error_state {
                inst.mode = Mode::Error;
                let api = inst.api;
                let ways = format!("{}, {} or {}", api.name("Reset"), api.name("SetFMUstate"), api.name("FreeInstance"));
                inst.log(status, category, &format!("{message} (the instance is now in the Error state: {ways})"));
            } else {
                inst.log(status, category, &message);
            }
            status
        }
        Err(panic) => {
            let what = panic.downcast_ref::<&str>().map(|s| s.to_string()).or_else(|| panic.downcast_ref::<String>().cloned()).unwrap_or_default();
            inst.mode = Mode::Fatal;
            inst.log(Status::Fatal, "logStatusFatal", &format!("{function}: internal error ({what}); the instance cannot continue"));
            Status::Fatal
        }
    };
    // The messages go to the host only now: from here on the instance is not touched, so a logger that
    // calls back into the library (or frees the instance) meets no borrow of it.
    let (logger, name, messages) = inst.take_log();
    for (s, category, message) in messages {
        logger.log(&name, s, &category, &message);
    }
    status
}

/// A C array as a slice; NULL is allowed only for an empty array.
///
/// # Safety
/// A non-NULL `p` must point to `n` initialized values of `T` that stay valid and unaliased by writes for
/// `'a` (the host's array argument for the duration of the call).
pub unsafe fn slice<'a, T>(p: *const T, n: usize, function: &str, name: &str) -> Call<&'a [T]> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return error(format!("{function}: argument `{name}` is NULL but its length is {n}"));
    }
    if n > MAX_ARRAY {
        return error(format!("{function}: length {n} of `{name}` is larger than any array of this unit"));
    }
    // SAFETY: `p` is non-NULL and the caller guarantees `n` readable elements (this function's contract).
    Ok(unsafe { std::slice::from_raw_parts(p, n) })
}

/// A C array as a mutable slice; NULL is allowed only for an empty array.
///
/// # Safety
/// A non-NULL `p` must point to `n` writable values of `T`, not aliased elsewhere, valid for `'a` (the host's
/// output array for the duration of the call).
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, function: &str, name: &str) -> Call<&'a mut [T]> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return error(format!("{function}: argument `{name}` is NULL but its length is {n}"));
    }
    if n > MAX_ARRAY {
        return error(format!("{function}: length {n} of `{name}` is larger than any array of this unit"));
    }
    // SAFETY: `p` is non-NULL and the caller guarantees `n` writable elements (this function's contract).
    Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
}

/// A C string argument as a String; NULL and non-UTF-8 are refused by name.
///
/// # Safety
/// A non-NULL `p` must point to a NUL-terminated string valid for the duration of the call.
pub unsafe fn c_str(p: *const c_char, function: &str, name: &str) -> Call<String> {
    if p.is_null() {
        return error(format!("{function}: argument `{name}` is NULL"));
    }
    // SAFETY: `p` is non-NULL and the caller guarantees a NUL-terminated string (this function's contract).
    unsafe { CStr::from_ptr(p) }.to_str().map(str::to_owned).map_err(|_| Failure {
        status: Status::Error,
        message: format!("{function}: argument `{name}` is not UTF-8"),
        enters_error_state: false,
    })
}

/// An output argument, refused when NULL.
pub fn out<T>(p: *mut T, function: &str, name: &str) -> Call<*mut T> {
    if p.is_null() {
        error(format!("{function}: output argument `{name}` is NULL"))
    } else {
        Ok(p)
    }
}
