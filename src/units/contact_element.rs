//! ContactElement: one contact law as a force element with direct feed-through. The inputs are the
//! wall's approach toward the sphere and its rate; the overlap is wall_displacement - initial_gap. The
//! masses live elsewhere in the system model (the damping uses the scene's m*).
//!
//! In shear: the wall's displacement along itself relative to the sphere and its rate drive the law's
//! tangential spring with its Coulomb limit (`impact::shear`: the bed's and the oblique impact's spring,
//! 004 Eqs. 3.11-3.13, 000 Eq. 23), whose history is accepted where the normal one is; a sliding spring
//! also keeps the point reached at every completed integrator step, so that a reversal unloads from
//! there. With both tangential inputs left at 0 nothing is sheared and the normal outputs are as before.
//!
//! The history follows the overlap inputs as a sequence of straight paths: at every accepted point (ME:
//! events; CS: each fmi2DoStep, with the inputs of its start), the history walks from the last accepted
//! overlap to the current one and stops at each branch point on the way.
//!
//! The work done on the contact (`dissipated_energy`) has two parts. The law's work, the integral of
//! f d alpha along that path (and of the tangential spring's F_t d delta_t), is a function of the overlap input and the accepted history: kept at each
//! accepted point, plus the integral along the accepted branch from there to the current overlap, in
//! Model Exchange as in Co-Simulation. So it is the same number in both, and Model Exchange needs no
//! state for it: a state whose derivative (force times wall_velocity) jumps wherever a master holds its
//! inputs between samples makes a BDF solver with a minimum step fail its error test (OMSimulator), and
//! a solver that is not restarted after an event integrates it on the old branch (fmusim). The damping's
//! work, the integral of f_damping times wall_velocity over time, is Model Exchange's one continuous
//! state (`damping_energy`); its derivative is 0 for an undamped contact (restitution_coefficient 1).

use super::contact_parts::{self, Outputs};
use super::scene_params;
use super::variables::{Role, Value, VarType, Variable};
use super::{EventUpdate, Model, UnitError, UnitInfo};
use crate::impact::contact::Memory;
use crate::impact::shear::ShearMemory;
use crate::impact::{Contact, Shear};
use crate::law::params::Effective;
use crate::law::tangential::TangentialStiffness;
use crate::law::NormalLaw;
use crate::numeric::tanh_sinh;
use serde::{Deserialize, Serialize};

/// The FMI modelIdentifier of the unit.
pub const MODEL_IDENTIFIER: &str = "ContactElement";

variable_table! {
    wall_displacement: Variable::input("wall_displacement", "m", "approach of the wall toward the sphere (overlap = wall_displacement - initial_gap)"),
    wall_velocity: Variable::input("wall_velocity", "m/s", "rate of the approach (for the viscous damping and the contact work)"),
    force: Variable::output("force", VarType::Real, "N", "normal contact force (law plus damping), positive repulsive"),
    overlap: Variable::output("overlap", VarType::Real, "m", "overlap alpha = wall_displacement - initial_gap, positive in compression")
        .with_nominal(1e-9),
    contact_state: contact_parts::contact_state_output(),
    max_overlap: contact_parts::max_overlap_output(),
    plastic_overlap: contact_parts::plastic_overlap_output(),
    pull_off_force: contact_parts::pull_off_force_output(),
    dissipated_energy: Variable::output(
        "dissipated_energy",
        VarType::Real,
        "J",
        "work done on the contact: the law's integral of force d(overlap) along the overlap path, the tangential spring's integral of tangential_force d(wall_tangential_displacement), plus the damping's work (damping_energy); after separation, the energy the contact dissipated",
    ),
    damping_energy: Variable::local("damping_energy", "J", "work of the viscous damping forces, the integral of f_damping wall_velocity + f_t,damping wall_tangential_velocity dt (ME's continuous state; part of dissipated_energy)", Role::State(0)),
    der_damping_energy: Variable::local("der(damping_energy)", "W", "power of the damping forces, f_damping wall_velocity + f_t,damping wall_tangential_velocity", Role::Derivative(0)),
    initial_gap: Variable::parameter("initial_gap", Value::Real(0.0), "m", "wall_displacement at which the surfaces touch"),
    wall_tangential_displacement: Variable::input(
        "wall_tangential_displacement",
        "m",
        "displacement of the wall along itself (x) relative to the sphere: the contact's shear; the tangential spring takes its increments",
    ),
    wall_tangential_velocity: Variable::input("wall_tangential_velocity", "m/s", "rate of wall_tangential_displacement (for the tangential damping while the spring sticks)"),
    tangential_force: Variable::output(
        "tangential_force",
        VarType::Real,
        "N",
        "tangential force on the sphere along x (spring and damping), positive in the direction the wall moved; at most friction_coefficient times the law's sliding normal load",
    ),
    sliding: Variable::output("sliding", VarType::Boolean, "", "true while the tangential spring is on its Coulomb limit"),
}

