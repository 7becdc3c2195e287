//! The yield locus of a shear test and what the Mohr circles read from it (`004` Sec. 2.2, Figs.
//! 2.3-2.5; `003` Sec. 7.1.4): a straight line tau = c + sigma tan(phi_i) through the points of incipient
//! flow (sigma_n, tau_peak) after one preshear, its angle of internal friction phi_i and cohesion c, the
//! unconfined yield strength sigma_c (the Mohr circle through the origin tangent to the locus) and the
//! major consolidation stress sigma_1 (the circle through the preshear point, the steady state, tangent
//! to the locus). The locus is fitted by least squares weighted by each point's standard error; the
//! parameters' errors are the fit's covariance, scaled up by chi^2 per degree of freedom where the
//! points scatter more than their errors say (Birge), and carried to sigma_c and sigma_1 by the chain
//! rule (c and tan phi_i correlated).

/// One point of the locus: the normal stress on the shear plane and the shear stress, with the latter's
/// standard error [Pa].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Normal stress on the shear plane [Pa].
    pub normal_stress: f64,
    /// Shear stress at incipient flow [Pa].
    pub shear_stress: f64,
    /// Its standard error [Pa] (0: unknown).
    pub shear_stress_error: f64,
}

/// The straight yield locus and what it gives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct YieldLocus {
    /// Cohesion c, the locus at sigma = 0 [Pa].
    pub cohesion: f64,
    /// Its standard error [Pa].
    pub cohesion_error: f64,
    /// tan(phi_i) [-].
    pub slope: f64,
    /// Its standard error [-].
    pub slope_error: f64,
    /// Covariance of c and tan(phi_i) [Pa].
    covariance: f64,
    /// chi^2 of the fit with the points' own errors.
    pub chi2: f64,
    /// Its degrees of freedom (points - 2).
    pub dof: usize,
}

