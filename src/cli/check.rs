//! `tirecontact check PRESET`: parse and validate, print a summary.

use super::{CliResult, load_scene};
use std::path::Path;
use tirecontact::{PreparedModel, Simulation, SolverOptions};

pub fn check(path: &Path) -> CliResult {
    let scene = load_scene(Some(path))?;
    // also identifies a ring, reads a measured road file and factors the modes
    let model = PreparedModel::of(&scene)?;
    let sim = Simulation::new(&model, SolverOptions::default())?;
    println!(
        "{}: ok — \"{}\": {}, {}, road {}, speed V = {} m/s ({:.0} km/h), dt = {:e} s, duration {} s ({} steps); CSV of `run -o` about {} (--every 1)",
        path.display(),
        scene.name,
        tirecontact::output::count(scene.num_points(), "point"),
        tirecontact::output::count(model.modes().len(), "mode"),
        scene.road.kind(),
        scene.speed_mps,
        scene.speed_mps * 3.6,
        scene.dt_s,
        scene.duration_s,
        scene.num_steps(),
        tirecontact::output::csv::human_bytes(tirecontact::output::csv::estimated_bytes(
            scene.num_steps(),
            1,
            scene.num_points()
        ))
    );
    drop(sim);
    Ok(())
}
