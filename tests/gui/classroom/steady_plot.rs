//! In classroom mode the scene plot keeps its place while points land and
//! leave the road: its legend row (above the plot) lists the contact force
//! at all times. It used to list it only while a point was in contact, so
//! the row wrapped to a second line and back, the plot changed height, and
//! at aspect 1 its x range jumped between ±0.2 m and ±0.15 m (guided 1a).

use crate::harness::texts;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::views::scene_view::{FORCE_NAME_SHORT, Y_TITLE, Y_TITLE_SHORT};
use tirecontact::gui::{App, Command};

#[test]
fn the_scene_plot_does_not_move_as_points_land_and_leave() {
    let scene = Scene::load(Path::new("presets/guided_1a_soft_tyre.ron")).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
    h.run();
    h.state_mut().apply(Command::ShowView(View::Scene));
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(3);
    let (mut with, mut without) = (0, 0);
    let mut centres: Vec<f32> = Vec::new();
    let n = h.state().simulation().num_points();
    for _ in 0..60 {
        crate::harness::advance(&mut h, 300);
        h.run_steps(2);
        let any_contact = h.state().simulation().in_contact().iter().any(|&c| c);
        let force = h.state().simulation().force_n()[..n]
            .iter()
            .any(|&q| q > 0.0);
        if any_contact || force {
            with += 1;
        } else {
            without += 1;
        }
        let all = texts(&h);
        assert!(
            all.iter()
                .any(|(t, _)| t == FORCE_NAME_SHORT || t == "force (N)"),
            "the force's legend entry is missing at t = {} s",
            h.state().simulation().time_s()
        );
        let title = all
            .iter()
            .find(|(t, _)| t == Y_TITLE || t == Y_TITLE_SHORT)
            .expect("the scene plot's y title")
            .1;
        centres.push(title.center().y);
        if h.state().simulation().finished() {
            break;
        }
    }
    assert!(
        with > 0 && without > 0,
        "{with} frames with force, {without} without"
    );
    let (lo, hi) = centres
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &c| {
            (a.min(c), b.max(c))
        });
    assert!(hi - lo < 0.5, "the plot moved by {} px", hi - lo);
}
