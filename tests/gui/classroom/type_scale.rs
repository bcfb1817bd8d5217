//! Classroom mode is read from the back of a room: every text of its views
//! (the phase strip, the scene's and the point plot's legends, the axis
//! numbers and titles) is at least 20 px at 1280 × 720, read from the
//! galleys' fonts over a run of the paper preset and a patch preset.

use crate::harness::{advance, harness_sized, shapes};
use egui::Shape;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::classroom::CLASSROOM_MIN_TEXT_PX;
use tirecontact::gui::{App, Command};

/// The views' area: below the toolbar (its Reset button), left of the
/// presenter panel (the scene plot fills the views' width) and down to the
/// point plot's time axis title, the lowest text of the views.
fn views_rect(h: &egui_kittest::Harness<'_, App>) -> egui::Rect {
    use egui_kittest::kittest::Queryable;
    use tirecontact::gui::views::scene_view::SCENE_PLOT_ID;
    let scene = *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(SCENE_PLOT_ID))
        .expect("scene plot shown")
        .transform()
        .frame();
    let toolbar = h.get_by_label("Reset").rect();
    let title = crate::harness::texts(h)
        .into_iter()
        .filter(|(t, r)| t == "time t (s)" && r.center().x < scene.right())
        .map(|(_, r)| r)
        .max_by(|a, b| a.bottom().total_cmp(&b.bottom()))
        .expect("the point plot's time axis title");
    egui::Rect::from_min_max(
        egui::pos2(0.0, toolbar.bottom() + 2.0),
        egui::pos2(f32::INFINITY, title.bottom() + 1.0),
    )
}

#[test]
fn every_classroom_view_text_is_at_least_the_classroom_size() {
    for (preset, size) in [
        ("paper.ron", [1280.0, 720.0]),
        ("three_points.ron", [1280.0, 720.0]),
        ("patch_texture.ron", [1280.0, 720.0]),
        ("random_road.ron", [1280.0, 720.0]),
        ("paper.ron", [1600.0, 1000.0]),
    ] {
        let scene = Scene::load(&Path::new("presets").join(preset)).unwrap();
        let mut h = harness_sized(App::new(scene, None).unwrap(), size);
        h.state_mut().apply(Command::SetClassroom(true));
        h.run_steps(4);
        advance(&mut h, 1500);
        h.run_steps(4);
        let area = views_rect(&h);
        // the views keep most of the window (a patch's 24 point buttons in
        // one row made the presenter panel as wide as the window)
        let scene = *egui_plot::PlotMemory::load(
            &h.ctx,
            egui::Id::unique(tirecontact::gui::views::scene_view::SCENE_PLOT_ID),
        )
        .expect("scene plot shown")
        .transform()
        .frame();
        assert!(
            scene.width() >= 0.45 * size[0],
            "{preset} {size:?}: the scene plot is {} px wide",
            scene.width()
        );
        let mut seen = Vec::new();
        let mut small = Vec::new();
        for s in shapes(&h) {
            if let Shape::Text(t) = s {
                let r = t.visual_bounding_rect();
                let text = t.galley.text().trim().to_owned();
                if text.is_empty() || !area.contains(r.center()) {
                    continue;
                }
                let px = t
                    .galley
                    .job
                    .sections
                    .iter()
                    .map(|s| s.format.font_id.size)
                    .fold(f32::INFINITY, f32::min);
                seen.push(text.clone());
                if px < CLASSROOM_MIN_TEXT_PX - 1e-3 {
                    small.push((text, px));
                }
            }
        }
        eprintln!("{preset} {size:?}: {} texts in the views", seen.len());
        // the phase strip, both legends, axis numbers and titles were read
        for want in ["contact phase:", "point 0", "time t (s)"] {
            assert!(
                seen.iter().any(|t| t.contains(want)),
                "{preset} {size:?}: no {want:?} among {seen:?}"
            );
        }
        // a strip too long for one row in the classroom's size counts the
        // points in each phase instead: every point counted once
        let counted: Vec<usize> = seen
            .iter()
            .filter_map(|t| {
                let (k, name) = t.split_once(' ')?;
                ["IMPACT", "RELEASE", "in contact", "free flight"]
                    .contains(&name)
                    .then(|| k.parse::<usize>().ok())?
            })
            .collect();
        let points = h.state().simulation().num_points();
        if points > 5 {
            assert_eq!(counted.len(), 4, "{preset} {size:?}: {seen:?}");
            assert_eq!(
                counted.iter().sum::<usize>(),
                points,
                "{preset}: {counted:?}"
            );
        }
        assert!(
            small.is_empty(),
            "{preset} {size:?}: texts under {CLASSROOM_MIN_TEXT_PX} px: {small:?}"
        );
    }
}
