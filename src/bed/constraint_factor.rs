//! The constraint factor C = H / sigma_c (`004` Eq. 2.10) of the `004` Ch. 6 material, measured against
//! the consolidation stress sigma_1: H the hardness of BallIndentation's default test on a quarter bed
//! consolidated to sigma_1, sigma_c the unconfined yield strength of UnconfinedCompression's default test
//! on a specimen of the same material consolidated to sigma_1 (`docs/data/constraint_factor_ch6_seed_window.csv`,
//! BallIndentation's default read over the seed's window; how it was measured in
//! docs/units/UnconfinedCompression.md). BallIndentation divides by it with
//! `constraint_factor_source = measured`.
//!
//! Between the measured stresses C is interpolated linearly in ln sigma_1; outside them it is refused (no
//! extrapolation). Its standard error is the table's, which holds the fill-to-fill scatter of both tests
//! (three fills at 10 kPa).

use std::sync::OnceLock;

/// The measurements, as committed.
const TABLE: &str = include_str!("../../docs/data/constraint_factor_ch6_seed_window.csv");

/// One measured stress.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// sigma_1 [Pa].
    pub consolidation_stress: f64,
    /// C [-].
    pub constraint_factor: f64,
    /// The standard error of C [-].
    pub standard_error: f64,
}

/// The table's points by increasing stress.
pub fn points() -> &'static [Point] {
    static POINTS: OnceLock<Vec<Point>> = OnceLock::new();
    POINTS.get_or_init(|| parse(TABLE).expect("docs/data/constraint_factor_ch6_seed_window.csv is well formed (tested)"))
}

/// The points of a table (comment lines start with '#'; the header names the columns).
pub fn parse(text: &str) -> Result<Vec<Point>, String> {
    let mut lines = text.lines().filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let header: Vec<&str> = lines.next().ok_or("no header")?.split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).ok_or(format!("no column {name}"));
    let (s, c, e) = (column("consolidation_stress_Pa")?, column("constraint_factor")?, column("constraint_factor_standard_error")?);
    let mut points = Vec::new();
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        let number = |k: usize| cells.get(k).and_then(|x| x.trim().parse::<f64>().ok()).ok_or(format!("not a number in column {k}: {line}"));
        points.push(Point { consolidation_stress: number(s)?, constraint_factor: number(c)?, standard_error: number(e)? });
    }
    if points.len() < 2 || points.windows(2).any(|w| w[1].consolidation_stress <= w[0].consolidation_stress) {
        return Err("at least two points, by increasing consolidation stress".into());
    }
    Ok(points)
}

/// C and its standard error at sigma_1 [Pa], interpolated in ln sigma_1 between the measured stresses;
/// refused outside them.
pub fn at(points: &[Point], sigma_1: f64) -> Result<(f64, f64), String> {
    let (first, last) = (points[0].consolidation_stress, points[points.len() - 1].consolidation_stress);
    if !(sigma_1 >= first && sigma_1 <= last) {
        return Err(format!("the constraint factor was measured for consolidation stresses {first:e} to {last:e} Pa, not {sigma_1:e} Pa"));
    }
    let k = points.partition_point(|p| p.consolidation_stress < sigma_1).max(1);
    let (a, b) = (points[k - 1], points[k]);
    let t = (sigma_1.ln() - a.consolidation_stress.ln()) / (b.consolidation_stress.ln() - a.consolidation_stress.ln());
    let lerp = |x: f64, y: f64| x + t * (y - x);
    Ok((lerp(a.constraint_factor, b.constraint_factor), lerp(a.standard_error, b.standard_error)))
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO: &str = "# a comment\nconsolidation_stress_Pa,x,constraint_factor,constraint_factor_standard_error\n1000,0,4,0.4\n10000,0,8,0.2\n";

    #[test]
    fn interpolates_in_the_log_of_the_stress_and_refuses_outside() {
        let p = parse(TWO).unwrap();
        assert_eq!(at(&p, 1000.0).unwrap(), (4.0, 0.4));
        assert_eq!(at(&p, 10000.0).unwrap(), (8.0, 0.2));
        // sqrt(1000 * 10000) is half-way in ln sigma_1.
        let (c, e) = at(&p, 1e3 * 10f64.sqrt()).unwrap();
        assert!((c - 6.0).abs() < 1e-12 && (e - 0.3).abs() < 1e-12, "{c} {e}");
        for outside in [999.0, 10001.0, f64::NAN] {
            let e = at(&p, outside).unwrap_err();
            assert!(e.contains("1e3 to 1e4 Pa"), "{e}");
        }
    }

    #[test]
    fn a_malformed_table_is_refused() {
        assert!(parse("consolidation_stress_Pa,constraint_factor\n1,2\n").unwrap_err().contains("constraint_factor_standard_error"));
        assert!(parse("consolidation_stress_Pa,constraint_factor,constraint_factor_standard_error\n2,1,0\n1,1,0\n").is_err());
    }

    #[test]
    fn the_committed_table_was_read_over_the_window_of_the_units_default() {
        // C belongs to the test that measured H: the table must name the window BallIndentation reads
        // by default, so changing the default without measuring C again fails here.
        let (a, b) = crate::bed::indentation::SEED_WINDOW;
        let named = format!("plateau_hardness over h/r {a}-{b})");
        assert!(TABLE.lines().take_while(|l| l.starts_with('#')).any(|l| l.contains(&named)), "the table's comment does not name {named}");
    }

    #[test]
    fn the_committed_table_covers_1_to_20_kpa_with_positive_factors() {
        let p = points();
        assert_eq!((p[0].consolidation_stress, p[p.len() - 1].consolidation_stress), (1e3, 2e4));
        assert!(p.iter().all(|p| p.constraint_factor > 0.0 && p.standard_error > 0.0), "{p:?}");
    }
}
