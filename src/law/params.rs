//! From material data to model parameters: effective properties and the correlations of
//! `000` Sec. 3 (yield point, stiffnesses, pull-off force). Each function is one equation.

use crate::error::ParamError;
use crate::numeric::cbrt;
use crate::vocabulary::Range;
use std::f64::consts::PI;

crate::choice_enum! {
    /// Correlation from yield stress to limiting contact pressure.
    pub enum YieldCorrelation {
        /// 000 Eq. 32: p_y = 1.295 exp(0.736 nu) sigma_y.
        JacksonGreen = "jackson_green",
        /// 000 Eq. 33: p_y = (0.454 + 0.41 nu) 2.8 sigma_y.
        Chang = "chang",
    }
}

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
