//! Closed-form results: the work terms of `000` App. A, the sticking and yield velocities of `000`
//! Sec. 4, restitution by energy balance (closed forms for the linear laws, `004` App. II-III, and a
//! quasi-static work integral for any law), the load-dependent adhesion of `003` Eqs. 5-7, and time steps.

pub mod adhesion;
pub mod energy_balance;
pub mod restitution;
pub mod sticking;
pub mod time_step;
pub mod work;
