//! A finished sweep of a rigid-contact scene says what its force figures
//! hold: the force without impacts, and the impacts as impulses (as
//! impulse / dt an impact would read tens of kN, and double when dt halves).

use crate::harness::harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::SweepState;
use tirecontact::gui::View;
use tirecontact::gui::views::sweep_view::RIGID_FORCE_NOTE;
use tirecontact::gui::{App, Command};

#[test]
fn a_rigid_sweep_says_its_forces_leave_impacts_to_impulses() {
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
    // the premise: impacts, which as impulse / dt dwarf the plotted max
    let ok: Vec<_> = r
        .points
        .iter()
        .filter_map(|p| p.result.as_ref().ok())
        .collect();
    let dt = h.state().scene().dt_s;
    assert!(
        ok.iter().any(|s| {
            let c = &s.contact;
            c.impulse_max_ns[0] / dt > 10.0 * c.force_max_n[0]
        }),
        "impacts in the sweep"
    );
    assert!(h.query_by_label(RIGID_FORCE_NOTE).is_some());
}
