//! A/B comparison in the GUI (no egui here): the current run as a
//! `Recording` built from the History, so that `crate::analysis::compare::PinnedRun`
//! pins it and differences it.

use crate::gui::model::history::{History, Quantity};
use crate::output::record::Recording;

/// [`History::to_recording`] with the force without impacts as `q`: what
/// a clipped force plot fits.
pub fn recording_without_impacts(h: &History) -> Recording {
    let mut r = h.to_recording();
    r.q_n = (0..h.num_points())
        .map(|i| {
            (0..h.len())
                .map(|k| h.value(Quantity::ForceWithoutImpacts, i, k))
                .collect()
        })
        .collect();
    r
}

/// A short label of a scene for legends: its name and speed.
pub fn pin_label(scene: &crate::Scene, t_s: f64) -> String {
    format!(
        "{}, V = {:.3} m/s, up to t = {t_s:.4} s",
        scene.name, scene.speed_mps
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scene;
    use crate::SceneSimulation;
    use crate::analysis::compare::PinnedRun;
    use crate::solver::simulation::Simulation;

    #[test]
    fn a_run_against_itself_is_zero_and_a_changed_run_is_not() {
        let scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/three_points.ron"
            )),
            "three_points",
        )
        .unwrap();
        let run = |s: &Scene| {
            let mut sim = Simulation::from_scene(s).unwrap();
            let mut h = History::new(s.num_points(), 1 << 20);
            h.record_initial(&sim);
            for _ in 0..3000 {
                sim.step().unwrap();
                h.after_step(&sim);
            }
            (h, sim)
        };
        let (h, sim) = run(&scene);
        let rec = h.to_recording();
        assert_eq!(rec.t_s.len(), h.len());
        // road from the gap: equals the simulation's road at the last sample
        for i in 0..3 {
            let r = *rec.r_m[i].last().unwrap();
            assert!(
                (r - sim.road_m()[i]).abs() < 1e-6,
                "{r} vs {}",
                sim.road_m()[i]
            );
        }
        let pin = PinnedRun::new(pin_label(&scene, 0.03), &scene, 1, &rec);
        let d = pin.difference(&scene.points, &rec);
        assert_eq!(d.t_s.len(), rec.t_s.len());
        assert!(d.rms_dq_n.iter().chain(&d.rms_du_m).all(|&x| x == 0.0));
        let mut faster = scene.clone();
        faster.speed_mps *= 1.2;
        let (h2, _) = run(&faster);
        let d = pin.difference(&faster.points, &h2.to_recording());
        assert!(d.rms_dq_n.iter().all(|&x| x > 0.0), "{:?}", d.rms_dq_n);
    }
}
