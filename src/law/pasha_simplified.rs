//! Pasha's simplified law (`004` Sec. 4.1.4-4.1.5, Fig. 4.20): no initial elastic stage, a linear
//! pull-off locus, and detachment at zero force.
//!
//! - loading (from first contact at alpha = 0): k_p (alpha - alpha_0), alpha_0 = 8/9 f_ce / k_p (004 Eq. A3.3);
//! - unloading k_e (alpha - alpha_p) down to the pull-off locus f_cp = k_cp alpha_cp + f_0p (Eq. 4.17),
//!   which it meets at alpha_cp = (k_e alpha_p - f_0p) / (k_e + k_cp);
//! - then k_e (2 alpha_cp - alpha_p - alpha) to zero force at alpha_fp = 2 alpha_cp - alpha_p, where the
//!   contact breaks (the zero-force breakage 004 Sec. 4.1.5 uses); re-contact at max(alpha_fp, 0).

use super::params::Effective;
use super::pasha::{pasha_evaluate, PashaHistory, PashaPoints, PashaStiffness};
use super::{Evaluation, LawInfo, LawOptions, NormalLaw};
use crate::error::ParamError;
use crate::vocabulary::Range;

/// Pasha's simplified law of one contact pair (the module documentation says which equations).
#[derive(Debug, Clone, PartialEq)]
pub struct PashaSimplified {
    /// JKR pull-off force f_ce = 1.5 pi Gamma R* (004 Eq. 4.1) [N].
    pub f_ce: f64,
    /// Unloading stiffness law and its constants (the `pasha` law's options).
    pub stiffness: PashaStiffness,
    /// Plastic loading stiffness k_p [N/m].
    pub k_p: f64,
    /// k_cp of Eq. 4.17 [N/m].
    pub k_cp: f64,
    /// f_0p of Eq. 4.17 [N].
    pub f_0p: f64,
    /// alpha_0 = 8/9 f_ce / k_p [m].
    pub alpha_0: f64,
}

impl PashaSimplified {
    /// The law from f_ce [N], the unloading stiffness, k_cp [N/m] and f_0p [N]; an error if f_0p is below
    /// 8/9 f_ce.
    pub fn new(f_ce: f64, stiffness: PashaStiffness, k_cp: f64, f_0p: f64) -> Result<PashaSimplified, ParamError> {
        if f_0p < 8.0 / 9.0 * f_ce * (1.0 - 1e-12) {
            return Err(ParamError::OutOfRange {
                name: "pasha_pull_off_intercept",
                value: f_0p,
                allowed: format!("[8/9 f_ce = {:e}, inf) N: the pull-off locus must lie below the loading line", 8.0 / 9.0 * f_ce),
            });
        }
        Ok(PashaSimplified { f_ce, stiffness, k_p: stiffness.k_p, k_cp, f_0p, alpha_0: 8.0 / 9.0 * f_ce / stiffness.k_p })
    }

    /// The branch points for a largest overlap alpha_max: the unloading line through (alpha_max, F_max),
    /// its meeting point with the pull-off locus of Eq. 4.17, and zero-force detachment (the module documentation says which equations).
    #[inline]
    pub fn points(&self, alpha_max: f64) -> PashaPoints {
        let k_e = self.stiffness.at(alpha_max);
        let f_max = self.k_p * (alpha_max - self.alpha_0);
        let alpha_p = alpha_max - f_max / k_e;
        let alpha_cp = (k_e * alpha_p - self.f_0p) / (k_e + self.k_cp);
        PashaPoints { k_e, alpha_p, f_cp: self.k_cp * alpha_cp + self.f_0p, alpha_cp, alpha_fp: 2.0 * alpha_cp - alpha_p }
    }
}

impl NormalLaw for PashaSimplified {
    type History = PashaHistory;

    fn initial_history(&self) -> PashaHistory {
        PashaHistory { established: false, alpha_max: 0.0 }
    }

    #[inline]
    fn evaluate(&self, alpha: f64, h: &PashaHistory) -> Evaluation<PashaHistory> {
        let pts = self.points(h.alpha_max);
        pasha_evaluate(alpha, h, &pts, |a| self.k_p * (a - self.alpha_0), self.k_p)
    }

    #[inline]
    fn has_yielded(&self, h: &PashaHistory) -> bool {
        h.alpha_max > 0.0
    }

    /// 004 Eq. 4.28: mu (F_n + k_cp alpha + f_0p - f_ce).
    #[inline]
    fn sliding_normal_force(&self, force: f64, alpha: f64, _h: &PashaHistory) -> f64 {
        force + self.k_cp * alpha + self.f_0p - self.f_ce
    }

    fn pull_off_force(&self, h: &PashaHistory) -> f64 {
        self.points(h.alpha_max).f_cp
    }

    fn plastic_overlap(&self, h: &PashaHistory) -> f64 {
        self.points(h.alpha_max).alpha_p
    }

    /// A detached contact re-forms only at max(alpha_fp, 0) >= 0 (`pasha_evaluate`): below zero overlap it
    /// stays separated with alpha_max kept.
    #[inline]
    fn rests_apart(&self, h: &PashaHistory) -> bool {
        !h.established
    }
}

crate::scene_options! {
    /// The simplified Pasha law's own scene keys (its unloading stiffness is the Pasha law's options).
    pub struct PashaSimplifiedOptions {
        pasha_pull_off_stiffness: number(0.0), "N/m", Range::ClosedLow(0.0, 1e12), "k_cp, slope of the linear pull-off locus f_cp = k_cp alpha_cp + f_0p (004 Eq. 4.17; pasha_simplified)";
        pasha_pull_off_intercept: derived("f_ce"), "N", Range::ClosedLow(0.0, 1e6), "f_0p of the linear pull-off locus (004 Eq. 4.17; pasha_simplified); at least 8/9 f_ce";
    }
}

impl LawInfo for PashaSimplified {
    type Options = PashaSimplifiedOptions;
    fn from_pair(pair: &Effective, options: &LawOptions) -> Result<PashaSimplified, ParamError> {
        let stiffness = PashaStiffness::from_options(pair, &options.stiffness, &options.pasha, "pasha_simplified")?;
        let own = &options.pasha_simplified;
        let f_ce = pair.f_ce();
        let f_0p = own.pasha_pull_off_intercept.unwrap_or(f_ce);
        PashaSimplified::new(f_ce, stiffness, own.pasha_pull_off_stiffness, f_0p)
    }
}
