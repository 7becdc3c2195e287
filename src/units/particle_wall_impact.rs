//! ParticleWallImpact: a sphere moving along the normal of a wall whose displacement and velocity are
//! inputs. The wall plane is at z = wall_displacement, the sphere centre at z = sphere_position, so the
//! overlap is particle_radius - (sphere_position - wall_displacement). Model Exchange: continuous states
//! are the height of the sphere's lowest point (sphere_position - particle_radius, so that CVode's
//! tolerances act on overlap-sized numbers), the velocity and the contact work; two event indicators follow
//! the branch interval of the law. Co-Simulation: `impact::Sphere::advance`.
//!
//! Oblique impacts (Co-Simulation): with a tangential velocity, a spin or a wall moving along itself the
//! sphere also moves along the wall and spins (`impact::oblique`, docs/models.md "Oblique impacts"): by
//! `verlet` when that is the solver, else by the oblique adaptive integrator, which locates the
//! stick-slip switches. Model Exchange: three more states (v_t, omega and the tangential spring) and a
//! fourth event indicator for the stick-slip switches, with the adaptive integrator's right-hand side and
//! switches (`impact::oblique_adaptive`); no rolling friction there.

use super::contact_parts::{self, Outputs};
use super::scene_params;
use super::variables::{Role, Value, VarType, Variable};
use super::{EventUpdate, Model, UnitError, UnitInfo};
use crate::impact::contact::Memory;
use crate::impact::{Solver, Sphere, Spin, State, StickSlip, Tangential, TangentialMode, WallMotion, OBLIQUE_ME_STATES};
use crate::law::tangential::TangentialStiffness;
use crate::law::{AnyLaw, NormalLaw};
use crate::scene::{ModelKind, Partner};
use crate::theory::time_step;
use serde::{Deserialize, Serialize};

/// The FMI modelIdentifier of the unit.
pub const MODEL_IDENTIFIER: &str = "ParticleWallImpact";

/// The largest speed of the sphere and the wall [m/s]: far beyond any impact of powder, and a bound
/// that keeps one step of the dynamics finite work.
const MAX_SPEED: f64 = 1e5;
/// The largest gravity (an ultracentrifuge's 1e6 m/s^2) [m/s^2].
const MAX_GRAVITY: f64 = 1e6;
/// The largest wall acceleration (an input derivative) [m/s^2]: a 1 nm vibration at 160 MHz, beyond any
/// ultrasonic or contact resonance of powder.
const MAX_WALL_ACCELERATION: f64 = 1e12;

variable_table! {
    wall_displacement: Variable::input("wall_displacement", "m", "position of the wall plane along the normal (z of the wall)"),
    wall_velocity: Variable::input("wall_velocity", "m/s", "velocity of the wall along the normal (positive toward the sphere's side)")
        .with_range(Some(-MAX_SPEED), Some(MAX_SPEED)),
    force: Variable::output("force", VarType::Real, "N", "normal contact force on the sphere (law plus damping), positive pushes it away from the wall"),
    overlap: Variable::output(
        "overlap",
        VarType::Real,
        "m",
        "overlap alpha = particle_radius - (sphere_position - wall_displacement), positive in compression",
    )
    .with_nominal(1e-9),
    contact_state: contact_parts::contact_state_output(),
    sphere_position: Variable::output("sphere_position", VarType::Real, "m", "height of the sphere centre"),
    sphere_velocity: Variable::output("sphere_velocity", VarType::Real, "m/s", "velocity of the sphere, positive away from the wall").with_role(Role::State(1)),
    max_overlap: contact_parts::max_overlap_output(),
    plastic_overlap: contact_parts::plastic_overlap_output(),
    pull_off_force: contact_parts::pull_off_force_output(),
    dissipated_energy: Variable::output(
        "dissipated_energy",
        VarType::Real,
        "J",
        "work done on the contact, the integral of force d(overlap), plus in oblique impacts the work of the tangential force and rolling torque against the motion along the wall and the spin; after the sphere has left the wall, the energy the contact dissipated",
    )
    .with_role(Role::State(2)),
    sphere_bottom: Variable::local("sphere_bottom", "m", "height of the sphere's lowest point, sphere_position - particle_radius (ME state)", Role::State(0))
        .with_nominal(1e-9),
    der_bottom: Variable::local("der(sphere_bottom)", "m/s", "velocity of the sphere's lowest point", Role::Derivative(0)),
    der_velocity: Variable::local("der(sphere_velocity)", "m/s2", "acceleration of the sphere", Role::Derivative(1)),
    der_energy: Variable::local(
        "der(dissipated_energy)",
        "W",
        "power of the contact force on the overlap rate, plus the tangential force's on the contact point's slip",
        Role::Derivative(2),
    ),
    initial_gap: Variable::parameter("initial_gap", Value::Real(1e-8), "m", "gap between the sphere surface and the wall at the start")
        .with_range(Some(0.0), None),
    initial_velocity: Variable::parameter("initial_velocity", Value::Real(1.0), "m/s", "approach speed of the sphere at the start, positive toward the wall")
        .with_range(Some(-MAX_SPEED), Some(MAX_SPEED)),
    gravity: Variable::parameter("gravity", Value::Real(0.0), "m/s2", "gravitational acceleration toward the wall")
        .with_range(Some(-MAX_GRAVITY), Some(MAX_GRAVITY)),
    solver: Variable::parameter(
        "solver",
        Value::String("auto".into()),
        "",
        &format!(
            "Co-Simulation integrator: exact (closed form per branch; {}), adaptive (Dormand-Prince 5(4) with event location; every law), verlet (fixed-step velocity Verlet at rayleigh_fraction of the Rayleigh time step, as DEM codes), auto (exact where it applies, else adaptive)",
            ModelKind::piecewise_linear_names()
        ),
    ),
    tolerance: Variable::parameter("tolerance", Value::Real(1e-10), "", "relative tolerance of the adaptive integrator, in [1e-14, 1e-2]")
        .with_range(Some(1e-14), Some(1e-2)),
    rayleigh_fraction: Variable::parameter("rayleigh_fraction", Value::Real(0.2), "", "step of the verlet integrator as a fraction of the Rayleigh time step (000 Eq. 71), in (0, 1]")
        .with_range(Some(0.0), Some(1.0)),
    wall_tangential_velocity: Variable::input(
        "wall_tangential_velocity",
        "m/s",
        "velocity of the wall along itself (a belt, a vibrating wall's in-plane motion), along x, the direction of positive tangential_velocity",
    )
    .with_range(Some(-MAX_SPEED), Some(MAX_SPEED)),
    tangential_velocity: Variable::output("tangential_velocity", VarType::Real, "m/s", "velocity of the sphere centre along the wall (x)").with_role(Role::State(3)),
    angular_velocity: Variable::output(
        "angular_velocity",
        VarType::Real,
        "rad/s",
        "spin about the axis in the wall plane normal to x (y = z x x, z away from the wall): positive rolls the sphere toward +x",
    )
    .with_role(Role::State(4)),
    tangential_force: Variable::output(
        "tangential_force",
        VarType::Real,
        "N",
        "tangential contact force on the sphere along x (spring and damping), at most friction_coefficient times the law's sliding normal load",
    ),
    sliding: Variable::output("sliding", VarType::Boolean, "", "true while the tangential force is on the Coulomb limit"),
    rebound_angle: Variable::output(
        "rebound_angle",
        VarType::Real,
        "rad",
        "once the sphere has left the wall after a contact: the angle of its velocity relative to the wall from the wall normal, atan((v_t - w_t) / (v - w')); 0 before",
    ),
    initial_tangential_velocity: Variable::parameter("initial_tangential_velocity", Value::Real(0.0), "m/s", "velocity of the sphere along the wall at the start (x)")
        .with_range(Some(-MAX_SPEED), Some(MAX_SPEED)),
    initial_angular_velocity: Variable::parameter(
        "initial_angular_velocity",
        Value::Real(0.0),
        "rad/s",
        "spin at the start about y = z x x: positive rolls toward +x (rolling without slip: tangential_velocity = particle_radius times it)",
    )
    .with_range(Some(-MAX_SPIN), Some(MAX_SPIN)),
    rolling_friction: Variable::parameter(
        "rolling_friction",
        Value::Real(0.0),
        "",
        "rolling friction mu_r: EDEM's constant directional torque mu_r |f_n| R against the spin (004 Table 5.3); needs solver = verlet (Co-Simulation)",
    )
    .with_range(Some(0.0), Some(1e3)),
    tangential_spring: Variable::local(
        "tangential_spring",
        "N",
        "force of the tangential spring on the sphere along x, before damping (ME state; while sliding, the limit mu N on its side)",
        Role::State(5),
    ),
    der_tangential_velocity: Variable::local("der(tangential_velocity)", "m/s2", "acceleration of the sphere along the wall", Role::Derivative(3)),
    der_angular_velocity: Variable::local("der(angular_velocity)", "rad/s2", "angular acceleration of the spin", Role::Derivative(4)),
    der_tangential_spring: Variable::local("der(tangential_spring)", "N/s", "rate of the spring, -k_t times the slip while it sticks, 0 while it slides", Role::Derivative(5)),
}

