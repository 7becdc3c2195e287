//! Luding's 2008 elasto-plastic adhesive law (`003` Eq. 4 and Fig. 10, `004` Sec. 3.4.4.5, Eqs. 3.71-3.75).
//!
//! Three lines, all shifted by the attraction f_0 at first contact (003 Eq. 4):
//! - plastic limit    P = k_1 alpha - f_0,
//! - un/reloading     L = k_2 (alpha - delta_0) - f_0,
//! - adhesion limit   A = -k_c alpha - f_0.
//!
//! The force is L while A < L < P. Reaching P (loading) moves delta_0 so the line passes through the
//! current point: delta_0 = (1 - k_1/k_2) alpha. Reaching A (unloading) moves it too:
//! delta_0 = (1 + k_c/k_2) alpha, so reloading from there runs parallel to the first unloading line
//! (004 Sec. 3.4.4.5). k_2 grows with the largest overlap reached (Eq. 3.74), capped at k_2_hat beyond
//! alpha* = k_2_hat / (k_2_hat - k_1) phi_f 2 R* (Eq. 3.71). The contact breaks at alpha = 0 and is then
//! new: it keeps no history (the model's defining flaw, 004 Sec. 3.4.4.5).

use super::params::{k_el_default, Effective};
use super::{Branch, Evaluation, LawInfo, LawOptions, NormalLaw};
use crate::error::ParamError;
use crate::scene::Range;

#[derive(Debug, Clone, PartialEq)]
pub struct Luding {
    /// k_1 [N/m].
    pub k1: f64,
    /// k_2 hat [N/m].
    pub k2_hat: f64,
    /// k_c [N/m].
    pub kc: f64,
    /// f_0 [N].
    pub f0: f64,
    /// alpha* [m].
    pub alpha_star: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LudingHistory {
    pub established: bool,
    /// Largest overlap reached; sets k_2 (Eq. 3.74) [m].
    pub delta_peak: f64,
    /// Zero of k_2 (alpha - delta_0): where the un/reloading line sits [m].
    pub delta_0: f64,
}

impl Luding {
    pub fn new(k1: f64, k2_hat: f64, kc: f64, f0: f64, phi_f: f64, r_star: f64) -> Luding {
        let alpha_star = k2_hat / (k2_hat - k1) * phi_f * 2.0 * r_star; // Eq. 3.71
        Luding { k1, k2_hat, kc, f0, alpha_star }
    }

    /// k_2 for a largest overlap (004 Eq. 3.74).
    pub fn k2(&self, delta_peak: f64) -> f64 {
        if delta_peak >= self.alpha_star {
            self.k2_hat
        } else {
            self.k1 + (self.k2_hat - self.k1) * delta_peak / self.alpha_star
        }
    }
}

impl NormalLaw for Luding {
    type History = LudingHistory;

    fn initial_history(&self) -> LudingHistory {
        LudingHistory { established: false, delta_peak: 0.0, delta_0: 0.0 }
    }

    fn evaluate(&self, alpha: f64, h: &LudingHistory) -> Evaluation<LudingHistory> {
        if alpha <= 0.0 {
            return Evaluation::separated(0.0, self.initial_history());
        }
        let k2 = self.k2(h.delta_peak);
        let spring = k2 * (alpha - h.delta_0);
        if spring >= self.k1 * alpha {
            let peak = h.delta_peak.max(alpha);
            let k2_new = self.k2(peak);
            return Evaluation {
                force: self.k1 * alpha - self.f0,
                stiffness: self.k1,
                branch: Branch::Plastic,
                lower: alpha,
                upper: f64::INFINITY,
                history: LudingHistory { established: true, delta_peak: peak, delta_0: (1.0 - self.k1 / k2_new) * alpha },
            };
        }
        if spring <= -self.kc * alpha {
            return Evaluation {
                force: -self.kc * alpha - self.f0,
                stiffness: -self.kc,
                branch: Branch::Adhesive,
                lower: 0.0,
                upper: alpha,
                history: LudingHistory { established: true, delta_peak: h.delta_peak, delta_0: (1.0 + self.kc / k2) * alpha },
            };
        }
        Evaluation {
            force: spring - self.f0,
            stiffness: k2,
            branch: Branch::Elastic,
            lower: k2 * h.delta_0 / (k2 + self.kc),
            upper: if k2 > self.k1 { k2 * h.delta_0 / (k2 - self.k1) } else { alpha },
            history: LudingHistory { established: true, ..*h },
        }
    }

