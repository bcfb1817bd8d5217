//! # tirecontact-report
//!
//! What runs leave and what is made of many runs: [`output`] (the one run
//! sampler, CSV time histories, arrays, recordings, animation frames and,
//! with the `figures` feature, PNG figures), [`analysis`] (spectra and bands,
//! run metrics, A/B compare, the fidelity of a modal model, the
//! work-precision and scaling benchmarks; the peer methods with `peers`)
//! and [`studies`] (sweeps over scene paths, studies of several factors,
//! their shards and merge).

pub mod analysis;
pub mod output;
pub mod studies;
