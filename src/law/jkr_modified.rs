//! The EDEM-style modified JKR law (`004` Sec. 5.1.1, Fig. 5.1): the JKR curve for alpha > 0 only.
//! At contact the force drops to -8/9 f_c as in JKR; on unloading the contact breaks as soon as the
//! overlap is zero, so the extra adhesion work of JKR below alpha = 0 is never done. No history.
//!
//! `jkr_friction_limit` chooses the normal force of the Coulomb limit: `pull_off`, F_n + 2 f_c (Thornton
//! and Yin's limit for adhesive contacts, 004 Eq. 3.49, as the `jkr` law), or `repulsive`, the repulsive
//! (Hertz) part of the JKR force 4 E* a^3 / (3 R*), which is how EDEM's JKR cohesion limits its friction
//! (its user manual: "it depends on the positive repulsive part of JKR normal force"). 004 ran its
//! Ch. 5 beds in EDEM. At zero net force the repulsive part is 4 f_c, twice the pull-off reading's 2 f_c,
//! and it grows with the contact (docs/models.md).

use super::jkr::{on_curve_at, JkrCurve};
use super::params::Effective;
use super::tangential::TangentialModel;
use super::{Branch, Evaluation, NormalLaw};
use super::{LawInfo, LawOptions};
use crate::error::ParamError;
use crate::vocabulary::Range;

crate::choice_enum! {
    /// The normal force a modified JKR contact's Coulomb limit is proportional to.
    pub enum JkrFrictionLimit {
        /// F_n + 2 f_c (004 Eq. 3.49, Thornton and Yin; the `jkr` law's).
        PullOff = "pull_off",
        /// The repulsive part of the JKR force, 4 E* a^3 / (3 R*) (EDEM's JKR cohesion).
        Repulsive = "repulsive",
    }
}

crate::choice_enum! {
    /// The radius r of a modified JKR contact's damping stiffness 2 E* r and Mindlin's 8 G* r.
    pub enum JkrStiffnessRadius {
        /// The JKR contact radius a (the `jkr` law's).
        Contact = "contact",
        /// Hertz's sqrt(R* alpha) at the same overlap (EDEM's JKR cohesion, whose manual computes the
        /// tangential spring and both dissipations as its Hertz-Mindlin model does).
        Hertz = "hertz",
    }
}

crate::scene_options! {
    /// The modified JKR law's own scene keys.
    pub struct JkrModifiedOptions {
        jkr_friction_limit: choice(JkrFrictionLimit::PullOff), "-", Range::Names, "the normal force of a jkr_modified contact's Coulomb limit mu N: pull_off, N = F_n + 2 f_c (004 Eq. 3.49), or repulsive, N = 4 E* a^3/(3 R*), the Hertz part of the JKR force (EDEM's JKR cohesion, with which 004 ran Ch. 5)";
        jkr_stiffness_radius: choice(JkrStiffnessRadius::Contact), "-", Range::Names, "the radius r of a jkr_modified contact's damping stiffness 2 E* r and Mindlin's tangential stiffness 8 G* r: contact, the JKR contact radius a, or hertz, sqrt(R* alpha), Hertz-Mindlin's at the same overlap (EDEM's JKR cohesion; with EDEM's damping also set damping_factor_elastic = (5/6)^(1/2) = 0.9129). hertz runs the scalar pair loop";
    }
}

/// The modified JKR law of one contact pair (the module documentation says which equations).
#[derive(Debug, Clone, PartialEq)]
pub struct JkrModified {
    /// The JKR curve of R*.
    pub curve: JkrCurve,
    /// The normal force of the Coulomb limit (`jkr_friction_limit`).
    pub friction_limit: JkrFrictionLimit,
    /// The radius of the damping and Mindlin stiffnesses (`jkr_stiffness_radius`).
    pub stiffness_radius: JkrStiffnessRadius,
}

impl JkrModified {
    /// The law of reduced radius R* [m], effective modulus E* [Pa] and interface energy Gamma [J/m^2],
    /// with the `pull_off` friction limit and the `contact` stiffness radius.
    pub fn new(radius: f64, youngs_modulus: f64, surface_energy: f64) -> JkrModified {
        JkrModified::with_friction_limit(radius, youngs_modulus, surface_energy, JkrFrictionLimit::PullOff)
    }

    /// `new` with the friction limit chosen; the stiffness radius is `contact`.
    pub fn with_friction_limit(radius: f64, youngs_modulus: f64, surface_energy: f64, friction_limit: JkrFrictionLimit) -> JkrModified {
        JkrModified { curve: JkrCurve::new(radius, youngs_modulus, surface_energy), friction_limit, stiffness_radius: JkrStiffnessRadius::Contact }
    }

    /// The damping stiffness 2 E* r at contact radius `a`, with r as `stiffness_radius` says.
    #[inline(always)]
    fn damping_at(&self, alpha: f64, a: f64) -> f64 {
        2.0 * self.curve.youngs_modulus
            * match self.stiffness_radius {
                JkrStiffnessRadius::Contact => a,
                JkrStiffnessRadius::Hertz => (self.curve.radius * alpha).sqrt(),
            }
    }
}

