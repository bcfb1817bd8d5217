//! Classroom mode at projector sizes (1600 × 1000, 1280 × 720): the scene's
//! description is shown whole above the mode bars (1600 × 1000) or scrolls
//! above them (1280 × 720), and the mode bars' buttons stay in the window.

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::{Path, PathBuf};
use tirecontact::Scene;
use tirecontact::gui::{App, Command};

fn classroom(name: &str, size: [f32; 2]) -> Harness<'static, App> {
    // opened from its file, as `tirecontact gui presets/…` does
    let path = PathBuf::from(format!("presets/{name}.ron"));
    let app = App::new(Scene::load(Path::new(&path)).unwrap(), Some(path)).unwrap();
    let mut h = crate::harness::harness_sized(app, size);
    h.run();
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(4);
    h
}

const SIZES: [[f32; 2]; 2] = [[1600.0, 1000.0], [1280.0, 720.0]];

/// At 1280 × 720 the description and the mode bars do not both fit: the
/// description scrolls and the bars keep their Mute buttons in the window.
#[test]
fn the_mode_bars_keep_their_buttons_in_a_small_window() {
    for size in SIZES {
        let h = classroom("guided_1a_soft_tyre", size);
        let status_top = h.get_by_label_contains("history:").rect().top();
        let mutes: Vec<egui::Rect> = h.get_all_by_label("Mute").map(|n| n.rect()).collect();
        assert_eq!(mutes.len(), 3, "{size:?}");
        for r in mutes {
            assert!(
                r.bottom() <= status_top,
                "{size:?}: Mute at {r:?}, status bar at {status_top}"
            );
        }
    }
}

#[test]
fn the_description_is_shown_whole_above_the_mode_bars() {
    {
        let size = SIZES[0];
        let h = classroom("guided_1a_soft_tyre", size);
        let d = h.state().scene().description.clone();
        let text = h.get_by_label(&d).rect();
        let below = h.get_by_label("Mode contributions").rect();
        eprintln!(
            "{size:?}: description {text:?}, next heading at {}",
            below.top()
        );
        assert!(
            text.bottom() <= below.top(),
            "{size:?}: description ends at {} px, below the mode bars' heading at {} px",
            text.bottom(),
            below.top()
        );
    }
}