/// The largest spin [rad/s]: a 1 um sphere at MAX_SPEED on its rim.
const MAX_SPIN: f64 = 1e11;

/// Why Model Exchange refuses a rolling friction.
const ME_NO_ROLLING: &str = "Model Exchange has no rolling friction (a torque that switches with the sign of the spin, which no event indicator watches); run it in Co-Simulation with solver = \"verlet\", or leave it at 0";

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
    variables.push(Variable::local(
        "event_indicator_stick_slip",
        "",
        "event indicator of the tangential contact: sticking, mu N - |tangential_spring|; sliding, how fast the spring would outgrow the limit; positive while the mode holds",
        Role::Indicator(3),
    ));
    variables.push(Variable::time());
    UnitInfo {
        model_identifier: MODEL_IDENTIFIER,
        description: "A sphere against a moving wall with an elasto-plastic adhesive contact law, normal and oblique (powderfmu)",
        variables,
        n_states: OBLIQUE_ME_STATES,
        n_event_indicators: 4,
        stop_time: 2e-7,
        step_size: 1e-9,
        model_exchange: true,
        can_interpolate_inputs: true,
        returns_early: true,
        new_model: |u, _| Box::new(ParticleWallImpact::new(u)),
        guid_cache: std::sync::OnceLock::new(),
        token_cache: std::sync::OnceLock::new(),
    }
}

/// The model of ParticleWallImpact: the sphere, its state and the wall it meets; the host integrates
/// the state in Model Exchange, `impact::Sphere` advances it in Co-Simulation.
pub struct ParticleWallImpact {
    variables: Vec<Variable>,
    radius: f64,
    sphere: Option<Sphere>,
    y: State,
    t: f64,
    /// CS: the wall inputs the last step started from and where the step left the wall.
    cs_wall: Option<CsWall>,
    /// ME: the wall inputs as last seen and the time they were first seen at (`SeenWall`).
    me_wall: Option<SeenWall>,
    /// CS: the input derivatives for the next step (fmi2SetRealInputDerivatives); cleared after it.
    derivatives: InputDerivatives,
    /// Messages for the logEvents category (the derived parameters at initialization).
    events: Vec<String>,
    /// The tangential contact (friction, the spring's history) and the motion along the wall and spin.
    tangential: Option<Tangential>,
    spin: Spin,
    /// Stick or slide, for the oblique adaptive integrator.
    mode: TangentialMode,
    /// Whether the integrator of the tangential motion has been named in the log.
    announced: bool,
    /// ME: the time of the last stick-slip switch and how many came in quick succession before it
    /// (`Sphere::oblique_me_event`).
    me_switches: (f64, u32),
}

/// Model Exchange: between two updates of its inputs the wall moves on with its velocity input, from
/// where and when it was last given. So the overlap rate is exactly wall_velocity - sphere_velocity
/// between updates, whatever the importer's sampling, and the indicators that watch the rate watch the
/// overlap's own derivative. An importer that sets the inputs at every evaluation sees them unchanged;
/// one that sets them only now and then (fmpy sets them where it evaluates event indicators, not in the
/// right-hand side) sees a wall that moves smoothly instead of one that stands still and jumps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct SeenWall {
    position: f64,
    velocity: f64,
    t: f64,
}

/// CS: what fmi2SetRealInputDerivatives gave for the next step.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
struct InputDerivatives {
    /// Order 1 of wall_displacement: the wall's velocity over the step, in place of the wall_velocity
    /// input (for masters that connect only the displacement) [m/s].
    velocity: Option<f64>,
    /// Order 1 of wall_velocity or order 2 of wall_displacement [m/s^2].
    acceleration: f64,
}

/// The dynamic state, for fmi2GetFMUstate and serialization: the state a save held before the chatter
/// guard's counter was kept (2026-12-04), then the counter. postcard writes a nested struct as its fields
/// in order, so an older save is the same bytes without the counter and loads as `SnapshotCore` alone,
/// with no recent switch.
#[derive(Serialize, Deserialize)]
struct Snapshot {
    core: SnapshotCore,
    /// ME: the last stick-slip switch's time and the run of quick switches before it (the chatter guard),
    /// so that a restored run widens its pull-in as the original did.
    me_switches: (f64, u32),
}

/// Everything but the chatter guard's counter.
#[derive(Serialize, Deserialize)]
struct SnapshotCore {
    y: State,
    t: f64,
    contact: Memory,
    last_step: f64,
    cs_wall: Option<CsWall>,
    me_wall: Option<SeenWall>,
    derivatives: InputDerivatives,
    /// The motion along the wall and the spin; the tangential spring's force along x, the tangential
    /// force and whether it slides; stick or slide for the adaptive integrator; whether the integrator
    /// was named in the log.
    spin: Spin,
    spring: f64,
    tangential_force: f64,
    sliding: bool,
    mode: TangentialMode,
    announced: bool,
}

