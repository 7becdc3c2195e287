//! Critical sticking velocity of the Nan law for a normal impact on a wall (`000` Sec. 4, Eqs. 73-81),
//! undamped (e_0 = 1).

use super::work::work_terms;
use crate::law::nan::Nan;
use crate::numeric::brent;
use crate::numeric::cbrt;
use std::f64::consts::PI;

/// The characteristic velocities of one particle-wall pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StickingVelocities {
    /// V_s = sqrt(2 W_0 / m*) (Eq. 73): adhesive sticking velocity without plasticity (JKR) [m/s].
    pub jkr_sticking_velocity: f64,
    /// V_y0 = sqrt(f_y^2 / (m* k_el)) (Eq. 74): yield velocity without cohesion [m/s].
    pub yield_velocity: f64,
    /// V_y = sqrt((f_y^2 - f_0^2) / (m* k_el)) (Eq. 75); `None` when f_y < f_0 (adhesion-induced
    /// plasticity: every contact that forms yields) [m/s].
    pub adhesive_yield_velocity: Option<f64>,
    /// V_ys (Eqs. 77-79): the plastic adhesive sticking velocity [m/s]. `None` where Eq. 78 has no root:
    /// with the pull-off force of Eq. 61, which drops from f_ce to 0 at yield (000 Sec. 3.4).
    pub sticking_velocity: Option<f64>,
    /// f_max at an impact of V_ys [N].
    pub max_force_at_sticking: f64,
    /// Whether the contact yields at an impact of V_ys (V_y < V_s, Eq. 77).
    pub yields_at_sticking: bool,
}

/// V_s, V_y0, V_y and V_ys for a sphere of mass `mass` (the paper's m = m* for a wall).
///
/// V_ys: where V_y >= V_s the contact has not yielded at V_ys and V_ys = V_s. Otherwise Eq. 78,
/// W_4 = W_5 + W_6, fixes f_max: f_max = f_cp sqrt(1 + 56/81 k_e/k_c) with f_cp and k_e following alpha_max
/// (Eqs. 10, 46, 59). The paper iterates this from f_max = f_y; we solve the same equation with a bracketed
/// root finder, which also converges where the fixed-point iteration is slow. Then Eq. 79 gives
/// V_ys^2 = V_y^2 + (f_max^2 - f_y^2)/(k_p m), with V_y^2 = (f_y^2 - f_0^2)/(m k_el) allowed negative.
pub fn sticking_velocities(law: &Nan, mass: f64) -> StickingVelocities {
    let p = &law.p;
    let w = work_terms(law, p.f_y);
    let v_s = (2.0 * w.w0 / mass).sqrt();
    let v_y0 = (p.f_y * p.f_y / (mass * p.k_el)).sqrt();
    let vy2 = 2.0 * (w.w2 - w.w1) / mass;
    let adhesive_yield_velocity = (vy2 >= 0.0).then(|| vy2.sqrt());
    let s = (1.0 + 56.0 / 81.0 * p.k_el / p.k_cl).sqrt();
    let residual = |f_max: f64| -> f64 {
        let alpha_max = p.alpha_y + (f_max - p.f_y) / p.k_p;
        f_max - s * law.points(alpha_max).f_cp
    };
    // Eq. 77: W_0 <= W_2 - W_1 is residual(f_y) >= 0.
    if residual(p.f_y) >= 0.0 || p.f_ce == 0.0 {
        return StickingVelocities {
            jkr_sticking_velocity: v_s,
            yield_velocity: v_y0,
            adhesive_yield_velocity,
            sticking_velocity: Some(v_s),
            max_force_at_sticking: (p.k_el * (mass * v_s * v_s + 2.0 * w.w1)).sqrt(),
            yields_at_sticking: false,
        };
    }
    let mut hi = 2.0 * p.f_y.max(p.f_ce);
    let mut doublings = 0;
    while residual(hi) < 0.0 && doublings < 200 {
        hi *= 2.0;
        doublings += 1;
    }
    // Brent also "converges" onto a jump of the residual; only a true root counts.
    let f_max = brent(residual, p.f_y, hi, 0.0).filter(|f| residual(*f).abs() <= 1e-9 * f.abs()).unwrap_or(f64::NAN);
    let vys2 = vy2 + (f_max * f_max - p.f_y * p.f_y) / (p.k_p * mass);
    StickingVelocities {
        jkr_sticking_velocity: v_s,
        yield_velocity: v_y0,
        adhesive_yield_velocity,
        sticking_velocity: (!f_max.is_nan()).then(|| vys2.max(0.0).sqrt()),
        max_force_at_sticking: f_max,
        yields_at_sticking: true,
    }
}

/// The closed form of Eq. 73: V_s = 1.84 (Gamma/R)^(5/6) / (rho^(1/2) E*^(1/3)).
pub fn jkr_sticking_velocity_closed(gamma: f64, radius: f64, density: f64, youngs_modulus: f64) -> f64 {
    1.84 * (gamma / radius).powf(5.0 / 6.0) / (density.sqrt() * cbrt(youngs_modulus))
}

/// The closed form of Eq. 74 (with k_el by Eq. 52): V_y0 = (pi / (2 E*))^2 (2 / (5 rho))^(1/2) p_y^(5/2).
pub fn yield_velocity_closed(youngs_modulus: f64, density: f64, yield_pressure: f64) -> f64 {
    (PI / (2.0 * youngs_modulus)).powi(2) * (2.0 / (5.0 * density)).sqrt() * yield_pressure.powf(2.5)
}

/// The yield pressure below which f_y < f_0 (adhesion-induced plasticity) with k_el by Eq. 52:
/// p_y = 2 / pi^(2/3) (5/6)^(1/6) (Gamma / (E* R*))^(1/3) E* (000 Eq. 80) [Pa].
pub fn critical_yield_pressure(gamma: f64, youngs_modulus: f64, radius: f64) -> f64 {
    2.0 / PI.powf(2.0 / 3.0) * (5.0f64 / 6.0).powf(1.0 / 6.0) * cbrt(gamma / (youngs_modulus * radius)) * youngs_modulus
}

/// Cohesion-yield number CY = p_y^3 R* / (E*^2 Gamma) (000 Eq. 81).
pub fn cohesion_yield_number(yield_pressure: f64, radius: f64, youngs_modulus: f64, gamma: f64) -> f64 {
    yield_pressure.powi(3) * radius / (youngs_modulus * youngs_modulus * gamma)
}
