//! Error types: every error carries the context a user needs to act on it.

use std::sync::Arc;

/// An I/O error kept in errors that are cloned and compared (a sweep's
/// failed runs, kept with its results): clones share the error, and two
/// are equal when they have the same kind and say the same.
#[derive(Debug, Clone)]
pub struct IoError(Arc<std::io::Error>);

impl IoError {
    /// The error's kind (`NotFound`, `InvalidData`, ...).
    pub fn kind(&self) -> std::io::ErrorKind {
        self.0.kind()
    }
    /// The I/O error itself.
    pub fn get(&self) -> &std::io::Error {
        &self.0
    }
}

impl From<std::io::Error> for IoError {
    fn from(e: std::io::Error) -> Self {
        IoError(Arc::new(e))
    }
}

impl PartialEq for IoError {
    fn eq(&self, other: &Self) -> bool {
        self.kind() == other.kind() && self.0.to_string() == other.0.to_string()
    }
}

impl std::fmt::Display for IoError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl std::error::Error for IoError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.0.source()
    }
}

/// One invalid value in a scene: which field, what it was, what was expected.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// Path of the field in the scene, e.g. `tyre.modes[2].damping_ratio`.
    pub field: String,
    /// The offending value, as the user wrote it (formatted).
    pub value: String,
    /// What would have been accepted.
    pub expected: String,
}

impl std::fmt::Display for FieldError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} = {}: expected {}",
            self.field, self.value, self.expected
        )
    }
}

/// A number as shown in error messages: as Rust prints it between 1e-4 and
/// 1e6, in exponent form outside (`1e300`, `5e-324`, not hundreds of
/// digits); both forms read back exactly.
pub fn fmt_num(x: f64) -> String {
    let a = x.abs();
    if x.is_finite() && a != 0.0 && !(1e-4..1e6).contains(&a) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// `x` rounded to `digits` significant digits, in the shortest form
/// that reads back as that rounded value (`0.9765649999999999` at 6
/// digits: `0.976565`; `51.5`; `1e-7`): measured axes and bands in
/// messages, without binary round-off.
pub fn fmt_sig(x: f64, digits: usize) -> String {
    if !x.is_finite() || x == 0.0 {
        return fmt_num(x);
    }
    let rounded: f64 = format!("{x:.*e}", digits.clamp(1, 17) - 1)
        .parse()
        .unwrap_or(x);
    fmt_num(rounded)
}

/// `n` and the noun, plural unless `n` is 1 ("1 point", "5 points"; a
/// noun of a noun takes its plural on its head: "3 degrees of freedom").
pub fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else if let Some((head, tail)) = noun.split_once(" of ") {
        format!("{n} {head}s of {tail}")
    } else {
        format!("{n} {noun}s")
    }
}

#[cfg(test)]
mod count_tests {
    #[test]
    fn counts_read_as_english() {
        assert_eq!(super::count(1, "point"), "1 point");
        assert_eq!(super::count(0, "mode"), "0 modes");
        assert_eq!(super::count(13, "mode"), "13 modes");
        assert_eq!(super::count(3, "degree of freedom"), "3 degrees of freedom");
        assert_eq!(super::count(1, "degree of freedom"), "1 degree of freedom");
    }

    #[test]
    fn significant_digits_drop_binary_round_off() {
        use super::fmt_sig;
        assert_eq!(fmt_sig(0.9765649999999999, 6), "0.976565");
        assert_eq!(fmt_sig(51.5, 6), "51.5");
        assert_eq!(fmt_sig(958.4999999999, 6), "958.5");
        assert_eq!(fmt_sig(1.23456789e-7, 3), "1.23e-7");
        assert_eq!(fmt_sig(0.0, 6), "0");
        // every value reads back within half a unit of its last digit
        for k in 1..2000 {
            let x = k as f64 * 0.48828125e-3 * 1.000_000_1;
            let y: f64 = fmt_sig(x, 6).parse().unwrap();
            assert!((x - y).abs() <= 0.5e-5 * x, "{x} -> {y}");
        }
    }
}

/// A mode's residue matrix could not be factored into rank terms that
/// rebuild it: nothing is run on a model that is not the one given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BasisError {
    #[error(
        "mode {mode} ({freq_hz} Hz): its residue matrix could not be factored into rank terms: {source}; nothing was run (a residue with huge or tiny entries, or NaN? check tyre.modes[{mode}].residue)"
    )]
    Residue {
        /// Index of the mode in the list given.
        mode: usize,
        freq_hz: f64,
        #[source]
        source: crate::base::linalg::LinalgError,
    },
}