/// The outputs both contact units write, at this unit's references.
const OUTPUTS: Outputs = Outputs {
    force: REFS.force,
    overlap: REFS.overlap,
    contact_state: REFS.contact_state,
    max_overlap: REFS.max_overlap,
    plastic_overlap: REFS.plastic_overlap,
    pull_off_force: REFS.pull_off_force,
};

/// The unit (Model Exchange and Co-Simulation): its own variables, the scene parameters, the event
/// indicators and time.
pub fn info() -> UnitInfo {
    let mut variables = own_variables();
    variables.extend(scene_params::variables());
    // Last, so that the references of the table above stay as they were.
    variables.extend(Variable::contact_indicators());
    variables.push(Variable::time());
    UnitInfo {
        model_identifier: MODEL_IDENTIFIER,
        description: "One elasto-plastic adhesive contact as a force element, in compression and in shear (powderfmu)",
        variables,
        n_states: 1,
        n_event_indicators: 3,
        stop_time: 1.0,
        step_size: 1e-3,
        model_exchange: true,
        can_interpolate_inputs: false,
        returns_early: false,
        new_model: |u, _| Box::new(ContactElement::new(u)),
        guid_cache: std::sync::OnceLock::new(),
        token_cache: std::sync::OnceLock::new(),
    }
}

/// The model of ContactElement: one contact law driven by the overlap inputs, its accepted history, and
/// the work done on the contact [J].
pub struct ContactElement {
    variables: Vec<Variable>,
    contact: Option<Contact>,
    /// The tangential spring, driven by wall_tangential_displacement.
    shear: Option<Shear>,
    gap: f64,
    /// The law's work along the path up to the accepted overlap [J].
    law_work: f64,
    /// The damping's work [J] (ME: the continuous state).
    damping_work: f64,
    /// Messages for the logEvents category (the derived parameters at initialization).
    events: Vec<String>,
}

#[derive(Serialize, Deserialize)]
struct Snapshot {
    law_work: f64,
    damping_work: f64,
    contact: Memory,
    shear: ShearMemory,
}

/// A state saved before the tangential inputs (2026-12-04): it loads with an unloaded spring at the
/// displacement the parameters give.
#[derive(Serialize, Deserialize)]
struct SnapshotNormalOnly {
    law_work: f64,
    damping_work: f64,
    contact: Memory,
}

impl ContactElement {
    fn new(u: &UnitInfo) -> ContactElement {
        ContactElement { variables: u.variables.clone(), contact: None, shear: None, gap: 0.0, law_work: 0.0, damping_work: 0.0, events: Vec::new() }
    }

