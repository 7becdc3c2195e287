//! Thornton & Ning's nonlinear elasto-plastic adhesive law (`004` Sec. 3.4.4.1 with the JKR relations of
//! Sec. 3.4.3.1): the high-fidelity reference the linear laws approximate.
//!
//! - Before yield: the JKR curve of R* (forms at alpha = 0 with -8/9 f_ce).
//! - Yield when the JKR pressure at the centre reaches p_y, at the contact radius a_y of Eq. 3.55:
//!   p_y = 2 E* a_y / (pi R*) - sqrt(2 Gamma E* / (pi a_y)).
//! - Plastic loading with the tangent stiffness of Eq. 3.56, with a the JKR contact radius at the current
//!   overlap (Eq. 3.42). Integrated in closed form (docs/models.md derives it):
//!   f_p(alpha) = f_y + pi R* p_y (alpha - alpha_y) - 2 pi Gamma R* (sqrt(a / a_y) - 1);
//!   when a_y is below the radius a_0 at which the contact forms (alpha_y < 0), the same integral starts
//!   at the formation point (0, -8/9 f_ce, a_0).
//! - Unloading and reloading below alpha_max: the JKR curve of the flattened radius
//!   R_p = R* F*_max / (F_max + sqrt(4 f_ce F*_max)) (Eq. 3.58), F*_max = 4 E* a_max^3 / (3 R*), shifted by
//!   alpha_p so that it passes through (alpha_max, F_max). Pull-off f_cp = 1.5 pi Gamma R_p (Eq. 3.59);
//!   detachment at -5/9 f_cp; re-contact at alpha_c0 = alpha_p with -8/9 f_cp (004 Sec. 3.4.4.1).

use super::jkr::{on_curve, JkrCurve};
use super::params::Effective;
use super::tangential::TangentialModel;
use super::{Branch, Evaluation, LawInfo, LawOptions, NormalLaw};
use crate::error::ParamError;
use crate::numeric::brent;
use crate::vocabulary::NoOptions;
use std::f64::consts::PI;
use crate::numeric::cbrt;

/// Thornton and Ning's law of one contact pair (the module documentation says which equations).
#[derive(Debug, Clone, PartialEq)]
pub struct ThorntonNing {
    /// The JKR curve of R*.
    pub curve: JkrCurve,
    /// Yield contact pressure p_y [Pa].
    pub yield_pressure: f64,
    /// Contact radius at yield (Eq. 3.55) [m].
    pub a_y: f64,
    /// Force at yield, on the JKR curve at a_y [N].
    pub f_y: f64,
    /// Overlap at yield, on the JKR curve at a_y; negative under adhesion-induced yield [m].
    pub alpha_y: f64,
    /// The overlap beyond which first loading is plastic: alpha_y, or 0 when the contact yields as soon
    /// as it forms (adhesion-induced yield, alpha_y < 0) [m].
    pub alpha_yield_start: f64,
    /// Where the plastic curve starts: (alpha, f, sqrt(a)) at yield, or at formation (0, -8/9 f_ce, a_0)
    /// when the contact forms yielded.
    anchor: (f64, f64, f64),
}

/// What a Thornton-Ning contact remembers.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TnHistory {
    /// In contact: formed (at alpha_c0 = alpha_p) and not detached since.
    pub established: bool,
    /// Largest overlap of plastic loading (starts at the yield overlap) [m].
    pub alpha_max: f64,
    /// Shift of the unloading curve, 0 before yield [m].
    pub alpha_p: f64,
    /// The unloading curve: the JKR curve of R_p (R* before yield), built only when plastic loading
    /// moves alpha_max.
    pub flat: JkrCurve,
}

