//! Error types: every error carries the context a user needs to act on it.

use std::path::PathBuf;
use std::sync::Arc;
use thiserror::Error;

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

/// `n` and the noun, plural unless `n` is 1 ("1 point", "5 points").
pub fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
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

/// Errors while reading or validating a scene.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SceneError {
    /// The RON text does not parse (line and column are 1-based).
    #[error("{file}:{line}:{col}: {message}")]
    Syntax {
        file: String,
        line: usize,
        col: usize,
        message: String,
    },
    /// The scene parses but some values are out of range.
    #[error("{}", format_invalid(.file, .errors, .at))]
    Invalid {
        file: String,
        errors: Vec<FieldError>,
        /// Where each error's field is written in the preset's text (line,
        /// column, 1-based), when the scene came from a text; may be empty.
        at: Vec<Option<(usize, usize)>>,
    },
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: IoError,
    },
    /// A measured road profile (`road.file`) is unusable.
    #[error("road.file = {path}: {message}{}", road_file_hint(.message))]
    RoadFile { path: PathBuf, message: String },
    /// A mode's residue could not be factored into rank terms that rebuild
    /// it (checked at set-up).
    #[error("scene \"{scene}\": {source}")]
    Basis {
        scene: String,
        #[source]
        source: BasisError,
    },
    /// An FE tyre's file does not give a modal model of the points
    /// (method §5.4).
    #[error("scene \"{scene}\": tyre.file: {source}")]
    FeModes {
        scene: String,
        #[source]
        source: crate::model::fe_modes::FeModesError,
    },
    /// The modal model of a ring tyre could not be identified (method §6).
    #[error("scene \"{scene}\": tyre identification failed: {message}")]
    Identification { scene: String, message: String },
}

/// What to do about a road file that cannot be opened: the path rule.
fn road_file_hint(message: &str) -> &'static str {
    if message.starts_with("cannot open") {
        " (a relative path is taken from the preset's folder: expected an existing CSV of `x_m, z_m` rows there, or an absolute path)"
    } else {
        ""
    }
}

fn format_invalid(file: &str, errors: &[FieldError], at: &[Option<(usize, usize)>]) -> String {
    let mut s = format!("{file}: {}", count(errors.len(), "invalid value"));
    for (k, e) in errors.iter().enumerate() {
        s.push_str("\n  ");
        // where the preset writes the field, as a syntax error is placed
        if let Some(Some((line, col))) = at.get(k) {
            s.push_str(&format!("{file}:{line}:{col}: "));
        }
        s.push_str(&e.to_string());
    }
    s
}

/// Why a run driven by [`crate::solver::drive::run`] stopped early.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// A step could not be solved.
    #[error(transparent)]
    Solver(#[from] SolverError),
    /// What the run's observer writes failed (a CSV file, a frame).
    #[error("writing the run's output: {0}")]
    Output(#[from] std::io::Error),
    /// The run's cancel flag was set.
    #[error("cancelled after {steps} steps")]
    Cancelled { steps: u64 },
}

/// Errors of the time stepper. A step that fails leaves the simulation at the
/// start of that step.
#[derive(Debug, Clone, Error, PartialEq)]
pub enum SolverError {
    /// The contact system of the active points could not be solved.
    #[error(
        "singular contact system at t = {t_s:.6e} s for points {points:?} (pivot {pivot:.3e} after scaling): the modal model cannot hold these points on the road independently (too few modes for the points in contact?)"
    )]
    SingularContactSystem {
        t_s: f64,
        points: Vec<usize>,
        pivot: f64,
    },
    /// A displacement, velocity or force became NaN or infinite.
    #[error(
        "non-finite {quantity} at t = {t_s:.6e} s, point {point}: the step cannot be solved in floating point (a road, slope or preload far beyond a tyre's deflection, e.g. huge values in a measured road file?)"
    )]
    NonFinite {
        t_s: f64,
        point: usize,
        quantity: &'static str,
    },
    /// A measured road profile was sampled outside its extent.
    #[error(
        "road profile sampled at x = {x_m} m (t = {t_s:.6e} s, point {point}) outside its extent [{min_m}, {max_m}] m: set `looped: true`, shorten `duration_s`, or extend the file"
    )]
    RoadOutOfRange {
        t_s: f64,
        point: usize,
        x_m: f64,
        min_m: f64,
        max_m: f64,
    },
}
