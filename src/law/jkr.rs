//! The JKR elastic-adhesive law with the contact radius solved from the overlap (`000` App. B,
//! `004` Sec. 3.4.3.1).
//!
//! The JKR curve, parameterised by the contact radius a (000 Eqs. B1, B3):
//!   alpha(a) = a^2/R* - sqrt(2 pi Gamma a / E*),   f(a) = 4 E* a^3 / (3 R*) - sqrt(8 pi Gamma E* a^3).
//! Under displacement control the contact forms at alpha = 0 with f = -8/9 f_c (000 Eq. B5-B6), passes the
//! pull-off force -f_c at a_c (004 Eq. 3.57) and breaks where d alpha / d a = 0, at -5/9 f_c.
//!
//! `jkr_detachment` chooses where the contact ends: `displacement` (the default, above: 000 Eq. 73's
//! W_JKR and Thornton & Ning) or `force`, at the force minimum -f_c, the reading of a force-controlled
//! pull-off and of LAMMPS's `granular jkr` (docs/porting.md). The adhesion work the contact keeps,
//! closed form in `JkrCurve::work`, is then 0.494 of W_JKR, the sticking velocity 0.703 of 000 Eq. 73's.

use super::params::Effective;
use super::tangential::TangentialModel;
use super::{Branch, Evaluation, NormalLaw};
use super::{LawInfo, LawOptions};
use crate::error::ParamError;
use crate::numeric::cbrt;
use crate::vocabulary::Range;
use std::f64::consts::PI;

crate::choice_enum! {
    /// Where a JKR contact ends on unloading.
    pub enum JkrDetachment {
        /// Where d alpha / d a = 0, at -5/9 f_c (displacement control; 000 Eq. 73, App. B).
        Displacement = "displacement",
        /// At the force minimum -f_c (force control; LAMMPS `granular jkr`).
        Force = "force",
    }
}

crate::scene_options! {
    /// The JKR law's own scene keys.
    pub struct JkrOptions {
        jkr_detachment: choice(JkrDetachment::Displacement), "-", Range::Names, "where a jkr contact ends on unloading: displacement (d alpha/d a = 0, at -5/9 f_c; 000 Eq. 73) or force (at the force minimum -f_c, as LAMMPS granular jkr)";
    }
}

/// The JKR curve of one radius of curvature: all the geometry Thornton-Ning and the JKR laws share.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct JkrCurve {
    /// Radius of curvature (R*, or R_p after plastic flattening) [m].
    pub radius: f64,
    /// Effective modulus E* [Pa].
    pub youngs_modulus: f64,
    /// Interface energy Gamma [J/m^2].
    pub surface_energy: f64,
    /// b = sqrt(2 pi Gamma / E*) in alpha = a^2/R - b sqrt(a).
    pub(crate) b: f64,
    /// sqrt(a) at detachment (d alpha/ d a = 0): (b R / 4)^(1/3).
    pub(crate) w_detach: f64,
    /// Detachment overlap, pull-off radius and overlap: fixed per curve, kept.
    pub(crate) alpha_detach: f64,
    a_pull_off: f64,
    alpha_pull_off: f64,
}

impl JkrCurve {
    /// The curve of radius of curvature R [m], effective modulus E* [Pa] and interface energy Gamma
    /// [J/m^2], with its detachment and pull-off points computed once.
    pub fn new(radius: f64, youngs_modulus: f64, surface_energy: f64) -> JkrCurve {
        let b = (2.0 * PI * surface_energy / youngs_modulus).sqrt();
        let w_detach = cbrt(b * radius / 4.0);
        let a_pull_off = cbrt(9.0 * PI * surface_energy * radius * radius / (8.0 * youngs_modulus));
        let c = JkrCurve { radius, youngs_modulus, surface_energy, b, w_detach: 0.0, alpha_detach: 0.0, a_pull_off: 0.0, alpha_pull_off: 0.0 };
        c.with_points(w_detach, a_pull_off)
    }

    /// This curve with its detachment point (sqrt(a) = w_detach) and pull-off radius, and their overlaps.
    fn with_points(self, w_detach: f64, a_pull_off: f64) -> JkrCurve {
        let mut c = JkrCurve { w_detach, a_pull_off, ..self };
        c.alpha_detach = c.overlap(w_detach * w_detach);
        c.alpha_pull_off = c.overlap(a_pull_off);
        c
    }

