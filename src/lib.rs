//! powderfmu: the contact mechanics of elasto-plastic, adhesive spheres (the laws of the seed papers
//! `000` Nan et al., `003` Tykhoniuk et al., `004` Pasha), for system models of powder handling.
//!
//! Layers, bottom to top, each using only those below (docs/architecture.md, "Layers", which
//! `tests/layers.rs` checks):
//! 0. `error`; 1. `numeric` (root finding, quadrature), `codec` (the byte format of saved data),
//!    `envelope` (the versioned, checksummed wrapper of bed files and FMU states), `vocabulary` (the
//!    parameter keys and `scene_options!`);
//! 2. `law` (the contact laws, their table and parameters); 3. `scene` (a contact's named inputs,
//!    composed above the laws), `theory` (closed-form results); 4. `analysis`, `curves` (the reports);
//! 5. `impact` (one contact in time, the sphere-wall integrators), `bed` (the DEM bed engine);
//! 6. `units` (the FMUs: variable tables and models); 7. `fmi` (what both C ABIs share);
//! 8. `fmi2`, `fmi3` (the C ABIs).

// `!(x > y)` is how this crate refuses NaN together with out-of-range values; clippy's suggestion
// (`partial_cmp`) would read worse and lose that on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// The bed's structure-of-arrays loops index several parallel arrays with one counter.
#![allow(clippy::needless_range_loop)]
#![deny(unsafe_op_in_unsafe_fn)]
// Every public item says what it holds, with its unit (docs/architecture.md, "One vocabulary").
#![warn(missing_docs)]
// Units are written in brackets ([m], [N], [Pa]), which rustdoc would take for links to items of those
// names: 242 false warnings in `cargo doc`.
#![allow(rustdoc::broken_intra_doc_links)]

pub mod analysis;
pub mod bed;
pub mod codec;
pub mod curves;
pub mod envelope;
pub mod error;
pub mod fmi;
pub mod fmi2;
pub mod fmi3;
pub mod impact;
pub mod law;
pub mod numeric;
pub mod scene;
pub mod theory;
pub mod units;
pub mod vocabulary;

pub use error::ParamError;
pub use law::{AnyHistory, AnyLaw, Branch, Evaluation, NormalLaw};
pub use scene::{ModelKind, Scene};
