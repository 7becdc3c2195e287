//! The one error type for bad input: it names the parameter, the value given and what is allowed.

/// A parameter that is missing, out of range, or inconsistent with another.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ParamError {
    /// A numeric value outside its allowed range.
    #[error("parameter `{name}` = {value:e} is out of range: allowed {allowed}")]
    OutOfRange {
        /// The parameter's scene key.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range as text, with its unit.
        allowed: String,
    },
    /// A value the law needs that the scene does not give.
    #[error("parameter `{name}` is required: {why}")]
    Missing {
        /// The parameter's scene key.
        name: &'static str,
        /// Why the value is needed.
        why: String,
    },
    /// A string value that is not one of the known choices.
    #[error("parameter `{name}` = \"{value}\" is not known: allowed {allowed}")]
    UnknownChoice {
        /// The parameter's scene key.
        name: String,
        /// The name given.
        value: String,
        /// The known names, comma-separated.
        allowed: String,
    },
    /// Two or more values that are each valid but not together.
    #[error("parameter `{name}`: {why}")]
    Inconsistent {
        /// The parameter's scene key.
        name: &'static str,
        /// Which values conflict, and how.
        why: String,
    },
    /// A scene key that no parameter has (most often a typo).
    #[error("unknown scene key `{name}`{hint}")]
    UnknownKey {
        /// The key as given.
        name: String,
        /// Text appended to the message: the nearest known key, or where to find the list of keys.
        hint: String,
    },
    /// The scene file is not what it should be (not JSON, wrong type of a value).
    #[error("malformed scene: {what}")]
    Malformed {
        /// What is wrong, and where.
        what: String,
    },
}

impl ParamError {
    /// The parameter the error is about, if it names one.
    pub fn parameter(&self) -> Option<&str> {
        match self {
            ParamError::OutOfRange { name, .. } | ParamError::Missing { name, .. } | ParamError::Inconsistent { name, .. } => Some(name),
            ParamError::UnknownChoice { name, .. } | ParamError::UnknownKey { name, .. } => Some(name),
            ParamError::Malformed { .. } => None,
        }
    }
}

/// Checks `lo < value < hi` (open bounds) and finiteness.
pub fn check_open(name: &'static str, value: f64, lo: f64, hi: f64, unit: &str) -> Result<f64, ParamError> {
    if value.is_finite() && value > lo && value < hi {
        Ok(value)
    } else {
        Err(ParamError::OutOfRange { name, value, allowed: range_text(lo, hi, false, unit) })
    }
}

/// Checks `lo <= value < hi` and finiteness.
pub fn check_closed_low(name: &'static str, value: f64, lo: f64, hi: f64, unit: &str) -> Result<f64, ParamError> {
    if value.is_finite() && value >= lo && value < hi {
        Ok(value)
    } else {
        Err(ParamError::OutOfRange { name, value, allowed: range_text(lo, hi, true, unit) })
    }
}

/// Checks `lo < value <= hi` and finiteness.
pub fn check_open_closed(name: &'static str, value: f64, lo: f64, hi: f64, unit: &str) -> Result<f64, ParamError> {
    if value.is_finite() && value > lo && value <= hi {
        Ok(value)
    } else {
        Err(ParamError::OutOfRange { name, value, allowed: open_closed_text(lo, hi, unit) })
    }
}

/// `(lo, hi] unit`.
pub fn open_closed_text(lo: f64, hi: f64, unit: &str) -> String {
    let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
    format!("({}, {}]{unit}", bound(lo), bound(hi))
}

/// A finite, strictly positive value.
pub fn check_positive(name: &'static str, value: f64, unit: &str) -> Result<f64, ParamError> {
    check_open(name, value, 0.0, f64::INFINITY, unit)
}

/// A finite, non-negative value.
pub fn check_non_negative(name: &'static str, value: f64, unit: &str) -> Result<f64, ParamError> {
    check_closed_low(name, value, 0.0, f64::INFINITY, unit)
}

/// `[lo, hi) unit` or `(lo, hi) unit`, as the errors and the help print a range.
pub fn range_text(lo: f64, hi: f64, closed_low: bool, unit: &str) -> String {
    let left = if closed_low { "[" } else { "(" };
    let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
    format!("{left}{}, {}){unit}", bound(lo), bound(hi))
}

/// A range bound as a reader writes it: 0.5, 1000, 1e-9, 1e13, inf.
fn bound(x: f64) -> String {
    if x.is_infinite() {
        if x > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        }
    } else if x != 0.0 && (x.abs() < 1e-3 || x.abs() >= 1e6) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}
