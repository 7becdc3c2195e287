//! The EDEM-style modified JKR law (`004` Sec. 5.1.1, Fig. 5.1): the JKR curve for alpha > 0 only.
//! At contact the force drops to -8/9 f_c as in JKR; on unloading the contact breaks as soon as the
//! overlap is zero, so the extra adhesion work of JKR below alpha = 0 is never done. No history.

use super::jkr::{on_curve_at, JkrCurve};
use super::params::Effective;
use super::tangential::TangentialModel;
use super::{LawInfo, LawOptions};
use super::{Branch, Evaluation, NormalLaw};
use crate::error::ParamError;
use crate::scene::NoOptions;

#[derive(Debug, Clone, PartialEq)]
pub struct JkrModified {
    pub curve: JkrCurve,
}

impl JkrModified {
    pub fn new(radius: f64, youngs_modulus: f64, surface_energy: f64) -> JkrModified {
        JkrModified { curve: JkrCurve::new(radius, youngs_modulus, surface_energy) }
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

    /// As JKR: mu (F_n + 2 F_c) (004 Eq. 3.49).
    #[inline]
    fn sliding_normal_force(&self, force: f64, _alpha: f64, _h: &()) -> f64 {
        force + 2.0 * self.curve.pull_off_force()
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

    /// 2 E* a: the Hertz stiffness at the JKR contact radius (the JKR slope is infinite at detachment).
    #[inline]
    fn damping_stiffness(&self, alpha: f64, h: &(), _branch_stiffness: f64) -> f64 {
        2.0 * self.curve.youngs_modulus * self.contact_radius(alpha, h).unwrap_or(0.0)
    }

    /// One contact-radius solve for force, stiffness, damping and Mindlin.
    #[inline]
    fn evaluate_with_radius(&self, alpha: f64, _h: &()) -> (Evaluation<()>, f64, Option<f64>) {
        if alpha <= 0.0 {
            return (Evaluation::separated(0.0, ()), 0.0, None);
        }
        let a = self.curve.contact_radius(alpha);
        (self.elastic_at(a), 2.0 * self.curve.youngs_modulus * a, Some(a))
    }

    #[inline]
    fn evaluate_near(&self, alpha: f64, _h: &(), guess: f64) -> (Evaluation<()>, f64, Option<f64>) {
        if alpha <= 0.0 {
            return (Evaluation::separated(0.0, ()), 0.0, None);
        }
        let a = self.curve.contact_radius_from(alpha, guess);
        (self.elastic_at(a), 2.0 * self.curve.youngs_modulus * a, Some(a))
    }
}

impl LawInfo for JkrModified {
    const TANGENTIAL: TangentialModel = TangentialModel::Mindlin;
    type Options = NoOptions;
    fn from_pair(eff: &Effective, _options: &LawOptions) -> Result<JkrModified, ParamError> {
        Ok(JkrModified::new(eff.radius, eff.youngs_modulus, eff.surface_energy))
    }
}
