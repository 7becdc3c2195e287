//! The packaging tool's library: the reproducible archive writer, the generated interface files (each
//! unit's `modelDescription.xml` and the variable table of its docs page) and the beds the FMUs ship.

pub mod archive;
pub mod beds;
pub mod interface;