    /// The curve of another radius of curvature with the same E* and Gamma (Thornton-Ning's flattened
    /// radius R_p, built at every step of plastic loading). The detachment and pull-off radii scale as
    /// R^(1/3) and R^(2/3): one cube root instead of `new`'s two.
    pub fn with_radius(&self, radius: f64) -> JkrCurve {
        self.scaled(radius, cbrt(radius / self.radius))
    }

    /// `with_radius` with the cube root found by Newton's method from a curve of a nearby radius (the
    /// same contact's curve a step earlier): two divisions instead of the pure-Rust cube root, which was
    /// 12 % of Thornton-Ning's bed time. Falls back to the cube root when the start is unusable.
    pub fn with_radius_near(&self, radius: f64, near: &JkrCurve) -> JkrCurve {
        let q = radius / self.radius;
        let mut s = near.w_detach / self.w_detach;
        if !(s > 0.0 && s.is_finite()) {
            return self.with_radius(radius);
        }
        for _ in 0..4 {
            let step = (s * s * s - q) / (3.0 * s * s);
            s -= step;
            // Quadratic convergence: after a relative step below 1e-8 the error is below rounding.
            if step.abs() <= 1e-8 * s {
                return self.scaled(radius, s);
            }
        }
        self.with_radius(radius)
    }

    /// The curve of radius `radius` = s^3 R with the same E* and Gamma.
    fn scaled(&self, radius: f64, s: f64) -> JkrCurve {
        JkrCurve { radius, ..*self }.with_points(self.w_detach * s, self.a_pull_off * s * s)
    }

    /// Overlap at contact radius a (000 Eq. B3).
    pub fn overlap(&self, a: f64) -> f64 {
        a * a / self.radius - self.b * a.sqrt()
    }

    /// Force at contact radius a (000 Eq. B1).
    pub fn force(&self, a: f64) -> f64 {
        4.0 * self.youngs_modulus * a.powi(3) / (3.0 * self.radius) - (8.0 * PI * self.surface_energy * self.youngs_modulus * a.powi(3)).sqrt()
    }

    /// df/dalpha at contact radius a (equal to 000 Eq. B2).
    pub fn stiffness(&self, a: f64) -> f64 {
        if self.b == 0.0 {
            return 2.0 * self.youngs_modulus * a; // Hertz (000 Eq. 41); also right at a = 0
        }
        let df_da = 4.0 * self.youngs_modulus * a * a / self.radius - 1.5 * (8.0 * PI * self.surface_energy * self.youngs_modulus * a).sqrt();
        // The slope is infinite at detachment (d alpha / d a = 0); cap it at a million times the Hertz
        // scale 2a/R so that damping and time steps built on it stay finite.
        let dalpha_da = (2.0 * a / self.radius - 0.5 * self.b / a.sqrt()).max(2e-6 * a / self.radius);
        df_da / dalpha_da
    }

    /// The repulsive (Hertz) part 4 E* a^3 / (3 R) of a force f on the stable branch (a above the
    /// pull-off radius): with x = a^(3/2), f = k x^2 - c x (k = 4 E*/(3R), c = 2 E* b) is a quadratic whose
    /// larger root is that branch. For f below -f_c, off the curve, the root at the pull-off radius.
    pub fn repulsive_part(&self, force: f64) -> f64 {
        let k = 4.0 * self.youngs_modulus / (3.0 * self.radius);
        let c = 2.0 * self.youngs_modulus * self.b;
        let x = (c + (c * c + 4.0 * k * force).max(0.0).sqrt()) / (2.0 * k);
        k * x * x
    }

    /// Pull-off force f_c = 1.5 pi Gamma R (000 Eq. 5).
    pub fn pull_off_force(&self) -> f64 {
        1.5 * PI * self.surface_energy * self.radius
    }

    /// Contact radius at the pull-off force, a_c = (9 pi Gamma R^2 / (8 E*))^(1/3) (004 Eq. 3.57).
    pub fn pull_off_radius(&self) -> f64 {
        self.a_pull_off
    }

    /// Overlap at the pull-off force.
    pub fn pull_off_overlap(&self) -> f64 {
        self.alpha_pull_off
    }

    /// Work of the force along the curve from contact radius a1 to a2, the integral of f d alpha [J]:
    /// with f = 4E a^3/(3R) - 2E b a^(3/2) and d alpha = (2a/R - b/(2 sqrt a)) da the integrand is a
    /// polynomial in sqrt(a), whose antiderivative is 8E a^5/(15 R^2) - 4E b a^(7/2)/(3R) + E b^2 a^2 / 2.
    pub fn work(&self, a1: f64, a2: f64) -> f64 {
        let (e, r, b) = (self.youngs_modulus, self.radius, self.b);
        let antiderivative = |a: f64| 8.0 * e * a.powi(5) / (15.0 * r * r) - 4.0 * e * b * a.powf(3.5) / (3.0 * r) + 0.5 * e * b * b * a * a;
        antiderivative(a2) - antiderivative(a1)
    }

