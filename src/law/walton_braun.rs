//! Walton & Braun's linear elasto-plastic law (`004` Sec. 3.4.2.3, Eqs. 3.36-3.38).
//!
//! Loading f = k_p alpha (Eq. 3.36); unloading f = k_e (alpha - alpha_0) (Eq. 3.37) with the permanent
//! overlap alpha_0 = alpha_max (1 - k_p/k_e); no force below alpha_0. k_e is constant, or
//! k_e = k_p + S F_max (Eq. 3.38) when a stiffening slope S > 0 is given. No adhesion.

use super::params::{k_el_default, Effective};
use super::{Branch, Evaluation, LawInfo, LawOptions, NormalLaw};
use crate::error::ParamError;
use crate::vocabulary::Range;

/// Walton and Braun's law of one contact pair (the module documentation says which equations).
#[derive(Debug, Clone, PartialEq)]
pub struct WaltonBraun {
    /// k_p [N/m].
    pub k_p: f64,
    /// Constant k_e [N/m] (used when `slope` is 0).
    pub k_e: f64,
    /// S of Eq. 3.38 [1/m].
    pub slope: f64,
}

/// What a Walton-Braun contact remembers.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WbHistory {
    /// Largest overlap [m].
    pub alpha_max: f64,
}

impl WaltonBraun {
    /// Unloading stiffness for a largest overlap.
    pub fn unloading_stiffness(&self, alpha_max: f64) -> f64 {
        if self.slope > 0.0 {
            self.k_p + self.slope * self.k_p * alpha_max // Eq. 3.38
        } else {
            self.k_e
        }
    }

    /// alpha_0 of Eq. 3.37.
    pub fn alpha_0(&self, alpha_max: f64) -> f64 {
        alpha_max * (1.0 - self.k_p / self.unloading_stiffness(alpha_max))
    }
}

impl NormalLaw for WaltonBraun {
    type History = WbHistory;

    fn initial_history(&self) -> WbHistory {
        WbHistory { alpha_max: 0.0 }
    }

    #[inline]
    fn evaluate(&self, alpha: f64, h: &WbHistory) -> Evaluation<WbHistory> {
        let alpha_0 = self.alpha_0(h.alpha_max);
        if alpha <= alpha_0 {
            return Evaluation::separated(alpha_0, *h);
        }
        if alpha <= h.alpha_max {
            let k_e = self.unloading_stiffness(h.alpha_max);
            return Evaluation {
                force: k_e * (alpha - alpha_0),
                stiffness: k_e,
                branch: Branch::Elastic,
                lower: alpha_0,
                upper: h.alpha_max,
                history: *h,
            };
        }
        Evaluation {
            force: self.k_p * alpha,
            stiffness: self.k_p,
            branch: Branch::Plastic,
            lower: alpha,
            upper: f64::INFINITY,
            history: WbHistory { alpha_max: alpha },
        }
    }

    #[inline]
    fn has_yielded(&self, h: &WbHistory) -> bool {
        h.alpha_max > 0.0
    }

    #[inline]
    fn sliding_normal_force(&self, force: f64, _alpha: f64, _h: &WbHistory) -> f64 {
        force
    }

    fn pull_off_force(&self, _h: &WbHistory) -> f64 {
        0.0
    }

    fn plastic_overlap(&self, h: &WbHistory) -> f64 {
        self.alpha_0(h.alpha_max)
    }
}

crate::scene_options! {
    /// The Walton-Braun law's own scene key.
    pub struct WaltonBraunOptions {
        walton_braun_stiffening_slope: number(0.0), "1/m", Range::ClosedLow(0.0, 1e12), "S of k_e = k_p + S F_max (004 Eq. 3.38); 0 keeps k_e constant";
    }
}

impl LawInfo for WaltonBraun {
    type Options = WaltonBraunOptions;
    /// k_e from `elastic_stiffness` (else pi R* p_y, 000 Eq. 52), k_p from `plastic_stiffness` (else k_e).
    fn from_pair(pair: &Effective, options: &LawOptions) -> Result<WaltonBraun, ParamError> {
        let s = &options.stiffness;
        let k_e = match s.elastic_stiffness {
            Some(k) => k,
            None => k_el_default(pair.radius, pair.require_yield_pressure("walton_braun (no elastic_stiffness given)")?),
        };
        let k_p = s.plastic_stiffness.unwrap_or(k_e);
        if k_p > k_e {
            return Err(ParamError::Inconsistent {
                name: "plastic_stiffness",
                why: format!("k_p = {k_p:e} N/m exceeds elastic_stiffness k_e = {k_e:e} N/m (004 Eq. 3.37 needs k_p <= k_e)"),
            });
        }
        Ok(WaltonBraun { k_p, k_e, slope: options.walton_braun.walton_braun_stiffening_slope })
    }
}
