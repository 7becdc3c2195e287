//! What each pair of species (and each species against each wall) needs in the force loop: the normal
//! law with its parameters for that pair's R* and m*, the damping coefficients (`000` Eqs. 24-26), the
//! tangential stiffness model and Coulomb limit (`000` Eqs. 22-23), and the rolling friction coefficient
//! (`004` Table 5.3).
//!
//! Each pair is mixed from the scene once parsed, as LAMMPS's `mix_coeffs` does: the effective
//! properties of the scene (E*, G*, p_y, Gamma) with the pair's own R* = R1 R2 / (R1 + R2) and
//! m* = m1 m2 / (m1 + m2) (a wall: the particle's radius against the wall's curvature, and its mass).
//! Every law and correlation of the seeds depends on the radii only through R* and on the masses only
//! through m* (000 Sec. 3; 004 Eq. 3.15), and each law is built from these pair properties
//! (`AnyLaw::from_pair`).

use super::engine::LaneLaw;
use crate::error::ParamError;
use crate::law::damping::{gamma, NormalDamping};
use crate::law::params::Effective;
use crate::law::tangential::TangentialStiffness;
use crate::law::{AnyLaw, Branch, NormalLaw};
use crate::scene::Scene;
use serde::{de::DeserializeOwned, Serialize};
use serde_json::{Map, Value};

/// A normal law the bed can step: every law of the core.
pub trait BedLaw: NormalLaw<History: Send + Sync + Serialize + DeserializeOwned> + LaneLaw + Clone + Send + Sync + 'static {
    fn from_any(law: AnyLaw) -> Option<Self>;
}

/// Makes every law of `law_table!` a `BedLaw`.
macro_rules! bed_law {
    ($d:tt; $($variant:ident, $module:ident, $ty:ty, $pl:literal;)*) => {
        $(impl BedLaw for $ty {
            fn from_any(law: AnyLaw) -> Option<Self> {
                match law {
                    AnyLaw::$variant(l) => Some(l),
                    _ => None,
                }
            }
        }
        no_lanes!($variant, $ty);)*
    };
}

/// The laws without an evaluation of their own on lanes (`engine::lanes`) take the trait's default: the
/// law once per lane, the rest of the contact on lanes. The others implement it in `engine/lanes/`.
macro_rules! no_lanes {
    (PashaSimplified, $ty:ty) => {};
    (Linear, $ty:ty) => {};
    (Hertz, $ty:ty) => {};
    (Jkr, $ty:ty) => {};
    (JkrModified, $ty:ty) => {};
    (Nan, $ty:ty) => {};
    ($variant:ident, $ty:ty) => {
        #[cfg(target_arch = "x86_64")]
        impl LaneLaw for $ty {}
    };
}

crate::law_table!(bed_law; $);

/// The template every pair of one kind of contact (particle-particle or particle-wall) is built from: the
/// bed's contact scene, parsed once, with the effective properties (E*, G*, p_y, Gamma) every pair
/// shares; each pair of species sets its own R* and m* (`Interaction::particle_pair`, `particle_wall`).
#[derive(Debug, Clone)]
pub struct ContactTemplate {
    pub scene: Scene,
    pub effective: Effective,
}

impl ContactTemplate {
    /// The particle-particle scene of a bed (`contact_partner` particle). `radius` and `density` are
    /// any species', for the checks of the scene; the pairs set their own R* and m*.
    pub fn particle(map: &Map<String, Value>, radius: f64, density: f64) -> Result<ContactTemplate, ParamError> {
        ContactTemplate::with_partner(map, "particle", radius, density)
    }

    /// The particle-wall scene of a bed (`contact_partner` wall).
    pub fn wall(map: &Map<String, Value>, radius: f64, density: f64) -> Result<ContactTemplate, ParamError> {
        ContactTemplate::with_partner(map, "wall", radius, density)
    }

    fn with_partner(map: &Map<String, Value>, partner: &str, radius: f64, density: f64) -> Result<ContactTemplate, ParamError> {
        let mut map = map.clone();
        map.insert("contact_partner".into(), Value::from(partner));
        map.insert("particle_radius".into(), Value::from(radius));
        map.insert("particle_density".into(), Value::from(density));
        let scene = Scene::from_map(&map)?;
        let effective = Effective::from_scene(&scene)?;
        Ok(ContactTemplate { scene, effective })
    }
}

/// The parameters of one pair of species, or of one species against one wall.
#[derive(Debug, Clone)]
pub struct Interaction<L: BedLaw> {
    pub law: L,
    /// The history of a contact that has never touched.
    pub initial: L::History,
    /// The largest separation (negative overlap) at which a contact of this pair can still carry force
    /// [m]: the JKR and Nan necks, the Tomas attraction range. Beyond it the force loop skips the pair.
    pub reach: f64,
    /// 2 gamma(e, beta) sqrt(m*) before and after yield: the damping coefficient is this times sqrt(k_n)
    /// (000 Eqs. 24-26) [sqrt(kg)].
    pub damping_elastic: f64,
    pub damping_plastic: f64,
    pub tangential: TangentialStiffness,
    /// sqrt(k_t / k_n) where that ratio is the same at every overlap for this pair (k_n the damping
    /// stiffness): then the tangential damping needs no square root of its own. Found by probing.
    pub tangential_root_ratio: Option<f64>,
    /// Sliding friction coefficient mu [-].
    pub friction: f64,
    /// Rolling friction coefficient mu_r [-] (constant directional torque mu_r |F_n| R, EDEM's model).
    pub rolling_friction: f64,
    /// m* [kg] and R* [m], for the stability limit and the docs.
    pub mass: f64,
    pub radius: f64,
}

