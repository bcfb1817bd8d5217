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
    if let Some(g) = model.road().surface() {
        let mpd = g.mpd_m().map_or(
            "no mean profile depth (rows shorter than 100 mm)".to_string(),
            |d| format!("mean profile depth (ISO 13473-1) {:.3} mm", d * 1e3),
        );
        println!(
            "  road surface: {} × {} nodes, {:.3} mm along × {:.3} mm across, {}; {mpd}",
            g.nx,
            g.ny,
            g.dx_m * 1e3,
            g.dy_m * 1e3,
            if g.looped {
                "looped along x"
            } else {
                "not looped"
            }
        );
    }
    if let (tirecontact::scene::Tyre::Plate { .. }, Some(first), Some(last)) =
        (&scene.tyre, model.modes().first(), model.modes().last())
    {
        println!(
            "  plate tyre: {} modes from {:.1} Hz to {:.1} Hz",
            model.modes().len(),
            first.freq_hz,
            last.freq_hz
        );
    }
    drop(sim);
    Ok(())
}
