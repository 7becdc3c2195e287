//! The FMI 3.0 C ABI: all 75 `fmi3*` functions, over the same `Instance` and units as FMI 2.0
//! (`crate::fmi`). `exports` holds the `extern "C"` functions; `types` the C types.

pub mod exports;
pub mod types;
