//! Layer 0, the ground floor: errors, checked dense linear algebra, atomic file
//! writes, modes and their Green functions, the kernels' worker threads.

pub mod error;
pub mod fsio;
pub mod linalg;
pub mod modal;
pub mod threads;
