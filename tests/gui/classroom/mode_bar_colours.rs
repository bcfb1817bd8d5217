//! The classroom's mode bars are drawn in one colour (grey when muted), not
//! in the points' colours: beside the coloured point picker, mode k in
//! point k+1's colour read as that point's bar.

use crate::harness::shapes;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::classroom::mode_bar_color;
use tirecontact::gui::views::point_color;
use tirecontact::gui::{App, Command};

#[test]
fn mode_bars_are_not_in_point_colours() {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), [1500.0, 950.0]);
    h.run();
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(2);
    crate::harness::advance(&mut h, 2000);
    h.run_steps(2);
    let visuals = h.ctx.global_style().visuals.clone();
    let bar = mode_bar_color(&visuals, false);
    let fills: Vec<egui::Color32> = shapes(&h)
        .into_iter()
        .filter_map(|s| match s {
            egui::Shape::Rect(r) => Some(r.fill),
            _ => None,
        })
        .collect();
    let bars = fills.iter().filter(|&&f| f == bar).count();
    assert!(
        bars >= 3,
        "{bars} bars in the mode bar colour (three modes)"
    );
    for k in 1..8 {
        let c = point_color(k);
        let n = fills.iter().filter(|&&f| f == c).count();
        assert_eq!(n, 0, "{n} filled rects in point {k}'s colour");
    }
    assert_ne!(mode_bar_color(&visuals, true), bar);
}
