//! From material data to model parameters: effective properties and the correlations of
//! `000` Sec. 3 (yield point, stiffnesses, pull-off force). Each function is one equation.

use crate::error::ParamError;
use super::nan::{AdhesiveStiffnessLaw, NanOptions, PullOffLaw, UnloadingStiffnessLaw};
use crate::scene::{Partner, Range, Scene, YieldCorrelation};
use std::f64::consts::PI;
use crate::numeric::cbrt;

crate::scene_options! {
    /// The stiffnesses several laws share (nan, the Pasha laws, linear, walton_braun, luding): given, or
    /// derived from the pair by 000 Eq. 52 or a measured unloading line.
    pub struct StiffnessOptions {
        elastic_stiffness: derived("pi R* p_y"), "N/m", Range::Open(0.0, 1e12), "k_el, elastic stiffness before yield (nan); constant k_e (pasha, pasha_simplified); unloading k_e (walton_braun). Default 000 Eq. 52";
        unloading_stiffness_reference: derived("none"), "N/m", Range::Open(0.0, 1e12), "k_e0 of a measured unloading line; with unloading_overlap_reference gives k_el by 000 Eqs. 45 and 29 (or 49)";
        unloading_overlap_reference: derived("none"), "m", Range::Open(0.0, 1.0), "alpha_max0, the overlap at which the measured unloading line with k_e0 starts (000 Eq. 43)";
        plastic_stiffness: derived("elastic_stiffness"), "N/m", Range::Open(0.0, 1e12), "k_p, plastic loading stiffness (000 Eq. 18, 004 Eq. 4.3); must not exceed k_el";
    }
}

/// The typed description of a contact pair every law is built from (docs/architecture.md, "Contact law conventions"): effective
/// geometry, mass and materials. A scene gives one (`from_scene`); the bed mixes one per pair of species.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Effective {
    /// R* = R1 R2 / (R1 + R2); a wall: R [m].
    pub radius: f64,
    /// m* likewise; a wall: m [kg].
    pub mass: f64,
    /// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (004 Eq. 3.15) [Pa].
    pub youngs_modulus: f64,
    /// 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2 [Pa].
    pub shear_modulus: f64,
    /// Interface energy Gamma [J/m^2].
    pub surface_energy: f64,
    /// p_y = min(p_y1, p_y2) (000 Sec. 3.1), after the strain-rate law if one is given [Pa].
    pub yield_pressure: Option<f64>,
}

impl Effective {
    pub fn from_scene(s: &Scene) -> Result<Effective, ParamError> {
        s.validate()?;
        let (r, m) = (s.particle_radius, s.particle_mass());
        let (e1, nu1, g1) = (s.particle_youngs_modulus, s.particle_poisson_ratio, s.particle_shear_modulus());
        let (radius, mass, inv_e2, inv_g2) = match s.contact_partner {
            Partner::Wall => match s.wall_youngs_modulus {
                Some(e2) => {
                    let nu2 = s.wall_poisson_ratio;
                    let g2 = e2 / (2.0 * (1.0 + nu2));
                    (r, m, (1.0 - nu2 * nu2) / e2, (2.0 - nu2) / g2)
                }
                None => (r, m, 0.0, 0.0),
            },
            Partner::Particle => (r / 2.0, m / 2.0, (1.0 - nu1 * nu1) / e1, (2.0 - nu1) / g1),
        };
        let youngs_modulus = 1.0 / ((1.0 - nu1 * nu1) / e1 + inv_e2);
        let shear_modulus = 1.0 / ((2.0 - nu1) / g1 + inv_g2);
        let particle_py = match (s.particle_yield_pressure, s.particle_yield_stress) {
            (Some(_), Some(_)) => {
                return Err(ParamError::Inconsistent {
                    name: "particle_yield_stress",
                    why: "give particle_yield_pressure or particle_yield_stress, not both".into(),
                })
            }
            (Some(p), None) => Some(p),
            (None, Some(sigma)) => Some(yield_pressure_from_stress(sigma, nu1, s.yield_pressure_correlation)),
            (None, None) => None,
        };
        let wall_py = if s.contact_partner == Partner::Particle { particle_py } else { s.wall_yield_pressure };
        let mut yield_pressure = match (particle_py, wall_py) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        if s.yield_stress_rate_coefficient > 0.0 {
            let factor = strain_rate_factor(s.yield_stress_rate_coefficient, s.strain_rate.unwrap_or(1.0), s.reference_strain_rate.unwrap_or(1.0));
            if !(factor > 0.0) {
                return Err(ParamError::Inconsistent {
                    name: "yield_stress_rate_coefficient",
                    why: format!("1 + Y ln(V_i/V_0) = {factor:.4} must be positive (000 Eq. 34): raise strain_rate or lower the coefficient"),
                });
            }
            yield_pressure = yield_pressure.map(|p| p * factor);
        }
        Ok(Effective {
            radius,
            mass,
            youngs_modulus,
            shear_modulus,
            surface_energy: s.surface_energy,
            yield_pressure,
        })
    }

    /// p_y, or an error naming the keys that give it.
    pub fn require_yield_pressure(&self, model: &str) -> Result<f64, ParamError> {
        self.yield_pressure.ok_or_else(|| ParamError::Missing {
            name: "particle_yield_pressure",
            why: format!(
                "contact_model {model} needs a limiting contact pressure: give particle_yield_pressure, particle_yield_stress or wall_yield_pressure"
            ),
        })
    }

    /// JKR pull-off force f_ce = 1.5 pi Gamma R* (000 Eq. 5, 004 Eq. 4.1) [N].
    pub fn f_ce(&self) -> f64 {
        1.5 * PI * self.surface_energy * self.radius
    }
}

