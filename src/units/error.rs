//! Why a unit refused or failed a call. The FMI glue logs the message (which names the parameter, the
//! input or the cause) and returns fmi2Error; the kind tells the host's code what went wrong.

use crate::error::ParamError;
use crate::impact::StepError;

/// Why a unit refused or failed a call.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnitError {
    /// A scene parameter out of its range or inconsistent with another (named, with the allowed range).
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A unit's own parameter or input refused; the message names it and its allowed range.
    #[error("{why}")]
    Variable {
        /// The name of the parameter or input.
        name: &'static str,
        /// What is wrong with its value, and what is allowed.
        why: String,
    },
    /// The integrator could not complete the step (the state stays that of the step's start).
    #[error(transparent)]
    Step(#[from] StepError),
    /// A saved state that cannot be read, or that no contact of these parameters can be in.
    #[error("{0}")]
    SavedState(String),
    /// A call this unit does not offer (the message says which and why).
    #[error("{0}")]
    Unsupported(String),
    /// A call that needs an initialized unit.
    #[error("the unit is not initialized")]
    NotInitialized,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::variables::Value;

    fn pwi_with(name: &str, value: Value) -> Result<(), UnitError> {
        let u = crate::units::by_identifier("ParticleWallImpact").unwrap();
        let mut values = u.start_values();
        values[u.vr(name).expect("a variable of the unit")] = value;
        (u.new_model)(u, None).initialize(&values, 0.0, false)
    }

    #[test]
    fn each_refusal_says_what_kind_it_is_and_names_the_variable() {
        assert!(matches!(pwi_with("tolerance", Value::Real(1.0)), Err(UnitError::Variable { name: "tolerance", .. })));
        assert!(matches!(pwi_with("solver", Value::String("euler".into())), Err(UnitError::Variable { name: "solver", .. })));
        assert!(matches!(
            pwi_with("particle_radius", Value::Real(-1.0)),
            Err(UnitError::Param(ParamError::OutOfRange { name: "particle_radius", .. }))
        ));
        assert_eq!(pwi_with("tolerance", Value::Real(1e-8)), Ok(()));
        let u = crate::units::by_identifier("ContactElement").unwrap();
        let values = u.start_values();
        assert_eq!((u.new_model)(u, None).do_step(&values, 0.0, 1e-3), Err(UnitError::NotInitialized));
    }
}
