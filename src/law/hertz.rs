//! Hertz's elastic law (`004` Eq. 3.14): f = 4/3 E* sqrt(R*) alpha^(3/2) for alpha > 0. No history.

use super::params::Effective;
use super::tangential::TangentialModel;
use super::{Branch, Evaluation, NormalLaw};
use super::{LawInfo, LawOptions};
use crate::error::ParamError;
use crate::vocabulary::NoOptions;

/// Hertz's elastic law of one contact pair (the module documentation says which equations).
#[derive(Debug, Clone, PartialEq)]
pub struct Hertz {
    /// Reduced radius R* [m].
    pub radius: f64,
    /// Effective modulus E* (004 Eq. 3.15) [Pa].
    pub youngs_modulus: f64,
}

impl Hertz {
    /// The law of reduced radius R* [m] and effective modulus E* [Pa].
    pub fn new(radius: f64, youngs_modulus: f64) -> Hertz {
        Hertz { radius, youngs_modulus }
    }
}

impl NormalLaw for Hertz {
    type History = ();

    fn initial_history(&self) {}

    #[inline]
    fn evaluate(&self, alpha: f64, _h: &()) -> Evaluation<()> {
        if alpha <= 0.0 {
            return Evaluation::separated(0.0, ());
        }
        let root = (self.radius * alpha).sqrt();
        Evaluation {
            force: 4.0 / 3.0 * self.youngs_modulus * root * alpha,
            stiffness: 2.0 * self.youngs_modulus * root, // 000 Eq. 41
            branch: Branch::Elastic,
            lower: 0.0,
            upper: f64::INFINITY,
            history: (),
        }
    }

    #[inline]
    fn has_yielded(&self, _h: &()) -> bool {
        false
    }

    #[inline]
    fn sliding_normal_force(&self, force: f64, _alpha: f64, _h: &()) -> f64 {
        force
    }

    fn pull_off_force(&self, _h: &()) -> f64 {
        0.0
    }

    fn plastic_overlap(&self, _h: &()) -> f64 {
        0.0
    }

    #[inline]
    fn contact_radius(&self, alpha: f64, _h: &()) -> Option<f64> {
        Some((self.radius * alpha.max(0.0)).sqrt())
    }

    /// One square root for force, stiffness, damping and Mindlin.
    #[inline(always)]
    fn evaluate_with_radius(&self, alpha: f64, h: &()) -> (Evaluation<()>, f64, Option<f64>) {
        let ev = self.evaluate(alpha, h);
        let a = ev.stiffness / (2.0 * self.youngs_modulus); // 2 E* a = 2 E* sqrt(R* alpha)
        (ev, ev.stiffness, Some(a))
    }
}

impl LawInfo for Hertz {
    const TANGENTIAL: TangentialModel = TangentialModel::Mindlin;
    type Options = NoOptions;
    fn from_pair(eff: &Effective, _options: &LawOptions) -> Result<Hertz, ParamError> {
        Ok(Hertz::new(eff.radius, eff.youngs_modulus))
    }
}