impl JkrModified {
    /// The curve at alpha > 0 with its contact radius a solved.
    fn elastic_at(&self, a: f64) -> Evaluation<()> {
        let mut e = on_curve_at(&self.curve, 0.0, a, ());
        // For alpha > 0 the JKR contact radius is above a_c: always the elastic branch.
        e.branch = Branch::Elastic;
        e.lower = 0.0;
        e.upper = f64::INFINITY;
        e
    }
}

impl NormalLaw for JkrModified {
    type History = ();

    fn initial_history(&self) {}

    #[inline]
    fn evaluate(&self, alpha: f64, _h: &()) -> Evaluation<()> {
        if alpha <= 0.0 {
            return Evaluation::separated(0.0, ());
        }
        self.elastic_at(self.curve.contact_radius(alpha))
    }

    #[inline]
    fn has_yielded(&self, _h: &()) -> bool {
        false
    }

    /// `pull_off`: as JKR, F_n + 2 f_c (004 Eq. 3.49). `repulsive`: 4 E* a^3 / (3 R*), from the force in
    /// closed form (`JkrCurve::repulsive_part`), so no second contact-radius solve.
    #[inline]
    fn sliding_normal_force(&self, force: f64, _alpha: f64, _h: &()) -> f64 {
        match self.friction_limit {
            JkrFrictionLimit::PullOff => force + 2.0 * self.curve.pull_off_force(),
            JkrFrictionLimit::Repulsive => self.curve.repulsive_part(force),
        }
    }

    /// The largest tension on the curve for alpha > 0: 8/9 f_c, at alpha = 0.
    fn pull_off_force(&self, _h: &()) -> f64 {
        8.0 / 9.0 * self.curve.pull_off_force()
    }

    fn plastic_overlap(&self, _h: &()) -> f64 {
        0.0
    }

    #[inline]
    fn contact_radius(&self, alpha: f64, _h: &()) -> Option<f64> {
        (alpha > 0.0).then(|| self.curve.contact_radius(alpha))
    }

    /// 2 E* a: the Hertz stiffness at the JKR contact radius (the JKR slope is infinite at detachment);
    /// 2 E* sqrt(R* alpha) with `jkr_stiffness_radius = hertz`.
    #[inline]
    fn damping_stiffness(&self, alpha: f64, h: &(), _branch_stiffness: f64) -> f64 {
        self.contact_radius(alpha, h).map_or(0.0, |a| self.damping_at(alpha, a))
    }

    /// The contact radius a, or Hertz's sqrt(R* alpha) with `jkr_stiffness_radius = hertz`.
    #[inline(always)]
    fn mindlin_radius(&self, alpha: f64, _h: &(), contact_radius: Option<f64>) -> Option<f64> {
        match self.stiffness_radius {
            JkrStiffnessRadius::Contact => contact_radius,
            JkrStiffnessRadius::Hertz => contact_radius.map(|_| (self.curve.radius * alpha).sqrt()),
        }
    }

    /// One contact-radius solve for force, stiffness, damping and Mindlin.
    #[inline]
    fn evaluate_with_radius(&self, alpha: f64, _h: &()) -> (Evaluation<()>, f64, Option<f64>) {
        if alpha <= 0.0 {
            return (Evaluation::separated(0.0, ()), 0.0, None);
        }
        let a = self.curve.contact_radius(alpha);
        (self.elastic_at(a), self.damping_at(alpha, a), Some(a))
    }

    #[inline]
    fn evaluate_near(&self, alpha: f64, _h: &(), guess: f64) -> (Evaluation<()>, f64, Option<f64>) {
        if alpha <= 0.0 {
            return (Evaluation::separated(0.0, ()), 0.0, None);
        }
        let a = self.curve.contact_radius_from(alpha, guess);
        (self.elastic_at(a), self.damping_at(alpha, a), Some(a))
    }
}