    fn has_yielded(&self, h: &LudingHistory) -> bool {
        h.delta_peak > 0.0
    }

    /// 004 Eq. 3.75, measured from the adhesion limit -k_c alpha - f_0: mu (F_n + k_c alpha + f_0).
    fn sliding_normal_force(&self, force: f64, alpha: f64, _h: &LudingHistory) -> f64 {
        force + self.kc * alpha.max(0.0) + self.f0
    }

    /// Where the current un/reloading line meets the adhesion limit.
    fn pull_off_force(&self, h: &LudingHistory) -> f64 {
        let k2 = self.k2(h.delta_peak);
        self.kc * k2 * h.delta_0 / (k2 + self.kc) + self.f0
    }

    /// Zero-force overlap of the current un/reloading line.
    fn plastic_overlap(&self, h: &LudingHistory) -> f64 {
        if h.established {
            h.delta_0 + self.f0 / self.k2(h.delta_peak)
        } else {
            0.0
        }
    }
}

crate::scene_options! {
    /// The Luding law's own scene keys.
    pub struct LudingOptions {
        luding_loading_stiffness: derived("plastic_stiffness, else pi R* p_y"), "N/m", Range::Open(0.0, 1e12), "k_1, plastic loading stiffness (003 Eq. 4)";
        luding_max_unloading_stiffness: derived("5 k_1"), "N/m", Range::Open(0.0, 1e12), "k_2 hat, the unloading stiffness reached at alpha* (004 Eqs. 3.71, 3.74)";
        luding_adhesion_stiffness: number(0.0), "N/m", Range::ClosedLow(0.0, 1e12), "k_c, slope of the adhesion limit -k_c alpha - f_0 (003 Eq. 4)";
        luding_plasticity_depth: number(0.05), "-", Range::Open(0.0, 0.5), "phi_f, dimensionless plasticity depth: alpha* = k2/(k2 - k1) phi_f 2 R* (004 Eq. 3.71)";
        luding_contact_adhesion_force: derived("8/9 f_ce"), "N", Range::ClosedLow(0.0, 1e6), "f_0, attraction at first contact (003 Eq. 4; 004 Table 4.2 sets it to 8/9 f_ce)";
    }
}

impl LawInfo for Luding {
    type Options = LudingOptions;
    fn from_pair(pair: &Effective, options: &LawOptions) -> Result<Luding, ParamError> {
        let own = &options.luding;
        let k1 = match (own.luding_loading_stiffness, options.stiffness.plastic_stiffness) {
            (Some(k), _) | (None, Some(k)) => k,
            _ => k_el_default(pair.radius, pair.require_yield_pressure("luding (no luding_loading_stiffness given)")?),
        };
        let k2_hat = own.luding_max_unloading_stiffness.unwrap_or(5.0 * k1);
        if k2_hat <= k1 {
            return Err(ParamError::Inconsistent {
                name: "luding_max_unloading_stiffness",
                why: format!("k_2_hat = {k2_hat:e} N/m must exceed k_1 = {k1:e} N/m (004 Eq. 3.71)"),
            });
        }
        let f0 = own.luding_contact_adhesion_force.unwrap_or(8.0 / 9.0 * pair.f_ce());
        Ok(Luding::new(k1, k2_hat, own.luding_adhesion_stiffness, f0, own.luding_plasticity_depth, pair.radius))
    }
}
