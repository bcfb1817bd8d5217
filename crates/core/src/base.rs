//! The ground floor: errors of the solver and of model parameters, checked
//! dense linear algebra, modes and their Green functions, the kernels'
//! worker threads.

pub mod error;
pub mod linalg;
pub mod modal;
pub mod threads;
