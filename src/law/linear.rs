//! The linear spring (`004` Sec. 3.4.1.1, Eq. 3.9): f = k_n alpha for alpha > 0. No history.

use super::params::{k_el_default, Effective};
use super::{Branch, Evaluation, LawInfo, NormalLaw};
use crate::error::ParamError;
use crate::scene::{Key, KeyKind, Scene};

#[derive(Debug, Clone, PartialEq)]
pub struct Linear {
    /// k_n [N/m].
    pub stiffness: f64,
}

impl NormalLaw for Linear {
    type History = ();

    fn initial_history(&self) {}

    fn evaluate(&self, alpha: f64, _h: &()) -> Evaluation<()> {
        if alpha <= 0.0 {
            return Evaluation::separated(0.0, ());
        }
        Evaluation {
            force: self.stiffness * alpha,
            stiffness: self.stiffness,
            branch: Branch::Elastic,
            lower: 0.0,
            upper: f64::INFINITY,
            history: (),
        }
    }

    fn has_yielded(&self, _h: &()) -> bool {
        false
    }

    fn sliding_normal_force(&self, force: f64, _alpha: f64, _h: &()) -> f64 {
        force
    }

    fn pull_off_force(&self, _h: &()) -> f64 {
        0.0
    }

    fn plastic_overlap(&self, _h: &()) -> f64 {
        0.0
    }
}

impl LawInfo for Linear {
    /// This law's own scene keys (composed into `scene::KEYS`).
    const KEYS: &'static [Key] = &[
        Key { name: "linear_stiffness", unit: "N/m", kind: KeyKind::Derived, default: "elastic_stiffness", doc: "k_n of the linear spring (004 Eq. 3.9)" },
    ];
    /// k_n from `linear_stiffness`, else `elastic_stiffness`, else pi R* p_y (000 Eq. 52).
    fn from_scene(s: &Scene, eff: &Effective) -> Result<Linear, ParamError> {
        let k = match (s.linear_stiffness, s.elastic_stiffness) {
            (Some(k), _) | (None, Some(k)) => k,
            _ => k_el_default(eff.radius, eff.require_yield_pressure("linear (no linear_stiffness given)")?),
        };
        Ok(Linear { stiffness: k })
    }
}
