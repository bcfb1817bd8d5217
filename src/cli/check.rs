//! `tirecontact check PRESET`: parse and validate, print a summary.

use super::{CliResult, load_scene};
use std::path::Path;
use tirecontact::{PreparedModel, SolverOptions};

pub fn check(path: &Path) -> CliResult {
    let scene = load_scene(Some(path))?;
    // also identifies a ring, reads a measured road file and factors the modes
    let model = PreparedModel::of(&scene)?;
    let sim = model.simulation(SolverOptions::default())?;
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
        if let tirecontact::model::road::Road::Crg { .. } = &scene.road {
            let (lo, hi) = g.x_range_m();
            println!(
                "  OpenCRG road: the file covers u {:.3} m to {:.3} m; x = 0 at u = {:.3} m at the start, y = 0 at v = {:.3} m (y and v to the left); heights from the road's mean plane: {:.4} m (the absolute height offset) taken off the file's",
                lo + g.file_origin_m.0,
                hi + g.file_origin_m.0,
                g.file_origin_m.0,
                g.file_origin_m.1,
                g.datum_m
            );
        }
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
    if let tirecontact::scene::Tyre::FeModes { .. } = &scene.tyre {
        print_fe_modes(&scene)?;
    }
    drop(sim);
    Ok(())
}

/// An FE tyre: the unit factors, what the reading did, each mode read and
/// the node of each point.
fn print_fe_modes(scene: &tirecontact::Scene) -> CliResult {
    let fe = tirecontact::identify::fe_model(scene)?;
    println!(
        "  FE tyre: {} modes from {:.3} Hz to {:.3} Hz; file units: length × {}, force × {}, mass × {} of SI",
        fe.modes.len(),
        fe.modes.first().map_or(f64::NAN, |m| m.freq_hz),
        fe.modes.last().map_or(f64::NAN, |m| m.freq_hz),
        fe.length_factor,
        fe.force_factor,
        fe.mass_factor
    );
    for n in &fe.notes {
        println!("    {n}");
    }
    for (what, list) in [
        ("read", &fe.datasets_read),
        ("skipped", &fe.datasets_skipped),
    ] {
        let total: usize = list.iter().map(|(_, n)| n).sum();
        println!("    datasets {what}: {total}");
        for (d, n) in list {
            println!("      {n:>6} × {d}");
        }
    }
    println!("    mode  record  dataset  freq_hz  modal_mass_kg  damping_ratio");
    for (k, r) in fe.read.iter().enumerate() {
        println!(
            "    {:>4}  {:>6}  {:>7}  {:.6}  {:.6e}  {:.6}  (mode {} of the file)",
            k, r.record, r.dataset, r.freq_hz, r.modal_mass_kg, r.damping_ratio, r.mode_number
        );
    }
    println!("    point  node  distance_mm");
    for (i, m) in fe.mapping.iter().enumerate() {
        println!(
            "    {:>5}  {:>4}  {}",
            i,
            m.node,
            m.distance_m
                .map_or("(no coordinates)".to_string(), |d| format!(
                    "{:.4}",
                    d * 1e3
                ))
        );
    }
    Ok(())
}
