//! Output: CSV time histories, atomic file writes, headless figures, and
//! the one sampler of a run's time histories ([`sampler`]).

pub mod animation;
pub mod arrays;
pub mod csv;
pub mod figures;
pub mod impacts;
pub mod paper_figures;
pub mod record;
pub mod sampler;
pub mod summary;

pub use crate::base::error::count;
pub use crate::base::fsio::{AtomicFile, write_atomic, write_atomic_with};