    fn build(&self, values: &[Value]) -> Result<(Contact, Shear, f64), UnitError> {
        let gap = values[REFS.initial_gap].as_real();
        if !gap.is_finite() {
            return Err(UnitError::Variable { name: "initial_gap", why: format!("parameter `initial_gap` = {gap} m is not a finite number") });
        }
        let rate_nominal = values[REFS.wall_velocity].as_real().abs().max(1e-3);
        let (contact, scene, eff) = contact_parts::build(&self.variables, values, rate_nominal)?;
        let shear = shear_of(&scene, &eff, values[REFS.wall_tangential_displacement].as_real());
        Ok((contact, shear, gap))
    }

    /// Overlap and rate of the current inputs.
    fn inputs(&self, values: &[Value]) -> (f64, f64) {
        (values[REFS.wall_displacement].as_real() - self.gap, values[REFS.wall_velocity].as_real())
    }

    /// Tangential displacement and rate of the current inputs.
    fn tangential_inputs(values: &[Value]) -> (f64, f64) {
        (values[REFS.wall_tangential_displacement].as_real(), values[REFS.wall_tangential_velocity].as_real())
    }
}

/// The tangential spring of the scene's law (its tangential model and friction coefficient), unloaded
/// at displacement `displacement` [m].
fn shear_of(scene: &crate::scene::Scene, eff: &Effective, displacement: f64) -> Shear {
    let stiffness = TangentialStiffness::for_model(scene.contact_model.tangential_model(), eff.shear_modulus, eff.youngs_modulus, eff.radius);
    Shear::new(stiffness, scene.friction_coefficient, displacement)
}

/// The law's work from the accepted overlap to `alpha` along the accepted branch and its continuation
/// (what the force output follows between events) [J].
fn branch_work(c: &Contact, alpha: f64) -> f64 {
    let from = c.accepted_alpha;
    if !from.is_finite() || from == alpha {
        return 0.0;
    }
    tanh_sinh(|x| c.force(x, 0.0).law, from, alpha)
}

impl Model for ContactElement {
    fn initialize(&mut self, values: &[Value], _t0: f64, _model_exchange: bool) -> Result<(), UnitError> {
        let (mut contact, shear, gap) = self.build(values)?;
        self.gap = gap;
        let (alpha, rate) = self.inputs(values);
        if !alpha.is_finite() || !rate.is_finite() {
            return Err(UnitError::Variable {
                name: "wall_displacement",
                why: format!("inputs `wall_displacement` = {alpha} m and `wall_velocity` = {rate} m/s must be finite"),
            });
        }
        let (delta, w_t) = Self::tangential_inputs(values);
        if !delta.is_finite() || !w_t.is_finite() {
            return Err(UnitError::Variable {
                name: "wall_tangential_displacement",
                why: format!("inputs `wall_tangential_displacement` = {delta} m and `wall_tangential_velocity` = {w_t} m/s must be finite"),
            });
        }
        contact.accept(alpha, rate);
        // The spring starts unloaded where the tangential input stands.
        self.shear = Some(shear);
        self.contact = Some(contact);
        self.law_work = 0.0;
        self.damping_work = 0.0;
        self.events.extend(contact_parts::derived_event(&self.variables, values));
        Ok(())
    }

    fn take_events(&mut self) -> Vec<String> {
        std::mem::take(&mut self.events)
    }

    fn compute(&mut self, values: &mut [Value], between_events: bool) {
        let (alpha, rate) = self.inputs(values);
        let Some(contact) = &self.contact else { return };
        // Feed-through: in Continuous-Time Mode the accepted branch; elsewhere the history walked to the
        // inputs, so that the output at an input is the value fmi2DoStep (or the next event) gives there.
        let walked;
        let (c, path_work) = if between_events {
            (contact, branch_work(contact, alpha))
        } else {
            let (w, path_work) = contact.walked_to(alpha, rate);
            walked = w;
            (&walked, path_work)
        };
        let f = OUTPUTS.write(values, c, alpha, rate);
        let (delta, w_t) = Self::tangential_inputs(values);
        let t = self.shear.as_ref().map(|s| s.at(c, alpha, delta, w_t)).unwrap_or_default();
        values[REFS.tangential_force] = Value::Real(t.total());
        values[REFS.sliding] = Value::Boolean(t.sliding);
        values[REFS.dissipated_energy] = Value::Real(self.law_work + path_work + t.work + self.damping_work);
        values[REFS.damping_energy] = Value::Real(self.damping_work);
        values[REFS.der_damping_energy] = Value::Real(f.damping * rate + t.damping * w_t);
    }