impl ThorntonNing {
    /// The law of reduced radius R* [m], effective modulus E* [Pa], interface energy Gamma [J/m^2] and
    /// yield contact pressure p_y [Pa]: finds a_y (Eq. 3.55) and where plastic loading starts.
    pub fn new(radius: f64, youngs_modulus: f64, surface_energy: f64, yield_pressure: f64) -> ThorntonNing {
        let curve = JkrCurve::new(radius, youngs_modulus, surface_energy);
        let a_y = yield_radius(radius, youngs_modulus, surface_energy, yield_pressure);
        let (f_y, alpha_y) = (curve.force(a_y), curve.overlap(a_y));
        // The contact forms at alpha = 0 with a_0 = (2 pi Gamma R*^2 / E*)^(1/3) (000 Eq. B5). If a_y < a_0 it
        // is already yielded then, and plastic loading starts from the formation point.
        let a_0 = curve.contact_radius(0.0);
        let (alpha_yield_start, anchor) =
            if alpha_y >= 0.0 || a_y >= a_0 { (alpha_y, (alpha_y, f_y, a_y.sqrt())) } else { (0.0, (0.0, curve.force(a_0), a_0.sqrt())) };
        ThorntonNing { curve, yield_pressure, a_y, f_y, alpha_y, alpha_yield_start, anchor }
    }

    /// Plastic loading force and its stiffness at an overlap (closed form of Eq. 3.56).
    pub fn plastic_force(&self, alpha: f64) -> (f64, f64) {
        let (f, k, _) = self.plastic_at(alpha);
        (f, k)
    }

    /// Force, stiffness and JKR contact radius on the plastic loading curve (one contact-radius solve).
    fn plastic_at(&self, alpha: f64) -> (f64, f64, f64) {
        let r = self.curve.radius;
        let gamma = self.curve.surface_energy;
        let a = self.curve.contact_radius(alpha);
        let k_flat = PI * r * self.yield_pressure;
        let (alpha_0, f_0, sqrt_a0) = self.anchor;
        let f = f_0 + k_flat * (alpha - alpha_0) - 2.0 * PI * gamma * r * (a.sqrt() - sqrt_a0) / self.a_y.sqrt();
        let dalpha_da = (2.0 * a / r - 0.5 * (2.0 * PI * gamma / self.curve.youngs_modulus / a).sqrt()).max(2e-6 * a / r);
        let k = k_flat - PI * gamma * r / (a * self.a_y).sqrt() / dalpha_da;
        (f, k, a)
    }

    /// The unloading curve after plastic loading to alpha_max: (R_p, alpha_p) of Eq. 3.58.
    pub fn unloading_curve(&self, alpha_max: f64) -> (f64, f64) {
        let (f_max, _, a_max) = self.plastic_at(alpha_max);
        let (flat, alpha_p) = self.flattened(alpha_max, f_max, a_max);
        (flat.radius, alpha_p)
    }

    /// The JKR curve of R_p and its shift alpha_p for a peak (alpha_max, F_max) at contact radius a_max.
    fn flattened(&self, alpha_max: f64, f_max: f64, a_max: f64) -> (JkrCurve, f64) {
        let (r, e) = (self.curve.radius, self.curve.youngs_modulus);
        let f_star = 4.0 * e * a_max.powi(3) / (3.0 * r);
        let r_p = r * f_star / (f_max + (4.0 * self.curve.pull_off_force() * f_star).sqrt());
        let flat = JkrCurve::new(r_p, e, self.curve.surface_energy);
        (flat, alpha_max - flat.overlap(a_max))
    }
}

/// a_y from 004 Eq. 3.55; the right side grows with a, so the root is unique.
pub fn yield_radius(r: f64, e: f64, gamma: f64, p_y: f64) -> f64 {
    let pressure = |a: f64| 2.0 * e * a / (PI * r) - (2.0 * gamma * e / (PI * a)).sqrt() - p_y;
    let mut hi = PI * r * p_y / (2.0 * e);
    while pressure(hi) < 0.0 {
        hi *= 2.0;
    }
    let mut lo = hi;
    while pressure(lo) > 0.0 {
        lo *= 0.5;
    }
    brent(pressure, lo, hi, 0.0).unwrap_or(hi)
}

impl NormalLaw for ThorntonNing {
    type History = TnHistory;