impl LawInfo for JkrModified {
    const TANGENTIAL: TangentialModel = TangentialModel::Mindlin;
    type Options = JkrModifiedOptions;
    fn from_pair(eff: &Effective, options: &LawOptions) -> Result<JkrModified, ParamError> {
        let mut law = JkrModified::with_friction_limit(eff.radius, eff.youngs_modulus, eff.surface_energy, options.jkr_modified.jkr_friction_limit);
        law.stiffness_radius = options.jkr_modified.jkr_stiffness_radius;
        Ok(law)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // 004 Tables 5.1-5.3's glass beads: a pair of 0.5 mm spheres, E = 55 GPa, nu = 0.25, Gamma = 1.0 J/m^2.
    fn law(limit: JkrFrictionLimit) -> JkrModified {
        let e_star = 55e9 / (2.0 * (1.0 - 0.25 * 0.25));
        JkrModified::with_friction_limit(0.25e-3, e_star, 1.0, limit)
    }

    #[test]
    fn the_repulsive_limit_is_the_hertz_part_of_the_force_on_the_whole_curve() {
        let l = law(JkrFrictionLimit::Repulsive);
        let c = &l.curve;
        for alpha in [1e-12, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6] {
            let a = c.contact_radius(alpha);
            let hertz = 4.0 * c.youngs_modulus * a.powi(3) / (3.0 * c.radius);
            let n = l.sliding_normal_force(l.evaluate(alpha, &()).force, alpha, &());
            assert!((n / hertz - 1.0).abs() < 1e-9, "alpha {alpha:e}: {n:e} vs {hertz:e}");
        }
    }

    #[test]
    fn at_zero_net_force_the_repulsive_limit_is_four_pull_off_forces_and_the_pull_off_reading_two() {
        let f_c = law(JkrFrictionLimit::PullOff).curve.pull_off_force();
        let repulsive = law(JkrFrictionLimit::Repulsive).sliding_normal_force(0.0, 0.0, &());
        let pull_off = law(JkrFrictionLimit::PullOff).sliding_normal_force(0.0, 0.0, &());
        assert!((repulsive / (4.0 * f_c) - 1.0).abs() < 1e-12, "{repulsive:e} vs 4 f_c = {:e}", 4.0 * f_c);
        assert!((pull_off / (2.0 * f_c) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_hertz_stiffness_radius_is_sqrt_r_alpha_for_damping_and_mindlin_and_the_force_is_unchanged() {
        let contact = law(JkrFrictionLimit::Repulsive);
        let mut hertz = contact.clone();
        hertz.stiffness_radius = JkrStiffnessRadius::Hertz;
        let (e_star, r) = (contact.curve.youngs_modulus, contact.curve.radius);
        for alpha in [1e-10, 1e-8, 1e-6] {
            let (ev_c, k_c, a_c) = contact.evaluate_with_radius(alpha, &());
            let (ev_h, k_h, a_h) = hertz.evaluate_near(alpha, &(), a_c.unwrap());
            let a = a_c.unwrap();
            // The force, its stiffness and the remembered contact radius (the next step's guess) stay JKR's.
            assert_eq!((ev_h.force, ev_h.stiffness), (ev_c.force, ev_c.stiffness));
            assert!((a_h.unwrap() / a - 1.0).abs() < 1e-12);
            assert_eq!(k_c, 2.0 * e_star * a);
            assert_eq!(contact.mindlin_radius(alpha, &(), a_c), a_c);
            let hertz_radius = (r * alpha).sqrt();
            assert!((k_h / (2.0 * e_star * hertz_radius) - 1.0).abs() < 1e-15, "alpha {alpha:e}");
            assert_eq!(hertz.damping_stiffness(alpha, &(), ev_h.stiffness), k_h);
            assert_eq!(hertz.mindlin_radius(alpha, &(), a_h), Some(hertz_radius));
            // Adhesion makes the JKR contact wider than Hertz's at the same overlap.
            assert!(a > hertz_radius, "alpha {alpha:e}: a {a:e} vs {hertz_radius:e}");
        }
        // Apart: no radius, no damping.
        assert_eq!(hertz.mindlin_radius(-1e-9, &(), hertz.contact_radius(-1e-9, &())), None);
        assert_eq!(hertz.damping_stiffness(-1e-9, &(), 0.0), 0.0);
    }

    #[test]
    fn the_scene_key_chooses_the_limit() {
        let scene = crate::scene::Scene::from_json(
            r#"{"contact_model": "jkr_modified", "particle_radius": 5e-4, "particle_density": 2500,
                "particle_youngs_modulus": 55e9, "particle_poisson_ratio": 0.25, "surface_energy": 1.0,
                "jkr_friction_limit": "repulsive"}"#,
        )
        .unwrap();
        assert_eq!(scene.laws.jkr_modified.jkr_friction_limit, JkrFrictionLimit::Repulsive);
        assert_eq!(scene.laws.jkr_modified.jkr_stiffness_radius, JkrStiffnessRadius::Contact);
        let scene = crate::scene::Scene::from_json(
            r#"{"contact_model": "jkr_modified", "particle_radius": 5e-4, "particle_density": 2500,
                "particle_youngs_modulus": 55e9, "particle_poisson_ratio": 0.25, "jkr_stiffness_radius": "hertz"}"#,
        )
        .unwrap();
        assert_eq!(scene.laws.jkr_modified.jkr_stiffness_radius, JkrStiffnessRadius::Hertz);
        let err = crate::scene::Scene::from_json(
            r#"{"particle_radius": 5e-4, "particle_density": 2500, "particle_youngs_modulus": 55e9,
                "particle_poisson_ratio": 0.25, "jkr_stiffness_radius": "edem"}"#,
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("jkr_stiffness_radius") && err.contains("hertz"), "{err}");
        let err = crate::scene::Scene::from_json(
            r#"{"particle_radius": 5e-4, "particle_density": 2500, "particle_youngs_modulus": 55e9,
                "particle_poisson_ratio": 0.25, "jkr_friction_limit": "edem"}"#,
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("jkr_friction_limit") && err.contains("repulsive"), "{err}");
    }
}
