//! The oblique impact of a sphere on a flat wall, in the plane of its motion: the 2D oblique impact of
//! the DEM benchmarks (Chung and Ooi 2011, Granular Matter 13:643-656, Tests 4-5). Beside the normal
//! dynamics of `sphere.rs` the sphere has a velocity along the wall and a spin.
//!
//! Conventions (docs/models.md, "Oblique impacts"):
//! - z points away from the wall (as in `sphere.rs`), x along the wall in the direction of positive
//!   tangential velocity, y = z x x (so x, y, z are right-handed);
//! - `angular_velocity` omega is the spin about +y; a positive omega rolls the sphere toward +x: rolling
//!   without slip on a wall at rest is v_t = R omega;
//! - the contact point's velocity relative to the wall (the slip) is s = v_t - l omega - w_t, with the
//!   lever l = R - alpha/2 (the bed's, `bed/engine/force_loop.rs`) and w_t the wall's tangential velocity;
//! - Newton and Euler: m dv_t/dt = F_t, I d omega/dt = -l F_t + T_r, with I = 2/5 m R^2 (a solid sphere).
//!
//! The tangential force is the bed's (`bed/kernel.rs`), on the same code path for the Coulomb limit
//! (`law::tangential::TangentialSpring::step`): an incremental spring k_t of the law's tangential model
//! (Mindlin 8 G* a for the Hertz-based laws, 4 G*/E* |k_n| for the linear ones, Tomas's for `tomas`), its
//! Coulomb limit mu N with N the law's `sliding_normal_force`, and viscous damping 2 gamma sqrt(m k_t) s
//! while it sticks (000 Eqs. 22-26). Rolling resistance is EDEM's constant directional torque mu_r |f_n| R
//! against the spin, which stops the spin but never reverses it within a step (as the bed's integrator).
//!
//! Left out by the 2D impact: the spin about the wall normal (twisting) and about the direction of
//! motion, and any motion out of the plane; the wall's own spin.
//!
//! The integrator is velocity Verlet at a fixed step, what DEM codes do: its normal part is `verlet.rs`
//! step for step (so a frictionless impact gives `verlet.rs`'s normal bits), and the tangential spring
//! takes the slip of the half-step velocities, as the bed does.

use super::contact::Contact;
use super::sphere::{Solver, Sphere, State, StepError, WallMotion};
use crate::error::ParamError;
use crate::law::damping::{self, NormalDamping};
use crate::law::params::Effective;
use crate::law::tangential::{TangentialSpring, TangentialStiffness};
use crate::law::{AnyLaw, NormalLaw};
use crate::scene::Scene;
use crate::theory::time_step::rayleigh_time_step;
use nalgebra::Vector3;

/// The tangential and rotational state of the sphere.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Spin {
    /// x: position of the centre along the wall [m].
    pub position: f64,
    /// v_t: velocity of the centre along the wall [m/s].
    pub velocity: f64,
    /// omega: spin about +y, positive rolling toward +x [rad/s].
    pub angular_velocity: f64,
    /// Energy the tangential force and the rolling torque have taken from the sphere's motion along the
    /// wall and its spin [J] (the trapezoidal rule of the step, like the normal work of `State`).
    pub work: f64,
}

/// Where the tangential force acts: its lever from the sphere's centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Lever {
    /// R - alpha/2, the middle of the overlap: the bed's (`bed/engine/force_loop.rs`), the default.
    #[default]
    MidOverlap,
    /// R: LAMMPS's `fix wall/gran` (docs/porting.md); differs from `MidOverlap` by alpha/(2R).
    Radius,
}

/// The tangential contact of the sphere with the wall: its parameters and the spring's history.
#[derive(Debug, Clone, PartialEq)]
pub struct Tangential {
    /// Sphere radius R [m].
    pub radius: f64,
    /// Moment of inertia I = 2/5 m R^2 [kg m^2].
    pub inertia: f64,
    /// The law's tangential stiffness model (`LawInfo::TANGENTIAL`).
    pub stiffness: TangentialStiffness,
    /// Sliding friction coefficient mu [-] (0: no tangential force at all).
    pub friction: f64,
    /// Rolling friction coefficient mu_r [-] (0: no rolling resistance).
    pub rolling_friction: f64,
    /// Where the force acts.
    pub lever: Lever,
    /// The spring: its force along x is the tangential force before damping [N].
    pub spring: TangentialSpring,
    /// Whether the last evaluated force was on the Coulomb limit.
    pub sliding: bool,
    /// Tangential force on the sphere at the end of the last step, damping included [N].
    pub force: f64,
}

