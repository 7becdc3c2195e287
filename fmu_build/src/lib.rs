//! The packaging tool's library: the reproducible archive writer.

pub mod archive;
