//! The command line, run as a process: outputs of `run`, `identify`,
//! `sweep` and `bench`, output paths, refused options and values, hostile
//! command lines, and faults (solver errors, budgets, interrupted writes).

#[allow(dead_code)] // each test binary uses a part of the shared helpers
#[path = "../support/mod.rs"]
mod support;

mod bench_scaling;
mod faults;
mod frames;
mod frf_fit;
mod hostile_args;
mod identify_figures;
mod output_paths;
mod refusals;
mod run;
mod share;
mod study;
mod sweep_names;