impl Tangential {
    /// The tangential contact of a solid sphere of radius `radius` [m] and mass `mass` [kg], with
    /// friction `friction`, rolling friction `rolling_friction` and the law's tangential stiffness; the
    /// spring unloaded.
    pub fn new(radius: f64, mass: f64, stiffness: TangentialStiffness, friction: f64, rolling_friction: f64) -> Tangential {
        Tangential {
            radius,
            inertia: 0.4 * mass * radius * radius,
            stiffness,
            friction,
            rolling_friction,
            lever: Lever::MidOverlap,
            spring: TangentialSpring::default(),
            sliding: false,
            force: 0.0,
        }
    }

    /// The lever l from the centre to where the force acts at overlap `alpha` [m] (`Lever`).
    pub fn lever(&self, alpha: f64) -> f64 {
        match self.lever {
            Lever::MidOverlap => self.radius - 0.5 * alpha.max(0.0),
            Lever::Radius => self.radius,
        }
    }

    /// The slip s = v_t - l omega - w_t of the contact point against the wall [m/s].
    pub fn slip(&self, alpha: f64, spin: &Spin, wall_tangential_velocity: f64) -> f64 {
        spin.velocity - self.lever(alpha) * spin.angular_velocity - wall_tangential_velocity
    }

    /// The tangential force on the sphere [N] after a step of `h` [s] at slip `slip` [m/s], overlap `alpha`
    /// and the sphere's accepted normal history; updates the spring and `sliding`. Out of contact the
    /// spring unloads and the force is 0; with no friction there is no tangential force at all.
    fn evaluate(&mut self, sphere: &Sphere, alpha: f64, slip: f64, h: f64) -> f64 {
        if self.friction == 0.0 {
            return 0.0;
        }
        let Some(load) = self.stiffness.load(&sphere.contact.law, alpha, &sphere.contact.accepted.history) else {
            self.spring = TangentialSpring::default();
            self.sliding = false;
            return 0.0;
        };
        let k_t = load.stiffness;
        let (f, sliding) = self.spring.step(Vector3::new(slip * h, 0.0, 0.0), k_t, self.friction, load.sliding_normal_force);
        self.sliding = sliding;
        if sliding {
            f.x
        } else {
            let d = &sphere.contact.damping;
            f.x - damping::coefficient(d.restitution, d.beta_elastic, d.mass, k_t) * slip
        }
    }

    /// The rolling load mu_r |f_n| [N] at overlap `alpha` (0 out of contact).
    fn rolling_load(&self, sphere: &Sphere, alpha: f64) -> f64 {
        if self.rolling_friction == 0.0 {
            return 0.0;
        }
        let ev = sphere.contact.law.evaluate(alpha, &sphere.contact.accepted.history);
        if ev.branch.in_contact() {
            self.rolling_friction * ev.force.abs()
        } else {
            0.0
        }
    }

    /// Half a kick of the tangential motion and the spin by the force `f_t` [N] and the rolling load
    /// `rolling` [N] over `half` [s]; returns the kinetic energy the rolling brake took [J].
    fn kick(&self, spin: &mut Spin, mass: f64, alpha: f64, f_t: f64, rolling: f64, half: f64) -> f64 {
        spin.velocity += half * f_t / mass;
        spin.angular_velocity -= half * self.lever(alpha) * f_t / self.inertia;
        if rolling > 0.0 {
            let before = spin.angular_velocity;
            let brake = rolling * self.radius * half / self.inertia;
            spin.angular_velocity = if before.abs() > brake { before - brake * before.signum() } else { 0.0 };
            return 0.5 * self.inertia * (before * before - spin.angular_velocity * spin.angular_velocity);
        }
        0.0
    }
}

