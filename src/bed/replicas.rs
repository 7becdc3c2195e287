//! The same indentation test on several independently prepared beds: replicas. One bed's
//! plateau scatters from bed to bed by more than its own standard error says (a quarter of the seed's
//! die by about 12 % at the default speed, docs/indentation.md "What a 5 % interval costs"), and only
//! other beds measure that. Every bed sees the same indenter motion; the outputs are the means over the
//! beds, and the plateau hardness gets its standard error over the beds beside the runs' own.
//!
//! The beds step one after the other within each step, each on every engine thread, so the first bed
//! reads what it reads alone, to the bit. Stepping them side by side, each on its own share of the
//! threads, was tried and not kept: on this machine's two vCPUs the default test on two and three beds
//! took 214 and 342 s that way against 247 and 350 s one after the other (98 s for one bed; one run
//! each, 2026-12-03, `benches/indentation_over_beds.py`), no gain beyond the machine's noise, and the
//! first bed then reads another trajectory than alone.

use super::indentation::{yield_strength_error, Indentation, Reading, TestState};
use super::series::MeanEstimate;
use super::{replica_difference, BedError, BedScene};

/// The plateau hardness over the beds: the mean of their plateaus and its standard error from their
/// spread [Pa].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OverBeds {
    /// Mean of the beds' plateau hardnesses [Pa].
    pub mean: f64,
    /// The sample standard deviation of the beds' plateaus (0 for one bed).
    pub standard_deviation: f64,
    /// standard_deviation / sqrt(beds) (0 for one bed).
    pub standard_error: f64,
    /// Number of beds.
    pub beds: usize,
}

