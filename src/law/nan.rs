//! Nan, Goh & Rahman's improved linear elasto-plastic adhesive law (`000` Sec. 2, Eqs. 3-20), read as
//! the state machine of docs/models.md, "Nan improved linear law".
//!
//! History: `established` (the paper's cs) and `alpha_max`, which starts at `alpha_y`, so the contact
//! before yield is the same formulas with k_e = k_el, alpha_p = alpha_0, f_cp = f_ce, alpha_c0 = 0.
//! The history also carries the branch points that follow from alpha_max, computed once when plastic
//! loading moves alpha_max, so that the elastic and adhesive branches cost a multiply and an add.
//!
//! Branches for an established contact (000 Fig. 1):
//! - `alpha < alpha_fp`: detached (force 0, history kept; re-established at `alpha_c0`, Fig. 2(d));
//! - `alpha_fp <= alpha <= alpha_cp`: f_c = -f_cp + k_c (alpha_cp - alpha)  (Eq. 19, lines AB / EF);
//! - `alpha_cp < alpha <= alpha_max`: f_e = k_e (alpha - alpha_p)            (Eq. 17, lines BC / DE);
//! - `alpha > alpha_max`: f_p = f_y + k_p (alpha - alpha_y)                    (Eq. 18, line CD),
//!   and alpha_max follows alpha (Eq. 10), which recomputes k_e, k_c, alpha_p, f_cp and the overlaps of
//!   Eqs. 11-14 so that the force stays continuous.

use super::nan_params::NanParams;
use super::params::Effective;
use super::{Branch, Evaluation, LawInfo, LawOptions, NormalLaw};
use crate::error::ParamError;
use crate::vocabulary::Range;

crate::choice_enum! {
    /// How k_e grows after yield in the Nan law.
    pub enum UnloadingStiffnessLaw {
        /// 000 Eqs. 42-46.
        Sqrt = "sqrt",
        /// 000 Eqs. 47-49.
        SqrtPlusPlastic = "sqrt_plus_plastic",
    }
}

crate::choice_enum! {
    /// How the maximum pull-off force grows after yield in the Nan law (000 Table 4).
    pub enum PullOffLaw {
        /// 000 Eq. 59.
        Energy = "energy",
        /// 000 Eq. 61.
        Pasha = "pasha",
        /// 000 Eq. 64.
        Curvature = "curvature",
        /// 000 Eq. 67.
        WorkRatio = "work_ratio",
    }
}

crate::choice_enum! {
    /// Which form of the k_cl correlation.
    pub enum AdhesiveStiffnessLaw {
        /// 000 Eq. 36 with Eq. 37.
        Exact = "exact",
        /// 000 Eq. 38.
        Approximate = "approximate",
    }
}

crate::scene_options! {
    /// The Nan law's own scene keys.
    pub struct NanOptions {
        unloading_stiffness_law: choice(UnloadingStiffnessLaw::Sqrt), "-", Range::Names, "nan k_e after yield: sqrt, k_e = k_el sqrt(alpha_max/alpha_y) (000 Eq. 46); sqrt_plus_plastic, k_e = k_p + (k_el - k_p) sqrt(alpha_max/alpha_y) (000 Eqs. 47-49)";
        pull_off_law: choice(PullOffLaw::Energy), "-", Range::Names, "nan f_cp: energy (000 Eq. 59), pasha (Eq. 61), curvature (Eq. 64), work_ratio (Eq. 67)";
        adhesive_stiffness_law: choice(AdhesiveStiffnessLaw::Exact), "-", Range::Names, "nan k_cl: exact (000 Eq. 36 with W_JKR of Eq. 37) or approximate (Eq. 38)";
    }
}

/// Nan's law of one contact pair (the module documentation says which equations).
#[derive(Debug, Clone, PartialEq)]
pub struct Nan {
    /// The law's parameters (000 Sec. 3).
    pub p: NanParams,
    /// The branch points before yield (alpha_max = alpha_y), computed once.
    before_yield: NanPoints,
}

