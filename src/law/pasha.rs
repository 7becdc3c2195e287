//! Pasha's linear elasto-plastic adhesive law (`004` Ch. 4, Fig. 4.1, Eqs. 4.1-4.11).
//!
//! Branches (004 Fig. 4.1), with alpha_0 = 8/9 f_ce / k_e:
//! - first contact at alpha = 0, force drops to -8/9 f_ce (Eq. 4.2);
//! - elastic k_e (alpha - alpha_0) up to alpha_0, then plastic loading k_p (alpha - alpha_0) (Eq. 4.3),
//!   alpha_max follows alpha;
//! - unloading k_e (alpha - alpha_p) (Eq. 4.4) down to the pull-off point alpha_cp, then the line of
//!   slope -k_e, k_e (2 alpha_cp - alpha_p - alpha) (Eq. 4.5), to detachment at -5/9 f_cp (alpha_fp,
//!   004 Eq. A1.5). Unloading and reloading are reversible; after detachment the contact is
//!   re-established at alpha_fp when alpha_fp > 0 (004 Sec. 4.1), else at alpha = 0.
//!
//! Pull-off force (004 Sec. 4.1.1): the adhesion work 137/162 k_e (alpha_p - alpha_cp)^2 (Eq. 4.9) equals
//! Gamma times the flattened area pi (2 R* alpha_pd - alpha_pd^2), alpha_pd = alpha_p - alpha_0 (Eqs. 4.6-4.8),
//! which is Eqs. 4.10-4.11 solved for f_cp = k_e (alpha_p - alpha_cp). At vanishing plastic deformation
//! that gives f_cp -> 0, below the elastic JKR value; the thesis states f_cp is always above f_ce, so we
//! take f_cp = max(f_ce, Eq. 4.10), which also keeps the law continuous in its history at yield
//! (docs/models.md).
//!
//! k_e is constant, or load-dependent by Eq. 4.23 (then k_e before yield is k_e(alpha_0), solved with
//! alpha_0 = 8/9 f_ce / k_e, so k_e is continuous at yield).

use super::params::Effective;
use super::params::StiffnessOptions;
use super::{Branch, Evaluation, LawInfo, LawOptions, NormalLaw};
use crate::error::ParamError;
use crate::vocabulary::Range;

crate::choice_enum! {
    /// Constant or load-dependent unloading stiffness in the Pasha laws.
    pub enum PashaStiffnessLaw {
        /// Constant k_e: `elastic_stiffness`, else pi R* p_y (000 Eq. 52).
        Constant = "constant",
        /// 004 Eq. 4.23.
        LoadDependent = "load_dependent",
    }
}

crate::scene_options! {
    /// The Pasha law's own scene keys (its unloading stiffness, which pasha_simplified shares).
    pub struct PashaOptions {
        pasha_stiffness_law: choice(PashaStiffnessLaw::Constant), "-", Range::Names, "pasha k_e: constant, or load_dependent k_e = k_p + (r/R*)^2 (k_e_max - k_p), r^2 = 2 R* alpha_max - alpha_max^2 (004 Eqs. 4.21-4.23)";
        pasha_max_elastic_stiffness: derived("none"), "N/m", Range::Open(0.0, 1e12), "k_e_max of 004 Eq. 4.23 (the stiffness at an overlap of R*); required with load_dependent";
    }
}
use std::f64::consts::PI;

/// Pasha's law of one contact pair (the module documentation says which equations).
#[derive(Debug, Clone, PartialEq)]
pub struct Pasha {
    /// Reduced radius R* [m].
    pub radius: f64,
    /// Interface energy Gamma [J/m^2].
    pub surface_energy: f64,
    /// f_ce (Eq. 4.1) [N].
    pub f_ce: f64,
    /// Unloading stiffness law and its constants.
    pub stiffness: PashaStiffness,
    /// k_p [N/m].
    pub k_p: f64,
    /// Stiffness of the elastic line before yield [N/m].
    pub k_e0: f64,
    /// alpha_0 = 8/9 f_ce / k_e0 [m].
    pub alpha_0: f64,
}

/// k_e of the Pasha laws: constant, or 004 Eq. 4.23.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PashaStiffness {
    /// Constant or load-dependent k_e (`pasha_stiffness_law`).
    pub law: PashaStiffnessLaw,
    /// Constant k_e, or k_e_max of Eq. 4.23 [N/m].
    pub k_e: f64,
    /// Plastic stiffness k_p, the value of Eq. 4.23 at alpha_max = 0 [N/m].
    pub k_p: f64,
    /// Reduced radius R* of Eq. 4.23 [m].
    pub radius: f64,
}

