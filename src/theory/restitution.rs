//! Rebound velocity and restitution of an undamped normal impact on a wall, by energy balance, in closed
//! form for the piecewise-linear laws (`000` Eqs. 76-79 and App. A; `004` App. II-III).
//! `energy_balance` computes the same for any law by integrating its force; the tests hold the two equal.

use crate::law::linear::Linear;
use crate::law::luding::{Luding, LudingVariant};
use crate::law::nan::Nan;
use crate::law::pasha::Pasha;
use crate::law::pasha_simplified::PashaSimplified;
use crate::law::walton_braun::WaltonBraun;
use crate::law::AnyLaw;

/// The outcome of one undamped impact at speed `impact_velocity`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactOutcome {
    /// Impact speed [m/s].
    pub impact_velocity: f64,
    /// Largest overlap [m].
    pub max_overlap: f64,
    /// Force at the largest overlap [N].
    pub max_force: f64,
    /// Rebound speed after detachment; 0 when the sphere sticks [m/s].
    pub rebound_velocity: f64,
    /// rebound / impact velocity.
    pub restitution: f64,
    /// Whether the sphere sticks (no kinetic energy left at detachment).
    pub sticks: bool,
}

impl ImpactOutcome {
    /// From the kinetic energy left at detachment (negative: the sphere never detaches).
    pub fn from_rebound_energy(mass: f64, impact_velocity: f64, max_overlap: f64, max_force: f64, rebound_energy: f64) -> ImpactOutcome {
        let sticks = rebound_energy <= 0.0;
        let rebound_velocity = if sticks { 0.0 } else { (2.0 * rebound_energy / mass).sqrt() };
        ImpactOutcome { impact_velocity, max_overlap, max_force, rebound_velocity, restitution: rebound_velocity / impact_velocity, sticks }
    }
}

/// Nan law (000 Eqs. 76-79): f_max from the impact energy, rebound energy W_4 - W_5 - W_6.
pub fn nan(law: &Nan, mass: f64, v: f64) -> ImpactOutcome {
    let p = &law.p;
    let w1 = 64.0 / 162.0 * p.f_ce * p.f_ce / p.k_el;
    let w2 = p.f_y * p.f_y / (2.0 * p.k_el);
    let energy = 0.5 * mass * v * v;
    let (f_max, alpha_max, overlap) = if energy + w1 <= w2 {
        let f = (p.k_el * (mass * v * v + 2.0 * w1)).sqrt();
        (f, p.alpha_y, p.alpha_0 + f / p.k_el)
    } else {
        let f = (p.f_y * p.f_y + p.k_p * (mass * v * v + 2.0 * (w1 - w2))).sqrt(); // Eq. 79
        let a = p.alpha_y + (f - p.f_y) / p.k_p;
        (f, a, a)
    };
    let pts = law.points(alpha_max);
    let w4 = f_max * f_max / (2.0 * pts.k_e);
    let w56 = 0.5 * pts.f_cp * pts.f_cp / pts.k_e * (1.0 + 56.0 / 81.0 * pts.k_e / pts.k_c); // Eq. 78
    ImpactOutcome::from_rebound_energy(mass, v, overlap, f_max, w4 - w56)
}

/// Pasha's full law (004 Eqs. 4.13, 4.16, App. II): every impact yields at alpha_0.
pub fn pasha(law: &Pasha, mass: f64, v: f64) -> ImpactOutcome {
    let a0 = law.alpha_0;
    let alpha_max = a0 + ((mass * v * v + law.k_e0 * a0 * a0) / law.k_p).sqrt(); // Eq. A2.8
    let f_max = law.k_p * (alpha_max - a0);
    let pts = law.points(alpha_max);
    let w_e = f_max * f_max / (2.0 * pts.k_e);
    let w_ut = 137.0 / 162.0 * pts.f_cp * pts.f_cp / pts.k_e; // Eq. A1.6
    ImpactOutcome::from_rebound_energy(mass, v, alpha_max, f_max, w_e - w_ut)
}