/// The beds' plateaus, summarized (`OverBeds`).
pub fn over_beds(plateaus: &[f64]) -> OverBeds {
    let n = plateaus.len();
    let mean = plateaus.iter().sum::<f64>() / n.max(1) as f64;
    let standard_deviation = if n < 2 { 0.0 } else { (plateaus.iter().map(|p| (p - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt() };
    OverBeds { mean, standard_deviation, standard_error: standard_deviation / (n.max(1) as f64).sqrt(), beds: n }
}

/// Refuses a replica bed that is not a fill of the first bed's scene (`replica_difference`): the message
/// names the key that differs. A mean over beds of two powders, two stresses or two dies measures
/// nothing.
pub fn check_replica(first: &BedScene, other: &BedScene) -> Result<(), String> {
    match replica_difference(first, other) {
        None => Ok(()),
        Some(key) => Err(format!(
            "it was prepared from another scene than replica 1: `{key}` differs; replicas are fills of one scene (prepared with other `seed`s only)"
        )),
    }
}

/// One reading from the beds' readings: every quantity the mean over the beds; the state the least
/// advanced bed's (the test is done when every bed has let go of the indenter); the contact depth from
/// a tangent only where every bed gave one; the plateau the mean of the beds' plateaus, with the runs'
/// own standard errors combined as independent (sqrt(sum se^2) / n) over all their samples.
pub fn mean_reading(readings: &[Reading]) -> Reading {
    let n = readings.len() as f64;
    let mean = |f: fn(&Reading) -> f64| readings.iter().map(f).sum::<f64>() / n;
    let plateau = combined_plateau(&readings.iter().map(|r| r.plateau).collect::<Vec<_>>());
    let state = least_advanced(readings.iter().map(|r| r.state));
    let unconfined_yield_strength = mean(|r| r.unconfined_yield_strength);
    Reading {
        force: mean(|r| r.force),
        depth: mean(|r| r.depth),
        dimensionless_depth: mean(|r| r.dimensionless_depth),
        projected_area: mean(|r| r.projected_area),
        hardness: mean(|r| r.hardness),
        hardness_standard_error: independent(readings.iter().map(|r| r.hardness_standard_error)),
        unconfined_yield_strength,
        // The hardness's part independent from bed to bed, C's common to every bed (the same material).
        unconfined_yield_strength_standard_error: yield_strength_error(
            independent(readings.iter().map(|r| r.hardness_standard_error / r.constraint_factor)),
            unconfined_yield_strength,
            mean(|r| r.constraint_factor_standard_error / r.constraint_factor),
        ),
        constraint_factor: mean(|r| r.constraint_factor),
        constraint_factor_standard_error: mean(|r| r.constraint_factor_standard_error),
        hydrostatic_stress: mean(|r| r.hydrostatic_stress),
        deviatoric_stress: mean(|r| r.deviatoric_stress),
        window_hydrostatic_stress: combined_plateau(&readings.iter().map(|r| r.window_hydrostatic_stress).collect::<Vec<_>>()),
        window_deviatoric_stress: combined_plateau(&readings.iter().map(|r| r.window_deviatoric_stress).collect::<Vec<_>>()),
        contacts: (readings.iter().map(|r| r.contacts).sum::<usize>() as f64 / n).round() as usize,
        kinetic_energy: mean(|r| r.kinetic_energy),
        state,
        contact_depth: mean(|r| r.contact_depth),
        contact_depth_from_tangent: readings.iter().all(|r| r.contact_depth_from_tangent),
        turn_force: mean(|r| r.turn_force),
        plateau,
        depth_origin_offset: mean(|r| r.depth_origin_offset),
    }
}

/// The standard error of the mean of n independent readings from their own: sqrt(sum se^2) / n.
pub fn independent(errors: impl ExactSizeIterator<Item = f64>) -> f64 {
    let n = errors.len() as f64;
    errors.map(|e| e * e).sum::<f64>().sqrt() / n
}

/// The beds' plateaus as one estimate: the mean of their means, their own standard errors combined as
/// independent (`independent`), all their samples, their mean correlation time.
pub fn combined_plateau(plateaus: &[MeanEstimate]) -> MeanEstimate {
    let n = plateaus.len() as f64;
    MeanEstimate {
        mean: plateaus.iter().map(|p| p.mean).sum::<f64>() / n,
        standard_error: independent(plateaus.iter().map(|p| p.standard_error)),
        samples: plateaus.iter().map(|p| p.samples).sum(),
        correlation_time: plateaus.iter().map(|p| p.correlation_time).sum::<f64>() / n,
    }
}

/// The state of the least advanced bed.
fn least_advanced(states: impl Iterator<Item = TestState>) -> TestState {
    states.min().unwrap_or(TestState::Loading)
}

/// The test on each bed.
pub struct Replicas {
    /// One indentation test per bed, the first the reference bed.
    pub tests: Vec<Indentation>,
}

impl Replicas {
    /// At least one test; every test the same set-up.
    pub fn new(tests: Vec<Indentation>) -> Replicas {
        assert!(!tests.is_empty(), "replicas need a bed");
        Replicas { tests }
    }

    /// The first bed's test (the set-up, the record's state changes, the events).
    pub fn first(&self) -> &Indentation {
        &self.tests[0]
    }

    /// Advances every bed by `h` seconds (`Indentation::advance`). The inputs are checked on every bed
    /// before any moves, so a refused step leaves them all as they were.
    pub fn advance(&mut self, h: f64, input: Option<(f64, f64)>) -> Result<(), BedError> {
        for t in &self.tests {
            t.input_target(h, input)?;
        }
        let beds = self.tests.len();
        self.tests.iter_mut().enumerate().try_for_each(|(k, t)| {
            t.advance(h, input).map_err(|e| match e {
                BedError::Setup(why) if beds > 1 => BedError::Setup(format!("replica {}: {why}", k + 1)),
                other => other,
            })
        })
    }

    /// How many beds.
    pub fn len(&self) -> usize {
        self.tests.len()
    }

    /// Never: there is at least one bed.
    pub fn is_empty(&self) -> bool {
        self.tests.is_empty()
    }

    /// The test's state: the least advanced bed's.
    pub fn state(&self) -> TestState {
        least_advanced(self.tests.iter().map(|t| t.record.state))
    }

    /// The mean over the beds of `f`.
    pub fn mean_of(&self, f: impl Fn(&Indentation) -> f64) -> f64 {
        self.tests.iter().map(f).sum::<f64>() / self.tests.len() as f64
    }

    /// The plateau hardness so far, the beds' combined (`combined_plateau`; one bed's own).
    pub fn plateau(&mut self) -> MeanEstimate {
        let mut p = self.plateaus();
        if p.len() == 1 {
            return p.remove(0);
        }
        combined_plateau(&p)
    }

    /// The beds' mean reading (`mean_reading`).
    pub fn reading(&mut self) -> Reading {
        let mut readings: Vec<Reading> = self.tests.iter_mut().map(Indentation::reading).collect();
        // One bed's reading is its own, to the bit.
        if readings.len() == 1 {
            return readings.remove(0);
        }
        mean_reading(&readings)
    }

    /// Each bed's plateau hardness so far [Pa].
    pub fn plateaus(&mut self) -> Vec<MeanEstimate> {
        self.tests.iter_mut().map(Indentation::plateau).collect()
    }

    /// The plateau hardness over the beds (`over_beds`).
    pub fn plateau_over_beds(&mut self) -> OverBeds {
        over_beds(&self.plateaus().iter().map(|p| p.mean).collect::<Vec<_>>())
    }

    /// Every bed's state (`Indentation::save`), in order.
    pub fn save(&self) -> Result<Vec<u8>, BedError> {
        let states: Vec<Vec<u8>> = self.tests.iter().map(Indentation::save).collect::<Result<_, _>>()?;
        crate::codec::to_bytes(&states).map_err(|e| BedError::Setup(format!("the replicas' states cannot be saved: {e}")))
    }

    /// Reads back what `save` wrote, each bed with `threads` engine threads.
    pub fn restore(bytes: &[u8], threads: usize) -> Result<Replicas, BedError> {
        let states: Vec<Vec<u8>> = crate::codec::from_bytes(bytes).map_err(|e| BedError::Setup(format!("the saved replicas cannot be read: {e}")))?;
        if states.is_empty() {
            return Err(BedError::Setup("the saved replicas hold no bed".into()));
        }
        let tests = states.iter().map(|b| Indentation::restore(b, Some(threads))).collect::<Result<Vec<_>, _>>()?;
        Ok(Replicas { tests })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spread_over_beds_is_the_sample_standard_deviation() {
        let o = over_beds(&[7000.0, 8000.0, 9000.0]);
        assert_eq!(o.mean, 8000.0);
        assert!((o.standard_deviation - 1000.0).abs() < 1e-9);
        assert!((o.standard_error - 1000.0 / 3f64.sqrt()).abs() < 1e-9);
        let one = over_beds(&[7000.0]);
        assert_eq!((one.mean, one.standard_deviation, one.standard_error, one.beds), (7000.0, 0.0, 0.0, 1));
    }

    fn reading(force: f64, state: TestState, tangent: bool, plateau: (f64, f64, usize)) -> Reading {
        Reading {
            force,
            depth: 1e-3,
            dimensionless_depth: 0.125,
            projected_area: 4e-5,
            hardness: force / 4e-5,
            hardness_standard_error: force / 4e-6,
            unconfined_yield_strength: force / 4e-5 / 3.0,
            unconfined_yield_strength_standard_error: force / 4e-6 / 3.0,
            constraint_factor: 3.0,
            constraint_factor_standard_error: 0.0,
            hydrostatic_stress: 2.0 * force,
            deviatoric_stress: force,
            window_hydrostatic_stress: MeanEstimate { mean: 2.0 * plateau.0, standard_error: plateau.1, samples: plateau.2, correlation_time: 10.0 },
            window_deviatoric_stress: MeanEstimate { mean: plateau.0, standard_error: plateau.1, samples: plateau.2, correlation_time: 10.0 },
            contacts: 3,
            kinetic_energy: 1e-9,
            state,
            contact_depth: 1e-3,
            contact_depth_from_tangent: tangent,
            turn_force: force,
            plateau: MeanEstimate { mean: plateau.0, standard_error: plateau.1, samples: plateau.2, correlation_time: 10.0 },
            depth_origin_offset: 0.0,
        }
    }

    #[test]
    fn the_mean_reading_averages_and_waits_for_the_slowest_bed() {
        let a = reading(0.2, TestState::Done, true, (7000.0, 300.0, 100));
        let b = reading(0.4, TestState::Unloading, false, (9000.0, 400.0, 120));
        let m = mean_reading(&[a, b]);
        assert!((m.force - 0.3).abs() < 1e-15);
        assert!((m.hardness - 0.3 / 4e-5).abs() < 1e-9);
        assert_eq!(m.state, TestState::Unloading, "done only when every bed is");
        assert!(!m.contact_depth_from_tangent, "from a tangent only where every bed gave one");
        assert_eq!(m.plateau.mean, 8000.0);
        assert!((m.plateau.standard_error - 250.0).abs() < 1e-9, "sqrt(300^2 + 400^2) / 2");
        // Each bed's hardness error 0.2 / 4e-6 = 5e4 and 1e5 Pa: sqrt(5e4^2 + 1e5^2) / 2.
        let both = (5e4f64.powi(2) + 1e5f64.powi(2)).sqrt() / 2.0;
        assert!((m.hardness_standard_error / both - 1.0).abs() < 1e-12, "{}", m.hardness_standard_error);
        assert!((m.unconfined_yield_strength_standard_error / (both / 3.0) - 1.0).abs() < 1e-12);
        assert_eq!(m.plateau.samples, 220);
        // The window's bin stresses are combined as the plateau is (2 x and 1 x the plateau in `reading`).
        assert_eq!((m.window_hydrostatic_stress.mean, m.window_deviatoric_stress.mean), (16000.0, 8000.0));
        assert!((m.window_hydrostatic_stress.standard_error - 250.0).abs() < 1e-9 && m.window_deviatoric_stress.samples == 220);
        assert_eq!(m.contacts, 3);
        let alone = mean_reading(&[a]);
        assert_eq!(alone, a, "one bed's reading is its own");
    }

    #[test]
    fn a_measured_constraint_factors_error_is_common_to_the_beds_and_does_not_average_down() {
        // C = 6 +- 0.6 (10 %) on both beds; their hardness errors 5e4 and 1e5 Pa as above.
        let with_c = |r: Reading| {
            let (c, e) = (6.0, 0.6);
            let s = r.hardness / c;
            Reading {
                unconfined_yield_strength: s,
                unconfined_yield_strength_standard_error: yield_strength_error(r.hardness_standard_error / c, s, e / c),
                constraint_factor: c,
                constraint_factor_standard_error: e,
                ..r
            }
        };
        let (a, b) =
            (with_c(reading(0.2, TestState::Done, true, (7000.0, 300.0, 100))), with_c(reading(0.4, TestState::Done, true, (9000.0, 400.0, 120))));
        let m = mean_reading(&[a, b]);
        let from_hardness = (5e4f64.powi(2) + 1e5f64.powi(2)).sqrt() / 2.0 / 6.0;
        let s = 0.3 / 4e-5 / 6.0;
        assert!((m.unconfined_yield_strength - s).abs() < 1e-9);
        let expected = (from_hardness.powi(2) + (0.1 * s).powi(2)).sqrt();
        assert!(
            (m.unconfined_yield_strength_standard_error / expected - 1.0).abs() < 1e-12,
            "{} {expected}",
            m.unconfined_yield_strength_standard_error
        );
        assert_eq!((m.constraint_factor, m.constraint_factor_standard_error), (6.0, 0.6));
        // One bed: its own error, the hardness's and C's in quadrature.
        assert_eq!(mean_reading(&[a]), a);
        let own = ((5e4f64 / 6.0).powi(2) + (0.2f64 / 4e-5 / 6.0 * 0.1).powi(2)).sqrt();
        assert!((a.unconfined_yield_strength_standard_error / own - 1.0).abs() < 1e-12);
    }
}
