//! powderfmu: the contact mechanics of elasto-plastic, adhesive spheres (the laws of the seed papers
//! `000` Nan et al., `003` Tykhoniuk et al., `004` Pasha), for system models of powder handling.
//!
//! Layers, one way (DESIGN 2): `scene` (named inputs) -> `law` (contact laws and their parameters) ->
//! `theory` (closed-form results) -> `analysis` (the report of the command-line tool).

pub mod analysis;
pub mod bed;
pub mod curves;
pub mod error;
pub mod fmi2;
pub mod impact;
pub mod law;
pub mod numeric;
pub mod scene;
pub mod theory;
pub mod units;

pub use error::ParamError;
pub use law::{AnyHistory, AnyLaw, Branch, Evaluation, NormalLaw};
pub use scene::{ModelKind, Scene};