/// Co-Simulation: the wall inputs a step started from and the wall's position and velocity at its end.
/// Inputs the master has not set again since are continued from where the wall got to: the position
/// moved with the velocity, the velocity with the acceleration (an input derivative) when one was given.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct CsWall {
    position_input: f64,
    velocity_input: f64,
    position_end: f64,
    velocity_end: f64,
}

impl CsWall {
    /// The wall a step or an output starts from, given the current inputs.
    fn continued(self, mut wall: WallMotion) -> WallMotion {
        if wall.position == self.position_input {
            wall.position = self.position_end;
        }
        if wall.velocity == self.velocity_input {
            wall.velocity = self.velocity_end;
        }
        wall
    }
}

fn real(values: &[Value], vr: usize) -> f64 {
    values[vr].as_real()
}

impl ParticleWallImpact {
    fn new(u: &UnitInfo) -> ParticleWallImpact {
        ParticleWallImpact {
            variables: u.variables.clone(),
            radius: 0.0,
            sphere: None,
            y: State::default(),
            t: 0.0,
            cs_wall: None,
            me_wall: None,
            derivatives: InputDerivatives::default(),
            events: Vec::new(),
            tangential: None,
            spin: Spin::default(),
            mode: TangentialMode::default(),
            announced: false,
            me_switches: (f64::NAN, 0),
        }
    }

    /// The sphere of the current parameters (law, damping, mass, tolerances) and its tangential contact;
    /// the state is not touched.
    fn build(&self, values: &[Value]) -> Result<(Sphere, f64, Tangential), UnitError> {
        let rate_nominal = real(values, REFS.initial_velocity).abs().max(real(values, REFS.wall_velocity).abs()).max(1e-3);
        let (contact, scene, eff) = contact_parts::build(&self.variables, values, rate_nominal)?;
        if scene.contact_partner != Partner::Wall {
            return Err(UnitError::Variable {
                name: "contact_partner",
                why: "parameter `contact_partner` = \"particle\" is not allowed in ParticleWallImpact: the sphere hits a wall; use \"wall\" (two identical particles: use ContactElement)".into(),
            });
        }
        within(values, REFS.initial_velocity, "initial_velocity", MAX_SPEED, "m/s")?;
        let g = within(values, REFS.gravity, "gravity", MAX_GRAVITY, "m/s2")?;
        let tol = finite(values, REFS.tolerance, "tolerance", "")?;
        if !(1e-14..=1e-2).contains(&tol) {
            return Err(UnitError::Variable {
                name: "tolerance",
                why: format!("parameter `tolerance` = {tol:e} is out of range: allowed [1e-14, 1e-2]"),
            });
        }
        within(values, REFS.wall_velocity, "wall_velocity", MAX_SPEED, "m/s")?;
        let fraction = finite(values, REFS.rayleigh_fraction, "rayleigh_fraction", "")?;
        if !(fraction > 0.0 && fraction <= 1.0) {
            return Err(UnitError::Variable {
                name: "rayleigh_fraction",
                why: format!("parameter `rayleigh_fraction` = {fraction:e} is out of range: allowed (0, 1]"),
            });
        }
        let rayleigh = time_step::rayleigh_time_step(
            scene.particle_radius,
            scene.particle_density,
            scene.particle_shear_modulus(),
            scene.particle_poisson_ratio,
        );
        let solver = solver(values[REFS.solver].as_str(), &contact.law, fraction * rayleigh)?;
        let rolling = finite(values, REFS.rolling_friction, "rolling_friction", "")?;
        if !(0.0..=1e3).contains(&rolling) {
            return Err(UnitError::Variable {
                name: "rolling_friction",
                why: format!("parameter `rolling_friction` = {rolling:e} is out of range: allowed [0, 1e3]"),
            });
        }
        if rolling > 0.0 && !matches!(solver, Solver::Verlet { .. }) {
            return Err(UnitError::Variable {
                name: "rolling_friction",
                why: format!(
                    "parameter `rolling_friction` = {rolling:e} needs solver = \"verlet\": the rolling torque switches with the sign of the spin, which the other integrators do not locate"
                ),
            });
        }
        for (vr, name, max, unit) in [
            (REFS.initial_tangential_velocity, "initial_tangential_velocity", MAX_SPEED, "m/s"),
            (REFS.initial_angular_velocity, "initial_angular_velocity", MAX_SPIN, "rad/s"),
            (REFS.wall_tangential_velocity, "wall_tangential_velocity", MAX_SPEED, "m/s"),
        ] {
            within(values, vr, name, max, unit)?;
        }
        let stiffness = TangentialStiffness::for_model(scene.contact_model.tangential_model(), eff.shear_modulus, eff.youngs_modulus, eff.radius);
        let tangential = Tangential::new(scene.particle_radius, eff.mass, stiffness, scene.friction_coefficient, rolling);
        Ok((Sphere::new(eff.mass, g, contact, solver, tol), scene.particle_radius, tangential))
    }

    /// Whether the sphere moves along the wall or spins, or the wall moves along itself: the oblique
    /// dynamics are needed (else the normal integrators run exactly as without them).
    fn oblique(&self, w_t: f64) -> bool {
        self.spin.velocity != 0.0
            || self.spin.angular_velocity != 0.0
            || w_t != 0.0
            || self.tangential.as_ref().is_some_and(|tg| tg.spring.force.x != 0.0 || tg.force != 0.0)
    }

    /// The wall at the current time: as given (CS, and ME at an input update), or moved on with its
    /// velocity since the inputs were last given (ME, `SeenWall`).
    fn wall(&self, values: &[Value]) -> WallMotion {
        let (position, velocity) = (real(values, REFS.wall_displacement), real(values, REFS.wall_velocity));
        match self.me_wall {
            Some(s) if s.position == position && s.velocity == velocity => WallMotion { t0: s.t, position, velocity },
            _ => WallMotion { t0: self.t, position, velocity },
        }
    }