    fn initial_history(&self) -> TnHistory {
        TnHistory { established: false, alpha_max: self.alpha_yield_start, alpha_p: 0.0, flat: self.curve }
    }

    #[inline]
    fn evaluate(&self, alpha: f64, h: &TnHistory) -> Evaluation<TnHistory> {
        let flat = h.flat;
        let alpha_c0 = h.alpha_p;
        let alpha_f = h.alpha_p + flat.detach_overlap();
        if (!h.established && alpha < alpha_c0) || alpha < alpha_f {
            return Evaluation::separated(alpha_c0, TnHistory { established: false, ..*h });
        }
        if alpha > h.alpha_max {
            let (force, stiffness, a) = self.plastic_at(alpha);
            let (flat, alpha_p) = self.flattened(alpha, force, a);
            return Evaluation {
                force,
                stiffness,
                branch: Branch::Plastic,
                lower: alpha,
                upper: f64::INFINITY,
                history: TnHistory { established: true, alpha_max: alpha, alpha_p, flat },
            };
        }
        let mut e = on_curve(&flat, h.alpha_p, alpha, TnHistory { established: true, ..*h });
        e.upper = e.upper.min(h.alpha_max);
        e
    }

    #[inline]
    fn has_yielded(&self, h: &TnHistory) -> bool {
        h.alpha_max > self.alpha_yield_start
    }

    /// Thornton & Yin's criterion with the flattened radius: mu (F_n + 2 f_cp) (004 Eqs. 3.49, 3.59).
    #[inline]
    fn sliding_normal_force(&self, force: f64, _alpha: f64, h: &TnHistory) -> f64 {
        force + 3.0 * PI * self.curve.surface_energy * h.flat.radius
    }

    /// f_cp = 1.5 pi Gamma R_p (004 Eq. 3.59).
    fn pull_off_force(&self, h: &TnHistory) -> f64 {
        1.5 * PI * self.curve.surface_energy * h.flat.radius
    }

    /// Where the unloading curve crosses zero force: alpha_p plus the JKR zero-force overlap of R_p.
    fn plastic_overlap(&self, h: &TnHistory) -> f64 {
        if h.alpha_p == 0.0 {
            return 0.0;
        }
        let flat = h.flat;
        // f = 0 where F_H = 4 f_c (000 Eq. B9): a^3 = 3 R_p f_c / E*.
        let a0 = cbrt(3.0 * flat.radius * flat.pull_off_force() / self.curve.youngs_modulus);
        h.alpha_p + flat.overlap(a0)
    }

    #[inline]
    fn contact_radius(&self, alpha: f64, h: &TnHistory) -> Option<f64> {
        if alpha > h.alpha_max {
            Some(self.curve.contact_radius(alpha))
        } else {
            (alpha >= h.alpha_p + h.flat.detach_overlap()).then(|| h.flat.contact_radius(alpha - h.alpha_p))
        }
    }

    /// 2 E* a: the Hertz stiffness at the JKR contact radius (the JKR slope is infinite at detachment).
    #[inline]
    fn damping_stiffness(&self, alpha: f64, h: &TnHistory, _branch_stiffness: f64) -> f64 {
        2.0 * self.curve.youngs_modulus * self.contact_radius(alpha, h).unwrap_or(0.0)
    }

    /// The adhesive part of the unloading curve (JKR of R_p) ends vertically at detachment, -5/9 f_cp.
    fn vertical_end(&self, branch: Branch, h: &TnHistory) -> Option<f64> {
        (branch == Branch::Adhesive).then(|| h.flat.pull_off_overlap() - h.flat.detach_overlap())
    }
}

impl LawInfo for ThorntonNing {
    const TANGENTIAL: TangentialModel = TangentialModel::Mindlin;
    type Options = NoOptions;
    fn from_pair(eff: &Effective, _options: &LawOptions) -> Result<ThorntonNing, ParamError> {
        let p_y = eff.require_yield_pressure("thornton_ning")?;
        Ok(ThorntonNing::new(eff.radius, eff.youngs_modulus, eff.surface_energy, p_y))
    }
}
