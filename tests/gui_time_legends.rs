//! The time plots' legends keep off the newest samples: while following a
//! full window (newest samples at the right edge) they sit at the left; before
//! the window fills (samples on the left only), at the right.
#![cfg(feature = "gui")]

mod common;
use common::{advance, harness};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::App;

/// Horizontal centres of the legend entries "point 0" of the four plots.
fn legend_x(h: &Harness<'_, App>) -> Vec<f32> {
    h.get_all_by_label("point 0")
        .map(|n| n.rect().center().x)
        .collect()
}

#[test]
fn the_legends_keep_off_the_newest_samples() {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    // 0.02 s of a 0.1 s window: samples on the left, legends on the right
    advance(&mut h, 2_000);
    h.run_steps(2);
    let xs = legend_x(&h);
    assert_eq!(xs.len(), 4, "one legend per plot: {xs:?}");
    let plot_mid = 0.5 * (h.ctx.content_rect().right() + 360.0);
    assert!(xs.iter().all(|&x| x > plot_mid), "{xs:?} vs {plot_mid}");
    // 0.15 s: the window is full and its newest samples are at the right
    advance(&mut h, 13_000);
    h.run_steps(2);
    let xs = legend_x(&h);
    assert_eq!(xs.len(), 4, "{xs:?}");
    assert!(xs.iter().all(|&x| x < plot_mid), "{xs:?} vs {plot_mid}");
}

/// The contact scheme's combo box says what the schemes are on hover.
#[test]
fn the_contact_scheme_explains_itself_on_hover() {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    assert!(
        h.query_by_label_contains("contact decided at step ends")
            .is_none()
    );
    // the grid's label, then the combo box of the same name
    let combo = h
        .get_all_by_label("contact scheme")
        .last()
        .expect("combo box");
    combo.hover();
    // tooltips show after a short delay
    for _ in 0..60 {
        h.run_steps(1);
    }
    assert!(
        h.query_by_label_contains("contact decided at step ends")
            .is_some(),
        "the tooltip names the schemes"
    );
}