    /// CS: one step from `t` by `h`, or (`stop_at_event`) to the first change of the contact state in it,
    /// whose time it returns.
    fn step(&mut self, values: &[Value], t: f64, h: f64, stop_at_event: bool) -> Result<Option<f64>, UnitError> {
        let mut wall = self.wall(values);
        wall.t0 = t;
        if let Some(c) = self.cs_wall {
            wall = c.continued(wall);
        }
        let InputDerivatives { velocity, acceleration: a } = self.derivatives;
        if let Some(v) = velocity {
            wall.velocity = v;
        }
        if !((wall.velocity + a * h).abs() <= MAX_SPEED) {
            return Err(UnitError::Variable {
                name: "wall_acceleration",
                why: format!(
                    "the wall's acceleration {a:e} m/s2 over a step of {h:e} s takes its velocity to {:e} m/s; allowed at most {MAX_SPEED:e} m/s",
                    wall.velocity + a * h
                ),
            });
        }
        let w_t = real(values, REFS.wall_tangential_velocity);
        let oblique = self.oblique(w_t);
        let sphere = self.sphere.as_mut().ok_or(UnitError::NotInitialized)?;
        let saved = (sphere.clone(), self.y, self.tangential.clone(), self.spin, self.mode);
        if oblique && !self.announced {
            self.announced = true;
            self.events.push(match sphere.solver {
                Solver::Verlet { step } => format!("t = {t:e} s: tangential motion and spin by velocity Verlet at {step:e} s (the verlet solver)"),
                Solver::Exact => format!(
                    "t = {t:e} s: tangential motion and spin by the oblique adaptive integrator at tolerance {:e}, stick-slip switches located (the exact solver's closed forms cover the normal motion only)",
                    sphere.tolerance
                ),
                Solver::Adaptive => format!("t = {t:e} s: tangential motion and spin by the oblique adaptive integrator at tolerance {:e}, stick-slip switches located", sphere.tolerance),
            });
        }
        // A wall accelerating at a (an input derivative): in the frame that moves with a t^2/2 the wall
        // moves at constant velocity, as the integrators expect, and the sphere feels gravity g + a. The
        // overlap, and so the force and the contact work, are the same in both frames.
        let g = sphere.gravity;
        sphere.gravity = g + a;
        let mut y = self.y;
        let result = if oblique {
            // Early return (FMI 3.0) at a change of the contact state or of `sliding`.
            let tg = self.tangential.as_mut().ok_or(UnitError::NotInitialized)?;
            sphere.follow_jump(&wall, t, &mut y);
            match sphere.solver {
                Solver::Verlet { step } => sphere.advance_oblique_verlet(tg, step, &wall, w_t, t, t + h, &mut y, &mut self.spin, stop_at_event),
                Solver::Exact | Solver::Adaptive => {
                    sphere.advance_oblique_adaptive(tg, &mut self.mode, &wall, w_t, t, t + h, &mut y, &mut self.spin, stop_at_event)
                }
            }
        } else {
            sphere.advance_until(&wall, t, t + h, &mut y, stop_at_event)
        };
        sphere.gravity = g; // as it was, not (g + a) - a
        let event = match result {
            Ok(event) => event,
            Err(e) => {
                // Nothing half-done: the state stays at the start of the step.
                (*sphere, self.y, self.tangential, self.spin, self.mode) = saved;
                return Err(e.into());
            }
        };
        // The step's end: its full length, or the event's time.
        let h = event.map_or(h, |te| te - t);
        let frame = 0.5 * a * h * h;
        y.bottom += frame;
        y.velocity += a * h;
        self.y = y;
        self.t = t + h;
        self.derivatives = InputDerivatives::default();
        self.cs_wall = Some(CsWall {
            position_input: real(values, REFS.wall_displacement),
            velocity_input: real(values, REFS.wall_velocity),
            position_end: wall.at(t + h) + frame,
            velocity_end: wall.velocity + a * h,
        });
        Ok(event)
    }

    /// ME: the continuous states (`impact::OBLIQUE_ME_STATES`): the normal state, the motion along the
    /// wall and the spin, the tangential spring.
    fn me_states(&self) -> [f64; OBLIQUE_ME_STATES] {
        let spring = self.tangential.as_ref().map_or(0.0, |tg| tg.spring.force.x);
        [self.y.bottom, self.y.velocity, self.y.work, self.spin.velocity, self.spin.angular_velocity, spring]
    }

    /// ME: notes inputs that changed since they were last seen, with the current time.
    fn see_inputs(&mut self, values: &[Value]) {
        if let Some(seen) = &mut self.me_wall {
            let (position, velocity) = (real(values, REFS.wall_displacement), real(values, REFS.wall_velocity));
            if seen.position != position || seen.velocity != velocity {
                *seen = SeenWall { position, velocity, t: self.t };
            }
        }
    }
}

/// The integrator the `solver` parameter names for this law.
fn solver(name: &str, law: &AnyLaw, verlet_step: f64) -> Result<Solver, UnitError> {
    match name {
        "auto" if law.is_piecewise_linear() => Ok(Solver::Exact),
        "auto" | "adaptive" => Ok(Solver::Adaptive),
        "exact" if law.is_piecewise_linear() => Ok(Solver::Exact),
        "exact" => Err(UnitError::Variable {
            name: "solver",
            why: format!(
                "parameter `solver` = \"exact\" needs a piecewise-linear contact_model ({}), not \"{}\"; use \"adaptive\" or \"auto\"",
                ModelKind::piecewise_linear_names(),
                law.model().name()
            ),
        }),
        "verlet" => Ok(Solver::Verlet { step: verlet_step }),
        other => {
            Err(UnitError::Variable { name: "solver", why: format!("parameter `solver` = \"{other}\" is not one of {}", Solver::NAMES.join(", ")) })
        }
    }
}

/// A real parameter or input with |x| <= max, or an error naming it and the range.
fn within(values: &[Value], vr: usize, name: &'static str, max: f64, unit: &str) -> Result<f64, UnitError> {
    let x = finite(values, vr, name, unit)?;
    if x.abs() > max {
        return Err(UnitError::Variable { name, why: format!("`{name}` = {x:e} {unit} is out of range: allowed [-{max:e}, {max:e}] {unit}") });
    }
    Ok(x)
}

/// A finite real parameter or input, or an error naming it.
fn finite(values: &[Value], vr: usize, name: &'static str, unit: &str) -> Result<f64, UnitError> {
    let x = real(values, vr);
    if x.is_finite() {
        Ok(x)
    } else {
        Err(UnitError::Variable { name, why: format!("`{name}` = {x} {unit} is not a finite number") })
    }
}

impl Model for ParticleWallImpact {
    fn initialize(&mut self, values: &[Value], t0: f64, model_exchange: bool) -> Result<(), UnitError> {
        let (mut sphere, radius, tangential) = self.build(values)?;
        if model_exchange && tangential.rolling_friction != 0.0 {
            return Err(UnitError::Variable {
                name: "rolling_friction",
                why: format!("`rolling_friction` = {:e}: {ME_NO_ROLLING}", tangential.rolling_friction),
            });
        }
        let gap = finite(values, REFS.initial_gap, "initial_gap", "m")?;
        if gap < 0.0 {
            return Err(UnitError::Variable {
                name: "initial_gap",
                why: format!("parameter `initial_gap` = {gap:e} m is out of range: allowed >= 0 (the sphere starts out of contact)"),
            });
        }
        let w = finite(values, REFS.wall_displacement, "wall_displacement", "m")?;
        let v0 = real(values, REFS.initial_velocity);
        self.t = t0;
        self.y = State::new(w + gap, -v0, 0.0);
        self.radius = radius;
        self.cs_wall = None;
        let wall = WallMotion { t0, position: w, velocity: real(values, REFS.wall_velocity) };
        self.me_wall = model_exchange.then_some(SeenWall { position: wall.position, velocity: wall.velocity, t: t0 });
        // Model Exchange crosses the end of a vertical branch in Event Mode (`Sphere::accept_crossing`).
        sphere.contact.lead_vertical_ends = model_exchange;
        sphere.accept(&wall, t0, &self.y);
        sphere.contact.max_overlap = f64::NEG_INFINITY;
        self.sphere = Some(sphere);
        self.spin = Spin {
            velocity: real(values, REFS.initial_tangential_velocity),
            angular_velocity: real(values, REFS.initial_angular_velocity),
            ..Spin::default()
        };
        self.tangential = Some(tangential);
        self.mode = TangentialMode::default();
        self.announced = false;
        self.me_switches = (f64::NAN, 0);
        self.events.extend(contact_parts::derived_event(&self.variables, values));
        Ok(())
    }

