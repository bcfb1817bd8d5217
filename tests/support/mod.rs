//! Helpers shared by the test binaries (each declares this module with
//! `#[path = "../support/mod.rs"] mod support;`).

pub mod colour;
