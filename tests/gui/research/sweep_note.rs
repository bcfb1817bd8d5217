//! A finished sweep of a rigid-contact scene says what its force figures
//! hold: the step-mean force, with an impact as impulse / dt (its "max
//! contact force" of tens of kN is the largest impact, not a rolling force).

use crate::harness::harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::SweepState;
use tirecontact::gui::View;
use tirecontact::gui::views::sweep_view::RIGID_FORCE_NOTE;
use tirecontact::gui::{App, Command};

#[test]
fn a_rigid_sweep_says_its_max_force_counts_impacts_as_impulse_over_dt() {
    let mut scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    scene.duration_s = 0.05;
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    h.state_mut().apply(Command::ShowView(View::Sweep));
    h.run_steps(2);
    assert!(h.query_by_label(RIGID_FORCE_NOTE).is_none());
    h.get_by_label("Run sweep").click();
    h.run_steps(1);
    for _ in 0..20_000 {
        if !h.state().research().sweep().is_running() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.run_steps(1);
    }
    h.run_steps(2);
    let SweepState::Finished(r) = h.state().research().sweep() else {
        panic!("sweep not finished")
    };
    // the premise: the max holds impacts, far above the RMS
    let ok: Vec<_> = r
        .points
        .iter()
        .filter_map(|p| p.result.as_ref().ok())
        .collect();
    assert!(
        ok.iter()
            .any(|s| s.max_force_n[0] > 10.0 * s.force_rms_n[0]),
        "impacts in the max"
    );
    assert!(h.query_by_label(RIGID_FORCE_NOTE).is_some());
}