    fn set_time(&mut self, _t: f64) {}

    fn get_states(&self, x: &mut [f64]) {
        x[0] = self.damping_work;
    }

    fn set_states(&mut self, x: &[f64]) {
        self.damping_work = x[0];
    }

    fn derivatives(&mut self, values: &[Value], dx: &mut [f64]) {
        let (alpha, rate) = self.inputs(values);
        let (delta, w_t) = Self::tangential_inputs(values);
        dx[0] = self.contact.as_ref().map_or(0.0, |c| {
            let tangential = self.shear.as_ref().map_or(0.0, |s| s.at(c, alpha, delta, w_t).damping * w_t);
            c.force(alpha, rate).damping * rate + tangential
        });
    }

    fn event_indicators(&mut self, values: &[Value], z: &mut [f64]) {
        let (alpha, rate) = self.inputs(values);
        if let Some(c) = &self.contact {
            z.copy_from_slice(&c.indicators(alpha, rate));
        }
    }

    fn nominals(&self, x: &mut [f64]) {
        // The work of the contact's force scale (its force at the nominal overlap, or its pull-off force)
        // over the nominal overlap.
        x[0] = self.contact.as_ref().map_or(1.0, |c| {
            let fresh = c.law.initial_history();
            let f = c.law.evaluate(c.alpha_nominal, &fresh).force.abs().max(c.law.pull_off_force(&fresh)).max(1e-12);
            f * c.alpha_nominal
        });
    }

    fn accept(&mut self, values: &[Value]) -> EventUpdate {
        let (alpha, rate) = self.inputs(values);
        let Some(c) = self.contact.as_mut() else { return EventUpdate::default() };
        let before = c.accepted;
        self.law_work += c.follow(alpha);
        c.accept(alpha, rate);
        let after = c.accepted;
        if let Some(s) = self.shear.as_mut() {
            self.law_work += s.accept(c, alpha, Self::tangential_inputs(values).0);
        }
        let message = (before.branch != after.branch).then(|| format!("branch {:?} -> {:?} at overlap {alpha:e} m", before.branch, after.branch));
        // The damping power follows the branch's stiffness: a new branch or history is a new right-hand side.
        EventUpdate { message, restart: before.branch != after.branch || before.history != after.history }
    }

    fn completed_step(&mut self, values: &[Value]) {
        let (alpha, _) = self.inputs(values);
        if let Some(c) = self.contact.as_mut() {
            self.law_work += c.keep_growth(alpha);
            if let Some(s) = self.shear.as_mut() {
                self.law_work += s.keep_sliding(c, alpha, Self::tangential_inputs(values).0);
            }
        }
    }

    /// The inputs are held over the step: the history walks to the overlap of the step's start and the
    /// work of the law's force along that walk, plus the damping force times the walk, is added.
    fn do_step(&mut self, values: &[Value], _t: f64, _h: f64) -> Result<(), UnitError> {
        let (alpha, rate) = self.inputs(values);
        let (delta, w_t) = Self::tangential_inputs(values);
        let c = self.contact.as_mut().ok_or(UnitError::NotInitialized)?;
        let from = c.accepted_alpha;
        self.law_work += c.follow(alpha);
        let damping = c.force(alpha, rate).damping;
        c.accept(alpha, rate);
        self.damping_work += damping * (alpha - from);
        if let Some(s) = self.shear.as_mut() {
            let from = s.accepted.displacement;
            let t = s.at(c, alpha, delta, w_t);
            self.law_work += s.accept(c, alpha, delta);
            self.damping_work += t.damping * (delta - from);
        }
        Ok(())
    }