/// What the contact remembers. In C layout: the pair loop's lanes read and write alpha_max and the points
/// as one row of eight f64 (`engine::lanes::nan`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[repr(C)]
pub struct NanHistory {
    /// The paper's cs: the contact is established (000 Eq. 20).
    pub established: bool,
    /// Largest overlap of plastic loading, at least alpha_y (000 Eq. 10) [m].
    pub alpha_max: f64,
    /// `Nan::points(alpha_max)`, kept so it is not recomputed at every evaluation.
    pub points: NanPoints,
}

/// The quantities that follow from alpha_max (000 Eqs. 11-14, 46, 59).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[repr(C)]
pub struct NanPoints {
    /// Elastic un/reloading stiffness k_e: k_el before yield, 000 Eq. 46 or 47-49 after [N/m].
    pub k_e: f64,
    /// Adhesive stiffness k_c = k_e k_cl / k_el of lines AB / EF (000 Sec. 3.2) [N/m].
    pub k_c: f64,
    /// Zero-force overlap alpha_p of the elastic line (000 Eq. 16; alpha_0 before yield) [m].
    pub alpha_p: f64,
    /// Maximum pull-off force f_cp (000 Table 4; f_ce before yield) [N].
    pub f_cp: f64,
    /// Overlap alpha_c0 at which a detached contact is re-established, at -8/9 f_cp (000 Eq. 12; 0
    /// before yield) [m].
    pub alpha_c0: f64,
    /// Overlap alpha_cp of the pull-off point, f = -f_cp (000 Eq. 13) [m].
    pub alpha_cp: f64,
    /// Overlap alpha_fp at which the contact detaches, at -5/9 f_cp (000 Eq. 14) [m].
    pub alpha_fp: f64,
}

// The lanes' row of a history: alpha_max, then the points in the order of `History::points`.
const _: () = {
    use std::mem::{offset_of, size_of};
    assert!(offset_of!(NanHistory, points) == offset_of!(NanHistory, alpha_max) + 8);
    assert!(offset_of!(NanPoints, k_e) == 0 && offset_of!(NanPoints, k_c) == 8 && offset_of!(NanPoints, alpha_p) == 16);
    assert!(offset_of!(NanPoints, f_cp) == 24 && offset_of!(NanPoints, alpha_c0) == 32 && offset_of!(NanPoints, alpha_cp) == 40);
    assert!(offset_of!(NanPoints, alpha_fp) == 48 && size_of::<NanPoints>() == 56);
};

impl Nan {
    /// The law of a parameter set, with its branch points before yield set exactly to k_el, k_cl,
    /// alpha_0, f_ce, 0, alpha_ce and alpha_fe (000 Sec. 2.1, Eqs. 8-9).
    pub fn new(p: NanParams) -> Nan {
        let mut law = Nan { p, before_yield: NanPoints { k_e: 0.0, k_c: 0.0, alpha_p: 0.0, f_cp: 0.0, alpha_c0: 0.0, alpha_cp: 0.0, alpha_fp: 0.0 } };
        law.before_yield = law.points_after_yield(p.alpha_y);
        // Before yield the general formulas reduce exactly to these (000 Sec. 2.1); set them exactly.
        law.before_yield.k_e = p.k_el;
        law.before_yield.k_c = p.k_cl;
        law.before_yield.alpha_p = p.alpha_0;
        law.before_yield.f_cp = p.f_ce;
        law.before_yield.alpha_c0 = 0.0;
        law.before_yield.alpha_cp = p.alpha_0 - p.f_ce / p.k_el; // alpha_ce, Eq. 8
        law.before_yield.alpha_fp = law.before_yield.alpha_cp - 4.0 / 9.0 * p.f_ce / p.k_cl; // alpha_fe, Eq. 9
        law
    }

    /// Branch points for a given alpha_max.
    #[inline]
    pub fn points(&self, alpha_max: f64) -> NanPoints {
        if alpha_max <= self.p.alpha_y {
            self.before_yield
        } else {
            self.points_after_yield(alpha_max)
        }
    }

