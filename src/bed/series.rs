//! The mean of an autocorrelated series of one run's readings, with its standard error.
//!
//! The force on an indenter fluctuates as the bed rearranges, and successive samples are correlated
//! over many samples: the naive sigma / sqrt(n) would understate the error of their mean by the square
//! root of the correlation time. The error here uses the integrated autocorrelation time tau of the
//! deviations from the mean:
//!
//!   var(mean) = sigma^2 tau / n,   tau = 1 + 2 sum_{t=1..W} rho(t),
//!
//! with rho the residuals' normalised autocorrelation and the window W chosen by Sokal's rule, the
//! smallest W with W >= C_WINDOW tau(W) (A. D. Sokal, "Monte Carlo methods in statistical mechanics",
//! 1997, Sec. 3; the estimator emcee and most molecular-dynamics analysis use). Tested on autoregressive
//! series of known variance of the mean (the tests below).
//!
//! A trend within the series counts as fluctuation: in one run a slow wander of the force cannot be told
//! from a change of the mean curve, and over the recorded runs of docs/data the hardness's trend across
//! the plateau window ranged from -49 % to +43 %, of either sign: mostly wander. (Taken about a
//! least-squares line instead, one run's error fell from 514 to 64 Pa.)

/// Sokal's window factor: W >= 5 tau keeps the window's bias below e^-5 for an exponential correlation.
const C_WINDOW: f64 = 5.0;
/// Below this many samples per correlation time the estimate of tau is itself unreliable (Sokal; emcee
/// warns below 50).
pub const RELIABLE_SAMPLES_PER_TAU: f64 = 50.0;

/// The mean of a series and its standard error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeanEstimate {
    /// Mean of the series [the series' unit].
    pub mean: f64,
    /// sqrt(sigma^2 tau / n) [the series' unit]; 0 for fewer than `MIN_SAMPLES` samples.
    pub standard_error: f64,
    /// Number of samples in the series.
    pub samples: usize,
    /// The integrated autocorrelation time tau of the residuals [samples]; 0 when not estimated.
    pub correlation_time: f64,
}

impl MeanEstimate {
    /// Whether the series holds at least `RELIABLE_SAMPLES_PER_TAU` correlation times.
    pub fn reliable(&self) -> bool {
        self.correlation_time > 0.0 && self.samples as f64 >= RELIABLE_SAMPLES_PER_TAU * self.correlation_time
    }
}

/// Fewer samples than this give the mean alone.
pub const MIN_SAMPLES: usize = 8;

/// The largest mean of `value` over `w` consecutive items, as (first item, mean): the peak of a test's
/// curve read over a window (the uniaxial test's sigma_c, the shear cell's tau_peak). None when fewer
/// than `w` items.
pub fn largest_window_mean<T>(items: &[T], w: usize, value: impl Fn(&T) -> f64) -> Option<(usize, f64)> {
    if items.len() < w {
        return None;
    }
    let mut sum: f64 = items[..w].iter().map(&value).sum();
    let mut best = (0, sum / w as f64);
    for i in 1..=items.len() - w {
        sum += value(&items[i + w - 1]) - value(&items[i - 1]);
        if sum / w as f64 > best.1 {
            best = (i, sum / w as f64);
        }
    }
    Some(best)
}

/// Whether the curve has softened: a positive window peak followed by at least one whole window, and the
/// last window's mean below `fraction` of the peak.
pub fn has_softened<T>(items: &[T], w: usize, value: impl Fn(&T) -> f64, fraction: f64) -> bool {
    let Some((i, peak)) = largest_window_mean(items, w, &value) else { return false };
    if peak <= 0.0 || items.len() < i + 2 * w {
        return false;
    }
    let last = items[items.len() - w..].iter().map(&value).sum::<f64>() / w as f64;
    last < fraction * peak
}