    fn take_events(&mut self) -> Vec<String> {
        std::mem::take(&mut self.events)
    }

    fn compute(&mut self, values: &mut [Value], between_events: bool) {
        self.see_inputs(values);
        let Some(sphere) = &self.sphere else { return };
        let mut wall = self.wall(values);
        if let Some(c) = self.cs_wall {
            wall = c.continued(wall);
        }
        let (alpha, rate) = sphere.overlap(&wall, self.t, &self.y);
        // A wall moved outside Continuous-Time Mode: the outputs the next step or event starts from.
        let walked;
        let c = if !between_events && sphere.jumped(&wall, self.t, &self.y) {
            walked = sphere.contact.walked_to(alpha, rate).0;
            &walked
        } else {
            &sphere.contact
        };
        let f = OUTPUTS.write(values, c, alpha, rate).total();
        values[REFS.sphere_position] = Value::Real(self.y.bottom + self.radius);
        values[REFS.sphere_velocity] = Value::Real(self.y.velocity);
        values[REFS.dissipated_energy] = Value::Real(if self.spin.work != 0.0 { self.y.work + self.spin.work } else { self.y.work });
        values[REFS.sphere_bottom] = Value::Real(self.y.bottom);
        // The derivatives of `Sphere::derivatives`, from the force just evaluated.
        values[REFS.der_bottom] = Value::Real(self.y.velocity);
        values[REFS.der_velocity] = Value::Real(f / sphere.mass - sphere.gravity);
        values[REFS.der_energy] = Value::Real(f * rate);
        let w_t = real(values, REFS.wall_tangential_velocity);
        values[REFS.tangential_velocity] = Value::Real(self.spin.velocity);
        values[REFS.angular_velocity] = Value::Real(self.spin.angular_velocity);
        let (f_t, sliding) = match (&self.tangential, self.me_wall) {
            // Model Exchange: the force at the host's states (CS keeps the force its step ended with).
            (Some(tg), Some(_)) => {
                (sphere.oblique_me_force(tg, &self.mode, &wall, w_t, self.t, &self.me_states()), matches!(self.mode.mode, StickSlip::Slide(_)))
            }
            (Some(tg), None) => (tg.force, tg.sliding),
            (None, _) => (0.0, false),
        };
        values[REFS.tangential_force] = Value::Real(f_t);
        values[REFS.sliding] = Value::Boolean(sliding);
        let x = self.me_states();
        values[REFS.tangential_spring] = Value::Real(x[5]);
        if let Some(tg) = &self.tangential {
            let mut dx = [0.0; OBLIQUE_ME_STATES];
            let power = sphere.oblique_me_derivatives(tg, &self.mode, &wall, w_t, self.t, &x, &mut dx);
            if power != 0.0 {
                values[REFS.der_energy] = Value::Real(f * rate + power);
            }
            values[REFS.der_tangential_velocity] = Value::Real(dx[3]);
            values[REFS.der_angular_velocity] = Value::Real(dx[4]);
            values[REFS.der_tangential_spring] = Value::Real(dx[5]);
        }
        // After a contact, apart and moving away: the direction it leaves in, relative to the wall.
        let away = self.y.velocity - wall.velocity;
        let left = c.max_overlap > 0.0 && !c.accepted.branch.in_contact() && alpha < 0.0 && away > 0.0;
        values[REFS.rebound_angle] = Value::Real(if left { (self.spin.velocity - w_t).atan2(away) } else { 0.0 });
    }

    fn set_time(&mut self, t: f64) {
        self.t = t;
    }

    fn get_states(&self, x: &mut [f64]) {
        x.copy_from_slice(&self.me_states());
    }

    fn set_states(&mut self, x: &[f64]) {
        self.y = State::from_slice(&x[..3]);
        self.spin.velocity = x[3];
        self.spin.angular_velocity = x[4];
        if let Some(tg) = self.tangential.as_mut() {
            tg.spring.force.x = x[5];
        }
    }

    fn derivatives(&mut self, values: &[Value], dx: &mut [f64]) {
        self.see_inputs(values);
        if let (Some(sphere), Some(tg)) = (&self.sphere, &self.tangential) {
            let w_t = real(values, REFS.wall_tangential_velocity);
            let _ = sphere.oblique_me_derivatives(tg, &self.mode, &self.wall(values), w_t, self.t, &self.me_states(), dx);
        }
    }

    fn event_indicators(&mut self, values: &[Value], z: &mut [f64]) {
        self.see_inputs(values);
        if let (Some(sphere), Some(tg)) = (&self.sphere, &self.tangential) {
            let wall = self.wall(values);
            z[..3].copy_from_slice(&sphere.indicators(&wall, self.t, &self.y));
            z[3] = sphere.oblique_me_indicator(tg, &self.mode, &wall, real(values, REFS.wall_tangential_velocity), self.t, &self.me_states());
        }
    }

    fn nominals(&self, x: &mut [f64]) {
        if let Some(s) = &self.sphere {
            let c = &s.contact;
            // The contact work's scale: the larger of the approach's kinetic energy and the work of the
            // contact's own force scale over the overlap scale. A sphere set down on the wall at rest has
            // no kinetic scale, and a nominal from it alone (1e-19 J here) made CVode's error test on
            // the work fail at any step above 1e-13 s.
            let fresh = c.law.initial_history();
            let force_scale = c.law.evaluate(c.alpha_nominal, &fresh).force.abs().max(c.law.pull_off_force(&fresh)).max(s.mass * s.gravity.abs());
            let energy = (0.5 * s.mass * c.rate_nominal * c.rate_nominal).max(force_scale * c.alpha_nominal);
            // The motion along the wall at the approach's speed scale, the spin at that over R, the spring at
            // the contact's force scale. (A spring nominal 1e-4 to 1e-12 of it, tried for the first touch,
            // where the spring and its limit are 1e-14 N: CVode then ran out of steps at rtol 1e-10 on
            // Chung and Ooi's 5 deg impact, or chattered at 1e-6; `oblique_me_event`'s widening pull-in
            // is what settles the first touch.)
            let radius = self.tangential.as_ref().map_or(1.0, |tg| tg.radius);
            x.copy_from_slice(&[c.alpha_nominal, c.rate_nominal, energy, c.rate_nominal, c.rate_nominal / radius, force_scale]);
        } else {
            x.fill(1.0);
        }
    }

