//! The stabilisation diagram's frequency axis ends on a labelled mark
//! (a band of 0 to 476.2 Hz: egui_plot's 5 % margins end the axis at
//! 500 Hz): its last tick label, centred on that mark, lies whole inside
//! the area the view draws in (half of it was cut at the view's right
//! edge).

use crate::harness::{harness_sized, settle};
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::workbench_view::DIAGRAM_PLOT_ID;
use tirecontact::gui::{App, Command, View};
use tirecontact::model::lsce::IdentifyOptions;
use tirecontact::scene::Tyre;

#[test]
fn the_diagram_keeps_its_last_frequency_label_inside_the_view() {
    for size in [[1280.0, 720.0], [1500.0, 950.0]] {
        let mut s = Scene::load(Path::new("presets/three_points.ron")).unwrap();
        s.tyre = Tyre::Measured {
            file: std::fs::canonicalize("tests/data/uff/time3.uff").unwrap(),
            identification: IdentifyOptions {
                band_hz: (0.0, 476.2),
                duration_s: 0.5,
                ..IdentifyOptions::default()
            },
            nodes: Vec::new(),
        };
        let mut h = harness_sized(App::new(s, None).unwrap(), size);
        settle(&mut h);
        h.state_mut().apply(Command::ShowView(View::Workbench));
        h.run_steps(1);
        for _ in 0..20_000 {
            if h.state().research().workbench().is_some()
                && !h.state().research().workbench_computing()
            {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(2));
            h.run_steps(1);
        }
        h.run_steps(3);
        let t = PlotMemory::load(&h.ctx, egui::Id::unique(DIAGRAM_PLOT_ID))
            .expect("the diagram")
            .transform();
        let frame = *t.frame();
        let hi = t.bounds().max()[0];
        // the tick labels under the frame, with where they may be drawn
        let labels: Vec<(String, egui::Rect, egui::Rect)> = h
            .output()
            .shapes
            .iter()
            .filter_map(|c| match &c.shape {
                egui::Shape::Text(t) => {
                    let r = t.visual_bounding_rect();
                    let text = t.galley.text().to_owned();
                    (text.parse::<f64>().is_ok()
                        && r.top() >= frame.bottom()
                        && r.top() <= frame.bottom() + 30.0
                        && r.center().x > frame.left())
                    .then_some((text, r, c.clip_rect))
                }
                _ => None,
            })
            .collect();
        let (last, r, clip) = labels
            .iter()
            .max_by(|a, b| a.1.center().x.total_cmp(&b.1.center().x))
            .unwrap_or_else(|| panic!("{size:?}: no frequency labels"));
        assert!(
            (last.parse::<f64>().unwrap() - hi).abs() < 0.05 * hi,
            "{size:?}: the last label {last:?} is not at the axis's end {hi} Hz"
        );
        assert!(
            clip.contains_rect(*r),
            "{size:?}: the last label {last:?} at {r:?} is cut by the view at {clip:?}"
        );
    }
}
