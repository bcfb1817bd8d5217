//! The stabilisation diagram's frequency axis ends on a labelled mark
//! (a band of 0 to 476.2 Hz: egui_plot's 5 % margins end the axis at
//! 500 Hz): its last tick label, centred on that mark, lies whole inside
//! the area the view draws in (half of it was cut at the view's right
//! edge). On a phone's width the axis keeps at least two painted labels.

use crate::harness::{harness_sized, settle};
use egui_kittest::Harness;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::workbench_view::DIAGRAM_PLOT_ID;
use tirecontact::gui::{App, Command, View};
use tirecontact::model::lsce::IdentifyOptions;
use tirecontact::scene::Tyre;

/// The workbench on a measured file identified over 0 to 476.2 Hz, in a
/// `size` window, once its identification is shown.
fn workbench(size: [f32; 2]) -> Harness<'static, App> {
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
        if h.state().research().workbench().is_some() && !h.state().research().workbench_computing()
        {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
        h.run_steps(1);
    }
    h.run_steps(3);
    h
}

/// The diagram's frame and its painted frequency labels (numbers just
/// under the frame), each with the rect it may be drawn in.
fn frequency_labels(
    h: &Harness<'_, App>,
) -> (egui::Rect, f64, Vec<(String, egui::Rect, egui::Rect)>) {
    let t = PlotMemory::load(&h.ctx, egui::Id::unique(DIAGRAM_PLOT_ID))
        .expect("the diagram")
        .transform();
    let frame = *t.frame();
    let labels = h
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
                    && r.right() > frame.left()
                    && r.left() < frame.right())
                .then_some((text, r, c.clip_rect))
            }
            _ => None,
        })
        .collect();
    (frame, t.bounds().max()[0], labels)
}

#[test]
fn the_diagram_keeps_its_last_frequency_label_inside_the_view() {
    for size in [[1280.0, 720.0], [1500.0, 950.0]] {
        let h = workbench(size);
        let (_, hi, labels) = frequency_labels(&h);
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

/// At a phone's width (390 px) the diagram's frequency axis shows at least
/// two labels, each whole inside the plot and the window.
#[test]
fn the_diagram_on_a_phone_labels_its_frequency_axis() {
    let size = [390.0, 844.0];
    let h = workbench(size);
    let (frame, _, labels) = frequency_labels(&h);
    let names: Vec<&str> = labels.iter().map(|(t, _, _)| t.as_str()).collect();
    assert!(
        labels.len() >= 2,
        "the frequency axis {frame:?} shows {names:?}"
    );
    for (t, r, clip) in &labels {
        assert!(
            clip.contains_rect(*r) && r.left() >= 0.0 && r.right() <= size[0],
            "the label {t:?} at {r:?} is cut (drawn in {clip:?}); labels {names:?}"
        );
        // under the frame, at its mark: within the frame's span, or half a
        // label before its left end (the mark at the axis's start)
        assert!(
            r.center().x >= frame.left() - 1.0 && r.center().x <= frame.right() + 1.0,
            "the label {t:?} at {r:?} is off the frame {frame:?}"
        );
    }
}
