//! Classroom mode's scene plot labels its height axis: at 1280 × 720 the
//! plot (about 185 px high) had eight height steps, closer than a label in
//! classroom text, and egui_plot drew no y tick label at all. Read from the
//! painted text shapes: at least two numeric labels left of the frame, in
//! order, apart, and the axis title with its unit.

use crate::harness::{advance, texts};
use egui::Rect;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::scene_view::SCENE_PLOT_ID;
use tirecontact::gui::{App, Command};

fn check(preset: &str, size: [f32; 2]) {
    let scene = Scene::load(&Path::new("presets").join(preset)).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), size);
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(4);
    advance(&mut h, 3_000);
    h.run_steps(4);
    let frame = *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(SCENE_PLOT_ID))
        .expect("scene plot shown")
        .transform()
        .frame();
    let all = texts(&h);
    // numbers right-aligned against the frame's left edge, beside it
    let mut ticks: Vec<(f64, Rect)> = all
        .iter()
        .filter(|(_, r)| {
            r.right() <= frame.left() + 1.0
                && r.right() >= frame.left() - 12.0
                && r.center().y >= frame.top() - 1.0
                && r.center().y <= frame.bottom() + 1.0
        })
        .filter_map(|(t, r)| {
            t.replace('−', "-")
                .trim()
                .parse::<f64>()
                .ok()
                .map(|v| (v, *r))
        })
        .collect();
    ticks.sort_by(|a, b| a.1.center().y.total_cmp(&b.1.center().y));
    eprintln!(
        "{preset} {size:?}: scene frame {:.0} px high; height labels {:?}",
        frame.height(),
        ticks.iter().map(|t| t.0).collect::<Vec<_>>()
    );
    assert!(
        ticks.len() >= 2,
        "{preset} {size:?}: {} height labels in a {:.0} px frame",
        ticks.len(),
        frame.height()
    );
    for w in ticks.windows(2) {
        // higher on the screen, higher values; no two labels overlap
        assert!(w[0].0 > w[1].0, "{preset} {size:?}: {ticks:?}");
        assert!(
            w[0].1.bottom() <= w[1].1.top(),
            "{preset} {size:?}: {ticks:?}"
        );
    }
    // equal steps between labels (a linear axis in true mm)
    let steps: Vec<f64> = ticks.windows(2).map(|w| w[0].0 - w[1].0).collect();
    assert!(
        steps
            .iter()
            .all(|s| (s - steps[0]).abs() <= 1e-6 * steps[0].abs()),
        "{steps:?}"
    );
    // the title, with its unit, beside the labels
    assert!(
        all.iter().any(|(t, r)| t.contains("height (mm)")
            && r.right() <= frame.left()
            && r.center().y > frame.top()
            && r.center().y < frame.bottom()),
        "{preset} {size:?}: no height title with its unit"
    );
}

#[test]
fn the_classroom_scene_labels_its_height_axis() {
    for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
        for preset in [
            "paper.ron",
            "single_mode.ron",
            "three_points.ron",
            "guided_1a_soft_tyre.ron",
        ] {
            check(preset, size);
        }
    }
}

/// The classroom scene plot's position axis: at least three numbers under
/// the frame, increasing to the right, not overlapping.
#[test]
fn the_classroom_scene_labels_its_position_axis() {
    for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
        for preset in ["paper.ron", "three_points.ron"] {
            let scene = Scene::load(&Path::new("presets").join(preset)).unwrap();
            let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), size);
            h.state_mut().apply(Command::SetClassroom(true));
            h.run_steps(4);
            advance(&mut h, 1_000);
            h.run_steps(4);
            let frame = *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(SCENE_PLOT_ID))
                .expect("scene plot shown")
                .transform()
                .frame();
            let mut ticks: Vec<(f64, Rect)> = texts(&h)
                .into_iter()
                .filter(|(_, r)| {
                    r.top() >= frame.bottom() - 1.0
                        && r.top() <= frame.bottom() + 30.0
                        && r.center().x >= frame.left() - 20.0
                        && r.center().x <= frame.right() + 20.0
                })
                .filter_map(|(t, r)| {
                    t.replace('−', "-")
                        .trim()
                        .parse::<f64>()
                        .ok()
                        .map(|v| (v, r))
                })
                .collect();
            ticks.sort_by(|a, b| a.1.center().x.total_cmp(&b.1.center().x));
            assert!(
                ticks.len() >= 3,
                "{preset} {size:?}: position labels {:?}",
                ticks.iter().map(|t| t.0).collect::<Vec<_>>()
            );
            for w in ticks.windows(2) {
                assert!(
                    w[0].0 < w[1].0 && w[0].1.right() <= w[1].1.left(),
                    "{ticks:?}"
                );
            }
        }
    }
}
