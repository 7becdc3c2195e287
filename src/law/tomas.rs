//! Tomas' elasto-plastic adhesive law for ultrafine particles (`003` Table 1 and Eqs. 5-11,
//! `004` Sec. 3.4.4.3, Eqs. 3.61-3.67).
//!
//! Tomas writes the Hertz term as 2/3 E* sqrt(r) h^(3/2) with his E* = 2 [(1-nu1^2)/E1 + (1-nu2^2)/E2]^-1,
//! twice ours, so here it is c h^(3/2) with c = 4/3 E* sqrt(R*) (the Hertz force). With
//! k_1 = pi R* p_f (kappa_A - kappa_p) (plastic line) and k_A = pi R* kappa_p p_f (adhesion limit, p_vdW = kappa_p p_f):
//! - approach: van der Waals attraction -F_H0 a_F^2 / (a_F - alpha)^2 for alpha < 0 (004 Eq. 3.61);
//! - elastic loading c alpha^(3/2) - F_H0 up to alpha_y = R* (3 pi p_f (kappa_A - kappa_p) / (2 E*_Tomas))^2
//!   (004 Eq. 3.62), where it meets the plastic line k_1 alpha - F_H0 (003 Table 1);
//! - unloading from (alpha_max, F_max): c (alpha - h_min)^(3/2) - k_A h_min - F_H0, with h_min found
//!   iteratively so the curve starts at F_max (003 Table 1, note *); it ends on the adhesion limit at
//!   point A (h_min, F_A), the largest tension;
//! - reloading: F_max - c (alpha_max - alpha)^(3/2), the mirror curve from A back to (alpha_max, F_max);
//!   a reversal inside the lens starts a scaled copy of the other curve from the reversal point, so the
//!   force stays continuous (docs/models.md);
//! - below h_min the contact has failed and the separation s = h_min - alpha is bridged by the van der
//!   Waals tail -F_H0 a_F^2/(a_F + s)^2 - k_A h_min a_F^3/(a_F + s)^3 (004 Eq. 3.67, measured from A so it
//!   starts at F_A); beyond s = 99 a_F (tail below 1e-4 of F_H0) the surfaces are apart, and once the
//!   overlap is also below -99 a_F (where a fresh contact is apart as well) the contact forgets its history:
//!   Tomas' model keeps no permanent deformation (004 Sec. 3.4.4.3).

use super::params::Effective;
use super::tangential::TangentialModel;
use super::{Branch, Evaluation, LawInfo, LawOptions, NormalLaw};
use crate::error::{check_closed_low, ParamError};
use crate::numeric::brent;
use crate::vocabulary::Range;
use std::f64::consts::PI;

/// Tomas' law of one contact pair (the module documentation says which equations).
#[derive(Debug, Clone, PartialEq)]
pub struct Tomas {
    /// c = 4/3 E* sqrt(R*) [N/m^1.5].
    pub c: f64,
    /// k_1 = pi R* p_f (kappa_A - kappa_p) [N/m].
    pub k1: f64,
    /// k_A = pi R* kappa_p p_f [N/m].
    pub k_a: f64,
    /// F_H0 [N].
    pub f0: f64,
    /// a_F [m].
    pub a_f: f64,
    /// alpha_y [m].
    pub alpha_y: f64,
    /// kappa = kappa_p / (kappa_A - kappa_p), the contact consolidation coefficient (003 Eq. 6).
    pub kappa: f64,
}

/// Which lens curve the contact is on after yield.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum LensMode {
    /// The unloading curve, ending at point A (h_min, F_A) (branch `Elastic`).
    Unloading,
    /// The reloading curve, ending at (alpha_max, F_max) (branch `Reloading`).
    Reloading,
}

/// What a Tomas contact remembers.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TomasHistory {
    /// The contact has been loaded plastically: below alpha_max it is on the lens curves, not the
    /// reversible Hertz branch.
    pub yielded: bool,
    /// Largest overlap (at least alpha_y) [m].
    pub alpha_max: f64,
    /// h_min of the unloading curve from alpha_max [m].
    pub h_min: f64,
    /// Force at point A (negative) [N].
    pub f_a: f64,
    /// The lens curve the contact is on.
    pub mode: LensMode,
    /// Overlap at the start of the current lens curve [m].
    pub anchor_alpha: f64,
    /// Force at the start of the current lens curve [N].
    pub anchor_force: f64,
    /// Overlap of the last accepted state: tells loading from unloading [m].
    pub last_alpha: f64,
}

