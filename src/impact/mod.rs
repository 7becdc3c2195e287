//! Dynamics of one contact in time (docs/architecture.md, "Layers", layer 4): the contact bookkeeping shared by the
//! units (`contact`), a sphere moving along a wall normal (`sphere`) and its three integrators (`exact`,
//! `adaptive`, `verlet`); the oblique impact's motion along the wall and spin (`oblique`); a contact sheared by a prescribed
//! displacement (`shear`). Knows laws through `AnyLaw`, time and geometry; knows nothing of FMI.

mod adaptive;
pub mod contact;
mod exact;
pub mod oblique;
mod oblique_adaptive;
pub mod shear;
pub mod sphere;
mod verlet;

pub use contact::{Contact, ContactForce};
pub use oblique::{Spin, Tangential};
pub use oblique_adaptive::{Mode as StickSlip, TangentialMode, ME_STATES as OBLIQUE_ME_STATES};
pub use shear::{Shear, ShearForce};
pub use sphere::{Solver, Sphere, State, StepError, WallMotion};