    fn accept(&mut self, values: &[Value]) -> EventUpdate {
        self.see_inputs(values);
        let wall = self.wall(values);
        let t = self.t;
        let mut y = self.y;
        let Some(sphere) = self.sphere.as_mut() else { return EventUpdate::default() };
        let before = sphere.contact.accepted;
        let (alpha, _) = sphere.overlap(&wall, t, &y);
        let (switched, crossed) = sphere.accept_crossing(&wall, t, &mut y);
        let after = sphere.contact.accepted;
        self.y = y;
        // The tangential contact as the oblique adaptive integrator settles it at a step.
        let mode_before = self.mode;
        let spring_before = self.tangential.as_ref().map_or(0.0, |tg| tg.spring.force.x);
        let mut x = [y.bottom, y.velocity, y.work, self.spin.velocity, self.spin.angular_velocity, spring_before];
        // Switches closer together than a millionth of the time the sphere takes to cross its nominal
        // overlap are the host's integration error against the hysteresis, not the contact's physics.
        let chatter_window = 1e-6 * sphere.contact.alpha_nominal / sphere.contact.rate_nominal;
        if let Some(tg) = self.tangential.as_mut() {
            let w_t = real(values, REFS.wall_tangential_velocity);
            let repeat = if t - self.me_switches.0 <= chatter_window { self.me_switches.1 } else { 0 };
            sphere.oblique_me_event(tg, &mut self.mode, &wall, w_t, t, &mut x, before.branch.in_contact(), repeat);
            tg.spring.force.x = x[5];
            tg.sliding = matches!(self.mode.mode, StickSlip::Slide(_));
        }
        let tangential_changed = self.mode != mode_before || x[5] != spring_before;
        // A switch, or a switch and back within this event (the spring pulled in at its limit).
        if tangential_changed {
            self.me_switches = if t - self.me_switches.0 <= chatter_window { (t, self.me_switches.1 + 1) } else { (t, 1) };
        }
        let mut message = switched.then(|| {
            let how = if crossed { format!(", crossed to the vertical end in Event Mode (leaves at {:e} m/s)", y.velocity) } else { String::new() };
            format!("t = {t:e} s: branch {:?} -> {:?} at overlap {alpha:e} m{how}", before.branch, after.branch)
        });
        if self.mode != mode_before {
            let line = format!("t = {t:e} s: tangential contact {:?} -> {:?}", mode_before.mode, self.mode.mode);
            message = Some(message.map_or(line.clone(), |m| format!("{m}; {line}")));
        }
        // The right-hand side follows the accepted branch and its history, and the tangential mode: a
        // change of any (or of the states) is a restart for the host's integrator.
        EventUpdate { message, restart: crossed || before.branch != after.branch || before.history != after.history || tangential_changed }
    }

    fn completed_step(&mut self, values: &[Value]) {
        self.see_inputs(values);
        let wall = self.wall(values);
        if let Some(sphere) = self.sphere.as_mut() {
            let (alpha, _) = sphere.overlap(&wall, self.t, &self.y);
            // The work is the state's; only the history is kept.
            sphere.contact.keep_growth(alpha);
        }
    }

    fn do_step(&mut self, values: &[Value], t: f64, h: f64) -> Result<(), UnitError> {
        self.step(values, t, h, false).map(|_| ())
    }

    fn do_step_to_event(&mut self, values: &[Value], t: f64, h: f64) -> Result<Option<f64>, UnitError> {
        self.step(values, t, h, true)
    }

    fn set_input_derivatives(&mut self, derivatives: &[(usize, i32, f64)]) -> Result<(), UnitError> {
        let mut d = self.derivatives;
        for &(vr, order, value) in derivatives {
            let name = &self.variables[vr].name;
            let (max, unit) = match (vr, order) {
                (vr, 1) if vr == REFS.wall_displacement => (MAX_SPEED, "m/s"),
                (vr, 1) if vr == REFS.wall_velocity => (MAX_WALL_ACCELERATION, "m/s2"),
                (vr, 2) if vr == REFS.wall_displacement => (MAX_WALL_ACCELERATION, "m/s2"),
                _ => {
                    return Err(UnitError::Unsupported(format!(
                        "derivative of order {order} of `{name}` is not taken: the wall's velocity is order 1 of `wall_displacement` (or the `wall_velocity` input), its acceleration order 1 of `wall_velocity` or order 2 of `wall_displacement`"
                    )))
                }
            };
            if !(value.is_finite() && value.abs() <= max) {
                return Err(UnitError::Variable {
                    name: if unit == "m/s" { "wall_velocity" } else { "wall_acceleration" },
                    why: format!("derivative of order {order} of `{name}` = {value:e} {unit} is out of range: allowed [-{max:e}, {max:e}] {unit}"),
                });
            }
            if unit == "m/s" {
                d.velocity = Some(value);
            } else {
                d.acceleration = value;
            }
        }
        self.derivatives = d;
        Ok(())
    }

    fn check_set(&self, vr: usize, value: &Value, model_exchange: bool) -> Result<(), String> {
        match value {
            Value::Real(x) if model_exchange && *x != 0.0 && vr == REFS.rolling_friction => Err(format!("{x:e}: {ME_NO_ROLLING}")),
            _ => Ok(()),
        }
    }

    fn save(&self) -> Result<Vec<u8>, UnitError> {
        let Some(s) = &self.sphere else { return Ok(Vec::new()) };
        let core = SnapshotCore {
            y: self.y,
            t: self.t,
            contact: s.contact.memory(),
            last_step: s.last_step,
            cs_wall: self.cs_wall,
            me_wall: self.me_wall,
            derivatives: self.derivatives,
            spin: self.spin,
            spring: self.tangential.as_ref().map_or(0.0, |tg| tg.spring.force.x),
            tangential_force: self.tangential.as_ref().map_or(0.0, |tg| tg.force),
            sliding: self.tangential.as_ref().is_some_and(|tg| tg.sliding),
            mode: self.mode,
            announced: self.announced,
        };
        contact_parts::encode(&Snapshot { core, me_switches: self.me_switches })
    }

