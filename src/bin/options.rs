//! Value checks of the command line: each names the allowed range and its unit; clap adds the option's
//! name (`invalid value '-2' for '--velocity <M_PER_S>': ...`).

/// A finite number [unit].
pub fn finite(unit: &'static str) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |text| match text.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("give a finite number in {unit}")),
    }
}

/// A finite number > 0 [unit].
pub fn positive(unit: &'static str) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    in_range(0.0, f64::INFINITY, false, unit)
}

/// A number in (lo, hi), or [lo, hi) with `closed_low` [unit]; `inf` is allowed when hi is infinite.
pub fn in_range(lo: f64, hi: f64, closed_low: bool, unit: &'static str) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |text| {
        let allowed = powderfmu::error::range_text(lo, hi, closed_low, unit);
        match text.parse::<f64>() {
            Ok(v) if (v > lo || (closed_low && v == lo)) && (v < hi || (v.is_infinite() && hi.is_infinite())) => Ok(v),
            _ => Err(format!("allowed {allowed}")),
        }
    }
}