impl Tomas {
    /// The law from R* [m], E* [Pa] (ours, half of Tomas' E*), p_f [Pa], kappa_A and kappa_p [-], F_H0 [N]
    /// and a_F [m]; derives c, k_1, k_A, alpha_y and kappa.
    pub fn new(r: f64, e_star: f64, p_f: f64, kappa_a: f64, kappa_p: f64, f0: f64, a_f: f64) -> Tomas {
        let c = 4.0 / 3.0 * e_star * r.sqrt();
        let k1 = PI * r * p_f * (kappa_a - kappa_p);
        Tomas { c, k1, k_a: PI * r * kappa_p * p_f, f0, a_f, alpha_y: (k1 / c).powi(2), kappa: kappa_p / (kappa_a - kappa_p) }
    }

    /// h_min for unloading from alpha_max: c (alpha_max - h)^(3/2) - k_A h = k_1 alpha_max (003 Table 1 *).
    pub fn h_min(&self, alpha_max: f64) -> f64 {
        let g = |h: f64| {
            self.c * {
                let d = (alpha_max - h).max(0.0);
                d * d.sqrt()
            } - self.k_a * h
                - self.k1 * alpha_max
        };
        brent(g, 0.0, alpha_max, 0.0).unwrap_or(0.0)
    }

    /// `h_min` by Newton's method from a nearby root `guess` (the contact's h_min a step earlier). The
    /// function is convex and decreasing in h: from the left Newton climbs to the root without passing it,
    /// from the right its first step lands left of it. Brent's method from scratch was 64 % of this law's
    /// bed time (perf, quarter bed, one thread); it stays the fallback without a usable guess.
    pub fn h_min_near(&self, alpha_max: f64, guess: f64) -> f64 {
        let mut h = guess;
        for _ in 0..8 {
            if !(h > 0.0 && h < alpha_max) {
                break;
            }
            let d = alpha_max - h;
            let root = d.sqrt();
            let step = (self.c * d * root - self.k_a * h - self.k1 * alpha_max) / (-1.5 * self.c * root - self.k_a);
            h -= step;
            // Quadratic convergence: the error after a step is about step^2 / (4 (alpha_max - h)), below
            // rounding once the step is below 1e-8 of both h and alpha_max - h.
            if step.abs() <= 1e-8 * h.min(alpha_max - h) {
                return h;
            }
        }
        self.h_min(alpha_max)
    }

    fn after_plastic(&self, alpha: f64, from: &TomasHistory) -> TomasHistory {
        // Before the first yield h_min is 0: no usable guess, Brent's method.
        let h_min = self.h_min_near(alpha, from.h_min);
        TomasHistory {
            yielded: true,
            alpha_max: alpha,
            h_min,
            f_a: -self.k_a * h_min - self.f0,
            mode: LensMode::Unloading,
            anchor_alpha: alpha,
            anchor_force: self.k1 * alpha - self.f0,
            last_alpha: alpha,
        }
    }

    /// The van der Waals tail at separation s beyond the failure point at h_min.
    fn tail(&self, s: f64, h_min: f64) -> (f64, f64) {
        let d = self.a_f + s;
        let (q2, q3) = ((self.a_f / d).powi(2), (self.a_f / d).powi(3));
        let f = -self.f0 * q2 - self.k_a * h_min * q3;
        // df/dalpha = -df/ds.
        let k = -(2.0 * self.f0 * q2 / d + 3.0 * self.k_a * h_min * q3 / d);
        (f, k)
    }

    /// Force and stiffness on a lens curve.
    fn lens(&self, h: &TomasHistory, mode: LensMode, anchor_alpha: f64, anchor_force: f64, alpha: f64) -> (f64, f64) {
        let f_max = self.k1 * h.alpha_max - self.f0;
        match mode {
            LensMode::Unloading => {
                let span = anchor_alpha - h.h_min;
                if span <= 0.0 {
                    return (h.f_a, 0.0);
                }
                let x = ((alpha - h.h_min) / span).max(0.0);
                let df = anchor_force - h.f_a;
                (h.f_a + df * x * x.sqrt(), 1.5 * df / span * x.sqrt())
            }
            LensMode::Reloading => {
                let span = h.alpha_max - anchor_alpha;
                if span <= 0.0 {
                    return (f_max, 0.0);
                }
                let x = ((h.alpha_max - alpha) / span).max(0.0);
                let df = f_max - anchor_force;
                (f_max - df * x * x.sqrt(), 1.5 * df / span * x.sqrt())
            }
        }
    }
}