/// Pasha's simplified law (004 Eqs. A3.6, A3.9).
pub fn pasha_simplified(law: &PashaSimplified, mass: f64, v: f64) -> ImpactOutcome {
    let a0 = law.alpha_0;
    let alpha_max = a0 + (a0 * a0 + mass * v * v / law.k_p).sqrt(); // Eq. A3.6
    let f_max = law.k_p * (alpha_max - a0);
    let pts = law.points(alpha_max);
    let w_e = f_max * f_max / (2.0 * pts.k_e);
    let w_ad = pts.f_cp * (pts.alpha_p - pts.alpha_cp); // Eq. A3.8
    ImpactOutcome::from_rebound_energy(mass, v, alpha_max, f_max, w_e - w_ad)
}

/// Luding's law: loading work (k_1 alpha^2)/2 - f_0 alpha; unloading along k_2 to the adhesion limit,
/// along it to alpha = 0, where the contact breaks (004 Sec. 4.1.5). The mercurydpm reading loads on the
/// k_2_hat line through delta_0 = phi_f 2 R* beyond alpha* and unloads on the same line.
pub fn luding(law: &Luding, mass: f64, v: f64) -> ImpactOutcome {
    let (k1, f0, kc) = (law.k1, law.f0, law.kc);
    let energy = 0.5 * mass * v * v;
    let mut alpha_max = (f0 + (f0 * f0 + 2.0 * k1 * energy).sqrt()) / k1;
    let (mut k2, mut d0, mut f_max) = (law.k2(alpha_max), 0.0, k1 * alpha_max - f0);
    d0 += (1.0 - k1 / k2) * alpha_max;
    if law.variant == LudingVariant::Mercurydpm && alpha_max > law.alpha_star {
        // The rest of the energy goes into the k_2_hat line from alpha*: (k2_hat/2)((a - cap)^2 - (a* - cap)^2)
        // - f_0 (a - a*) = E - W(a*), a quadratic in a - cap.
        let (a_s, cap, k2h) = (law.alpha_star, law.delta0_cap, law.k2_hat);
        let rest = energy - (0.5 * k1 * a_s * a_s - f0 * a_s);
        let (b, c) = (-2.0 * f0 / k2h, -(a_s - cap).powi(2) - 2.0 * (rest - f0 * (a_s - cap)) / k2h);
        let x = 0.5 * (-b + (b * b - 4.0 * c).sqrt());
        alpha_max = cap + x;
        (k2, d0, f_max) = (k2h, cap, k2h * x - f0);
    }
    let a_c = k2 * d0 / (k2 + kc);
    // Work the contact returns from alpha_max down to a_c on the k_2 line, then from a_c to 0 on the limit.
    let on_line = 0.5 * k2 * ((alpha_max - d0).powi(2) - (a_c - d0).powi(2)) - f0 * (alpha_max - a_c);
    let on_limit = -0.5 * kc * a_c * a_c - f0 * a_c;
    ImpactOutcome::from_rebound_energy(mass, v, alpha_max, f_max, on_line + on_limit)
}

/// Walton & Braun: all loading work above the unloading line is lost, e = sqrt(k_p / k_e) for constant k_e
/// (004 Sec. 3.4.2.3).
pub fn walton_braun(law: &WaltonBraun, mass: f64, v: f64) -> ImpactOutcome {
    let alpha_max = v * (mass / law.k_p).sqrt();
    let f_max = law.k_p * alpha_max;
    let k_e = law.unloading_stiffness(alpha_max);
    ImpactOutcome::from_rebound_energy(mass, v, alpha_max, f_max, f_max * f_max / (2.0 * k_e))
}

/// The linear spring: perfectly elastic, alpha_max = v sqrt(m / k).
pub fn linear(law: &Linear, mass: f64, v: f64) -> ImpactOutcome {
    let alpha_max = v * (mass / law.stiffness).sqrt();
    ImpactOutcome::from_rebound_energy(mass, v, alpha_max, law.stiffness * alpha_max, 0.5 * mass * v * v)
}

/// The closed form of an undamped impact for the piecewise-linear laws; `None` for the others.
pub fn closed_form(law: &AnyLaw, mass: f64, v: f64) -> Option<ImpactOutcome> {
    Some(match law {
        AnyLaw::Nan(l) => nan(l, mass, v),
        AnyLaw::Pasha(l) => pasha(l, mass, v),
        AnyLaw::PashaSimplified(l) => pasha_simplified(l, mass, v),
        AnyLaw::Luding(l) => luding(l, mass, v),
        AnyLaw::WaltonBraun(l) => walton_braun(l, mass, v),
        AnyLaw::Linear(l) => linear(l, mass, v),
        _ => return None,
    })
}
