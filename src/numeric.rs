//! Small numerical tools shared by the laws and the closed-form theory: a bracketed root finder
//! and tanh-sinh quadrature. No allocation, no panics.

/// Brent's method on `[a, b]` where `f(a)` and `f(b)` have opposite signs (or one is zero).
/// Returns `None` if the bracket is not valid or the inputs are not finite.
/// Converges to within a few ulps of the root: the tolerance is `4 eps |x| + xtol`.
pub fn brent<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64, xtol: f64) -> Option<f64> {
    let (mut a, mut b) = (a, b);
    let (mut fa, mut fb) = (f(a), f(b));
    if !(fa.is_finite() && fb.is_finite()) {
        return None;
    }
    if fa == 0.0 {
        return Some(a);
    }
    if fb == 0.0 {
        return Some(b);
    }
    if fa.signum() == fb.signum() {
        return None;
    }
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 4.0 * f64::EPSILON * b.abs() + 0.5 * xtol;
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            return Some(b);
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol { d } else { tol.copysign(m) };
        fb = f(b);
        if !fb.is_finite() {
            return None;
        }
    }
    Some(b)
}

/// Tanh-sinh (double exponential) quadrature of `f` over `[a, b]`. Accurate to near machine precision
/// for integrands that are smooth inside but have square-root behaviour at an end, as the JKR curve has
/// at detachment. About 100 evaluations; `f` is never evaluated at the end points themselves.
pub fn tanh_sinh<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64) -> f64 {
    if a == b {
        return 0.0;
    }
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    let h = 1.0 / 16.0;
    let mut sum = 0.0;
    let n = (3.2 / h) as i32;
    for k in -n..=n {
        let t = h * k as f64;
        let u = std::f64::consts::FRAC_PI_2 * t.sinh();
        let x = u.tanh();
        let w = std::f64::consts::FRAC_PI_2 * t.cosh() / (u.cosh() * u.cosh());
        // Distance to the nearer end, computed without cancellation.
        let d = 1.0 / (u.abs().exp() * u.cosh());
        let point = if x < 0.0 { a + half * d } else { b - half * d };
        let point = if k == 0 { mid } else { point };
        if point > a.min(b) && point < a.max(b) || k == 0 {
            sum += w * f(point);
        }
    }
    half * h * sum
}

/// One bracket [lo, hi] with the inside at `lo` and the outside at `hi`, narrowed by Illinois regula
/// falsi (bisection where the secant leaves the bracket) until `narrow(lo, hi)`; returns `hi`, the first
/// point found outside. `inside(g)` says which side a value of `g` is on. The event location of both
/// impact integrators.
pub fn first_outside(
    g: impl Fn(f64) -> f64,
    inside: impl Fn(f64) -> bool,
    (mut lo, mut g_lo): (f64, f64),
    (mut hi, mut g_hi): (f64, f64),
    narrow: impl Fn(f64, f64) -> bool,
) -> f64 {
    let mut side = 0i8;
    for _ in 0..200 {
        if narrow(lo, hi) {
            break;
        }
        let mut t = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
        if !(t > lo && t < hi) {
            t = 0.5 * (lo + hi);
        }
        let g_t = g(t);
        if inside(g_t) {
            lo = t;
            g_lo = g_t;
            if side == 1 {
                g_hi *= 0.5;
            }
            side = 1;
        } else {
            hi = t;
            g_hi = g_t;
            if side == -1 {
                g_lo *= 0.5;
            }
            side = -1;
        }
    }
    hi
}

/// The cube root, the same bits on every platform: the C libraries' `cbrt` differ in the last bit
/// (glibc's and mingw's, measured), and a DEM bed turns one bit into another trajectory, so a win64 FMU
/// would not repeat the linux64 one. `libm` is a pure-Rust port of musl's.
pub fn cbrt(x: f64) -> f64 {
    libm::cbrt(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brent_finds_cube_root_to_machine_precision() {
        let r = brent(|x| x * x * x - 2.0, 0.0, 2.0, 0.0).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 4.0 * f64::EPSILON);
    }

    #[test]
    fn brent_rejects_a_bracket_without_sign_change() {
        assert!(brent(|x| x * x + 1.0, -1.0, 1.0, 0.0).is_none());
        assert!(brent(|_| f64::NAN, -1.0, 1.0, 0.0).is_none());
    }

    #[test]
    fn tanh_sinh_integrates_a_square_root_end_to_near_machine_precision() {
        let v = tanh_sinh(|x| (x - 1.0).sqrt() + x * x, 1.0, 2.0);
        let exact = 2.0 / 3.0 + 7.0 / 3.0;
        assert!((v - exact).abs() < 1e-13, "{v} {exact}");
        let back = tanh_sinh(|x| (x - 1.0).sqrt(), 2.0, 1.0);
        assert!((back + 2.0 / 3.0).abs() < 1e-13);
    }
}
