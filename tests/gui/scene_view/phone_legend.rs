//! On a phone (412 × 915) the scene view's legend keeps off the plot: a
//! compact row of keys above it, in rows as high as their text (in a
//! corner of the narrow plot, its six entries covered about half of it),
//! while a wide window keeps the legend in the plot's corner.

use crate::harness::{advance, harness_sized, plot_frame, settle};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::scene_view::{
    CONTACT_NAME, DISPLACED_NAME, FLIGHT_NAME, FORCE_NAME, FORCE_NAME_SHORT, ROAD_NAME,
    ROAD_NAME_LEFT, SCENE_PLOT_ID, UNDEFORMED_NAME,
};
use tirecontact::gui::{App, Command, View};

/// The rects of the legend entries shown.
fn entries(h: &Harness<'_, App>) -> Vec<(&'static str, egui::Rect)> {
    [
        ROAD_NAME,
        ROAD_NAME_LEFT,
        UNDEFORMED_NAME,
        DISPLACED_NAME,
        CONTACT_NAME,
        FLIGHT_NAME,
        FORCE_NAME,
        FORCE_NAME_SHORT,
    ]
    .into_iter()
    .flat_map(|l| {
        h.query_all_by_label(l)
            .map(|n| (l, n.rect()))
            .collect::<Vec<_>>()
    })
    .collect()
}

fn scene_at(size: [f32; 2]) -> Harness<'static, App> {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness_sized(App::new(scene, None).unwrap(), size);
    h.state_mut().apply(Command::ShowView(View::Scene));
    settle(&mut h);
    advance(&mut h, 3000);
    h.run_steps(3);
    h
}

#[test]
fn the_scene_legend_keeps_off_the_plot_on_a_phone() {
    let size = [412.0, 915.0];
    let h = scene_at(size);
    let frame = plot_frame(&h, SCENE_PLOT_ID);
    let shown = entries(&h);
    assert!(shown.len() >= 5, "legend entries: {shown:?}");
    for (label, r) in &shown {
        let over = r.intersect(frame);
        assert!(
            !(over.width() > 0.0 && over.height() > 0.0),
            "{size:?}: the legend entry {label:?} at {r:?} covers the plot {frame:?}"
        );
        assert!(
            r.left() >= 0.0 && r.right() <= size[0],
            "{size:?}: {label:?} at {r:?} off the window"
        );
    }
    // compact: rows as high as their text (not a phone's 44 px touch
    // rows), at most two of them
    let legend = shown
        .iter()
        .map(|(_, r)| *r)
        .reduce(|a, b| a.union(b))
        .unwrap();
    let entry_h = shown.iter().map(|(_, r)| r.height()).fold(0.0, f32::max);
    assert!(
        legend.height() <= 2.5 * entry_h && legend.height() < 0.25 * frame.height(),
        "{size:?}: the legend {legend:?} (entries {entry_h} px high) vs the plot {frame:?}"
    );

    // a wide window: the legend in the plot's corner, as before
    let wide = scene_at([1280.0, 720.0]);
    let frame = plot_frame(&wide, SCENE_PLOT_ID);
    let (label, r) = entries(&wide)
        .into_iter()
        .find(|(l, _)| *l == UNDEFORMED_NAME)
        .expect("the undeformed tyre's entry");
    assert!(
        frame.contains_rect(r),
        "{label:?} at {r:?} outside {frame:?}"
    );
}
