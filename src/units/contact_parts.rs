//! What the two units share about their contact: building it from the parameter values, the outputs
//! both report with the same meaning, and writing those outputs.

use super::scene_params;
use super::variables::{Value, VarType, Variable};
use super::UnitError;
use crate::impact::{Contact, ContactForce};
use crate::law::damping::NormalDamping;
use crate::law::params::Effective;
use crate::law::{AnyLaw, NormalLaw};
use crate::scene::Scene;

/// The contact of the scene in `values`: law, damping with the scene's m*, indicator scales 1e-3 R* and
/// `rate_nominal`. Errors name the parameter.
pub fn build(variables: &[Variable], values: &[Value], rate_nominal: f64) -> Result<(Contact, Scene, Effective), UnitError> {
    let scene = scene_params::scene(variables, values)?;
    let law = AnyLaw::from_scene(&scene)?;
    let eff = Effective::from_scene(&scene)?;
    let damping = NormalDamping::from_scene(&scene, eff.mass);
    Ok((Contact::new(law, damping, 1e-3 * eff.radius, rate_nominal), scene, eff))
}

/// What every "0 = derive it" parameter became, for the log (logEvents) at initialization.
pub fn derived_event(variables: &[Variable], values: &[Value]) -> Option<String> {
    let scene = scene_params::scene(variables, values).ok()?;
    crate::analysis::derived_line(&scene).ok()
}

pub fn contact_state_output() -> Variable {
    Variable::output(
        "contact_state",
        VarType::Integer,
        "",
        "branch of the law: 0 not in contact, 1 elastic, 2 plastic loading, 3 adhesive (beyond pull-off), 4 reloading (tomas), 5 attracted without contact (tomas)",
    )
}

pub fn max_overlap_output() -> Variable {
    Variable::output("max_overlap", VarType::Real, "m", "largest overlap reached so far (0 before contact)").with_nominal(1e-9)
}

pub fn plastic_overlap_output() -> Variable {
    Variable::output("plastic_overlap", VarType::Real, "m", "overlap at which the current unloading branch meets zero force (alpha_p)")
        .with_nominal(1e-9)
}

pub fn pull_off_force_output() -> Variable {
    Variable::output("pull_off_force", VarType::Real, "N", "largest tensile force the contact can take with its current history (f_cp)")
}

/// Value references of the outputs every contact unit writes (each unit fills them from its table).
#[derive(Debug, Clone, Copy)]
pub struct Outputs {
    pub force: usize,
    pub overlap: usize,
    pub contact_state: usize,
    pub max_overlap: usize,
    pub plastic_overlap: usize,
    pub pull_off_force: usize,
}

impl Outputs {
    /// Writes force, overlap, state and history at `alpha`, `rate` on the accepted branch of `c`; returns
    /// the total force.
    pub fn write(&self, values: &mut [Value], c: &Contact, alpha: f64, rate: f64) -> ContactForce {
        let (f, history) = c.state_at(alpha, rate);
        values[self.force] = Value::Real(f.total());
        values[self.overlap] = Value::Real(alpha);
        values[self.contact_state] = Value::Integer(c.accepted.branch.contact_state());
        values[self.max_overlap] = Value::Real(c.max_overlap.max(alpha).max(0.0));
        values[self.plastic_overlap] = Value::Real(c.law.plastic_overlap(&history));
        values[self.pull_off_force] = Value::Real(c.law.pull_off_force(&history));
        f
    }
}

/// Serializes a unit's snapshot; a failure is an error the host sees, never an empty state (which
/// `restore` would read as "not initialized").
pub fn encode<T: serde::Serialize>(snapshot: &T) -> Result<Vec<u8>, UnitError> {
    crate::codec::to_bytes(snapshot).map_err(|e| UnitError::SavedState(format!("the model state cannot be serialized: {e}")))
}
