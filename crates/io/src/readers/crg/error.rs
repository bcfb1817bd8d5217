//! Why an OpenCRG file is refused: where in the file, the field, the value
//! read and what was expected.

use super::super::road::RoadFileError;
use std::fmt;
use std::path::PathBuf;

/// Where in an OpenCRG file a refused field is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CrgPlace {
    /// A line of the text (1-based): a header line, or a record of
    /// formatted data with the column (1-based) its value starts at.
    Line { line: usize, column: Option<usize> },
    /// A byte offset from the file's start (binary data).
    Byte(u64),
    /// The header as a whole: a key it lacks, its channels taken together.
    Header,
    /// The grid as read: its size, the reference line built from it.
    Grid,
}

impl CrgPlace {
    /// A header line or a data record without a column.
    pub fn line(line: usize) -> Self {
        CrgPlace::Line { line, column: None }
    }

    /// A value of a data record.
    pub fn column(line: usize, column: usize) -> Self {
        CrgPlace::Line {
            line,
            column: Some(column),
        }
    }
}

impl fmt::Display for CrgPlace {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CrgPlace::Line { line, column: None } => write!(f, "line {line}"),
            CrgPlace::Line {
                line,
                column: Some(c),
            } => write!(f, "line {line}, column {c}"),
            CrgPlace::Byte(b) => write!(f, "byte {b}"),
            CrgPlace::Header => write!(f, "header"),
            CrgPlace::Grid => write!(f, "grid"),
        }
    }
}

/// A refused field of an OpenCRG file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{place}: {field}{}: expected {expected}", value_text(value))]
pub struct CrgFault {
    pub place: CrgPlace,
    /// What is refused: a key, a channel, a modifier, a value of the data
    /// (its cross section and channel), the data as a whole.
    pub field: String,
    /// The value read (empty when the field is missing).
    pub value: String,
    /// What was expected.
    pub expected: String,
}

fn value_text(value: &str) -> String {
    if value.is_empty() {
        String::new()
    } else {
        format!(" = {value}")
    }
}

impl CrgFault {
    pub fn new(
        place: CrgPlace,
        field: impl Into<String>,
        value: impl fmt::Display,
        expected: impl Into<String>,
    ) -> Self {
        CrgFault {
            place,
            field: field.into(),
            value: value.to_string(),
            expected: expected.into(),
        }
    }
}

/// An OpenCRG file that cannot be opened, or whose contents are refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CrgError {
    /// Not found, not a regular file, too large.
    #[error(transparent)]
    Open(#[from] RoadFileError),
    /// A field of the file refused.
    #[error("{path}: {fault}")]
    Fault {
        path: PathBuf,
        #[source]
        fault: CrgFault,
    },
}

impl CrgError {
    /// The refused field, for a file that opened.
    pub fn fault(&self) -> Option<&CrgFault> {
        match self {
            CrgError::Fault { fault, .. } => Some(fault),
            CrgError::Open(_) => None,
        }
    }
}

impl From<CrgError> for RoadFileError {
    fn from(e: CrgError) -> Self {
        match e {
            CrgError::Open(e) => e,
            CrgError::Fault { path, fault } => RoadFileError {
                path,
                message: fault.to_string(),
            },
        }
    }
}