impl NormalLaw for Tomas {
    type History = TomasHistory;

    fn initial_history(&self) -> TomasHistory {
        TomasHistory {
            yielded: false,
            alpha_max: self.alpha_y,
            h_min: 0.0,
            f_a: -self.f0,
            mode: LensMode::Unloading,
            anchor_alpha: 0.0,
            anchor_force: -self.f0,
            last_alpha: f64::NEG_INFINITY,
        }
    }

    #[inline]
    fn evaluate(&self, alpha: f64, h: &TomasHistory) -> Evaluation<TomasHistory> {
        let cutoff = 99.0 * self.a_f;
        if alpha > h.alpha_max {
            return Evaluation {
                force: self.k1 * alpha - self.f0,
                stiffness: self.k1,
                branch: Branch::Plastic,
                lower: alpha,
                upper: f64::INFINITY,
                history: self.after_plastic(alpha, h),
            };
        }
        if alpha < h.h_min {
            let s = h.h_min - alpha;
            if s > cutoff {
                // Apart. The history is forgotten only where a fresh contact would be apart too (below
                // -cutoff): between there and h_min - cutoff, a fresh history would put a flattened sphere
                // back into plastic contact, so the remembered one is kept until then.
                if alpha < -cutoff {
                    return Evaluation::separated(-cutoff, self.initial_history());
                }
                return Evaluation::separated(h.h_min - cutoff, TomasHistory { last_alpha: alpha, ..*h });
            }
            let (force, stiffness) = self.tail(s, h.h_min);
            let history = if h.yielded {
                TomasHistory { mode: LensMode::Reloading, anchor_alpha: h.h_min, anchor_force: h.f_a, last_alpha: alpha, ..*h }
            } else {
                TomasHistory { last_alpha: alpha, ..*h }
            };
            return Evaluation { force, stiffness, branch: Branch::Attraction, lower: h.h_min - cutoff, upper: h.h_min, history };
        }
        if !h.yielded {
            // Reversible Hertz branch before yield (h_min = 0).
            let root = alpha.sqrt();
            return Evaluation {
                force: self.c * root * alpha - self.f0,
                stiffness: 1.5 * self.c * root,
                branch: Branch::Elastic,
                lower: 0.0,
                upper: h.alpha_max,
                history: TomasHistory { last_alpha: alpha, ..*h },
            };
        }
        // Inside the lens: a reversal starts the other curve at the last accepted point.
        let (mut mode, mut anchor_alpha, mut anchor_force) = (h.mode, h.anchor_alpha, h.anchor_force);
        let reversed = match h.mode {
            LensMode::Unloading => alpha > h.last_alpha,
            LensMode::Reloading => alpha < h.last_alpha,
        };
        if reversed && h.last_alpha.is_finite() && h.last_alpha >= h.h_min && h.last_alpha <= h.alpha_max {
            let (f_last, _) = self.lens(h, h.mode, h.anchor_alpha, h.anchor_force, h.last_alpha);
            mode = if h.mode == LensMode::Unloading { LensMode::Reloading } else { LensMode::Unloading };
            anchor_alpha = h.last_alpha;
            anchor_force = f_last;
        }
        let (force, stiffness) = self.lens(h, mode, anchor_alpha, anchor_force, alpha);
        let (branch, lower, upper) = match mode {
            LensMode::Unloading => (Branch::Elastic, h.h_min, alpha),
            LensMode::Reloading => (Branch::Reloading, alpha, h.alpha_max),
        };
        Evaluation { force, stiffness, branch, lower, upper, history: TomasHistory { mode, anchor_alpha, anchor_force, last_alpha: alpha, ..*h } }
    }

    #[inline]
    fn has_yielded(&self, h: &TomasHistory) -> bool {
        h.yielded
    }