impl<L: BedLaw> Interaction<L> {
    /// Builds the interaction of a scene's law for a pair of these effective properties.
    fn from_pair(scene: &Scene, pair: &Effective, rolling_friction: f64) -> Result<Interaction<L>, ParamError> {
        let any = AnyLaw::from_pair(scene.contact_model, pair, &scene.laws)?;
        let model = any.model();
        let law = L::from_any(any).ok_or_else(|| ParamError::Inconsistent {
            name: "contact_model",
            why: format!("the particle-wall law must be of the same kind as the particle-particle law ({model:?} given)"),
        })?;
        let (radius, mass) = (pair.radius, pair.mass);
        let damping = NormalDamping::from_scene(scene, mass);
        let initial = law.initial_history();
        let mut it = Interaction {
            law,
            initial,
            reach: 0.0,
            damping_elastic: 2.0 * gamma(damping.restitution, damping.beta_elastic) * mass.sqrt(),
            damping_plastic: 2.0 * gamma(damping.restitution, damping.beta_plastic) * mass.sqrt(),
            tangential: TangentialStiffness::for_model(model.tangential_model(), pair.shear_modulus, pair.youngs_modulus, radius),
            tangential_root_ratio: None,
            friction: scene.friction_coefficient,
            rolling_friction,
            mass,
            radius,
        };
        it.reach = it.probe_reach();
        it.tangential_root_ratio = it.probe_tangential_ratio();
        Ok(it)
    }

    /// The interaction of two particles of radii and masses (r1, m1), (r2, m2) under a particle-particle
    /// scene (`ContactTemplate::particle`).
    pub fn particle_pair(base: &ContactTemplate, r1: f64, m1: f64, r2: f64, m2: f64, rolling: f64) -> Result<Interaction<L>, ParamError> {
        let pair = Effective { radius: r1 * r2 / (r1 + r2), mass: m1 * m2 / (m1 + m2), ..base.effective };
        Interaction::from_pair(&base.scene, &pair, rolling)
    }

    /// The interaction of a particle (r, m) with a wall whose surface has radius of curvature
    /// `wall_radius` (convex, the indenter) or none (plane, and the die's inside, whose curvature
    /// 1/19.5 mm is neglected beside the particle's), under a particle-wall scene (`ContactTemplate::wall`).
    pub fn particle_wall(base: &ContactTemplate, r: f64, m: f64, wall_radius: Option<f64>, rolling: f64) -> Result<Interaction<L>, ParamError> {
        let radius = match wall_radius {
            Some(rw) => r * rw / (r + rw),
            None => r,
        };
        let pair = Effective { radius, mass: m, ..base.effective };
        Interaction::from_pair(&base.scene, &pair, rolling)
    }

    /// Follows the law along loading to a set of peak overlaps and back along its unloading branches
    /// (each evaluation names the lower end of its branch) until the contact lets go; the reach is the
    /// largest separation at which any of these paths still carried force, with a 10 % margin.
    fn probe_reach(&self) -> f64 {
        let mut reach: f64 = 0.0;
        for peak in [1e-6, 1e-4, 1e-3, 1e-2, 5e-2] {
            let alpha_peak = peak * self.radius;
            let mut h = self.initial;
            for k in 1..=50 {
                h = self.law.evaluate(alpha_peak * k as f64 / 50.0, &h).history;
            }
            let mut alpha = alpha_peak;
            for _ in 0..64 {
                let ev = self.law.evaluate(alpha, &h);
                h = ev.history;
                let acts = ev.branch.in_contact() || ev.branch == Branch::Attraction;
                if !acts || !ev.lower.is_finite() {
                    break;
                }
                reach = reach.max(-ev.lower);
                alpha = ev.lower - 1e-9 * self.radius;
            }
        }
        1.1 * reach.max(0.0)
    }

    /// sqrt(k_t / k_n) if it is one constant along loading and unloading (to 1e-12), else None.
    fn probe_tangential_ratio(&self) -> Option<f64> {
        let mut h = self.initial;
        let mut ratio: Option<f64> = None;
        let path = (1..=40).map(|k| k as f64 / 40.0).chain((0..40).map(|k| 1.0 - k as f64 / 40.0 * 0.9));
        for x in path {
            let alpha = 1e-2 * self.radius * x;
            let (ev, k_damp, a) = self.law.evaluate_with_radius(alpha, &h);
            h = ev.history;
            if !ev.branch.in_contact() || !(k_damp > 0.0) {
                continue;
            }
            let load = self.law.sliding_normal_force(ev.force, alpha, &h);
            let q = self.tangential.at(alpha, ev.stiffness, load, self.law.mindlin_radius(alpha, &h, a)) / k_damp.abs();
            match ratio {
                None => ratio = Some(q),
                Some(r) if ((q - r) / r).abs() <= 1e-12 => {}
                Some(_) => return None,
            }
        }
        ratio.filter(|r| r.is_finite() && *r > 0.0).map(f64::sqrt)
    }
}
