//! The parameters of the Nan improved linear law from material data (000 Sec. 3): k_el by Eq. 52, given,
//! or from a measured unloading line (Eqs. 43-49); k_cl by Eq. 36 or 38; the yield point by Eqs. 28-29;
//! f_cp after yield by the method of 000 Table 4. The correlations every law shares are in `params`.

use super::nan::{AdhesiveStiffnessLaw, NanOptions, PullOffLaw, UnloadingStiffnessLaw};
use super::params::{alpha_y, alpha_y0, f_y, k_el_default, kel_over_kcl_approx, kel_over_kcl_exact, w_jkr, Effective, StiffnessOptions};
use crate::error::ParamError;
use std::f64::consts::PI;

/// k_el from a measured unloading line (k_e0 at alpha_max0): Eq. 45 (or Eq. 49 with k_p) solved together
/// with Eq. 29 by fixed-point iteration from alpha_y = alpha_y0, as 000 Sec. 3.3 prescribes.
pub fn k_el_from_unloading_line(
    eff: &Effective,
    p_y: f64,
    k_e0: f64,
    alpha_max0: f64,
    k_p: Option<f64>,
    law: UnloadingStiffnessLaw,
) -> Result<f64, ParamError> {
    let (r, e, f_ce) = (eff.radius, eff.youngs_modulus, eff.f_ce());
    let kel_of = |ay: f64| -> f64 {
        let s = (ay / alpha_max0).sqrt();
        match (law, k_p) {
            (UnloadingStiffnessLaw::SqrtPlusPlastic, Some(kp)) => kp + (k_e0 - kp) * s,
            _ => k_e0 * s,
        }
    };
    if law == UnloadingStiffnessLaw::SqrtPlusPlastic && k_p.is_none() {
        return Err(ParamError::Missing {
            name: "plastic_stiffness",
            why: "k_el from a measured unloading line with unloading_stiffness_law sqrt_plus_plastic needs k_p (000 Eq. 49)".into(),
        });
    }
    let mut ay = alpha_y0(r, e, p_y);
    for _ in 0..500 {
        let k_el = kel_of(ay);
        if !(k_el > 0.0) {
            break;
        }
        let next = alpha_y(r, e, p_y, k_el, f_ce);
        if (next - ay).abs() <= 1e-14 * next {
            if alpha_max0 < next {
                return Err(ParamError::Inconsistent {
                    name: "unloading_overlap_reference",
                    why: format!(
                        "alpha_max0 = {alpha_max0:e} m lies below the yield overlap alpha_y = {next:e} m: the unloading line of 000 Eq. 43 must start after yield"
                    ),
                });
            }
            return Ok(kel_of(next));
        }
        ay = next;
    }
    Err(ParamError::Inconsistent {
        name: "unloading_stiffness_reference",
        why: "the iteration of 000 Eqs. 45 and 29 for k_el did not converge: check k_e0 and alpha_max0 against p_y and E*".into(),
    })
}

/// All parameters of the Nan improved linear law (000 Sec. 3) and the quantities derived from them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NanParams {
    /// Reduced radius R* [m].
    pub radius: f64,
    /// Effective modulus E* [Pa].
    pub youngs_modulus: f64,
    /// Interface energy Gamma [J/m^2].
    pub surface_energy: f64,
    /// Yield contact pressure p_y [Pa].
    pub yield_pressure: f64,
    /// f_ce (Eq. 5) [N].
    pub f_ce: f64,
    /// f_0 = 8/9 f_ce (Eq. 4) [N].
    pub f_0: f64,
    /// k_el [N/m].
    pub k_el: f64,
    /// k_cl [N/m].
    pub k_cl: f64,
    /// k_p [N/m].
    pub k_p: f64,
    /// f_y (Eq. 28) [N].
    pub f_y: f64,
    /// alpha_y (Eq. 29) [m].
    pub alpha_y: f64,
    /// alpha_0 = f_0 / k_el (Eq. 6) [m].
    pub alpha_0: f64,
    /// W_JKR (Eq. 37) [J].
    pub w_jkr: f64,
    /// How k_e grows after yield (`unloading_stiffness_law`).
    pub unloading_stiffness_law: UnloadingStiffnessLaw,
    /// How f_cp grows after yield (`pull_off_law`, 000 Table 4).
    pub pull_off_law: PullOffLaw,
}