impl Sphere {
    /// Velocity Verlet over [t0, t_end] for the oblique impact: the normal motion exactly as
    /// `advance_verlet`, the tangential motion and spin of `spin` under `tangential`, the wall moving as
    /// `wall` and along itself at `wall_tangential_velocity` [m/s]. The communication step is cut into equal
    /// steps no longer than `step`. With `stop_at_event` it stops at the end of the first step where the
    /// contact state or `sliding` changed (FMI 3.0 early return) and returns that step's end.
    #[allow(clippy::too_many_arguments)] // the normal and the tangential state, the wall's two motions
    pub fn advance_oblique_verlet(
        &mut self,
        tangential: &mut Tangential,
        step: f64,
        wall: &WallMotion,
        wall_tangential_velocity: f64,
        t0: f64,
        t_end: f64,
        y: &mut State,
        spin: &mut Spin,
        stop_at_event: bool,
    ) -> Result<Option<f64>, StepError> {
        let Some((n, h)) = super::verlet::steps(step, t0, t_end)? else { return Ok(None) };
        let (state0, sliding0) = (self.contact_state(), tangential.sliding);
        let (alpha, rate) = self.overlap(wall, t0, y);
        let mut f = self.contact.law_force(alpha, rate).total();
        let mut alpha = alpha;
        let mut f_t = tangential.force;
        let mut rolling = tangential.rolling_load(self, alpha);
        for i in 0..n {
            let t1 = t0 + (i + 1) as f64 * h;
            let v_half = y.velocity + 0.5 * h * (f / self.mass - self.gravity);
            let mut half = *spin;
            let braked = tangential.kick(&mut half, self.mass, alpha, f_t, rolling, 0.5 * h);
            y.bottom += h * v_half;
            half.position += h * half.velocity;
            let (alpha1, rate1) = (wall.at(t1) - y.bottom, wall.velocity - v_half);
            let f1 = self.contact.law_force(alpha1, rate1).total();
            y.velocity = v_half + 0.5 * h * (f1 / self.mass - self.gravity);
            y.work += 0.5 * (f + f1) * (alpha1 - alpha);
            let slip = tangential.slip(alpha1, &half, wall_tangential_velocity);
            let f_t1 = tangential.evaluate(self, alpha1, slip, h);
            let rolling1 = tangential.rolling_load(self, alpha1);
            *spin = half;
            let braked1 = tangential.kick(spin, self.mass, alpha1, f_t1, rolling1, 0.5 * h);
            // The tangential force's work on the slip (trapezoidal, the scheme's order) and the brake's.
            spin.work -= 0.5 * (f_t + f_t1) * slip * h;
            spin.work += braked + braked1;
            if !(y.bottom.is_finite() && y.velocity.is_finite() && spin.velocity.is_finite() && spin.angular_velocity.is_finite()) {
                return Err(StepError::NotFinite { t: t1 });
            }
            self.contact.accept(alpha1, wall.velocity - y.velocity);
            self.steps += 1;
            if stop_at_event && (self.contact_state() != state0 || tangential.sliding != sliding0) {
                tangential.force = f_t1;
                return Ok(Some(t1));
            }
            (f, alpha, f_t, rolling) = (f1, alpha1, f_t1, rolling1);
        }
        tangential.force = f_t;
        Ok(None)
    }
}

/// The integrator of `impact`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ObliqueSolver {
    /// Velocity Verlet at the step `ImpactOptions::rayleigh_fraction` of the Rayleigh step.
    Verlet,
    /// Dormand-Prince 5(4) at this relative tolerance, landing on the normal branch switches and the
    /// stick-slip switches (`oblique_adaptive.rs`); no rolling friction.
    Adaptive(f64),
}

/// How `impact` runs: the sphere's spin and rolling friction, the lever, the time step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactOptions {
    /// Spin before the impact [rad/s].
    pub angular_velocity: f64,
    /// Rolling friction coefficient mu_r [-].
    pub rolling_friction: f64,
    /// Where the tangential force acts.
    pub lever: Lever,
    /// The time step (Verlet), or the interval at which the outcome is watched (adaptive: the contact
    /// time's resolution), as a fraction of the Rayleigh time step (000 Eq. 71) [-].
    pub rayleigh_fraction: f64,
    /// The integrator.
    pub solver: ObliqueSolver,
}

