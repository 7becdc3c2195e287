//! The FMI 2.0 C ABI (docs/architecture.md, "Layers", layers 6-7): all 44 `fmi2*` functions, generic over `units::Model`.
//! `exports` holds the `extern "C"` functions and the one `catch_unwind` boundary; the instance, its
//! calling sequence and the saved states are shared with FMI 3.0 (`crate::fmi`); `types` the C types.

pub mod exports;
pub mod types;