    fn restore(&mut self, values: &[Value], bytes: &[u8]) -> Result<(), UnitError> {
        if bytes.is_empty() {
            self.sphere = None;
            return Ok(());
        }
        let (snap, me_switches) = match super::decode::<Snapshot>(bytes) {
            Ok(s) => (s.core, s.me_switches),
            Err(e) => match super::decode::<SnapshotCore>(bytes) {
                Ok(core) => (core, (f64::NAN, 0)),
                Err(_) => return Err(e),
            },
        };
        let (mut sphere, radius, mut tangential) = self.build(values)?;
        // Finite, and a speed no impact of powder reaches (a corrupted state that passed the checksum).
        let spin_ok = [snap.spin.position, snap.spin.work, snap.spring, snap.tangential_force].iter().all(|x| x.is_finite())
            && snap.spin.velocity.abs() <= MAX_SPEED
            && snap.spin.angular_velocity.abs() <= MAX_SPIN;
        if !(snap.y.to_array().iter().all(|x| x.is_finite()) && snap.t.is_finite() && snap.last_step.is_finite() && snap.last_step >= 0.0 && spin_ok)
            || snap.y.velocity.abs() > MAX_SPEED
            || snap.me_wall.is_some_and(|w| !(w.position.is_finite() && w.t.is_finite() && w.velocity.abs() <= MAX_SPEED))
        {
            return Err(UnitError::SavedState(format!(
                "the saved sphere state is not plausible (velocity {:e} m/s; allowed finite and at most {MAX_SPEED:e})",
                snap.y.velocity
            )));
        }
        sphere.contact.remember(snap.contact).map_err(UnitError::SavedState)?;
        sphere.contact.lead_vertical_ends = snap.me_wall.is_some();
        sphere.last_step = snap.last_step;
        self.sphere = Some(sphere);
        self.radius = radius;
        self.y = snap.y;
        self.t = snap.t;
        self.cs_wall = snap.cs_wall;
        self.me_wall = snap.me_wall;
        // The input derivatives set for the next step, like the inputs, are part of the state.
        self.derivatives = snap.derivatives;
        tangential.spring.force.x = snap.spring;
        tangential.force = snap.tangential_force;
        tangential.sliding = snap.sliding;
        self.tangential = Some(tangential);
        self.spin = snap.spin;
        self.mode = snap.mode;
        self.announced = snap.announced;
        self.me_switches = if me_switches.0.is_infinite() { (f64::NAN, 0) } else { me_switches };
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default scene with damping (e = 0.5, beta = 1), the sphere set down on the wall at rest; `settled`
    /// after 2 us (the contact rings at about 8 MHz and decays in 0.1 us).
    fn set_down(gravity: f64) -> (ParticleWallImpact, Vec<Value>) {
        let u = super::super::by_identifier(MODEL_IDENTIFIER).unwrap();
        let mut values = u.start_values();
        values[REFS.initial_gap] = Value::Real(0.0);
        values[REFS.initial_velocity] = Value::Real(0.0);
        values[REFS.gravity] = Value::Real(gravity);
        values[u.vr("restitution_coefficient").unwrap()] = Value::Real(0.5);
        // The contact yields at first touch (adhesion-induced plasticity); Nan's beta = 0.1 after yield
        // would take 20 us to settle.
        values[u.vr("damping_factor_plastic").unwrap()] = Value::Real(1.0);
        let mut m = ParticleWallImpact::new(u);
        m.initialize(&values, 0.0, false).unwrap();
        (m, values)
    }

    fn settled(gravity: f64) -> (ParticleWallImpact, Vec<Value>) {
        let (mut m, values) = set_down(gravity);
        m.do_step(&values, 0.0, 2e-6).unwrap();
        (m, values)
    }

    fn output(m: &mut ParticleWallImpact, values: &mut [Value], vr: usize) -> f64 {
        m.compute(values, false);
        values[vr].as_real()
    }

    #[test]
    fn a_wall_accelerating_at_a_is_gravity_a_in_the_walls_frame() {
        let a = 8e5;
        // From the touch on: the wall accelerates at a under one sphere, the other feels gravity a.
        let (mut moving, mut mv) = set_down(0.0);
        let (mut heavy, mut hv) = set_down(a);
        let (t0, h) = (0.0, 1e-8);
        let v0 = 0.0;
        for i in 0..100 {
            let t = t0 + i as f64 * h;
            // The wall's velocity at the step's start, its acceleration over the step; its position is
            // continued by the unit.
            mv[REFS.wall_velocity] = Value::Real(a * (t - t0));
            moving.set_input_derivatives(&[(REFS.wall_velocity, 1, a)]).unwrap();
            moving.do_step(&mv, t, h).unwrap();
            heavy.do_step(&hv, t, h).unwrap();
            for vr in [REFS.overlap, REFS.force, REFS.dissipated_energy] {
                let (x, y) = (output(&mut moving, &mut mv, vr), output(&mut heavy, &mut hv, vr));
                assert!((x - y).abs() <= 1e-9 * y.abs().max(1e-30), "{} at step {i}: {x:e} vs {y:e}", moving.variables[vr].name);
            }
            let dv = output(&mut moving, &mut mv, REFS.sphere_velocity) - output(&mut heavy, &mut hv, REFS.sphere_velocity) - v0;
            let expected = a * (t + h - t0);
            assert!((dv - expected).abs() <= 1e-9 * expected, "velocity in the wall's frame: {dv:e} vs {expected:e}");
        }
        // In contact, settled and pressed by m a.
        let mass = moving.sphere.as_ref().unwrap().mass;
        let f = output(&mut moving, &mut mv, REFS.force);
        assert!((f - mass * a).abs() < 1e-3 * mass * a, "{f:e} vs m a = {:e}", mass * a);
    }

    /// The maximum deviation of the contact force from m a_w(t) over one period of a harmonic wall
    /// (20 kHz, peak 1e5 m/s^2, starting at rest), stepped at T/1000, relative to m a_max; the first 1 %
    /// of the period (the ring-down of the start) is not counted.
    fn harmonic_force_error(with_acceleration: bool) -> f64 {
        let (mut m, mut values) = settled(0.0);
        let mass = m.sphere.as_ref().unwrap().mass;
        let f0 = output(&mut m, &mut values, REFS.force);
        let (omega, a_max) = (2.0 * std::f64::consts::PI * 2e4, 1e5);
        let amp = a_max / (omega * omega);
        let (t0, h) = (2e-6, 2.0 * std::f64::consts::PI / omega / 1000.0);
        let mut worst: f64 = 0.0;
        for i in 0..1000 {
            let (t, s) = (t0 + i as f64 * h, i as f64 * h);
            // w = A (1 - cos wt): the wall starts at rest where it stood while the sphere settled.
            values[REFS.wall_displacement] = Value::Real(amp * (1.0 - (omega * s).cos()));
            if with_acceleration {
                values[REFS.wall_velocity] = Value::Real(amp * omega * (omega * s).sin());
                m.set_input_derivatives(&[(REFS.wall_velocity, 1, a_max * (omega * s).cos())]).unwrap();
            } else {
                // The secant velocity to the next sample: a continuous, piecewise-linear wall.
                values[REFS.wall_velocity] = Value::Real(amp * ((omega * s).cos() - (omega * (s + h)).cos()) / h);
            }
            m.do_step(&values, t, h).unwrap();
            let wall_acceleration = a_max * (omega * (s + h)).cos();
            let f = output(&mut m, &mut values, REFS.force) - f0;
            if i >= 10 {
                worst = worst.max((f - mass * wall_acceleration).abs() / (mass * a_max));
            }
        }
        worst
    }

    #[test]
    fn a_harmonic_wall_given_its_acceleration_loads_the_contact_quasi_statically() {
        let (with, without) = (harmonic_force_error(true), harmonic_force_error(false));
        // Given the acceleration, the wall's velocity is continuous and the acceleration steps by 0.6 % of
        // its peak per step; without it, the velocity jumps by a h at every step and the stiff contact
        // (8 MHz) rings at a multiple of the load.
        assert!(with < 0.02, "with the acceleration: {with:e} of m a_max");
        assert!(without > 0.2, "without: {without:e} of m a_max");
    }

    #[test]
    fn bad_input_derivatives_are_refused_and_change_nothing() {
        let (mut m, _) = settled(0.0);
        m.set_input_derivatives(&[(REFS.wall_velocity, 1, 5.0)]).unwrap();
        for bad in [
            vec![(REFS.wall_velocity, 1, 7.0), (REFS.wall_displacement, 3, 1.0)],
            vec![(REFS.wall_velocity, 2, 1.0)],
            vec![(REFS.wall_displacement, 2, f64::NAN)],
            vec![(REFS.wall_velocity, 1, 2.0 * MAX_WALL_ACCELERATION)],
        ] {
            let e = m.set_input_derivatives(&bad).unwrap_err().to_string();
            assert!(e.contains("wall_velocity") || e.contains("wall_displacement"), "{e}");
            assert_eq!(m.derivatives, InputDerivatives { velocity: None, acceleration: 5.0 }, "{bad:?}");
        }
        // Order 1 of the displacement is the wall's velocity over the step.
        m.set_input_derivatives(&[(REFS.wall_displacement, 1, 9.0)]).unwrap();
        assert_eq!(m.derivatives, InputDerivatives { velocity: Some(9.0), acceleration: 5.0 });
        let ce = super::super::by_identifier("ContactElement").unwrap();
        let e = (ce.new_model)(ce, None).set_input_derivatives(&[(0, 1, 1.0)]).unwrap_err();
        assert!(e.to_string().contains("canInterpolateInputs is false"), "{e}");
    }
}

#[cfg(test)]
mod derivative_state_tests {
    use super::*;