impl YieldLocus {
    /// The weighted least-squares line through at least two points (three for an error from the
    /// scatter), or None when the points cannot give one: fewer than two distinct normal stresses, or a
    /// line that does not rise with sigma (phi_i <= 0 is no Mohr-Coulomb locus, and sigma_c read off it
    /// nonsense; four shears within 0.8-0.99 sigma_pre of 003's TiO2 case, 2.7 kPa apart in sigma against
    /// errors of 0.3-1.2 kPa in tau, gave phi_i = -30 deg and sigma_c = 40 kPa).
    pub fn fit(points: &[Point]) -> Option<YieldLocus> {
        if points.len() < 2 {
            return None;
        }
        // Weights 1/se^2; a point without an error (too few samples) weighs as the mean of the others.
        let known: Vec<f64> =
            points.iter().filter(|p| p.shear_stress_error > 0.0).map(|p| 1.0 / (p.shear_stress_error * p.shear_stress_error)).collect();
        let fallback = if known.is_empty() { 1.0 } else { known.iter().sum::<f64>() / known.len() as f64 };
        let w: Vec<f64> =
            points.iter().map(|p| if p.shear_stress_error > 0.0 { 1.0 / (p.shear_stress_error * p.shear_stress_error) } else { fallback }).collect();
        let (mut s, mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for (p, w) in points.iter().zip(&w) {
            s += w;
            sx += w * p.normal_stress;
            sy += w * p.shear_stress;
            sxx += w * p.normal_stress * p.normal_stress;
            sxy += w * p.normal_stress * p.shear_stress;
        }
        let det = s * sxx - sx * sx;
        if !(det > 1e-12 * s * sxx) {
            return None;
        }
        let slope = (s * sxy - sx * sy) / det;
        if !(slope > 0.0) {
            return None;
        }
        let cohesion = (sxx * sy - sx * sxy) / det;
        let chi2: f64 = points.iter().zip(&w).map(|(p, w)| w * (p.shear_stress - cohesion - slope * p.normal_stress).powi(2)).sum();
        let dof = points.len() - 2;
        // Birge's factor: the points' own scatter where it exceeds their errors.
        let scale = if dof > 0 { (chi2 / dof as f64).max(1.0) } else { 1.0 };
        let (var_c, var_m, cov) = (scale * sxx / det, scale * s / det, -scale * sx / det);
        Some(YieldLocus { cohesion, cohesion_error: var_c.sqrt(), slope, slope_error: var_m.sqrt(), covariance: cov, chi2, dof })
    }

    /// The angle of internal friction phi_i [rad].
    pub fn internal_friction_angle(&self) -> f64 {
        self.slope.atan()
    }

    /// Its standard error [rad].
    pub fn internal_friction_angle_error(&self) -> f64 {
        self.slope_error / (1.0 + self.slope * self.slope)
    }

    /// The locus at `sigma` [Pa] and its standard error.
    pub fn at(&self, sigma: f64) -> (f64, f64) {
        let var = self.cohesion_error.powi(2) + sigma * sigma * self.slope_error.powi(2) + 2.0 * sigma * self.covariance;
        (self.cohesion + self.slope * sigma, var.max(0.0).sqrt())
    }

    /// The unconfined yield strength sigma_c = 2 c (1 + sin phi_i) / cos phi_i: the Mohr circle through the
    /// origin tangent to the locus (004 Fig. 2.5) [Pa], with its standard error.
    pub fn unconfined_yield_strength(&self) -> (f64, f64) {
        let f = |c: f64, m: f64| {
            let phi = m.atan();
            2.0 * c * (1.0 + phi.sin()) / phi.cos()
        };
        self.propagate(f)
    }

    /// The major consolidation stress sigma_1 [Pa]: the larger principal stress of the Mohr circle through
    /// the preshear point (sigma_pre, tau_pre) tangent to the locus, with its standard error (the
    /// locus's; the preshear point's own error is the caller's to add). None when the point lies so far
    /// above the locus that no such circle exists; a point on the locus within rounding gives the circle
    /// tangent there.
    pub fn major_consolidation_stress(&self, sigma_pre: f64, tau_pre: f64) -> Option<(f64, f64)> {
        let f = |c: f64, m: f64| sigma_1(c, m, sigma_pre, tau_pre);
        f(self.cohesion, self.slope)?;
        let (value, error) = self.propagate(|c, m| f(c, m).unwrap_or(f64::NAN));
        Some((value, if error.is_finite() { error } else { f64::NAN }))
    }

    /// f(c, tan phi) and its standard error by central differences and the covariance.
    fn propagate(&self, f: impl Fn(f64, f64) -> f64) -> (f64, f64) {
        let (c, m) = (self.cohesion, self.slope);
        let v = f(c, m);
        let hc = 1e-6 * c.abs().max(1.0);
        let hm = 1e-6 * m.abs().max(1e-3);
        let dc = (f(c + hc, m) - f(c - hc, m)) / (2.0 * hc);
        let dm = (f(c, m + hm) - f(c, m - hm)) / (2.0 * hm);
        let var = dc * dc * self.cohesion_error.powi(2) + dm * dm * self.slope_error.powi(2) + 2.0 * dc * dm * self.covariance;
        (v, var.max(0.0).sqrt())
    }
}

/// sigma_1 of the circle centred at (p, 0) through (sigma_pre, tau_pre) and tangent to tau = c + m sigma:
/// its radius is the distance to the line, c cos phi + p sin phi, which gives
/// p^2 cos^2 phi - 2 p (sigma_pre + c sin phi cos phi) + sigma_pre^2 + tau_pre^2 - c^2 cos^2 phi = 0;
/// the larger root is the steady-state circle (its tangent point at or left of the preshear point).
fn sigma_1(c: f64, m: f64, sigma_pre: f64, tau_pre: f64) -> Option<f64> {
    let phi = m.atan();
    let (s, k) = (phi.sin(), phi.cos());
    let a = k * k;
    let b = sigma_pre + c * s * k;
    let q = sigma_pre * sigma_pre + tau_pre * tau_pre - c * c * k * k;
    let disc = b * b - a * q;
    // A point on the locus gives a double root; rounding can take it just below zero.
    let tolerance = 1e-9 * b * b;
    if disc < -tolerance {
        return None;
    }
    let p = (b + disc.max(0.0).sqrt()) / a;
    Some(p + c * k + p * s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(sigma: f64, tau: f64, e: f64) -> Point {
        Point { normal_stress: sigma, shear_stress: tau, shear_stress_error: e }
    }

    #[test]
    fn a_line_through_exact_points_is_found_and_its_circles_are_the_textbooks() {
        // tau = 1000 + tan(30 deg) sigma
        let m = (30f64).to_radians().tan();
        let pts: Vec<Point> = [2e3, 4e3, 6e3, 8e3].iter().map(|&s| point(s, 1e3 + m * s, 10.0)).collect();
        let yl = YieldLocus::fit(&pts).unwrap();
        assert!((yl.cohesion - 1e3).abs() < 1e-8 && (yl.slope - m).abs() < 1e-12, "{yl:?}");
        assert!((yl.internal_friction_angle().to_degrees() - 30.0).abs() < 1e-9);
        // sigma_c = 2 c (1 + sin 30) / cos 30 = 3 c / cos 30
        let (sc, _) = yl.unconfined_yield_strength();
        assert!((sc - 3e3 / (30f64).to_radians().cos()).abs() < 1e-6, "{sc}");
        // The circle through the origin tangent to the line: its centre's distance to the line is its radius.
        let p = 0.5 * sc;
        let phi = m.atan();
        assert!(((yl.cohesion * phi.cos() + p * phi.sin()) - p).abs() < 1e-6);
        // A preshear point on the locus: the circle tangent there; its sigma_1 from geometry.
        let sp = 10e3;
        let tp = 1e3 + m * sp;
        let (s1, _) = yl.major_consolidation_stress(sp, tp).unwrap();
        // Tangent at (sp, tp): the centre is where the normal to the line through the point meets the axis.
        let centre = sp + tp * m;
        let radius = ((sp - centre).powi(2) + tp * tp).sqrt();
        assert!((s1 - (centre + radius)).abs() < 1e-6 * s1, "{s1} against {}", centre + radius);
        // Below the locus: a larger circle through the point, tangent elsewhere; above it: none.
        let (lower, _) = yl.major_consolidation_stress(sp, 0.9 * tp).unwrap();
        assert!(lower > 0.0 && (lower - (centre + radius)).abs() > 1.0);
        assert!(yl.major_consolidation_stress(sp, 1.2 * tp).is_none());
    }

    #[test]
    fn the_errors_follow_the_scatter_and_the_weights() {
        // Points scattered by +-50 Pa with claimed errors of 1 Pa: Birge's factor takes the errors to the scatter.
        let pts = [point(1e3, 1550.0, 1.0), point(2e3, 1950.0, 1.0), point(3e3, 2550.0, 1.0), point(4e3, 2950.0, 1.0)];
        let yl = YieldLocus::fit(&pts).unwrap();
        assert!(yl.chi2 > 1e3 && yl.dof == 2);
        assert!(yl.slope_error > 0.01 && yl.cohesion_error > 30.0, "{yl:?}");
        // A point with a huge error hardly moves the line.
        let mut pts: Vec<Point> = [1e3, 2e3, 3e3].iter().map(|&s| point(s, 500.0 + 0.5 * s, 5.0)).collect();
        pts.push(point(2.5e3, 5e3, 1e6));
        let yl = YieldLocus::fit(&pts).unwrap();
        assert!((yl.slope - 0.5).abs() < 1e-4 && (yl.cohesion - 500.0).abs() < 0.1, "{yl:?}");
        // Too few or degenerate points: no line.
        assert!(YieldLocus::fit(&pts[..1]).is_none());
        assert!(YieldLocus::fit(&[point(1e3, 1.0, 1.0), point(1e3, 2.0, 1.0)]).is_none());
    }

    #[test]
    fn a_cohesionless_locus_through_the_origin_has_no_unconfined_strength() {
        let pts: Vec<Point> = [1e3, 2e3, 3e3].iter().map(|&s| point(s, 0.4 * s, 3.0)).collect();
        let yl = YieldLocus::fit(&pts).unwrap();
        let (sc, e) = yl.unconfined_yield_strength();
        assert!(sc.abs() < 1e-6 && e > 0.0, "{sc} +- {e}");
    }

    #[test]
    fn a_line_that_does_not_rise_with_sigma_is_no_locus() {
        // 003's TiO2 case sheared at 0.8-0.99 sigma_pre: points too close in sigma for their scatter.
        let pts = [point(18634.0, 24086.0, 620.0), point(20551.0, 22664.0, 320.0), point(19827.0, 23439.0, 350.0), point(21300.0, 24277.0, 1200.0)];
        assert!(YieldLocus::fit(&pts).is_none());
        assert!(YieldLocus::fit(&[point(1e3, 2e3, 10.0), point(2e3, 2e3, 10.0)]).is_none(), "a flat line");
        assert!(YieldLocus::fit(&[point(1e3, 2e3, 10.0), point(2e3, 2.5e3, 10.0)]).is_some());
    }
}