/// The mean of `values` (in the order taken) and its standard error (module docs).
pub fn mean_with_error(values: &[f64]) -> MeanEstimate {
    let n = values.len();
    let mean = if n == 0 { 0.0 } else { values.iter().sum::<f64>() / n as f64 };
    let none = MeanEstimate { mean, standard_error: 0.0, samples: n, correlation_time: 0.0 };
    if n < MIN_SAMPLES {
        return none;
    }
    let r: Vec<f64> = values.iter().map(|v| v - mean).collect();
    let c0 = r.iter().map(|v| v * v).sum::<f64>() / n as f64;
    if !(c0 > 0.0) {
        return MeanEstimate { correlation_time: 1.0, ..none };
    }
    let (mut tau, mut window) = (1.0, 0usize);
    for w in 1..n / 2 {
        let ct = r[..n - w].iter().zip(&r[w..]).map(|(a, b)| a * b).sum::<f64>() / n as f64;
        tau += 2.0 * ct / c0;
        window = w;
        if w as f64 >= C_WINDOW * tau {
            break;
        }
    }
    // Deviations from the sample mean miss the mean's own wander, var(mean) = sigma^2 tau / n, at every
    // lag: the 2W + 1 lags summed give tau (1 - (2W + 1) / n). Put back (at most four times: a series
    // that short is flagged by `reliable`). Without it the error of a series of 900 samples with tau =
    // 60 read 1.30 times too small on autoregressive series; with it, 0.86 (the tests below).
    let tau = tau / (1.0 - (2 * window + 1) as f64 / n as f64).max(0.25);
    // An anti-correlated series would give tau < 1: kept at 1 (the error of independent samples).
    let tau = tau.max(1.0);
    let sigma2 = c0 * n as f64 / (n - 1) as f64;
    MeanEstimate { mean, standard_error: (sigma2 * tau / n as f64).sqrt(), samples: n, correlation_time: tau }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bed::random::Random;

    fn normal(rng: &mut Random) -> f64 {
        // Box-Muller.
        let (u, v) = (1.0 - rng.uniform(), rng.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }

    /// x_k = phi x_{k-1} + e_k with unit e, started in its stationary state: var = 1 / (1 - phi^2),
    /// tau = (1 + phi) / (1 - phi).
    fn ar1(rng: &mut Random, n: usize, phi: f64) -> Vec<f64> {
        let mut x = normal(rng) / (1.0 - phi * phi).sqrt();
        (0..n)
            .map(|_| {
                x = phi * x + normal(rng);
                x
            })
            .collect()
    }

    /// Over many autoregressive series the estimated error matches the spread of their means, and about
    /// 95 % of the intervals mean +- 1.96 SE hold the true mean (0).
    fn check_ar1(phi: f64, n: usize, series: usize, seed: u64) {
        let mut rng = Random::new(seed);
        let (mut se2, mut m2, mut covered, mut tau) = (0.0, 0.0, 0, 0.0);
        for _ in 0..series {
            let x = ar1(&mut rng, n, phi);
            let e = mean_with_error(&x);
            se2 += e.standard_error * e.standard_error / series as f64;
            m2 += e.mean * e.mean / series as f64;
            tau += e.correlation_time / series as f64;
            covered += usize::from(e.mean.abs() < 1.96 * e.standard_error);
        }
        let true_tau = (1.0 + phi) / (1.0 - phi);
        let true_var = true_tau / (1.0 - phi * phi) / n as f64;
        let coverage = covered as f64 / series as f64;
        // The spread of 400 means is known to +-7 % (one sigma of a variance from 400 samples).
        assert!((se2 / true_var - 1.0).abs() < 0.15, "phi {phi}: mean SE^2 {se2:.4e} against var(mean) {true_var:.4e}");
        assert!((m2 / true_var - 1.0).abs() < 0.25, "phi {phi}: spread of the means {m2:.4e} against {true_var:.4e}");
        assert!((tau / true_tau - 1.0).abs() < 0.15, "phi {phi}: tau {tau:.2} against {true_tau:.2}");
        assert!((0.90..=0.99).contains(&coverage), "phi {phi}: coverage {coverage}");
    }

    #[test]
    fn independent_samples_give_sigma_over_root_n() {
        check_ar1(0.0, 1000, 400, 1);
    }

    #[test]
    fn correlated_samples_give_the_error_of_their_correlation_time() {
        // tau = 9 and 19 samples: sigma / sqrt(n) would understate the error 3 and 4.4 times.
        check_ar1(0.8, 2000, 400, 2);
        check_ar1(0.9, 4000, 400, 3);
    }

    #[test]
    fn a_short_series_of_long_correlation_is_not_read_too_precise() {
        // 896 samples (the default test's window) with tau = 59: 15 correlation times. Over many series
        // the estimated error is not below the spread of the means (uncorrected it read 1.3 times too
        // small), at most 1.3 times above it, and most intervals hold the true mean.
        let (n, phi, series) = (896, 0.9672, 400);
        let mut rng = Random::new(5);
        let (mut se2, mut m2, mut covered, mut flagged) = (0.0, 0.0, 0, 0);
        for _ in 0..series {
            let e = mean_with_error(&ar1(&mut rng, n, phi));
            se2 += e.standard_error * e.standard_error / series as f64;
            m2 += e.mean * e.mean / series as f64;
            covered += usize::from(e.mean.abs() < 1.96 * e.standard_error);
            flagged += usize::from(!e.reliable());
        }
        assert!(flagged as f64 >= 0.9 * series as f64, "{flagged} of {series} flagged as under 50 correlation times");
        let ratio = (m2 / se2).sqrt();
        assert!((0.7..=1.05).contains(&ratio), "spread of the means / estimated error = {ratio}");
        assert!(covered as f64 / series as f64 >= 0.85, "coverage {covered} of {series}");
    }

    #[test]
    fn a_trend_counts_as_a_slow_fluctuation() {
        // White noise of unit variance, and the same with a line across it: the line widens the error.
        let mut rng = Random::new(4);
        let noise: Vec<f64> = (0..2000).map(|_| normal(&mut rng)).collect();
        let white = mean_with_error(&noise);
        assert!((white.standard_error * (2000f64).sqrt() - 1.0).abs() < 0.1, "{white:?}");
        let sloped: Vec<f64> = noise.iter().enumerate().map(|(k, v)| v + 0.002 * k as f64).collect();
        let trend = mean_with_error(&sloped);
        assert!(trend.standard_error > 3.0 * white.standard_error && trend.correlation_time > 10.0, "{trend:?}");
    }

    #[test]
    fn too_few_samples_give_the_mean_alone() {
        let e = mean_with_error(&[1.0, 3.0, 2.0]);
        assert_eq!((e.mean, e.standard_error, e.samples), (2.0, 0.0, 3));
        assert!(!e.reliable());
        assert_eq!(mean_with_error(&[]).mean, 0.0);
    }
}
