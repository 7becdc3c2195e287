//! The packaging tool's library: the reproducible archive writer and the generated interface files
//! (each unit's `modelDescription.xml` and the variable table of its docs page).

pub mod archive;
pub mod interface;