    fn model() -> (ParticleWallImpact, Vec<Value>) {
        let u = super::super::by_identifier(MODEL_IDENTIFIER).unwrap();
        let mut values = u.start_values();
        values[REFS.initial_gap] = Value::Real(1e-6); // far from the wall: the sphere flies on
        values[REFS.initial_velocity] = Value::Real(0.0);
        values[REFS.gravity] = Value::Real(9.81);
        let mut m = ParticleWallImpact::new(u);
        m.initialize(&values, 0.0, false).unwrap();
        (m, values)
    }

    fn wall_after_step(m: &mut ParticleWallImpact, values: &mut [Value], h: f64) -> f64 {
        m.do_step(values, m.t, h).unwrap();
        m.cs_wall.unwrap().position_end
    }

    #[test]
    fn the_chatter_guards_switch_count_is_saved_and_an_older_state_loads_without_it() {
        let (mut m, _) = model();
        m.me_switches = (1.5e-6, 7);
        let saved = m.save().unwrap();
        let (mut fresh, fresh_values) = model();
        fresh.restore(&fresh_values, &saved).unwrap();
        assert_eq!(fresh.me_switches, (1.5e-6, 7));
        // The same state in the layout saved before the counter was kept.
        let s = m.sphere.as_ref().unwrap();
        let old = contact_parts::encode(&SnapshotCore {
            y: m.y,
            t: m.t,
            contact: s.contact.memory(),
            last_step: s.last_step,
            cs_wall: m.cs_wall,
            me_wall: m.me_wall,
            derivatives: m.derivatives,
            spin: m.spin,
            spring: 0.0,
            tangential_force: 0.0,
            sliding: false,
            mode: m.mode,
            announced: m.announced,
        })
        .unwrap();
        // The nested layout is the older bytes followed by the counter.
        assert!(saved.len() > old.len() && saved.starts_with(&old));
        fresh.restore(&fresh_values, &old).unwrap();
        assert!(fresh.me_switches.0.is_nan() && fresh.me_switches.1 == 0);
        assert_eq!(fresh.y, m.y);
    }

    #[test]
    fn order_1_of_the_displacement_moves_the_wall_at_that_velocity_for_the_step() {
        let (mut m, mut values) = model();
        m.set_input_derivatives(&[(REFS.wall_displacement, 1, 2.0)]).unwrap();
        assert_eq!(wall_after_step(&mut m, &mut values, 1e-6), 2e-6);
        // Then it is gone; the wall, its velocity input not set again, continues at the velocity it had.
        assert_eq!(wall_after_step(&mut m, &mut values, 1e-6), 4e-6);
    }

    #[test]
    fn a_saved_state_keeps_the_derivatives_set_for_the_next_step_and_gravity_stays_exact() {
        let (mut m, mut values) = model();
        m.set_input_derivatives(&[(REFS.wall_velocity, 1, 8e5)]).unwrap();
        let saved = m.save().unwrap();
        let once = wall_after_step(&mut m, &mut values, 1e-6);
        assert_eq!(m.sphere.as_ref().unwrap().gravity, 9.81, "gravity restored to the bit");
        m.restore(&values, &saved).unwrap();
        assert_eq!(wall_after_step(&mut m, &mut values, 1e-6), once, "the restored state steps as the saved one");
        assert!((once - 0.5 * 8e5 * 1e-12).abs() < 1e-22, "{once:e}");
    }

    #[test]
    fn an_acceleration_that_would_take_the_wall_past_the_speed_limit_is_refused_before_the_step() {
        let (mut m, values) = model();
        m.set_input_derivatives(&[(REFS.wall_velocity, 1, 1e12)]).unwrap();
        let before = (m.t, m.y);
        let e = m.do_step(&values, 0.0, 1e-6).unwrap_err().to_string();
        assert!(e.contains("wall_acceleration") || e.contains("m/s"), "{e}");
        assert_eq!((m.t, m.y), before);
    }

    /// The default sphere thrown at 3 m/s and 30 deg (tangential 1.5 m/s), `solver` as given.
    fn oblique(solver: &str) -> (ParticleWallImpact, Vec<Value>) {
        let u = super::super::by_identifier(MODEL_IDENTIFIER).unwrap();
        let mut values = u.start_values();
        values[REFS.initial_velocity] = Value::Real(3.0 * 30f64.to_radians().cos());
        values[REFS.initial_tangential_velocity] = Value::Real(1.5);
        values[REFS.solver] = Value::String(solver.into());
        let mut m = ParticleWallImpact::new(u);
        m.initialize(&values, 0.0, false).unwrap();
        (m, values)
    }

    #[test]
    fn an_oblique_state_saved_mid_contact_restores_to_the_bit() {
        for solver in ["adaptive", "verlet"] {
            let (mut m, mut values) = oblique(solver);
            let h = 2e-9;
            let mut t = 0.0;
            // Into the contact, where the spring and the stick-slip mode carry history.
            while m.sphere.as_ref().unwrap().contact.max_overlap <= 0.0 || t < 2e-8 {
                m.do_step(&values, t, h).unwrap();
                t += h;
            }
            assert!(m.tangential.as_ref().unwrap().force != 0.0, "{solver}: in contact with a tangential force");
            let saved = m.save().unwrap();
            let run = |m: &mut ParticleWallImpact, values: &mut Vec<Value>| {
                for k in 0..100 {
                    m.do_step(values, t + k as f64 * h, h).unwrap();
                }
                m.compute(values, false);
                [REFS.tangential_velocity, REFS.angular_velocity, REFS.tangential_force, REFS.sphere_velocity, REFS.dissipated_energy]
                    .map(|vr| values[vr].as_real())
            };
            let first = run(&mut m, &mut values);
            let (mut fresh, mut fresh_values) = oblique(solver);
            fresh.restore(&fresh_values, &saved).unwrap();
            assert_eq!(run(&mut fresh, &mut fresh_values), first, "{solver}");
            assert!(first[0] < 1.5 && first[1] > 0.0, "{solver}: friction slowed the sphere along the wall and spun it forward: {first:?}");
        }
    }
}