    /// Contact radius where the overlap is 0 on the stable branch, (b R)^(2/3) [m].
    pub fn zero_overlap_radius(&self) -> f64 {
        cbrt(self.b * self.radius).powi(2)
    }

    /// Contact radius at detachment (the minimum of alpha(a)).
    pub fn detach_radius(&self) -> f64 {
        self.w_detach * self.w_detach
    }

    /// Overlap at detachment alpha_f (negative with adhesion, 0 without).
    pub fn detach_overlap(&self) -> f64 {
        self.alpha_detach
    }

    /// Contact radius on the stable branch (a >= detach radius) for an overlap; below the detachment
    /// overlap the detachment radius. With w = sqrt(a), alpha(a) = a^2/R - b sqrt(a) is the depressed
    /// quartic w^4 - b R w - alpha R = 0, solved in closed form (Ferrari): m > 0 solves the resolvent cubic
    /// m^3 + alpha R m - (b R)^2 / 8 = 0 (Cardano, or its trigonometric form where it has three real
    /// roots), and the largest root is w = (sqrt(2m) + sqrt(sqrt(2) b R / sqrt(m) - 2m)) / 2. One Newton
    /// step on the quartic then polishes w to rounding (docs/models.md, JKR).
    #[inline]
    pub fn contact_radius(&self, alpha: f64) -> f64 {
        if self.b == 0.0 {
            return (self.radius * alpha.max(0.0)).sqrt();
        }
        let alpha_f = self.detach_overlap();
        if alpha <= alpha_f {
            return self.detach_radius();
        }
        let r = self.radius;
        let wf = self.w_detach;
        let p = alpha * r;
        let q = 0.125 * (self.b * r).powi(2);
        let disc = 0.25 * q * q + (p / 3.0).powi(3);
        let m = if disc >= 0.0 {
            let u = cbrt(0.5 * q + disc.sqrt());
            let m = u - p / (3.0 * u);
            // m = q / (m^2 + p) is the same root without the cancellation of u - p/(3u) when p is large.
            if m * m + p > 0.0 {
                q / (m * m + p)
            } else {
                m
            }
        } else {
            let s = (-p / 3.0).sqrt();
            2.0 * s * ((0.5 * q / (s * s * s)).clamp(-1.0, 1.0).acos() / 3.0).cos()
        };
        let root2m = (2.0 * m).sqrt();
        let inner = (std::f64::consts::SQRT_2 * self.b * r / m.sqrt() - 2.0 * m).max(0.0);
        let mut w = 0.5 * (root2m + inner.sqrt());
        let df = 4.0 * w * w * w / r - self.b;
        if df > 0.0 {
            let step = (w.powi(4) / r - self.b * w - alpha) / df;
            if step.abs() < 1e-6 * w {
                w -= step;
            }
        }
        let w = w.max(wf);
        w * w
    }
}

impl JkrCurve {
    /// The contact radius of `alpha` by Newton's method on the quartic from a nearby radius `guess` (the
    /// same contact a step earlier). On the stable branch the quartic increases and is convex, so from
    /// either side Newton converges (from the left it first overshoots to the right); two or three
    /// steps reach rounding. Falls back to the closed form without a usable guess.
    #[inline]
    pub fn contact_radius_from(&self, alpha: f64, guess: f64) -> f64 {
        let wf = self.w_detach;
        if self.b == 0.0 || alpha <= self.alpha_detach || !(guess > wf * wf * (1.0 + 1e-6)) {
            return self.contact_radius(alpha);
        }
        let r = self.radius;
        let mut w = guess.sqrt();
        for _ in 0..8 {
            let df = 4.0 * w * w * w / r - self.b;
            if !(df > 0.0) {
                break;
            }
            let step = (w * w * w * w / r - self.b * w - alpha) / df;
            w -= step;
            // Convergence is quadratic: after a step of relative size s the error is about
            // (w f''/2f') s^2. Away from detachment (f' at least a tenth of its Hertz part) that factor
            // is of order one, so a step below 1e-8 w leaves an error below rounding.
            let settled = if df > 0.4 * w * w * w / r { 1e-8 * w } else { 4.0 * f64::EPSILON * w };
            if step.abs() <= settled {
                return w.max(wf).powi(2);
            }
        }
        self.contact_radius(alpha)
    }
}