impl Default for ImpactOptions {
    fn default() -> ImpactOptions {
        ImpactOptions {
            angular_velocity: 0.0,
            rolling_friction: 0.0,
            lever: Lever::MidOverlap,
            rayleigh_fraction: 0.01,
            solver: ObliqueSolver::Verlet,
        }
    }
}

/// One oblique impact of a scene's sphere on its wall, from first touch until it has left.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObliqueOutcome {
    /// Normal velocity before, toward the wall [m/s].
    pub normal_velocity_in: f64,
    /// Tangential velocity of the centre before [m/s].
    pub tangential_velocity_in: f64,
    /// Spin before [rad/s].
    pub angular_velocity_in: f64,
    /// Normal velocity after, away from the wall [m/s].
    pub normal_velocity_out: f64,
    /// Tangential velocity of the centre after [m/s].
    pub tangential_velocity_out: f64,
    /// Spin after [rad/s].
    pub angular_velocity_out: f64,
    /// Largest overlap [m].
    pub max_overlap: f64,
    /// Largest normal contact force, law and damping [N].
    pub max_force: f64,
    /// Time in contact [s], to one step of `ImpactOptions::rayleigh_fraction` of the Rayleigh step.
    pub contact_time: f64,
    /// Steps of `ImpactOptions::rayleigh_fraction` of the Rayleigh step in contact.
    pub steps: u64,
    /// Whether the contact slid (sat on the Coulomb limit) at every step it carried force.
    pub slid_throughout: bool,
    /// How the contact broke: sliding (on the Coulomb limit at its last step in contact) or sticking (the
    /// contact point held to the wall while it broke). Without adhesion the limit mu N falls to 0 as
    /// the contact ends, so a sheared contact breaks sliding; an adhesive limit mu (N + 2 f_c) need not.
    pub sliding_at_separation: bool,
    /// Energy dissipated: normal and tangential contact work [J].
    pub dissipated_energy: f64,
    /// Kinetic energy lost, translation and spin [J] (equal to `dissipated_energy` to the scheme's error).
    pub kinetic_energy_lost: f64,
}

impl ObliqueOutcome {
    /// Tangential restitution v_t,out / v_t,in of the centre [-].
    pub fn tangential_restitution(&self) -> f64 {
        self.tangential_velocity_out / self.tangential_velocity_in
    }

    /// Angle of the centre's rebound from the wall normal, atan(v_t,out / v_n,out) [rad].
    pub fn rebound_angle(&self) -> f64 {
        self.tangential_velocity_out.atan2(self.normal_velocity_out)
    }
}

/// Why an oblique impact could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ObliqueError {
    /// The scene's parameters.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// The integrator.
    #[error(transparent)]
    Step(#[from] StepError),
    /// The sphere had not left the wall (an adhesive law holds it): where it is then.
    #[error("the sphere has not left the wall after {:e} s: it sticks, {}", .0.time, .0.mechanism())]
    Sticks(Held),
}

/// A sphere the adhesion holds on the wall, when the impact gives up watching it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Held {
    /// Time since the start [s].
    pub time: f64,
    /// Tangential velocity of the centre [m/s].
    pub tangential_velocity: f64,
    /// Spin [rad/s].
    pub angular_velocity: f64,
    /// The contact on its Coulomb limit: the sphere slides along the wall; otherwise it rolls (or rests).
    pub sliding: bool,
}

impl Held {
    /// "sliding along the wall", "rolling along the wall" or "at rest on the wall".
    pub fn mechanism(&self) -> &'static str {
        if self.sliding {
            "sliding along the wall"
        } else if self.tangential_velocity != 0.0 || self.angular_velocity != 0.0 {
            "rolling along the wall"
        } else {
            "at rest on the wall"
        }
    }
}