impl PashaStiffness {
    /// k_e at a given alpha_max: constant, or k_p + (r/R*)^2 (k_e_max - k_p) with r^2 = 2 R* alpha_max - alpha_max^2
    /// (004 Eqs. 4.21-4.23); r is capped at R* (alpha_max >= R* is outside the model).
    #[inline]
    pub fn at(&self, alpha_max: f64) -> f64 {
        match self.law {
            PashaStiffnessLaw::Constant => self.k_e,
            PashaStiffnessLaw::LoadDependent => {
                let a = alpha_max.clamp(0.0, self.radius);
                let r2 = 2.0 * self.radius * a - a * a;
                self.k_p + r2 / (self.radius * self.radius) * (self.k_e - self.k_p)
            }
        }
    }

    /// Reads `elastic_stiffness` (or `pasha_max_elastic_stiffness`) and `plastic_stiffness` and checks k_e >= k_p.
    pub fn from_options(eff: &Effective, s: &StiffnessOptions, own: &PashaOptions, model: &str) -> Result<PashaStiffness, ParamError> {
        let k_e = match s.elastic_stiffness {
            Some(k) => k,
            None => super::params::k_el_default(eff.radius, eff.require_yield_pressure(model)?),
        };
        let k_p = s.plastic_stiffness.unwrap_or(k_e);
        let (law, k_top, top_name) = match own.pasha_stiffness_law {
            PashaStiffnessLaw::Constant => (PashaStiffnessLaw::Constant, k_e, "elastic_stiffness"),
            PashaStiffnessLaw::LoadDependent => {
                let k_max = own.pasha_max_elastic_stiffness.ok_or_else(|| ParamError::Missing {
                    name: "pasha_max_elastic_stiffness",
                    why: "pasha_stiffness_law load_dependent needs k_e_max (004 Eq. 4.23)".into(),
                })?;
                (PashaStiffnessLaw::LoadDependent, k_max, "pasha_max_elastic_stiffness")
            }
        };
        if k_p > k_top {
            return Err(ParamError::Inconsistent {
                name: "plastic_stiffness",
                why: format!("k_p = {k_p:e} N/m exceeds {top_name} = {k_top:e} N/m; the Pasha laws need k_p <= k_e"),
            });
        }
        Ok(PashaStiffness { law, k_e: k_top, k_p, radius: eff.radius })
    }
}

/// What a Pasha contact remembers (both the full and the simplified law).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PashaHistory {
    /// In contact: formed (or re-formed at max(alpha_fp, 0)) and not detached since.
    pub established: bool,
    /// Largest overlap of plastic loading [m].
    pub alpha_max: f64,
}

/// The quantities that follow from alpha_max.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PashaPoints {
    /// Unloading stiffness k_e at this alpha_max [N/m].
    pub k_e: f64,
    /// Zero-force overlap alpha_p of the unloading line k_e (alpha - alpha_p) (Eq. 4.4) [m].
    pub alpha_p: f64,
    /// Pull-off force f_cp: max(f_ce, Eqs. 4.6-4.11) in the full law, on the locus of Eq. 4.17 in the
    /// simplified one [N].
    pub f_cp: f64,
    /// Overlap alpha_cp of the pull-off point, f = -f_cp [m].
    pub alpha_cp: f64,
    /// Overlap alpha_fp at which the contact detaches: at -5/9 f_cp in the full law, at zero force in
    /// the simplified one [m].
    pub alpha_fp: f64,
}

impl Pasha {
    /// The law of reduced radius R* [m], interface energy Gamma [J/m^2] and unloading stiffness: f_ce by
    /// Eq. 4.1, k_e0 = k_e(alpha_0) solved by fixed point.
    pub fn new(radius: f64, surface_energy: f64, stiffness: PashaStiffness) -> Pasha {
        let f_ce = 1.5 * PI * surface_energy * radius;
        // Before yield the elastic line ends at alpha_0 = 8/9 f_ce / k_e0; with Eq. 4.23 k_e depends on
        // alpha_max, so k_e0 = k_e(alpha_0) is solved by fixed point (it contracts: k_e varies little over
        // alpha_0 << R*), which keeps k_e continuous at yield. For constant k_e this is k_e itself.
        let mut k_e0 = stiffness.at(0.0);
        for _ in 0..100 {
            let next = stiffness.at(8.0 / 9.0 * f_ce / k_e0);
            if (next - k_e0).abs() <= 1e-15 * next {
                break;
            }
            k_e0 = next;
        }
        Pasha { radius, surface_energy, f_ce, stiffness, k_p: stiffness.k_p, k_e0, alpha_0: 8.0 / 9.0 * f_ce / k_e0 }
    }

