//! Layer 5, what a run leaves: CSV time histories, headless figures,
//! animation frames, recordings, and the one sampler of a run's time
//! histories ([`sampler`]); files are written atomically by
//! [`tirecontact_io::fsio`].

#[cfg(feature = "figures")]
pub mod animation;
pub mod arrays;
pub mod csv;
pub mod figures;
pub mod impacts;
pub mod paper_figures;
pub mod patch;
pub mod record;
pub mod sampler;
pub mod sci;
#[cfg(feature = "figures")]
pub mod stabilisation;
pub mod summary;

pub use tirecontact_core::base::error::count;
pub use tirecontact_io::fsio::{AtomicFile, write_atomic, write_atomic_with};