/// The oblique impact of the scene's sphere on its wall at normal velocity `normal_velocity` [m/s] (toward
/// the wall) and tangential velocity `tangential_velocity` [m/s], no gravity, by velocity Verlet.
pub fn impact(scene: &Scene, normal_velocity: f64, tangential_velocity: f64, options: &ImpactOptions) -> Result<ObliqueOutcome, ObliqueError> {
    let ImpactOptions { angular_velocity, rolling_friction, lever, rayleigh_fraction, solver } = *options;
    for (name, value, ok) in [
        ("normal_velocity", normal_velocity, normal_velocity > 0.0 && normal_velocity.is_finite()),
        ("tangential_velocity", tangential_velocity, tangential_velocity.is_finite()),
        ("angular_velocity", angular_velocity, angular_velocity.is_finite()),
        ("rolling_friction", rolling_friction, (0.0..=1e3).contains(&rolling_friction)),
        ("rayleigh_fraction", rayleigh_fraction, rayleigh_fraction > 0.0 && rayleigh_fraction <= 1.0),
    ] {
        if !ok {
            let allowed = match name {
                "normal_velocity" => "(0, inf) m/s",
                "rolling_friction" => "[0, 1e3]",
                "rayleigh_fraction" => "(0, 1]",
                _ => "a finite number",
            };
            return Err(ParamError::OutOfRange { name, value, allowed: allowed.into() }.into());
        }
    }
    if let ObliqueSolver::Adaptive(tol) = solver {
        if !(1e-14..=1e-2).contains(&tol) {
            return Err(ParamError::OutOfRange { name: "tolerance", value: tol, allowed: "[1e-14, 1e-2]".into() }.into());
        }
        if rolling_friction != 0.0 {
            return Err(ParamError::Inconsistent {
                name: "rolling_friction",
                why: "the adaptive integrator has no rolling friction (a torque that switches with the spin's sign); use the verlet integrator"
                    .into(),
            }
            .into());
        }
    }
    let law = AnyLaw::from_scene(scene)?;
    let eff = Effective::from_scene(scene)?;
    let damping = NormalDamping::from_scene(scene, eff.mass);
    let h = rayleigh_fraction
        * rayleigh_time_step(scene.particle_radius, scene.particle_density, scene.particle_shear_modulus(), scene.particle_poisson_ratio);
    // Start one step before the first touch, on the way in.
    let gap = normal_velocity * h;
    let mut contact = Contact::new(law, damping, 1e-3 * eff.radius, normal_velocity);
    contact.accept(-gap, normal_velocity);
    let tolerance = if let ObliqueSolver::Adaptive(tol) = solver { tol } else { 1e-8 };
    let mut sphere = Sphere::new(eff.mass, 0.0, contact, Solver::Verlet { step: h }, tolerance);
    let mut mode = super::oblique_adaptive::TangentialMode::default();
    let stiffness = TangentialStiffness::for_model(scene.contact_model.tangential_model(), eff.shear_modulus, eff.youngs_modulus, eff.radius);
    let mut tangential = Tangential::new(scene.particle_radius, eff.mass, stiffness, scene.friction_coefficient, rolling_friction);
    tangential.lever = lever;
    let mut y = State::new(gap, -normal_velocity, 0.0);
    let mut spin = Spin { velocity: tangential_velocity, angular_velocity, ..Spin::default() };
    let wall = WallMotion { t0: 0.0, position: 0.0, velocity: 0.0 };
    let inertia = tangential.inertia;
    let kinetic = |y: &State, s: &Spin| {
        0.5 * eff.mass * (y.velocity * y.velocity + s.velocity * s.velocity) + 0.5 * inertia * s.angular_velocity * s.angular_velocity
    };
    let before = kinetic(&y, &spin);
    let (mut t, mut max_overlap, mut max_force, mut slid_throughout, mut contact_steps) = (0.0, 0.0f64, 0.0f64, true, 0u64);
    let mut sliding_at_separation = false;
    // A generous bound on the contact time: a thousand Rayleigh steps (Hertz's contact time is 4-15 of
    // them from 4 m/s down to 1 cm/s); a sphere still held then has stuck.
    let t_max = 1e3 * h / rayleigh_fraction;
    loop {
        match solver {
            ObliqueSolver::Verlet => sphere.advance_oblique_verlet(&mut tangential, h, &wall, 0.0, t, t + h, &mut y, &mut spin, false).map(|_| ())?,
            ObliqueSolver::Adaptive(_) => {
                sphere.advance_oblique_adaptive(&mut tangential, &mut mode, &wall, 0.0, t, t + h, &mut y, &mut spin, false).map(|_| ())?
            }
        }
        t += h;
        let alpha = -y.bottom;
        max_overlap = max_overlap.max(alpha);
        max_force = max_force.max(sphere.contact.force(alpha, -y.velocity).total());
        if sphere.contact.accepted.branch.in_contact() {
            contact_steps += 1;
            sliding_at_separation = tangential.sliding;
            if tangential.friction > 0.0 && tangential.spring.force.x != 0.0 {
                slid_throughout &= tangential.sliding;
            }
        }
        if alpha < 0.0 && y.velocity > 0.0 && !sphere.contact.accepted.branch.in_contact() && sphere.contact.force(alpha, -y.velocity).total() == 0.0
        {
            break;
        }
        if t > t_max {
            return Err(ObliqueError::Sticks(Held {
                time: t,
                tangential_velocity: spin.velocity,
                angular_velocity: spin.angular_velocity,
                sliding: tangential.sliding,
            }));
        }
    }
    let after = kinetic(&y, &spin);
    Ok(ObliqueOutcome {
        normal_velocity_in: normal_velocity,
        tangential_velocity_in: tangential_velocity,
        angular_velocity_in: angular_velocity,
        normal_velocity_out: y.velocity,
        tangential_velocity_out: spin.velocity,
        angular_velocity_out: spin.angular_velocity,
        max_overlap,
        max_force,
        contact_time: contact_steps as f64 * h,
        steps: contact_steps,
        slid_throughout,
        sliding_at_separation,
        dissipated_energy: y.work + spin.work,
        kinetic_energy_lost: before - after,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::{Contact, Solver};
    use crate::law::damping::NormalDamping;
    use crate::law::params::Effective;
    use crate::law::AnyLaw;
    use crate::scene::{ModelKind, Scene};

    /// A sphere of the scene over a rigid wall, `gap` [m] above it, falling at `v_n` [m/s] with tangential
    /// velocity `v_t` [m/s] and spin `omega` [rad/s], no gravity.
    fn setup(scene: &Scene, v_n: f64, v_t: f64, omega: f64, gap: f64) -> (Sphere, Tangential, State, Spin) {
        let law = AnyLaw::from_scene(scene).unwrap();
        let eff = Effective::from_scene(scene).unwrap();
        let damping = NormalDamping::from_scene(scene, eff.mass);
        let mut contact = Contact::new(law, damping, 1e-3 * eff.radius, v_n);
        contact.accept(-gap, v_n);
        let sphere = Sphere::new(eff.mass, 0.0, contact, Solver::Verlet { step: 1.0 }, 1e-8);
        let stiffness = TangentialStiffness::for_model(scene.contact_model.tangential_model(), eff.shear_modulus, eff.youngs_modulus, eff.radius);
        let tangential = Tangential::new(scene.particle_radius, eff.mass, stiffness, scene.friction_coefficient, 0.0);
        (sphere, tangential, State::new(gap, -v_n, 0.0), Spin { velocity: v_t, angular_velocity: omega, ..Spin::default() })
    }

    const COMMUNICATION_STEPS: f64 = 200.0;

    /// Runs until the sphere has left the wall (or `t_max`), in communication steps of `dt_comm`.
    fn run(s: &mut Sphere, t: &mut Tangential, y: &mut State, spin: &mut Spin, h: f64, t_max: f64) {
        let wall = WallMotion { t0: 0.0, position: 0.0, velocity: 0.0 };
        let dt_comm = COMMUNICATION_STEPS * h;
        let mut time = 0.0;
        let mut touched = false;
        while time < t_max {
            s.advance_oblique_verlet(t, h, &wall, 0.0, time, time + dt_comm, y, spin, false).unwrap();
            time += dt_comm;
            touched |= y.bottom < 0.0;
            if touched && y.bottom > 0.0 && y.velocity > 0.0 {
                return;
            }
        }
        panic!("the sphere did not leave the wall in {t_max} s");
    }

    /// Chung and Ooi's Test 4 material: aluminium oxide on a rigid wall.
    fn alumina(model: ModelKind) -> Scene {
        let mut s = Scene::new(model, 2.5e-3, 4000.0, 3.8e11, 0.23);
        s.friction_coefficient = 0.092;
        s.restitution_coefficient = 1.0;
        // The linear spring: Hertz's secant stiffness at the test's largest overlap, about 1e7 N/m.
        s.laws.linear.linear_stiffness = Some(1e7);
        s
    }

    #[test]
    fn a_frictionless_wall_leaves_the_tangential_velocity_and_gives_no_spin() {
        for model in [ModelKind::Hertz, ModelKind::Linear] {
            let mut scene = alumina(model);
            scene.friction_coefficient = 0.0;
            let (mut s, mut t, mut y, mut spin) = setup(&scene, 3.0, 2.0, 0.0, 1e-6);
            // The normal motion alone, by advance_verlet, for the bits.
            let (mut s0, _, mut y0, _) = setup(&scene, 3.0, 2.0, 0.0, 1e-6);
            run(&mut s, &mut t, &mut y, &mut spin, 1e-9, 1e-3);
            let wall = WallMotion { t0: 0.0, position: 0.0, velocity: 0.0 };
            let steps = s.steps;
            let mut time = 0.0;
            for _ in 0..steps / COMMUNICATION_STEPS as u64 {
                s0.advance_verlet(1e-9, &wall, time, time + COMMUNICATION_STEPS * 1e-9, &mut y0, false).unwrap();
                time += COMMUNICATION_STEPS * 1e-9;
            }
            assert_eq!(spin.velocity, 2.0, "{model:?}");
            assert_eq!(spin.angular_velocity, 0.0, "{model:?}");
            assert_eq!(spin.work, 0.0);
            assert_eq!(y, y0, "{model:?}: the normal motion is advance_verlet's");
        }
    }

    #[test]
    fn gross_sliding_takes_mu_1_plus_e_v_n_and_spins_at_2_5_over_r() {
        // A steep incidence slides throughout: Delta v_t = mu (1 + e_n) v_n, and, since one force drives
        // both, omega R = 5/2 Delta v_t for a solid sphere. The linear law with a constant damping
        // coefficient ends its contact at alpha = 0, so its damping impulse is zero and the Coulomb limit
        // (the law's force) carries the whole normal impulse.
        let mut scene = alumina(ModelKind::Linear);
        scene.restitution_coefficient = 0.7;
        let (v_n, v_t) = (1.0, 5.0);
        let (mut s, mut t, mut y, mut spin) = setup(&scene, v_n, v_t, 0.0, 1e-7);
        run(&mut s, &mut t, &mut y, &mut spin, 1e-10, 1e-3);
        let e_n = y.velocity / v_n;
        let dv = v_t - spin.velocity;
        let expected = scene.friction_coefficient * (1.0 + e_n) * v_n;
        assert!((dv / expected - 1.0).abs() < 1e-3, "Delta v_t {dv} against mu (1 + e) v_n {expected} (e_n {e_n})");
        let lever_ratio = spin.angular_velocity * scene.particle_radius / dv;
        assert!((lever_ratio / 2.5 - 1.0).abs() < 1e-3, "omega R / Delta v_t = {lever_ratio}");
    }

    #[test]
    fn the_energy_taken_is_the_kinetic_energy_lost() {
        // An elastic Hertz-Mindlin impact: what the sphere loses (translation and spin) is what the
        // tangential contact took, to the scheme's error.
        let scene = alumina(ModelKind::Hertz);
        for angle in [10.0f64, 30.0, 60.0] {
            let (v_n, v_t) = (3.9 * angle.to_radians().cos(), 3.9 * angle.to_radians().sin());
            let (mut s, mut t, mut y, mut spin) = setup(&scene, v_n, v_t, 0.0, 1e-7);
            let m = s.mass;
            let before = 0.5 * m * (v_n * v_n + v_t * v_t);
            run(&mut s, &mut t, &mut y, &mut spin, 5e-10, 1e-3);
            let after = 0.5 * m * (y.velocity.powi(2) + spin.velocity.powi(2)) + 0.5 * t.inertia * spin.angular_velocity.powi(2);
            let lost = before - after;
            let taken = spin.work + y.work;
            assert!(lost > 0.0, "friction dissipates at {angle} deg");
            assert!((taken - lost).abs() < 2e-3 * lost + 1e-6 * before, "at {angle} deg: taken {taken:e} J, lost {lost:e} J");
        }
    }
}