    /// The adhesion pull-off force of Eqs. 4.6-4.11 (before the max with f_ce).
    pub fn f_cp_energy(&self, k_e: f64, alpha_p: f64) -> f64 {
        let a_pd = (alpha_p - self.alpha_0).clamp(0.0, self.radius);
        let w_ad = PI * self.surface_energy * (2.0 * self.radius * a_pd - a_pd * a_pd); // Eq. 4.8
        (162.0 / 137.0 * k_e * w_ad).sqrt() // Eq. 4.9 with f_cp = k_e (alpha_p - alpha_cp)
    }

    /// The branch points for a largest overlap alpha_max; at or below alpha_0 (before yield) they use
    /// k_e0, alpha_p = alpha_0 and f_cp = f_ce.
    #[inline]
    pub fn points(&self, alpha_max: f64) -> PashaPoints {
        let (k_e, alpha_p, f_cp) = if alpha_max <= self.alpha_0 {
            (self.k_e0, self.alpha_0, self.f_ce)
        } else {
            let k_e = self.stiffness.at(alpha_max);
            let f_max = self.k_p * (alpha_max - self.alpha_0);
            let alpha_p = alpha_max - f_max / k_e;
            (k_e, alpha_p, self.f_cp_energy(k_e, alpha_p).max(self.f_ce))
        };
        let alpha_cp = alpha_p - f_cp / k_e;
        PashaPoints { k_e, alpha_p, f_cp, alpha_cp, alpha_fp: alpha_cp - 4.0 / 9.0 * f_cp / k_e }
    }
}

/// The branch logic the full and the simplified Pasha laws share: reversible elastic line of slope k_e
/// through (alpha_p, 0), the mirrored line of slope -k_e beyond alpha_cp, plastic loading above alpha_max,
/// re-contact at max(alpha_fp, 0).
#[inline]
pub(crate) fn pasha_evaluate(alpha: f64, h: &PashaHistory, pts: &PashaPoints, plastic: impl Fn(f64) -> f64, k_p: f64) -> Evaluation<PashaHistory> {
    let recontact = pts.alpha_fp.max(0.0);
    if (!h.established && alpha < recontact) || alpha < pts.alpha_fp {
        return Evaluation::separated(recontact, PashaHistory { established: false, alpha_max: h.alpha_max });
    }
    let history = PashaHistory { established: true, alpha_max: h.alpha_max };
    if alpha <= pts.alpha_cp {
        return Evaluation {
            force: pts.k_e * (2.0 * pts.alpha_cp - pts.alpha_p - alpha), // Eq. 4.5
            stiffness: -pts.k_e,
            branch: Branch::Adhesive,
            lower: pts.alpha_fp,
            upper: pts.alpha_cp,
            history,
        };
    }
    if alpha <= h.alpha_max {
        return Evaluation {
            force: pts.k_e * (alpha - pts.alpha_p), // Eqs. 4.2, 4.4
            stiffness: pts.k_e,
            branch: Branch::Elastic,
            lower: pts.alpha_cp,
            upper: h.alpha_max,
            history,
        };
    }
    Evaluation {
        force: plastic(alpha), // Eq. 4.3
        stiffness: k_p,
        branch: Branch::Plastic,
        lower: alpha,
        upper: f64::INFINITY,
        history: PashaHistory { established: true, alpha_max: alpha },
    }
}

impl NormalLaw for Pasha {
    type History = PashaHistory;

    fn initial_history(&self) -> PashaHistory {
        PashaHistory { established: false, alpha_max: self.alpha_0 }
    }

    #[inline]
    fn evaluate(&self, alpha: f64, h: &PashaHistory) -> Evaluation<PashaHistory> {
        let pts = self.points(h.alpha_max);
        pasha_evaluate(alpha, h, &pts, |a| self.k_p * (a - self.alpha_0), self.k_p)
    }

    #[inline]
    fn has_yielded(&self, h: &PashaHistory) -> bool {
        h.alpha_max > self.alpha_0
    }

    /// 004 Eq. 4.27: mu (F_n + f_cp - f_ce).
    #[inline]
    fn sliding_normal_force(&self, force: f64, _alpha: f64, h: &PashaHistory) -> f64 {
        force + self.points(h.alpha_max).f_cp - self.f_ce
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

impl LawInfo for Pasha {
    type Options = PashaOptions;
    fn from_pair(pair: &Effective, options: &LawOptions) -> Result<Pasha, ParamError> {
        let stiffness = PashaStiffness::from_options(pair, &options.stiffness, &options.pasha, "pasha")?;
        Ok(Pasha::new(pair.radius, pair.surface_energy, stiffness))
    }
}
