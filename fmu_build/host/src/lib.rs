//! `fmi_host`: what an FMI host does with a loaded FMU binary, written once for the two Rust hosts of
//! the project (the test suite, which loads the cdylib of the current sources, and `fmu_check`, which
//! loads the binary of an unzipped `.fmu` on Linux or under wine).
//!
//! It declares the C types itself, from the standard's headers, and does not use the powderfmu crate:
//! a host that shared the FMU's own declarations would not notice if they were wrong.
//!
//! - [`Binary`]: a loaded shared library and typed symbol lookup;
//! - [`Log`]: an instance's messages, collected by the loggers of [`fmi2`] and [`fmi3`] through the
//!   instance environment pointer, so concurrent instances never mix their messages;
//! - [`fmi2`], [`fmi3`]: the callback structures, the function types, low-level calls that return the
//!   status, and an owning [`fmi2::Instance`] / [`fmi3::Instance`] whose calls return `Result` with the
//!   function's name and the instance's last message.

#![deny(unsafe_op_in_unsafe_fn)]
#![warn(missing_docs)]

use libloading::Library;
use std::ffi::{c_int, c_void};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

pub mod fmi2;
pub mod fmi3;

/// A status as both standards return it: a C enum (int-sized); 0 is OK in both.
pub type Status = c_int;
/// The status OK (fmi2OK, fmi3OK).
pub const OK: Status = 0;
/// An instance handle (fmi2Component, fmi3Instance): opaque to the host.
pub type Component = *mut c_void;

/// One logged message: (status, category, text).
pub type Message = (Status, String, String);

/// The messages of one instance, in the order logged. The host passes a pointer to its `Log` as the
/// instance environment; the loggers of this crate append to it.
pub type Log = Mutex<Vec<Message>>;

/// The text of the last message in `log`, or an empty string.
pub fn last_message(log: &Log) -> String {
    log.lock().unwrap_or_else(|e| e.into_inner()).last().map(|m| m.2.clone()).unwrap_or_default()
}

/// `Ok` for OK, else an error naming the function, the status and the instance's last message.
pub fn check(function: &str, status: Status, log: &Log) -> Result<(), String> {
    if status == OK {
        Ok(())
    } else {
        Err(format!("{function} returned status {status}: {}", last_message(log)))
    }
}

/// A loaded FMU binary.
pub struct Binary {
    library: Library,
    path: PathBuf,
}

impl Binary {
    /// Loads the shared library at `path`.
    pub fn load(path: &Path) -> Result<Binary, String> {
        // SAFETY: loading runs the library's initialisers, which a host must trust for any FMU it runs.
        let library = unsafe { Library::new(path) }.map_err(|e| format!("cannot load {}: {e}", path.display()))?;
        Ok(Binary { library, path: path.to_path_buf() })
    }

    /// Where the library was loaded from.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The exported function `name` as the function pointer type `T`.
    ///
    /// # Safety
    /// `T` must be a function pointer type with the symbol's signature (the standard's header).
    pub unsafe fn sym<T: Copy>(&self, name: &[u8]) -> Result<T, String> {
        // SAFETY: the caller names the symbol's type.
        unsafe { self.library.get::<T>(name) }.map(|s| *s).map_err(|e| format!("{} not exported: {e}", String::from_utf8_lossy(name)))
    }
}

/// The environment pointer of an instance whose messages go to `log`.
pub fn environment(log: &Log) -> *mut c_void {
    log as *const Log as *mut c_void
}

/// A function that maps a variable's name to its value reference (the model description's, or the
/// crate's own table in the test suite).
pub type Names<'a> = Box<dyn Fn(&str) -> Result<u32, String> + 'a>;