    /// 003 Eq. 10: mu (1 + kappa) (F_H0 + F_N).
    #[inline]
    fn sliding_normal_force(&self, force: f64, _alpha: f64, _h: &TomasHistory) -> f64 {
        (1.0 + self.kappa) * (self.f0 + force)
    }

    /// The tension at point A: F_H0 + k_A h_min.
    fn pull_off_force(&self, h: &TomasHistory) -> f64 {
        -h.f_a
    }

    /// Zero force on the full unloading curve from alpha_max.
    fn plastic_overlap(&self, h: &TomasHistory) -> f64 {
        if !h.yielded {
            return 0.0;
        }
        let f_max = self.k1 * h.alpha_max - self.f0;
        h.h_min + (h.alpha_max - h.h_min) * (-h.f_a / (f_max - h.f_a)).powf(2.0 / 3.0)
    }
}

crate::scene_options! {
    /// The Tomas law's own scene keys.
    pub struct TomasOptions {
        tomas_yield_strength: derived("p_y"), "Pa", Range::Open(0.0, 1e13), "p_f, plastic micro-yield strength of the contact (003 Table 1)";
        tomas_area_coefficient: number(0.834), "-", Range::ClosedLow(2.0 / 3.0, 1.0 + f64::EPSILON), "kappa_A, elastic-plastic contact area coefficient in [2/3, 1] (004 Sec. 3.4.4.3); default from 003 Sec. 3.3 limestone";
        tomas_repulsion_coefficient: number(0.152), "-", Range::ClosedLow(0.0, 1.0), "kappa_p, plastic repulsion coefficient p_vdW/p_f in [0, kappa_A) (003 Sec. 3.3 limestone)";
        tomas_contact_adhesion_force: derived("2 pi Gamma R*"), "N", Range::ClosedLow(0.0, 1e6), "F_H0, van der Waals attraction at contact (004 Eqs. 3.50, 3.61)";
        tomas_separation: number(4e-10), "m", Range::Open(0.0, 1.0), "a_F=0, minimum centre separation of the van der Waals force (004 Eq. 3.61: 0.3-0.4 nm)";
    }
}

impl LawInfo for Tomas {
    type Options = TomasOptions;
    const TANGENTIAL: TangentialModel = TangentialModel::Tomas;
    fn from_pair(pair: &Effective, options: &LawOptions) -> Result<Tomas, ParamError> {
        let own = &options.tomas;
        // kappa_p < kappa_A (003 Sec. 3.3): a range across two keys.
        check_closed_low(
            "tomas_repulsion_coefficient",
            own.tomas_repulsion_coefficient,
            0.0,
            own.tomas_area_coefficient,
            "(below tomas_area_coefficient)",
        )?;
        let p_f = match own.tomas_yield_strength {
            Some(p) => p,
            None => pair.require_yield_pressure("tomas (no tomas_yield_strength given)")?,
        };
        let f0 = own.tomas_contact_adhesion_force.unwrap_or(2.0 * PI * pair.surface_energy * pair.radius);
        Ok(Tomas::new(pair.radius, pair.youngs_modulus, p_f, own.tomas_area_coefficient, own.tomas_repulsion_coefficient, f0, own.tomas_separation))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn newtons_h_min_from_a_nearby_root_is_brents() {
        // A fine-powder pair (not a seed table's): R* 1 um, E* 50 GPa, p_f 300 MPa, kappa_A 0.9, kappa_p 0.1,
        // F_H0 10 nN, a_F 0.4 nm.
        let law = Tomas::new(1e-6, 50e9, 300e6, 0.9, 0.1, 1e-8, 4e-10);
        for alpha_max in [2.0, 5.0, 50.0, 2000.0].map(|x| x * law.alpha_y) {
            let brent = law.h_min(alpha_max);
            for guess in [brent * (1.0 - 1e-4), brent * (1.0 + 1e-4), 0.5 * brent, 0.9 * alpha_max] {
                let newton = law.h_min_near(alpha_max, guess);
                assert!((newton / brent - 1.0).abs() < 1e-13, "alpha_max {alpha_max:e}, from {guess:e}: {newton:e} vs {brent:e}");
            }
            // No usable guess: Brent's method.
            assert_eq!(law.h_min_near(alpha_max, 0.0), brent);
        }
    }
}