/// The full JKR law: forms at alpha = 0, breaks at alpha_f, or at the pull-off overlap alpha_c with
/// `JkrDetachment::Force` (hysteresis between the two).
#[derive(Debug, Clone, PartialEq)]
pub struct Jkr {
    /// The JKR curve of R*.
    pub curve: JkrCurve,
    /// Where an established contact ends on unloading (`jkr_detachment`).
    pub detachment: JkrDetachment,
    /// The overlap at which an established contact ends [m].
    detach_at: f64,
}

/// What a JKR contact remembers.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct JkrHistory {
    /// The contact has formed (at alpha >= 0) and not yet ended: it then holds at negative overlap down
    /// to the detachment overlap.
    pub established: bool,
}

impl Jkr {
    /// The law of reduced radius R* [m], effective modulus E* [Pa] and interface energy Gamma [J/m^2],
    /// with displacement-controlled detachment (the default).
    pub fn new(radius: f64, youngs_modulus: f64, surface_energy: f64) -> Jkr {
        Jkr::with_detachment(radius, youngs_modulus, surface_energy, JkrDetachment::Displacement)
    }

    /// `new` with the detachment reading chosen.
    pub fn with_detachment(radius: f64, youngs_modulus: f64, surface_energy: f64, detachment: JkrDetachment) -> Jkr {
        let curve = JkrCurve::new(radius, youngs_modulus, surface_energy);
        let detach_at = match detachment {
            JkrDetachment::Displacement => curve.detach_overlap(),
            // Without adhesion the force minimum is at alpha = 0, where the curve also ends.
            JkrDetachment::Force if surface_energy > 0.0 => curve.pull_off_overlap(),
            JkrDetachment::Force => curve.detach_overlap(),
        };
        Jkr { curve, detachment, detach_at }
    }

    /// The overlap at which an established contact ends [m].
    pub fn detach_overlap(&self) -> f64 {
        self.detach_at
    }

    /// The contact radius at which an established contact ends [m].
    pub fn detach_radius(&self) -> f64 {
        match self.detachment {
            JkrDetachment::Force if self.curve.surface_energy > 0.0 => self.curve.pull_off_radius(),
            _ => self.curve.detach_radius(),
        }
    }

    /// The energy an impact loses to adhesion, undamped: the work of the tensile part of the curve from
    /// where the contact ends to alpha = 0, -(integral of f d alpha) [J] (000 Eq. 37's W_JKR for the
    /// displacement reading).
    pub fn adhesion_work(&self) -> f64 {
        -self.curve.work(self.detach_radius(), self.curve.zero_overlap_radius())
    }

    /// Whether an established contact has ended at this overlap.
    #[inline]
    fn separated(&self, alpha: f64, h: &JkrHistory) -> bool {
        (!h.established && alpha < 0.0) || alpha < self.detach_at
    }

    /// On the curve; with force detachment there is no adhesive branch: the contact's lower bound is the
    /// pull-off overlap (a radius that rounding puts just below a_c is still the elastic branch there).
    fn on_curve_at(&self, a: f64) -> Evaluation<JkrHistory> {
        let mut ev = on_curve_at(&self.curve, 0.0, a, JkrHistory { established: true });
        if self.detachment == JkrDetachment::Force && self.curve.surface_energy > 0.0 {
            ev.branch = Branch::Elastic;
            ev.lower = self.detach_at;
            ev.upper = f64::INFINITY;
        }
        ev
    }
}

/// Force on the JKR curve shifted by `offset` at the overlap whose contact radius is `a` (solved by the
/// caller), split at the pull-off point into elastic and adhesive branches.
pub(crate) fn on_curve_at<H>(curve: &JkrCurve, offset: f64, a: f64, history: H) -> Evaluation<H> {
    let a_c = curve.pull_off_radius();
    let alpha_c = offset + curve.pull_off_overlap();
    let adhesive = curve.surface_energy > 0.0 && a < a_c;
    Evaluation {
        force: curve.force(a),
        stiffness: curve.stiffness(a),
        branch: if adhesive { Branch::Adhesive } else { Branch::Elastic },
        lower: if adhesive { offset + curve.detach_overlap() } else { alpha_c },
        upper: if adhesive { alpha_c } else { f64::INFINITY },
        history,
    }
}

impl NormalLaw for Jkr {
    type History = JkrHistory;

