//! The particle size distribution of `004` Table 5.1: nine diameter classes around a 1 mm mean, by number.
//! Each class is one species of the bed, so each pair of classes has its own contact parameters
//! (R* and m* differ). `scale` multiplies every diameter (a bed of larger or smaller beads with the same
//! shape of distribution).

use crate::error::ParamError;

/// 004 Table 5.1: diameter [mm] and number frequency [%].
pub const TABLE_5_1: [(f64, f64); 9] =
    [(0.59, 0.33), (0.72, 3.84), (0.81, 11.24), (0.90, 21.00), (1.00, 27.75), (1.10, 20.85), (1.19, 10.95), (1.28, 3.74), (1.41, 0.29)];

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SizeDistribution {
    /// Class diameters [m].
    pub diameters: Vec<f64>,
    /// Number fractions, summing to 1.
    pub fractions: Vec<f64>,
}

impl SizeDistribution {
    /// Table 5.1 with every diameter multiplied by `scale`.
    pub fn table_5_1(scale: f64) -> SizeDistribution {
        let total: f64 = TABLE_5_1.iter().map(|c| c.1).sum();
        SizeDistribution {
            diameters: TABLE_5_1.iter().map(|c| c.0 * 1e-3 * scale).collect(),
            fractions: TABLE_5_1.iter().map(|c| c.1 / total).collect(),
        }
    }

    /// A distribution given by the user: diameters [m] and relative frequencies (normalized here).
    pub fn new(diameters: Vec<f64>, frequencies: Vec<f64>) -> Result<SizeDistribution, ParamError> {
        if diameters.is_empty() || diameters.len() != frequencies.len() || diameters.len() > 64 {
            return Err(ParamError::Inconsistent {
                name: "size_distribution",
                why: format!("give 1 to 64 diameters [m] and as many frequencies; got {} and {}", diameters.len(), frequencies.len()),
            });
        }
        for &d in &diameters {
            crate::error::check_open("size_distribution.diameters", d, 1e-9, 1.0, "m")?;
        }
        for &f in &frequencies {
            if !(f.is_finite() && f >= 0.0) {
                return Err(ParamError::OutOfRange { name: "size_distribution.frequencies", value: f, allowed: "[0, inf)".into() });
            }
        }
        let total: f64 = frequencies.iter().sum();
        if !(total > 0.0) {
            return Err(ParamError::Inconsistent { name: "size_distribution.frequencies", why: "at least one frequency must be positive".into() });
        }
        Ok(SizeDistribution { diameters, fractions: frequencies.iter().map(|f| f / total).collect() })
    }

    /// Number-mean diameter [m].
    pub fn mean_diameter(&self) -> f64 {
        self.diameters.iter().zip(&self.fractions).map(|(d, f)| d * f).sum()
    }

    pub fn max_diameter(&self) -> f64 {
        self.diameters.iter().cloned().fold(0.0, f64::max)
    }

    pub fn min_diameter(&self) -> f64 {
        self.diameters.iter().cloned().fold(f64::INFINITY, f64::min)
    }

    /// How many spheres of each class a bed of `count` gets: the fractions rounded by largest remainder,
    /// so the counts add up to `count` and follow the table as closely as whole numbers can.
    pub fn class_counts(&self, count: usize) -> Vec<usize> {
        let exact: Vec<f64> = self.fractions.iter().map(|f| f * count as f64).collect();
        let mut counts: Vec<usize> = exact.iter().map(|x| x.floor() as usize).collect();
        let mut rest = count - counts.iter().sum::<usize>();
        let mut order: Vec<usize> = (0..exact.len()).collect();
        order.sort_by(|&a, &b| (exact[b] - exact[b].floor()).total_cmp(&(exact[a] - exact[a].floor())).then(a.cmp(&b)));
        for &k in order.iter().cycle() {
            if rest == 0 {
                break;
            }
            counts[k] += 1;
            rest -= 1;
        }
        counts
    }

    /// Total solid volume of a bed of `count` spheres with `class_counts` [m^3].
    pub fn solid_volume(&self, count: usize) -> f64 {
        self.class_counts(count).iter().zip(&self.diameters).map(|(&n, d)| n as f64 * std::f64::consts::PI / 6.0 * d.powi(3)).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_5_1_has_a_1_mm_mean() {
        let d = SizeDistribution::table_5_1(1.0);
        assert!((d.mean_diameter() - 1.0e-3).abs() < 0.01e-3, "{}", d.mean_diameter());
        assert_eq!(d.class_counts(16000).iter().sum::<usize>(), 16000);
        // 27.75 % of 16000 in the 1 mm class.
        assert_eq!(d.class_counts(16000)[4], 4440);
    }

    #[test]
    fn bad_distributions_are_refused_by_name() {
        let e = SizeDistribution::new(vec![1e-3], vec![]).unwrap_err();
        assert!(e.to_string().contains("size_distribution"));
        let e = SizeDistribution::new(vec![-1e-3], vec![1.0]).unwrap_err();
        assert!(e.to_string().contains("size_distribution.diameters"));
    }
}