impl NanParams {
    /// Builds and checks the Nan parameters: k_el by Eq. 52, given, or from a measured unloading line;
    /// k_p given or k_el; k_cl by Eq. 36 or 38; the yield point by Eqs. 28-29.
    pub fn from_pair(eff: &Effective, stiffness: &StiffnessOptions, own: &NanOptions) -> Result<NanParams, ParamError> {
        let s = stiffness;
        let p_y = eff.require_yield_pressure("nan")?;
        let (r, e, gamma) = (eff.radius, eff.youngs_modulus, eff.surface_energy);
        let f_ce = eff.f_ce();
        let k_el = match (s.elastic_stiffness, s.unloading_stiffness_reference, s.unloading_overlap_reference) {
            (Some(k), _, _) => k,
            (None, Some(k_e0), Some(a0)) => k_el_from_unloading_line(eff, p_y, k_e0, a0, s.plastic_stiffness, own.unloading_stiffness_law)?,
            _ => k_el_default(r, p_y),
        };
        let k_p = s.plastic_stiffness.unwrap_or(k_el);
        if k_p > k_el {
            return Err(ParamError::Inconsistent {
                name: "plastic_stiffness",
                why: format!("k_p = {k_p:e} N/m exceeds k_el = {k_el:e} N/m; the Nan law needs 0 < k_p <= k_el"),
            });
        }
        let w = w_jkr(gamma, r, e);
        let kel_over_kcl = if gamma == 0.0 {
            1.0
        } else {
            match own.adhesive_stiffness_law {
                AdhesiveStiffnessLaw::Exact => kel_over_kcl_exact(f_ce, k_el, w).ok_or_else(|| {
                    // Gamma^(1/3) < 7.09 k_el 162 / (17 * 2.25 pi^2 (E* R*)^(2/3)) keeps Eq. 36 positive.
                    let g_max = (7.09 * 162.0 * k_el / (17.0 * 2.25 * PI * PI * (e * r).powf(2.0 / 3.0))).powi(3);
                    ParamError::OutOfRange {
                        name: "surface_energy",
                        value: gamma,
                        allowed: format!("[0, {g_max:.4e}) J/m^2 for this k_el = {k_el:.4e} N/m: a larger Gamma makes k_cl negative (000 Eq. 36)"),
                    }
                })?,
                AdhesiveStiffnessLaw::Approximate => {
                    let v = kel_over_kcl_approx(k_el, gamma, e, r);
                    if v <= 0.0 {
                        return Err(ParamError::OutOfRange {
                            name: "surface_energy",
                            value: gamma,
                            allowed: format!(
                                "below {:.4e} J/m^2 for this k_el: a larger Gamma makes k_cl negative (000 Eq. 38)",
                                (0.92 * k_el / 0.3).powi(3) / (e * e * r * r)
                            ),
                        });
                    }
                    v
                }
            }
        };
        let k_cl = k_el / kel_over_kcl;
        let f_y = f_y(r, e, p_y, k_el);
        let alpha_0 = 8.0 / 9.0 * f_ce / k_el;
        Ok(NanParams {
            radius: r,
            youngs_modulus: e,
            surface_energy: gamma,
            yield_pressure: p_y,
            f_ce,
            f_0: 8.0 / 9.0 * f_ce,
            k_el,
            k_cl,
            k_p,
            f_y,
            alpha_y: alpha_0 + f_y / k_el,
            alpha_0,
            w_jkr: w,
            unloading_stiffness_law: own.unloading_stiffness_law,
            pull_off_law: own.pull_off_law,
        })
    }

    /// k_e after yield as a function of alpha_max: Eq. 46, or Eqs. 47-49 written with k_el.
    pub fn k_e(&self, alpha_max: f64) -> f64 {
        let s = (alpha_max / self.alpha_y).sqrt();
        match self.unloading_stiffness_law {
            UnloadingStiffnessLaw::Sqrt => self.k_el * s,
            UnloadingStiffnessLaw::SqrtPlusPlastic => self.k_p + (self.k_el - self.k_p) * s,
        }
    }

    /// A of 000 Eq. 56.
    pub fn pull_off_a(&self) -> f64 {
        16.0 / 27.0 / (56.0 / 162.0 * self.k_el / self.k_cl + 17.0 / 162.0)
    }

    /// f_cp after yield by the chosen method of 000 Table 4, given k_e, alpha_p and alpha_max.
    pub fn f_cp(&self, k_e: f64, alpha_p: f64, alpha_max: f64) -> f64 {
        if self.f_ce == 0.0 {
            return 0.0;
        }
        let ke_rel = k_e / self.k_el;
        let ratio = match self.pull_off_law {
            PullOffLaw::Energy => {
                // Eq. 59.
                let a = self.pull_off_a();
                0.5 * (-a + (a * a + 4.0 * ke_rel * (alpha_p / self.alpha_0 * a + 1.0)).sqrt())
            }
            PullOffLaw::Pasha => {
                // Eq. 61 with B = 96/137 (Eq. 62); zero where alpha_p < alpha_y, as 000 Sec. 3.4 notes.
                let d = alpha_p - self.alpha_y;
                let b = 96.0 / 137.0;
                (b * ke_rel * d / self.alpha_0 * (2.0 - d / self.radius)).max(0.0).sqrt()
            }
            PullOffLaw::Curvature => {
                // Eq. 64.
                let d = alpha_max - self.alpha_y;
                (self.f_y + k_e * d) / (self.f_y + self.k_p * d)
            }
            PullOffLaw::WorkRatio => ke_rel.powf(1.5), // Eq. 67
        };
        ratio * self.f_ce
    }
}