    fn initial_history(&self) -> JkrHistory {
        JkrHistory { established: false }
    }

    #[inline]
    fn evaluate(&self, alpha: f64, h: &JkrHistory) -> Evaluation<JkrHistory> {
        if self.separated(alpha, h) {
            return Evaluation::separated(0.0, JkrHistory { established: false });
        }
        self.on_curve_at(self.curve.contact_radius(alpha))
    }

    #[inline]
    fn has_yielded(&self, _h: &JkrHistory) -> bool {
        false
    }

    /// Thornton & Yin's sliding criterion mu (F_n + 2 F_c) (004 Eq. 3.49).
    #[inline]
    fn sliding_normal_force(&self, force: f64, _alpha: f64, _h: &JkrHistory) -> f64 {
        force + 2.0 * self.curve.pull_off_force()
    }

    fn pull_off_force(&self, _h: &JkrHistory) -> f64 {
        self.curve.pull_off_force()
    }

    fn plastic_overlap(&self, _h: &JkrHistory) -> f64 {
        0.0
    }

    #[inline]
    fn contact_radius(&self, alpha: f64, h: &JkrHistory) -> Option<f64> {
        (h.established && alpha >= self.detach_at || alpha >= 0.0).then(|| self.curve.contact_radius(alpha))
    }

    /// 2 E* a: the Hertz stiffness at the JKR contact radius (the JKR slope is infinite at detachment).
    #[inline]
    fn damping_stiffness(&self, alpha: f64, h: &JkrHistory, _branch_stiffness: f64) -> f64 {
        2.0 * self.curve.youngs_modulus * self.contact_radius(alpha, h).unwrap_or(0.0)
    }

    /// The adhesive branch under displacement control ends vertically at alpha_f; the zone is alpha_c -
    /// alpha_f. With force detachment the contact ends at the force minimum, where the curve is smooth.
    fn vertical_end(&self, branch: Branch, _h: &JkrHistory) -> Option<f64> {
        (branch == Branch::Adhesive && self.detachment == JkrDetachment::Displacement)
            .then(|| self.curve.pull_off_overlap() - self.curve.detach_overlap())
    }

    /// One contact-radius solve for force, stiffness, damping and Mindlin (same numbers as the three
    /// separate calls).
    #[inline]
    fn evaluate_with_radius(&self, alpha: f64, h: &JkrHistory) -> (Evaluation<JkrHistory>, f64, Option<f64>) {
        if self.separated(alpha, h) {
            return (Evaluation::separated(0.0, JkrHistory { established: false }), 0.0, None);
        }
        let a = self.curve.contact_radius(alpha);
        let ev = self.on_curve_at(a);
        (ev, 2.0 * self.curve.youngs_modulus * a, Some(a))
    }

    #[inline]
    fn evaluate_near(&self, alpha: f64, h: &JkrHistory, guess: f64) -> (Evaluation<JkrHistory>, f64, Option<f64>) {
        if self.separated(alpha, h) {
            return (Evaluation::separated(0.0, JkrHistory { established: false }), 0.0, None);
        }
        let a = self.curve.contact_radius_from(alpha, guess);
        let ev = self.on_curve_at(a);
        (ev, 2.0 * self.curve.youngs_modulus * a, Some(a))
    }
}

impl LawInfo for Jkr {
    const TANGENTIAL: TangentialModel = TangentialModel::Mindlin;
    type Options = JkrOptions;
    fn from_pair(eff: &Effective, options: &LawOptions) -> Result<Jkr, ParamError> {
        Ok(Jkr::with_detachment(eff.radius, eff.youngs_modulus, eff.surface_energy, options.jkr.jkr_detachment))
    }
}

#[cfg(test)]
mod detachment_tests {
    use super::*;
    use crate::law::params::w_jkr;
    use crate::theory::energy_balance;

    // 000 Table 5's pair (ammonium fluorescein on silicon): R*, E*, Gamma; the sphere's mass.
    const R: f64 = 2.45e-6;
    const E: f64 = 1.33666e9;
    const GAMMA: f64 = 0.24;
    const MASS: f64 = 8.31612e-14;

    #[test]
    fn the_displacement_readings_adhesion_work_is_000_eq_37s_w_jkr() {
        let w = Jkr::new(R, E, GAMMA).adhesion_work();
        let eq37 = w_jkr(GAMMA, R, E);
        // Eq. 37's 7.09 is printed to three digits.
        assert!((w / eq37 - 1.0).abs() < 2e-3, "{w:e} vs {eq37:e}");
    }

