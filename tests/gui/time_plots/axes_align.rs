//! The stacked time plots keep one plot width whatever their tick labels:
//! a force axis labelled `1 000 000` N beside displacement in mm used to
//! push the force plot's frame right, so its time axis no longer lined up
//! with the others'.

use crate::harness::{advance, curves, harness_sized, texts};
use tirecontact::Scene;
use tirecontact::gui::views::point_color;
use tirecontact::gui::{App, Command};

/// Right edges (px) of the y axes' tick labels: numbers centred left of the
/// leftmost frame, whose right edges several labels share (an axis's labels
/// are stacked, right-aligned at its frame). One edge when the frames line
/// up.
fn y_label_right_edges(h: &egui_kittest::Harness<'_, App>) -> Vec<f32> {
    let left = curves(h, &[point_color(0)], 2)
        .concat()
        .iter()
        .map(|p| p.x)
        .fold(f32::INFINITY, f32::min);
    let edges: Vec<f32> = texts(h)
        .into_iter()
        .filter(|(t, r)| {
            // (the side panel's fields are numbers too, further left)
            // (the time labels are centred on ticks inside the frames)
            r.min.x >= left - 150.0
                && r.center().x < left - 1.0
                && t.replace([' ', '-'], "").parse::<f64>().is_ok()
        })
        .map(|(_, r)| r.max.x)
        .collect();
    edges
        .iter()
        .copied()
        .filter(|e| edges.iter().filter(|f| (*f - e).abs() <= 3.0).count() >= 2)
        .collect()
}

#[test]
fn time_axes_line_up_when_one_plot_has_wide_tick_labels() {
    let mut scene = Scene::load(std::path::Path::new("presets/single_mode.ron")).unwrap();
    // overdamped and stiff: contact forces of about a meganewton
    if let tirecontact::scene::Tyre::Modal { modes } = &mut scene.tyre {
        modes[0].freq_hz = 1000.0;
        modes[0].damping_ratio = 2.0;
    }
    let mut h = harness_sized(App::new(scene, None).unwrap(), [1500.0, 950.0]);
    // past the ramp, at the largest forces (about 1.2 MN)
    advance(&mut h, 99_000);
    h.state_mut().apply(Command::Pause);
    h.run_steps(3);
    let edges = y_label_right_edges(&h);
    let labels: Vec<String> = texts(&h).into_iter().map(|(t, _)| t).collect();
    assert!(
        labels.iter().any(|t| t.ends_with(" 000")),
        "force labels of hundreds of kN, grouped: {labels:?}"
    );
    assert!(
        edges.len() >= 6,
        "tick labels of three value axes: {edges:?}"
    );
    let spread = edges.iter().fold(0.0f32, |m, &x| m.max(x))
        - edges.iter().fold(f32::INFINITY, |m, &x| m.min(x));
    // (labels end within a few px of their axis: glyph rounding)
    assert!(spread <= 4.0, "y axes end {spread} px apart: {edges:?}");
}
