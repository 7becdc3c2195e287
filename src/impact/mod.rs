//! Dynamics of one contact in time (DESIGN 2, second layer): the contact bookkeeping shared by the
//! units (`contact`), a sphere moving along a wall normal (`sphere`) and its three integrators (`exact`,
//! `adaptive`, `verlet`). Knows laws through `AnyLaw`, time and geometry; knows nothing of FMI.

pub mod adaptive;
pub mod contact;
pub mod exact;
pub mod sphere;
pub mod verlet;

pub use contact::{Contact, ContactForce};
pub use sphere::{Solver, Sphere, State, StepError, WallMotion};