    #[test]
    fn a_curve_rescaled_to_another_radius_is_the_curve_of_that_radius() {
        let c = JkrCurve::new(R, E, GAMMA);
        for ratio in [0.3, 1.0, 1.7, 40.0] {
            let (scaled, direct) = (c.with_radius(ratio * R), JkrCurve::new(ratio * R, E, GAMMA));
            assert_eq!(scaled.radius, direct.radius);
            // From a curve within 1e-3 of the radius, or 30 % away, Newton's cube root agrees.
            for near in [c.with_radius(ratio * R * (1.0 + 1e-3)), c.with_radius(ratio * R * 0.7)] {
                let newton = c.with_radius_near(ratio * R, &near);
                assert!((newton.detach_radius() / direct.detach_radius() - 1.0).abs() < 1e-14, "ratio {ratio}");
                assert!((newton.pull_off_radius() / direct.pull_off_radius() - 1.0).abs() < 1e-14, "ratio {ratio}");
            }
            let pairs = [
                (scaled.detach_radius(), direct.detach_radius()),
                (scaled.detach_overlap(), direct.detach_overlap()),
                (scaled.pull_off_radius(), direct.pull_off_radius()),
                (scaled.pull_off_overlap(), direct.pull_off_overlap()),
            ];
            for (x, y) in pairs {
                assert!((x / y - 1.0).abs() < 1e-14, "ratio {ratio}: {x:e} vs {y:e}");
            }
        }
    }

    #[test]
    fn the_closed_form_work_is_the_quadrature_of_the_curve() {
        let c = JkrCurve::new(R, E, GAMMA);
        let (a1, a2) = (c.detach_radius(), 3.0 * c.pull_off_radius());
        let n = 200_000;
        let quad: f64 = (0..n)
            .map(|i| {
                let (x0, x1) = (a1 + (a2 - a1) * i as f64 / n as f64, a1 + (a2 - a1) * (i + 1) as f64 / n as f64);
                let xm = 0.5 * (x0 + x1);
                c.force(xm) * (c.overlap(x1) - c.overlap(x0))
            })
            .sum();
        assert!((c.work(a1, a2) / quad - 1.0).abs() < 1e-6, "{:e} vs {quad:e}", c.work(a1, a2));
    }

    #[test]
    fn force_detachment_ends_the_contact_at_the_force_minimum() {
        let law = Jkr::with_detachment(R, E, GAMMA, JkrDetachment::Force);
        let c = law.curve;
        let alpha_c = c.pull_off_overlap();
        let on = law.evaluate(alpha_c * (1.0 - 1e-9), &JkrHistory { established: true });
        assert_eq!(on.branch, Branch::Elastic);
        assert!((on.force + c.pull_off_force()).abs() < 1e-6 * c.pull_off_force(), "-f_c at alpha_c");
        assert_eq!(on.lower, alpha_c, "the contact's lower bound is where it ends");
        let off = law.evaluate(alpha_c * (1.0 + 1e-9), &JkrHistory { established: true });
        assert_eq!(off.branch, Branch::Separated);
        // The displacement reading goes on along the adhesive branch.
        let disp = Jkr::new(R, E, GAMMA).evaluate(alpha_c * (1.0 + 1e-3), &JkrHistory { established: true });
        assert_eq!(disp.branch, Branch::Adhesive);
    }

    #[test]
    fn force_detachment_sticks_below_0_703_of_the_displacement_readings_velocity() {
        let (disp, force) = (Jkr::new(R, E, GAMMA), Jkr::with_detachment(R, E, GAMMA, JkrDetachment::Force));
        let ratio_w = force.adhesion_work() / disp.adhesion_work();
        assert!((ratio_w - 0.494).abs() < 5e-4, "{ratio_w}");
        for law in [&disp, &force] {
            // The energy balance of the law's own path against the closed form sqrt(2 W / m).
            let balance = energy_balance::sticking_velocity(law, MASS, R, 1e-3, 10.0).unwrap();
            let closed = (2.0 * law.adhesion_work() / MASS).sqrt();
            assert!((balance / closed - 1.0).abs() < 1e-6, "{:?}: {balance} vs {closed}", law.detachment);
        }
        let v = |l: &Jkr| energy_balance::sticking_velocity(l, MASS, R, 1e-3, 10.0).unwrap();
        assert!((v(&force) / v(&disp) - 0.703).abs() < 5e-4, "{}", v(&force) / v(&disp));
    }
}
