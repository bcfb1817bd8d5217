//! The contact solver and the fast modal convolution (method §1-4), checked
//! against closed forms, independent implementations written in these
//! files, self-convergence and invariants; its options (steady path, rank
//! cut, residual flexibility, threads) against their controls; stress and
//! large scenes.

#[allow(dead_code)] // each test binary uses a part of the shared helpers
#[path = "../support/mod.rs"]
mod support;

mod dense;
mod oscillator;

mod compliant_robustness;
mod contact;
mod exact_step;
mod invariants;
mod joint_impacts;
mod large_sets;
mod many_points;
mod merged_events;
mod paper_scheme;
mod patch;
mod phases;
mod rank_tolerance;
mod residual_flexibility;
mod residues;
mod steady_path;
mod stress;
mod threads;