    fn save(&self) -> Result<Vec<u8>, UnitError> {
        let Some(c) = &self.contact else { return Ok(Vec::new()) };
        let shear = self.shear.as_ref().map(|s| s.accepted).unwrap_or_default();
        let snap = Snapshot { law_work: self.law_work, damping_work: self.damping_work, contact: c.memory(), shear };
        contact_parts::encode(&snap)
    }

    fn restore(&mut self, values: &[Value], bytes: &[u8]) -> Result<(), UnitError> {
        if bytes.is_empty() {
            self.contact = None;
            self.shear = None;
            return Ok(());
        }
        let (mut c, mut shear, gap) = self.build(values)?;
        let snap: Snapshot = match super::decode(bytes) {
            Ok(snap) => snap,
            // A state of the normal-only element: the spring unloaded at the current tangential input.
            Err(e) => match super::decode::<SnapshotNormalOnly>(bytes) {
                Ok(old) => Snapshot { law_work: old.law_work, damping_work: old.damping_work, contact: old.contact, shear: shear.accepted },
                Err(_) => return Err(e),
            },
        };
        if !(snap.shear.spring.is_finite() && snap.shear.displacement.is_finite()) {
            return Err(UnitError::SavedState("the saved tangential spring is not a finite number".into()));
        }
        shear.accepted = snap.shear;
        c.remember(snap.contact).map_err(UnitError::SavedState)?;
        self.contact = Some(c);
        self.shear = Some(shear);
        self.gap = gap;
        if !(snap.law_work.is_finite() && snap.damping_work.is_finite()) {
            return Err(UnitError::SavedState("the saved contact work is not a finite number".into()));
        }
        self.law_work = snap.law_work;
        self.damping_work = snap.damping_work;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An element pressed to 40 nm (the default Nan law carries a normal load there) and sheared by `delta` [m].
    fn sheared(delta: f64) -> (ContactElement, Vec<Value>) {
        let u = super::super::by_identifier(MODEL_IDENTIFIER).unwrap();
        let mut values = u.start_values();
        values[REFS.wall_displacement] = Value::Real(4e-8);
        let mut m = ContactElement::new(u);
        m.initialize(&values, 0.0, false).unwrap();
        values[REFS.wall_tangential_displacement] = Value::Real(delta);
        m.do_step(&values, 0.0, 1e-3).unwrap();
        (m, values)
    }

    #[test]
    fn a_state_of_the_normal_only_element_loads_with_an_unloaded_spring() {
        let (mut m, mut values) = sheared(1e-10);
        m.compute(&mut values, false);
        let before = values.clone();
        assert!(before[REFS.tangential_force].as_real() > 0.0);
        // The bytes an element saved before the tangential inputs: the same fields without the spring.
        let c = m.contact.as_ref().unwrap();
        let old = contact_parts::encode(&SnapshotNormalOnly { law_work: m.law_work, damping_work: m.damping_work, contact: c.memory() }).unwrap();
        let mut restored = ContactElement::new(super::super::by_identifier(MODEL_IDENTIFIER).unwrap());
        restored.restore(&values, &old).unwrap();
        restored.compute(&mut values, false);
        assert_eq!(values[REFS.force], before[REFS.force]);
        // Unloaded where the tangential input stands.
        assert_eq!(values[REFS.tangential_force].as_real(), 0.0);
        // The current state round-trips with its spring.
        let now = m.save().unwrap();
        restored.restore(&values, &now).unwrap();
        restored.compute(&mut values, false);
        assert_eq!(values[REFS.tangential_force], before[REFS.tangential_force]);
        // Bytes that are neither are refused.
        assert!(restored.restore(&values, &now[..now.len() - 3]).is_err());
    }
}
