//! The spectra's marker labels (the road excitation harmonics' and the
//! modal frequencies') never lie over one another, with a mode close to a
//! harmonic, on every frame: the first ones showing the spectra, the one
//! right after a zoom of the frequencies (out, then in) and after the
//! window changed size. Placed by the plot's transform of the frame before,
//! the labels kept the gaps of the scale before a zoom out and overlapped
//! in the frame drawn after it.

use crate::harness::{advance, harness_sized, plot_frame};
use egui::{Rect, Shape};
use egui_kittest::Harness;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::spectra_view::PLOT_IDS;
use tirecontact::gui::{App, Command, View};
use tirecontact::scene::Tyre;

/// The painted marker labels ("V/λ 100 Hz", "2V/λ", "f0", …) and their
/// rects.
fn marker_labels(h: &Harness<'_, App>) -> Vec<(String, Rect)> {
    crate::harness::shapes(h)
        .into_iter()
        .filter_map(|s| match s {
            Shape::Text(t) => {
                let s = t.galley.text().to_owned();
                let mode = s
                    .strip_prefix('f')
                    .is_some_and(|k| k.parse::<u32>().is_ok());
                let harmonic = s.starts_with("V/λ ")
                    || s.strip_suffix("V/λ")
                        .is_some_and(|n| n.parse::<u32>().is_ok());
                (mode || harmonic).then(|| (s, t.visual_bounding_rect()))
            }
            _ => None,
        })
        .collect()
}

/// No two marker labels of the last frame intersect; returns how many
/// there were.
fn apart(h: &Harness<'_, App>, when: &str) -> usize {
    let labels = marker_labels(h);
    for (i, (a, ra)) in labels.iter().enumerate() {
        for (b, rb) in &labels[i + 1..] {
            assert!(
                !ra.intersects(*rb),
                "{when}: {a:?} at {ra:?} over {b:?} at {rb:?}"
            );
        }
    }
    labels.len()
}

#[test]
fn marker_labels_never_overlap_even_in_the_frame_after_a_zoom() {
    let mut scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    // modes at 80, 205 and 300 Hz beside the harmonics of 100 Hz
    let Tyre::Modal { modes } = &mut scene.tyre else {
        panic!("three_points has a modal tyre")
    };
    modes[1].freq_hz = 205.0;
    let mut h = harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
    h.run();
    advance(&mut h, 12_000);
    h.state_mut().apply(Command::ShowView(View::Spectra));
    let mut shown = 0;
    for frame in 0..2_000 {
        h.run_steps(1);
        if apart(&h, &format!("frame {frame}")) > 0 {
            shown += 1;
            if shown == 3 {
                break;
            }
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    assert_eq!(shown, 3, "no marker labels painted");
    let labels = marker_labels(&h);
    for want in ["V/λ 100 Hz", "f1", "f2"] {
        assert!(
            labels.iter().any(|(t, _)| t == want),
            "{want} not labelled: {labels:?}"
        );
    }
    // the wheel with Ctrl over the force plot zooms its frequencies
    let frame = plot_frame(&h, PLOT_IDS[0]);
    h.hover_at(frame.center());
    h.run_steps(1);
    for (zoom, what) in [(0.4, "out"), (3.0, "in")] {
        h.event(egui::Event::Zoom(zoom));
        for k in 0..3 {
            h.run_steps(1);
            let n = apart(&h, &format!("zoomed {what}, frame {k}"));
            assert!(n > 0, "zoomed {what}, frame {k}: no labels");
        }
    }
    // a smaller window: smaller plots
    h.set_size(egui::vec2(1000.0, 560.0));
    for k in 0..3 {
        h.run_steps(1);
        assert!(apart(&h, &format!("resized, frame {k}")) > 0);
    }
}
