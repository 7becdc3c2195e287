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

use super::jkr::{on_curve_at, JkrCurve};
use super::params::Effective;
use super::tangential::TangentialModel;
use super::{Branch, Evaluation, LawInfo, LawOptions, NormalLaw};
use crate::error::ParamError;
use crate::numeric::brent;
use crate::numeric::cbrt;
use crate::vocabulary::NoOptions;
use std::f64::consts::PI;

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
        self.plastic_at_radius(alpha, self.curve.contact_radius(alpha))
    }

    /// `plastic_at` with the JKR contact radius `a` of `alpha` on the curve of R* already solved.
    fn plastic_at_radius(&self, alpha: f64, a: f64) -> (f64, f64, f64) {
        let r = self.curve.radius;
        let gamma = self.curve.surface_energy;
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
        let (flat, alpha_p) = self.flattened(alpha_max, f_max, a_max, None);
        (flat.radius, alpha_p)
    }

    /// The JKR curve of R_p and its shift alpha_p for a peak (alpha_max, F_max) at contact radius a_max;
    /// `near`, the contact's unloading curve before this step, starts the cube root of R_p.
    fn flattened(&self, alpha_max: f64, f_max: f64, a_max: f64, near: Option<&JkrCurve>) -> (JkrCurve, f64) {
        let (r, e) = (self.curve.radius, self.curve.youngs_modulus);
        let f_star = 4.0 * e * a_max.powi(3) / (3.0 * r);
        let r_p = r * f_star / (f_max + (4.0 * self.curve.pull_off_force() * f_star).sqrt());
        let flat = match near {
            Some(near) => self.curve.with_radius_near(r_p, near),
            None => self.curve.with_radius(r_p),
        };
        (flat, alpha_max - flat.overlap(a_max))
    }

    /// Plastic loading from history `h` to a new alpha_max = `alpha`, with the JKR contact radius `a` of R*
    /// at `alpha`.
    fn plastic_loading(&self, alpha: f64, a: f64, h: &TnHistory) -> Evaluation<TnHistory> {
        let (force, stiffness, a) = self.plastic_at_radius(alpha, a);
        let (flat, alpha_p) = self.flattened(alpha, force, a, Some(&h.flat));
        Evaluation {
            force,
            stiffness,
            branch: Branch::Plastic,
            lower: alpha,
            upper: f64::INFINITY,
            history: TnHistory { established: true, alpha_max: alpha, alpha_p, flat },
        }
    }

    /// `evaluate` with the damping stiffness 2 E* a and the contact radius a from one contact-radius solve,
    /// `solve(curve, overlap)` on the curve in play (the closed form, or Newton's method from last step's
    /// radius). On the plastic branch a is the radius of R* at alpha, which the new unloading curve passes
    /// through (Eq. 3.58's alpha_p is chosen so).
    #[inline(always)]
    fn evaluate_solving(&self, alpha: f64, h: &TnHistory, solve: impl Fn(&JkrCurve, f64) -> f64) -> (Evaluation<TnHistory>, f64, Option<f64>) {
        let flat = h.flat;
        if (!h.established && alpha < h.alpha_p) || alpha < h.alpha_p + flat.detach_overlap() {
            return (Evaluation::separated(h.alpha_p, TnHistory { established: false, ..*h }), 0.0, None);
        }
        let (ev, a) = if alpha > h.alpha_max {
            let a = solve(&self.curve, alpha);
            (self.plastic_loading(alpha, a, h), a)
        } else {
            let a = solve(&flat, alpha - h.alpha_p);
            let mut ev = on_curve_at(&flat, h.alpha_p, a, TnHistory { established: true, ..*h });
            ev.upper = ev.upper.min(h.alpha_max);
            (ev, a)
        };
        (ev, 2.0 * self.curve.youngs_modulus * a, Some(a))
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

    /// The closed-form solve of `evaluate_with_radius` (the same operations, so the same bits).
    #[inline]
    fn evaluate(&self, alpha: f64, h: &TnHistory) -> Evaluation<TnHistory> {
        self.evaluate_with_radius(alpha, h).0
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

    /// One contact-radius solve per call instead of three (evaluate, damping_stiffness, contact_radius).
    #[inline]
    fn evaluate_with_radius(&self, alpha: f64, h: &TnHistory) -> (Evaluation<TnHistory>, f64, Option<f64>) {
        self.evaluate_solving(alpha, h, |curve, x| curve.contact_radius(x))
    }

    /// The bed's call: Newton's method from the contact's radius a step earlier, as the JKR law does. The
    /// closed form's cube root (`numeric::cbrt`, pure Rust for equal bits on Linux and Windows) took 28 % of
    /// this law's bed time and its three solves per contact 42 % (perf, quarter bed, one thread).
    #[inline]
    fn evaluate_near(&self, alpha: f64, h: &TnHistory, guess: f64) -> (Evaluation<TnHistory>, f64, Option<f64>) {
        self.evaluate_solving(alpha, h, |curve, x| curve.contact_radius_from(x, guess))
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

#[cfg(test)]
mod one_solve_tests {
    use super::*;

    // 000 Table 5's pair (ammonium fluorescein on silicon) with a yield pressure that puts a_y above a_0.
    const R: f64 = 2.45e-6;
    const E: f64 = 1.33666e9;
    const GAMMA: f64 = 0.24;
    const P_Y: f64 = 90e6;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * a.abs().max(b.abs()) + 1e-300
    }

    /// The bed's one-solve calls (`evaluate_with_radius`, and `evaluate_near` from last step's radius) give
    /// the force, stiffness, branch, history, damping stiffness and contact radius of the three separate
    /// calls, along loading, plastic loading, unloading to detachment, re-contact and reloading past the
    /// old peak.
    #[test]
    fn one_contact_radius_solve_gives_what_the_three_calls_give() {
        for p_y in [P_Y, 20e6] {
            let law = ThorntonNing::new(R, E, GAMMA, p_y);
            let scale = law.a_y * law.a_y / R;
            let (mut h, mut guess) = (law.initial_history(), 0.0);
            let targets = [-0.5, 4.0, 1.0, -3.0, 2.0, 6.0, -1.0];
            let mut alpha = -scale;
            let mut seen = [false; 4];
            for target in targets.map(|t| t * scale) {
                let start = alpha;
                for i in 1..=200 {
                    alpha = start + (target - start) * i as f64 / 200.0;
                    let ev = law.evaluate(alpha, &h);
                    let k_damp = law.damping_stiffness(alpha, &ev.history, ev.stiffness);
                    let a = law.contact_radius(alpha, &ev.history);
                    for (one, name) in [(law.evaluate_with_radius(alpha, &h), "closed form"), (law.evaluate_near(alpha, &h, guess), "warm start")] {
                        let (e1, k1, a1) = one;
                        assert_eq!(e1.branch, ev.branch, "{name} at {alpha:e}");
                        assert!(close(e1.force, ev.force) && close(e1.stiffness, ev.stiffness), "{name} at {alpha:e}: {e1:?} vs {ev:?}");
                        assert!(e1.lower == ev.lower || close(e1.lower, ev.lower), "{name} at {alpha:e}: {e1:?} vs {ev:?}");
                        assert!(e1.upper == ev.upper || close(e1.upper, ev.upper), "{name} at {alpha:e}: {e1:?} vs {ev:?}");
                        assert_eq!(e1.history.established, ev.history.established);
                        assert!(close(e1.history.alpha_max, ev.history.alpha_max) && close(e1.history.flat.radius, ev.history.flat.radius));
                        if ev.branch.in_contact() {
                            assert!(close(k1, k_damp), "{name} at {alpha:e}: {k1:e} vs {k_damp:e}");
                            assert!(close(a1.unwrap(), a.unwrap()), "{name} at {alpha:e}");
                        } else {
                            assert_eq!(a1, None);
                        }
                    }
                    let (e1, _, a1) = law.evaluate_near(alpha, &h, guess);
                    seen[match e1.branch {
                        Branch::Plastic => 0,
                        Branch::Elastic => 1,
                        Branch::Adhesive => 2,
                        _ => 3,
                    }] = true;
                    h = e1.history;
                    guess = a1.unwrap_or(0.0);
                }
            }
            assert_eq!(seen, [true; 4], "the path crosses every branch (p_y {p_y:e})");
        }
    }
}