    /// Branch points for alpha_max > alpha_y (the plastic branch's new history; the lanes call it per lane).
    /// Out of line: the lane loop calls it only for a lane that loads plastically, and inlined it made
    /// the loop no faster (bench bed, medians of 5: 9.0e6 inlined against 9.8e6 particle-steps/s).
    #[inline(never)]
    pub fn points_after_yield(&self, alpha_max: f64) -> NanPoints {
        let p = &self.p;
        let k_e = p.k_e(alpha_max);
        let k_c = k_e * p.k_cl / p.k_el; // k_e/k_c = k_el/k_cl (000 Sec. 3.2)
        let alpha_p = (1.0 - p.k_p / k_e) * alpha_max + (p.k_p * p.alpha_y - p.f_y) / k_e; // Eq. 16
        let f_cp = p.f_cp(k_e, alpha_p, alpha_max);
        NanPoints {
            k_e,
            k_c,
            alpha_p,
            f_cp,
            alpha_c0: alpha_p - 8.0 / 9.0 * f_cp / k_e,              // Eq. 12
            alpha_cp: alpha_p - f_cp / k_e,                          // Eq. 13
            alpha_fp: alpha_p - f_cp / k_e - 4.0 / 9.0 * f_cp / k_c, // Eq. 14
        }
    }
}

impl NormalLaw for Nan {
    type History = NanHistory;

    fn initial_history(&self) -> NanHistory {
        NanHistory { established: false, alpha_max: self.p.alpha_y, points: self.before_yield }
    }

    #[inline]
    fn evaluate(&self, alpha: f64, h: &NanHistory) -> Evaluation<NanHistory> {
        let pts = h.points;
        // Not yet (re-)established below alpha_c0, or detached below alpha_fp.
        if (!h.established && alpha < pts.alpha_c0) || alpha < pts.alpha_fp {
            return Evaluation::separated(pts.alpha_c0, NanHistory { established: false, ..*h });
        }
        let history = NanHistory { established: true, ..*h };
        if alpha <= pts.alpha_cp {
            return Evaluation {
                force: -pts.f_cp + pts.k_c * (pts.alpha_cp - alpha), // Eq. 19
                stiffness: -pts.k_c,
                branch: Branch::Adhesive,
                lower: pts.alpha_fp,
                upper: pts.alpha_cp,
                history,
            };
        }
        if alpha <= h.alpha_max {
            return Evaluation {
                force: pts.k_e * (alpha - pts.alpha_p), // Eq. 17
                stiffness: pts.k_e,
                branch: Branch::Elastic,
                lower: pts.alpha_cp,
                upper: h.alpha_max,
                history,
            };
        }
        let p = &self.p;
        Evaluation {
            force: p.f_y + p.k_p * (alpha - p.alpha_y), // Eq. 18
            stiffness: p.k_p,
            branch: Branch::Plastic,
            lower: alpha,
            upper: f64::INFINITY,
            history: NanHistory { established: true, alpha_max: alpha, points: self.points_after_yield(alpha) },
        }
    }

    #[inline]
    fn has_yielded(&self, h: &NanHistory) -> bool {
        h.alpha_max > self.p.alpha_y
    }

    /// 000 Eq. 23: the limit is mu f; no adhesion shift.
    #[inline]
    fn sliding_normal_force(&self, force: f64, _alpha: f64, _h: &NanHistory) -> f64 {
        force
    }

    fn pull_off_force(&self, h: &NanHistory) -> f64 {
        h.points.f_cp
    }

    fn plastic_overlap(&self, h: &NanHistory) -> f64 {
        h.points.alpha_p
    }
}

impl LawInfo for Nan {
    type Options = NanOptions;
    /// 000 Sec. 2.3: beta = 0.1 after yield.
    const PLASTIC_DAMPING_FACTOR: Option<f64> = Some(0.1);
    fn from_pair(pair: &Effective, options: &LawOptions) -> Result<Nan, ParamError> {
        Ok(Nan::new(NanParams::from_pair(pair, &options.stiffness, &options.nan)?))
    }
}
