//! The FMI 2.0 C ABI (DESIGN 2, fourth layer): all 44 `fmi2*` functions, generic over `units::Model`.
//! `exports` holds the `extern "C"` functions and the one `catch_unwind` boundary; `instance` the calling
//! sequence and value handling; `saved_state` the byte format of saved states; `types` the C types.

pub mod exports;
mod instance;
pub(crate) mod saved_state;
pub mod types;
mod uri;
