//! Load-dependent adhesion force after consolidation by a normal force f_N (`003` Sec. 3.3, Eqs. 5-7).

use std::f64::consts::PI;

/// Tomas' adhesion force f_H(f_N) by the iteration of 003 Eq. 5, started from f_H = -f_N as the paper does.
/// `youngs_modulus_tomas` is Tomas' E* (twice the Hertz E* of 004 Eq. 3.15). Returns `None` if the iteration
/// does not settle within 200 steps.
pub fn tomas_adhesion_force(f_n: f64, f_0: f64, kappa: f64, kappa_p: f64, p_f: f64, radius: f64, youngs_modulus_tomas: f64) -> Option<f64> {
    let mut f_h = -f_n;
    for _ in 0..200 {
        let load = f_n + f_0;
        let bracket = 3.0 * load / (2.0 * radius * radius * youngs_modulus_tomas) * (1.0 + (f_h - f_0) / load);
        let next = f_0 + kappa * load - PI * radius * radius * kappa_p * p_f * bracket.max(0.0).powf(2.0 / 3.0);
        if (next - f_h).abs() <= 1e-13 * next.abs().max(f_0) {
            return Some(next);
        }
        f_h = next;
    }
    None
}

/// The linearised Tomas adhesion force (1 + kappa) f_0 + kappa f_N (003 Eq. 6).
pub fn tomas_adhesion_force_linear(f_n: f64, f_0: f64, kappa: f64) -> f64 {
    (1.0 + kappa) * f_0 + kappa * f_n
}

/// Luding's pull-off force after loading to f_N: (1 + kappa_L) f_0 + kappa_L f_N with
/// kappa_L = (k_2/k_1 - 1) / (k_2/k_c + 1) (003 Eq. 7).
pub fn luding_adhesion_force(f_n: f64, f_0: f64, k1: f64, k2: f64, kc: f64) -> f64 {
    let kappa_l = (k2 / k1 - 1.0) / (k2 / kc + 1.0);
    (1.0 + kappa_l) * f_0 + kappa_l * f_n
}
