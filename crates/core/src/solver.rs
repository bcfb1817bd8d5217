//! Layer 4, the time stepper and its driver: the simulation (prediction,
//! contact solve, events located in the step), the run driver with its `Probe`
//! observer, and the contact phase of each point.

pub mod drive;
pub mod error;
pub mod phase;
pub mod problem;
pub mod simulation;
#[cfg(test)]
pub(crate) mod test_problem;
