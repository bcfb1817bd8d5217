//! On a patch preset the normal scene view draws one row across the tread
//! in full (the row of the classroom's chosen point) and the others faded:
//! its tyre lines run along that row only, never from the end of one row
//! back to the start of the next.

use crate::classroom::patch_rows::markers;
use crate::harness::{advance, harness_sized, shapes};
use egui::epaint::{PathShape, Shape};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::scene_view::{SCENE_PLOT_ID, rows_y_m};
use tirecontact::gui::{App, Command, View};

/// The painted open polylines of at least `min` points inside `frame`.
fn polylines(shapes: &[Shape], frame: egui::Rect, min: usize) -> Vec<Vec<egui::Pos2>> {
    shapes
        .iter()
        .filter_map(|s| match s {
            Shape::Path(PathShape {
                points,
                closed: false,
                ..
            }) if points.len() >= min && points.iter().all(|p| frame.expand(2.0).contains(*p)) => {
                Some(points.clone())
            }
            _ => None,
        })
        .collect()
}

#[test]
fn a_patch_draws_one_row_and_no_line_between_rows() {
    for file in [
        "patch_chip_seal.ron",
        "patch_texture.ron",
        "patch_wheel_path.ron",
    ] {
        let preset = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("presets")
            .join(file);
        let scene = Scene::load(&preset).unwrap();
        let n = scene.points.len();
        let rows = rows_y_m(&scene.points).len();
        assert!(rows > 1, "{file}");
        let along = n / rows;
        let mut h = harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
        h.run();
        h.state_mut().apply(Command::ShowView(View::Scene));
        h.run_steps(2);
        advance(&mut h, 3000);
        h.run_steps(2);
        let frame = *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(SCENE_PLOT_ID))
            .expect("scene plot shown")
            .transform()
            .frame();
        let all = shapes(&h);
        let (full, faded) = markers(&all, frame);
        assert_eq!(full.len(), along, "{file}: markers in full");
        assert_eq!(faded.len(), n - along, "{file}: faded markers");
        // the tyre's lines (undeformed, displaced) have the row's points
        // and run one way along x: a line through two rows turns back
        let lines = polylines(&all, frame, along);
        assert!(!lines.is_empty(), "{file}: no tyre line");
        for line in &lines {
            if line.len() > 3 * along {
                // the road (400 samples) or its fill
                continue;
            }
            assert!(
                line.windows(2).all(|w| w[1].x >= w[0].x - 0.5),
                "{file}: a line turns back along x: {line:?}"
            );
        }
    }
}