/// p_y from the yield stress: 000 Eq. 32 (Jackson & Green) or Eq. 33 (Chang et al.).
pub fn yield_pressure_from_stress(sigma_y: f64, nu: f64, correlation: YieldCorrelation) -> f64 {
    match correlation {
        YieldCorrelation::JacksonGreen => 1.295 * (0.736 * nu).exp() * sigma_y,
        YieldCorrelation::Chang => (0.454 + 0.41 * nu) * 2.8 * sigma_y,
    }
}

/// The factor sigma_y / sigma_y^s = 1 + Y ln(V_i / V_0) of 000 Eq. 34.
pub fn strain_rate_factor(y: f64, v_i: f64, v_0: f64) -> f64 {
    1.0 + y * (v_i / v_0).ln()
}

/// Thornton-Ning yield force f_y0 = pi^3 R*^2 p_y^3 / (6 E*^2) (000 Eq. 30, 004 Eq. 3.27).
pub fn f_y0(r: f64, e: f64, p_y: f64) -> f64 {
    PI.powi(3) * r * r * p_y.powi(3) / (6.0 * e * e)
}

/// Thornton-Ning yield overlap alpha_y0 = pi^2 R* p_y^2 / (4 E*^2) (000 Eq. 31, 004 Eq. 3.29).
pub fn alpha_y0(r: f64, e: f64, p_y: f64) -> f64 {
    PI * PI * r * p_y * p_y / (4.0 * e * e)
}

/// Yield force of the linear law with the yield work of Thornton-Ning: f_y = f_y0 sqrt(6/5 k_el / (pi R* p_y)) (000 Eq. 28).
pub fn f_y(r: f64, e: f64, p_y: f64, k_el: f64) -> f64 {
    f_y0(r, e, p_y) * (1.2 * k_el / (PI * r * p_y)).sqrt()
}

/// W_JKR = 7.09 (Gamma^5 R*^4 / E*^2)^(1/3) (000 Eq. 37).
pub fn w_jkr(gamma: f64, r: f64, e: f64) -> f64 {
    7.09 * cbrt(gamma.powi(5) * r.powi(4) / (e * e))
}

/// k_el / k_cl by 000 Eq. 36 (W_0 = W_JKR). Errors when the denominator is not positive.
pub fn kel_over_kcl_exact(f_ce: f64, k_el: f64, w_jkr: f64) -> Option<f64> {
    let den = 56.0 / 162.0 * f_ce * f_ce / k_el;
    let num = w_jkr - 17.0 / 162.0 * f_ce * f_ce / k_el;
    (num > 0.0 && den > 0.0).then(|| num / den)
}

/// k_el / k_cl by the approximation 000 Eq. 38.
pub fn kel_over_kcl_approx(k_el: f64, gamma: f64, e: f64, r: f64) -> f64 {
    0.92 * k_el / (cbrt(gamma) * cbrt(e * e * r * r)) - 0.3
}

/// Stiffness of Hertz-JKR at alpha = 0: (16 pi / 27)^(1/3) (Gamma E*^2 R*^2)^(1/3) (000 Eqs. 40, B7).
pub fn k_hjkr_at_zero(gamma: f64, e: f64, r: f64) -> f64 {
    cbrt(16.0 * PI / 27.0) * cbrt(gamma * e * e * r * r)
}

/// Hertz stiffness 2 E* sqrt(R* alpha) (000 Eq. 41).
pub fn k_hertz(e: f64, r: f64, alpha: f64) -> f64 {
    2.0 * e * (r * alpha.max(0.0)).sqrt()
}

/// Default k_el = 2 E* sqrt(R* alpha_y0) = pi R* p_y (000 Eq. 52).
pub fn k_el_default(r: f64, p_y: f64) -> f64 {
    PI * r * p_y
}

/// alpha_y of 000 Eq. 29 (with Eq. 6): alpha_0 + alpha_y0 sqrt(8/15 pi R* p_y / k_el).
pub fn alpha_y(r: f64, e: f64, p_y: f64, k_el: f64, f_ce: f64) -> f64 {
    8.0 / 9.0 * f_ce / k_el + alpha_y0(r, e, p_y) * (8.0 / 15.0 * PI * r * p_y / k_el).sqrt()
}

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
    pub radius: f64,
    pub youngs_modulus: f64,
    pub surface_energy: f64,
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
    pub unloading_stiffness_law: UnloadingStiffnessLaw,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn yield_correlations_give_the_ratio_of_000_fig5() {
        // 000 Sec. 3.1: for nu = 0.2..0.4 both give p_y/sigma_y = 1.4..1.7.
        for nu in [0.2, 0.3, 0.4] {
            for c in [YieldCorrelation::JacksonGreen, YieldCorrelation::Chang] {
                let ratio = yield_pressure_from_stress(1.0, nu, c);
                assert!((1.4..=1.75).contains(&ratio), "nu {nu} {c:?} ratio {ratio}");
            }
        }
    }

    #[test]
    fn default_k_el_equals_hertz_stiffness_at_alpha_y0() {
        // 000 Eq. 52: 2 E* sqrt(R* alpha_y0) = pi R* p_y.
        let (r, e, p) = (2.45e-6, 1.3e9, 35e6);
        let a = 2.0 * e * (r * alpha_y0(r, e, p)).sqrt();
        assert!((a / k_el_default(r, p) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn b7_constant_is_the_1_23_of_eq_40() {
        assert!(((16.0 * PI / 27.0).cbrt() - 1.23).abs() < 0.005);
    }
}
