//! The FMU-state calls of both standards (fmi2GetFMUstate ... fmi2DeSerializeFMUstate, fmi3GetFMUState ...
//! fmi3DeserializeFMUState), written once: each ABI's export passes its registry of live states, its
//! function's name and the name of its state argument, and casts its C state pointer (a `void *` in both).
//! A state is the saved bytes (`state_format`) boxed behind the pointer handed to the host.

use super::ffi::{self, out, saved, slice, slice_mut, FmuState, Registry};
use super::instance::{error, Call, Instance};
use super::Status;
use std::ffi::c_void;

/// Saves `inst` into the state `*p`: the host's own, reused where it is live, or a new one.
///
/// # Safety
/// `p` is NULL or the host's output argument.
pub unsafe fn get(states: &Registry, inst: &mut Instance, p: *mut *mut c_void, function: &str, arg: &str) -> Call {
    let p = out(p, function, arg)?;
    let bytes = inst.save()?;
    // SAFETY: an output argument of the host, checked non-NULL by `out` above.
    let existing = unsafe { *p };
    if !existing.is_null() && states.live(existing as usize) {
        // SAFETY: a live state pointer came from Box::into_raw of a FmuState.
        unsafe { (*(existing as *mut FmuState)).bytes = bytes };
    } else {
        // SAFETY: `p` checked non-NULL above.
        unsafe { *p = new_state(states, bytes) };
    }
    Ok(())
}

/// Restores `inst` from a live state.
pub fn set(states: &Registry, inst: &mut Instance, state: *mut c_void, function: &str) -> Call {
    let bytes = saved(states, state, function)?.bytes.clone();
    inst.restore(&bytes)
}

/// Frees the state `*p` (and sets it to NULL); a host that passed the state itself is told so in the log.
///
/// # Safety
/// `p` is the host's argument, as `ffi::free_state` requires.
pub unsafe fn free(states: &Registry, inst: &mut Instance, p: *mut *mut c_void, function: &str, arg: &str) -> Call {
    // SAFETY: the caller's contract.
    if let Some(mistake) = unsafe { ffi::free_state(states, p, function, arg) }? {
        inst.log(Status::Warning, "logStatusWarning", &mistake);
    }
    Ok(())
}

/// The size of a live state's bytes, into `*size`.
///
/// # Safety
/// `size` is NULL or the host's output argument.
pub unsafe fn size(states: &Registry, state: *mut c_void, size: *mut usize, function: &str) -> Call {
    let p = out(size, function, "size")?;
    // SAFETY: an output argument of the host, checked non-NULL by `out` above.
    unsafe { *p = saved(states, state, function)?.bytes.len() };
    Ok(())
}

/// Copies a live state's bytes into the host's array of `size` bytes.
///
/// # Safety
/// `dst` is NULL or an array of at least `size` bytes.
pub unsafe fn serialize(states: &Registry, state: *mut c_void, dst: *mut u8, size: usize, function: &str, size_function: &str) -> Call {
    let bytes = &saved(states, state, function)?.bytes;
    if size < bytes.len() {
        return error(format!("{function}: size = {size} is smaller than the state ({} bytes, see {size_function})", bytes.len()));
    }
    // SAFETY: the caller's contract; NULL and impossible lengths are refused inside.
    let dst = unsafe { slice_mut(dst, bytes.len(), function, "serializedState") }?;
    dst.copy_from_slice(bytes);
    Ok(())
}

/// Reads `size` bytes of the host's into a new state `*p`, refused unless they are a state of this unit
/// saved through this standard.
///
/// # Safety
/// `src` is NULL or an array of `size` bytes; `p` NULL or the host's output argument.
pub unsafe fn deserialize(states: &Registry, inst: &Instance, src: *const u8, size: usize, p: *mut *mut c_void, function: &str, arg: &str) -> Call {
    let p = out(p, function, arg)?;
    // SAFETY: the caller's contract; NULL and impossible lengths are refused inside.
    let src = unsafe { slice(src, size, function, "serializedState") }?;
    if let Err(m) = super::state_format::read(inst.unit, inst.api, src) {
        return error(format!("{function}: {m}"));
    }
    // SAFETY: `p` checked non-NULL above.
    unsafe { *p = new_state(states, src.to_vec()) };
    Ok(())
}

/// A new state holding `bytes`, registered as live.
fn new_state(states: &Registry, bytes: Vec<u8>) -> *mut c_void {
    let s = Box::into_raw(Box::new(FmuState { bytes }));
    states.register(s as usize);
    s as *mut c_void
}
