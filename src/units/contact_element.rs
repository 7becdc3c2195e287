//! ContactElement: one contact law as a force element with direct feed-through. The inputs are the
//! wall's approach toward the sphere and its rate; the overlap is wall_displacement - initial_gap. The
//! masses live elsewhere in the system model (the damping uses the scene's m*).
//!
//! The history follows the overlap inputs as a sequence of straight paths: at every accepted point (ME:
//! events and completed integrator steps; CS: each fmi2DoStep, with the inputs of its start), the history
//! walks from the last accepted overlap to the current one and stops at each branch point on the way.
//! ME has one continuous state, the contact work (its derivative is force times wall_velocity).

use super::contact_parts::{self, Outputs};
use super::scene_params;
use super::variables::{Role, Value, VarType, Variable};
use super::{Model, UnitError, UnitInfo};
use crate::impact::contact::Memory;
use crate::impact::Contact;
use crate::law::NormalLaw;
use serde::{Deserialize, Serialize};

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
        "work done on the contact, the integral of force d(overlap); after separation, the energy the contact dissipated",
    )
    .with_role(Role::State(0)),
    der_energy: Variable::local("der(dissipated_energy)", "W", "power of the contact force, force times wall_velocity", Role::Derivative(0)),
    initial_gap: Variable::parameter("initial_gap", Value::Real(0.0), "m", "wall_displacement at which the surfaces touch"),
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

pub fn info() -> UnitInfo {
    let mut variables = own_variables();
    variables.extend(scene_params::variables());
    // Last, so that the references of the table above stay as they were.
    variables.extend(Variable::contact_indicators());
    variables.push(Variable::time());
    UnitInfo {
        model_identifier: MODEL_IDENTIFIER,
        description: "One elasto-plastic adhesive normal contact as a force element (powderfmu)",
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

pub struct ContactElement {
    variables: Vec<Variable>,
    contact: Option<Contact>,
    gap: f64,
    work: f64,
    /// Messages for the logEvents category (the derived parameters at initialization).
    events: Vec<String>,
}

#[derive(Serialize, Deserialize)]
struct Snapshot {
    work: f64,
    contact: Memory,
}

impl ContactElement {
    fn new(u: &UnitInfo) -> ContactElement {
        ContactElement {
            variables: u.variables.clone(),
            contact: None,
            gap: 0.0,
            work: 0.0,
            events: Vec::new(),
        }
    }

    fn build(&self, values: &[Value]) -> Result<(Contact, f64), UnitError> {
        let gap = values[REFS.initial_gap].as_real();
        if !gap.is_finite() {
            return Err(UnitError::Variable { name: "initial_gap", why: format!("parameter `initial_gap` = {gap} m is not a finite number") });
        }
        let rate_nominal = values[REFS.wall_velocity].as_real().abs().max(1e-3);
        let (contact, _, _) = contact_parts::build(&self.variables, values, rate_nominal)?;
        Ok((contact, gap))
    }

    /// Overlap and rate of the current inputs.
    fn inputs(&self, values: &[Value]) -> (f64, f64) {
        (values[REFS.wall_displacement].as_real() - self.gap, values[REFS.wall_velocity].as_real())
    }
}

impl Model for ContactElement {
    fn initialize(&mut self, values: &[Value], _t0: f64, _model_exchange: bool) -> Result<(), UnitError> {
        let (mut contact, gap) = self.build(values)?;
        self.gap = gap;
        let (alpha, rate) = self.inputs(values);
        if !alpha.is_finite() || !rate.is_finite() {
            return Err(UnitError::Variable {
                name: "wall_displacement",
                why: format!("inputs `wall_displacement` = {alpha} m and `wall_velocity` = {rate} m/s must be finite"),
            });
        }
        contact.accept(alpha, rate);
        self.contact = Some(contact);
        self.work = 0.0;
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
        let c = if between_events {
            contact
        } else {
            walked = contact.walked_to(alpha, rate);
            &walked
        };
        let f = OUTPUTS.write(values, c, alpha, rate);
        values[REFS.dissipated_energy] = Value::Real(self.work);
        values[REFS.der_energy] = Value::Real(f * rate);
    }

    fn set_time(&mut self, _t: f64) {}

    fn get_states(&self, x: &mut [f64]) {
        x[0] = self.work;
    }

    fn set_states(&mut self, x: &[f64]) {
        self.work = x[0];
    }

    fn derivatives(&mut self, values: &[Value], dx: &mut [f64]) {
        let (alpha, rate) = self.inputs(values);
        dx[0] = self.contact.as_ref().map_or(0.0, |c| c.force(alpha, rate).total() * rate);
    }

    fn event_indicators(&mut self, values: &[Value], z: &mut [f64]) {
        let (alpha, rate) = self.inputs(values);
        if let Some(c) = &self.contact {
            z.copy_from_slice(&c.indicators(alpha, rate));
        }
    }

    fn nominals(&self, x: &mut [f64]) {
        x[0] = self.contact.as_ref().map_or(1.0, |c| {
            let f = c.law.pull_off_force(c.history()).abs().max(1e-12);
            f * c.alpha_nominal
        });
    }

    fn accept(&mut self, values: &[Value]) -> Option<String> {
        let (alpha, rate) = self.inputs(values);
        let c = self.contact.as_mut()?;
        let before = c.accepted.branch;
        c.follow(alpha);
        c.accept(alpha, rate);
        let after = c.accepted.branch;
        (before != after).then(|| format!("branch {before:?} -> {after:?} at overlap {alpha:e} m"))
    }

    /// The inputs are held over the step: the history walks to the overlap of the step's start and the
    /// work of the law's force along that walk, plus the damping force times the walk, is added.
    fn do_step(&mut self, values: &[Value], _t: f64, _h: f64) -> Result<(), UnitError> {
        let (alpha, rate) = self.inputs(values);
        let c = self.contact.as_mut().ok_or(UnitError::NotInitialized)?;
        let from = c.accepted_alpha;
        let law_work = c.follow(alpha);
        let damping = c.force(alpha, rate).damping;
        c.accept(alpha, rate);
        self.work += law_work + damping * (alpha - from);
        Ok(())
    }

    fn save(&self) -> Result<Vec<u8>, UnitError> {
        let Some(c) = &self.contact else { return Ok(Vec::new()) };
        let snap = Snapshot { work: self.work, contact: c.memory() };
        contact_parts::encode(&snap)
    }

    fn restore(&mut self, values: &[Value], bytes: &[u8]) -> Result<(), UnitError> {
        if bytes.is_empty() {
            self.contact = None;
            return Ok(());
        }
        let snap: Snapshot = super::decode(bytes)?;
        let (mut c, gap) = self.build(values)?;
        c.remember(snap.contact).map_err(UnitError::SavedState)?;
        self.contact = Some(c);
        self.gap = gap;
        self.work = snap.work;
        Ok(())
    }
}
