//! Errors of the scene: reading, validating and preparing it.

use std::path::PathBuf;
use thiserror::Error;
use tirecontact_core::base::error::{BasisError, FieldError, IoError, count};
use tirecontact_core::solver::error::BuildError;

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
        source: crate::readers::fe_modes::FeModesError,
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

impl From<BuildError> for SceneError {
    /// A problem built from a scene names the scene: its basis, or the
    /// solver option that does not apply, as a field of the scene.
    fn from(e: BuildError) -> Self {
        match e {
            BuildError::Basis { problem, source } => SceneError::Basis {
                scene: problem,
                source,
            },
            BuildError::Option { problem, error } => SceneError::Invalid {
                file: problem,
                errors: vec![error],
                at: Vec::new(),
            },
        }
    }
}

impl From<crate::readers::road::RoadFileError> for SceneError {
    fn from(e: crate::readers::road::RoadFileError) -> Self {
        SceneError::RoadFile {
            path: e.path,
            message: e.message,
        }
    }
}
