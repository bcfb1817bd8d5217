//! Helpers shared by the test binaries (each declares this module with
//! `#[path = "../support/mod.rs"] mod support;`): the command-line binary,
//! temporary folders, and reference models used by several tests.

pub mod colour;

use std::process::Command;

/// The `tirecontact` binary cargo built for these tests, as a command.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tirecontact"))
}

/// A new, empty folder of its own in the system's temporary folder, removed
/// with its contents when the returned guard drops (a failed test too).
pub fn temp_dir() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("tirecontact-test-")
        .tempdir()
        .expect("a temporary folder")
}
