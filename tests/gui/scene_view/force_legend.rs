//! The scene view's legend entry of the force arrows has the arrows' colour
//! (the value labels share the entry; they had no item colour, so egui_plot
//! drew the entry's dot grey), while the value labels keep the strong text
//! colour. Read from the painted shapes, in the normal and classroom layouts.

use crate::harness::{advance, shapes};
use egui::epaint::{CircleShape, Shape};
use egui::{Color32, Rect};
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::views::force_labels::force_text;
use tirecontact::gui::views::scene_view::{FORCE_COLOR, FORCE_NAME, FORCE_NAME_SHORT};
use tirecontact::gui::{App, Command};

/// Fills of the filled circles inside `r` (the legend entry's dot).
fn dots_in(shapes: &[Shape], r: Rect) -> Vec<Color32> {
    shapes
        .iter()
        .filter_map(|s| match s {
            Shape::Circle(CircleShape { center, fill, .. }) if r.contains(*center) => Some(*fill),
            _ => None,
        })
        .collect()
}

fn check(size: [f32; 2], classroom: bool) {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), size);
    h.run();
    h.state_mut().apply(Command::ShowView(View::Scene));
    if classroom {
        h.state_mut().apply(Command::SetClassroom(true));
    }
    h.run_steps(2);
    // on until a point pushes
    for _ in 0..400 {
        if h.state().simulation().force_n().iter().any(|q| *q > 0.0) {
            break;
        }
        advance(&mut h, 25);
    }
    h.run_steps(2);
    let q: Vec<f64> = h.state().simulation().force_n().to_vec();
    assert!(q.iter().any(|q| *q > 0.0), "no point pushes: {q:?}");

    let entry = h
        .get_by_label(if classroom {
            FORCE_NAME_SHORT
        } else {
            FORCE_NAME
        })
        .rect();
    let all = shapes(&h);
    let dots = dots_in(&all, entry);
    eprintln!("{size:?} classroom {classroom}: legend entry {entry:?}, dots {dots:?}");
    assert!(
        dots.contains(&FORCE_COLOR),
        "{size:?}: the force legend's dot is not the arrows' colour: {dots:?}"
    );
    let grey = h
        .ctx
        .global_style()
        .visuals
        .widgets
        .noninteractive
        .fg_stroke
        .color;
    assert!(!dots.contains(&grey), "{size:?}: grey dot {grey:?}");

    // the value labels keep the strong text colour (the largest force's
    // label is always drawn)
    let strong = h.ctx.global_style().visuals.strong_text_color();
    let label = force_text(q.iter().copied().fold(0.0, f64::max));
    let text = all
        .iter()
        .find_map(|s| match s {
            Shape::Text(t) if t.galley.text() == label => Some(t.clone()),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no label {label}"));
    let colors: Vec<Color32> = text
        .galley
        .job
        .sections
        .iter()
        .map(|s| s.format.color)
        .collect();
    assert!(
        colors.iter().all(|c| *c == strong),
        "{colors:?} vs {strong:?}"
    );
}

#[test]
fn the_force_legend_entry_has_the_arrows_colour() {
    check([1500.0, 950.0], false);
    check([1280.0, 720.0], true);
}
