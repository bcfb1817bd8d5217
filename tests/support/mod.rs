//! Helpers shared by the test binaries (each declares this module with
//! `#[path = "../support/mod.rs"] mod support;`): the command-line binary,
//! temporary folders, and reference models used by several tests.

pub mod colour;
pub mod frf;
pub mod models;

use std::process::Command;

/// Relative RMS difference of two histories (rows of values) against the
/// second: `‖a - b‖ / ‖b‖` over every value.
pub fn rel_rms(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        for (p, q) in x.iter().zip(y) {
            num += (p - q) * (p - q);
            den += q * q;
        }
    }
    (num / den).sqrt()
}

/// The largest difference between two runs' values and the largest
/// value of the first, accumulated step by step.
#[derive(Debug, Default, Clone, Copy)]
pub struct Gap {
    pub diff: f64,
    pub max: f64,
}

impl Gap {
    /// Takes in one step's values of both runs.
    pub fn add(&mut self, a: &[f64], b: &[f64]) {
        for (x, y) in a.iter().zip(b) {
            self.diff = self.diff.max((x - y).abs());
            self.max = self.max.max(x.abs());
        }
    }

    /// The largest difference over the largest value.
    pub fn relative(&self) -> f64 {
        self.diff / self.max
    }
}

/// The shipped preset `presets/NAME.ron`.
pub fn preset(name: &str) -> tirecontact::Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets")
        .join(format!("{name}.ron"));
    tirecontact::Scene::load(&path).unwrap()
}

/// The `tirecontact` binary cargo built for these tests, as a command. It
/// is built with the feature `cli` only: a test that also checks the
/// library runs its command-line part when `cfg!(feature = "cli")`.
#[cfg(feature = "cli")]
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tirecontact"))
}

/// Without the feature `cli` there is no binary to run.
#[cfg(not(feature = "cli"))]
pub fn bin() -> Command {
    panic!("the `tirecontact` binary is built with the feature `cli`")
}

/// A new, empty folder of its own in the system's temporary folder, removed
/// with its contents when the returned guard drops (a failed test too).
pub fn temp_dir() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("tirecontact-test-")
        .tempdir()
        .expect("a temporary folder")
}

/// Cases per property test: `PROPTEST_CASES` if set, else `default` (a
/// `cases` written in a test's config would otherwise override the variable).
pub fn proptest_cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}
