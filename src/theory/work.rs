//! The work of deformation of the Nan law, stage by stage (`000` Fig. 4, App. A, Eqs. A1-A7).

use crate::law::nan::Nan;

/// W_0..W_6 for an impact that reaches the maximum force f_max [J].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkTerms {
    /// Adhesive sticking work before yield (Eq. A1, = W_JKR by Eq. 35).
    pub w0: f64,
    /// Attraction work from contact to alpha_0 (Eq. A2).
    pub w1: f64,
    /// Elastic work from alpha_0 to yield (Eq. A3).
    pub w2: f64,
    /// Plastic work (Eq. A4).
    pub w3: f64,
    /// Elastic work stored at f_max (Eq. A5).
    pub w4: f64,
    /// Work from zero force to alpha_c0 on unloading (Eq. A6).
    pub w5: f64,
    /// Adhesive work from alpha_c0 to detachment (Eq. A7).
    pub w6: f64,
}

/// The work terms for a plastic impact with maximum force `f_max` >= f_y (for f_max = f_y, the contact
/// just reaches yield and W_3 = 0 with k_e = k_el).
pub fn work_terms(law: &Nan, f_max: f64) -> WorkTerms {
    let p = &law.p;
    let alpha_max = p.alpha_y + (f_max - p.f_y).max(0.0) / p.k_p; // Eq. 10
    let pts = law.points(alpha_max);
    let (fce2, fcp2) = (p.f_ce * p.f_ce, pts.f_cp * pts.f_cp);
    WorkTerms {
        w0: 56.0 / 162.0 * fce2 / p.k_cl + 17.0 / 162.0 * fce2 / p.k_el,
        w1: 64.0 / 162.0 * fce2 / p.k_el,
        w2: p.f_y * p.f_y / (2.0 * p.k_el),
        w3: (f_max * f_max - p.f_y * p.f_y) / (2.0 * p.k_p) - f_max * f_max / (2.0 * pts.k_e),
        w4: f_max * f_max / (2.0 * pts.k_e),
        w5: 64.0 / 162.0 * fcp2 / pts.k_e,
        w6: 56.0 / 162.0 * fcp2 / pts.k_c + 17.0 / 162.0 * fcp2 / pts.k_e,
    }
}
