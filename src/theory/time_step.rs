//! Time steps (`000` Sec. 3.5, Eqs. 68-72; `004` Eq. 4.29).

use std::f64::consts::PI;

/// Critical step of a mass on a spring, 2 sqrt(m / k) (000 Eq. 68) [s].
pub fn critical_time_step(mass: f64, stiffness: f64) -> f64 {
    2.0 * (mass / stiffness).sqrt()
}

/// 000 Eq. 70: the critical step with k_e bounded by the Hertz stiffness at alpha_max [s].
pub fn critical_time_step_hertz(radius: f64, density: f64, youngs_modulus: f64, overlap_ratio: f64) -> f64 {
    PI * radius * (density / youngs_modulus).sqrt() * (8.0 / (3.0 * PI)).sqrt() * overlap_ratio.powf(-0.25)
}

/// Rayleigh time step pi R / (0.1631 nu + 0.8766) sqrt(rho / G) (000 Eq. 71) [s].
pub fn rayleigh_time_step(radius: f64, density: f64, shear_modulus: f64, poisson_ratio: f64) -> f64 {
    PI * radius / (0.1631 * poisson_ratio + 0.8766) * (density / shear_modulus).sqrt()
}

/// Delta T_crit / Delta T_R of 000 Eq. 72.
pub fn critical_to_rayleigh_ratio(poisson_ratio: f64, overlap_ratio: f64) -> f64 {
    (0.1631 * poisson_ratio + 0.8766) / (1.0 + poisson_ratio).sqrt() * (4.0 / (3.0 * PI)).sqrt() * overlap_ratio.powf(-0.25)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eq_72_is_the_ratio_of_eqs_70_and_71() {
        let (r, rho, e, nu) = (1e-3, 2500.0, 63e6, 0.25);
        let g = e / (2.0 * (1.0 + nu));
        for ratio in [0.001, 0.01, 0.1] {
            let direct = critical_time_step_hertz(r, rho, e, ratio) / rayleigh_time_step(r, rho, g, nu);
            assert!((direct / critical_to_rayleigh_ratio(nu, ratio) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn fig_8_ratio_is_0_9_to_1_at_a_tenth_of_the_radius() {
        // 000 Sec. 3.5: for 0.2 <= nu <= 0.4 the ratio is 0.9-1.0 at alpha_max/R = 0.1.
        for nu in [0.2, 0.3, 0.4] {
            let q = critical_to_rayleigh_ratio(nu, 0.1);
            assert!((0.88..=1.0).contains(&q), "nu {nu}: {q}");
        }
    }
}
