//! Dynamics of one contact in time (DESIGN 2, second layer): the contact bookkeeping shared by the
//! units (`contact`) and a sphere moving along a wall normal (`sphere`). Knows laws through `AnyLaw`,
//! time and geometry; knows nothing of FMI.

pub mod contact;
pub mod sphere;

pub use contact::{Contact, ContactForce};
pub use sphere::{Sphere, State, StepError, Wall};
