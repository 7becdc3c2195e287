//! The linear spring (`004` Sec. 3.4.1.1, Eq. 3.9): f = k_n alpha for alpha > 0. No history.

use super::params::{k_el_default, Effective};
use super::{Branch, Evaluation, LawInfo, LawOptions, NormalLaw};
use crate::error::ParamError;
use crate::vocabulary::Range;

/// The linear spring of one contact pair (the module documentation says which equations).
#[derive(Debug, Clone, PartialEq)]
pub struct Linear {
    /// k_n [N/m].
    pub stiffness: f64,
}

impl NormalLaw for Linear {
    type History = ();

    fn initial_history(&self) {}

    #[inline]
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
}

crate::scene_options! {
    /// The linear spring's own scene key.
    pub struct LinearOptions {
        linear_stiffness: derived("elastic_stiffness"), "N/m", Range::Open(0.0, 1e12), "k_n of the linear spring (004 Eq. 3.9)";
    }
}

impl LawInfo for Linear {
    type Options = LinearOptions;
    /// k_n from `linear_stiffness`, else `elastic_stiffness`, else pi R* p_y (000 Eq. 52).
    fn from_pair(pair: &Effective, options: &LawOptions) -> Result<Linear, ParamError> {
        let k = match (options.linear.linear_stiffness, options.stiffness.elastic_stiffness) {
            (Some(k), _) | (None, Some(k)) => k,
            _ => k_el_default(pair.radius, pair.require_yield_pressure("linear (no linear_stiffness given)")?),
        };
        Ok(Linear { stiffness: k })
    }
}
