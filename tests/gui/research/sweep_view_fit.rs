//! The sweep view: a cancelled sweep's note speaks of the scene it ran on,
//! so another document clears it, as it would a failure's, while a
//! finished sweep's results stay (they name their scene); and in a small
//! window (1280 × 720 with the mode bars) each plot's y title lies beside
//! its own frame, none running into the text above the plots.

use super::wait_sweep;
use crate::harness::{harness_sized, plot_frame, rotated_texts, settle, texts};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::sweep_view::{OTHER_SCENE_NOTE, PLOT_IDS, SHORT_Y_TITLES};
use tirecontact::gui::{App, Command, SweepState, View};
use tirecontact::studies::sweep::report::Y_TITLES;

const CANCELLED: &str = "The sweep was cancelled";

/// Opens the preset `path`, discarding edits.
fn open(h: &mut Harness<'_, App>, path: &str) {
    h.state_mut().apply(Command::OpenPath(path.into()));
    h.run_steps(1);
    h.state_mut().apply(Command::ConfirmDiscard);
    settle(h);
    h.run_steps(2);
}

/// The three-points preset (10 s long) in the sweep view, a sweep of it
/// started and cancelled.
fn cancelled_sweep() -> Harness<'static, App> {
    let mut scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    // runs far longer than the test takes to cancel
    scene.duration_s = 10.0;
    let mut h = harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
    h.run();
    h.state_mut().apply(Command::ShowView(View::Sweep));
    h.run_steps(2);
    h.get_by_label("Run sweep").click();
    h.run_steps(2);
    h.get_by_label("Cancel").click();
    wait_sweep(&mut h);
    h
}

#[test]
fn another_document_clears_a_cancelled_sweep_s_note_and_keeps_results() {
    let mut h = cancelled_sweep();
    assert!(matches!(
        h.state().research().sweep(),
        SweepState::Cancelled
    ));
    assert!(h.query_by_label_contains(CANCELLED).is_some());
    let single = Scene::load(Path::new("presets/single_mode.ron")).unwrap();
    open(&mut h, "presets/single_mode.ron");
    assert_eq!(h.state().scene().name, single.name);
    assert!(
        h.query_by_label_contains(CANCELLED).is_none(),
        "the note of the sweep cancelled on another scene stays"
    );
    assert!(matches!(h.state().research().sweep(), SweepState::Idle));
    assert!(h.query_by_label_contains("No sweep yet").is_some());

    // a finished sweep's results stay, naming their scene
    let mut short = h.state().scene().clone();
    short.duration_s = short.ramp_s + 0.05;
    h.state_mut().apply(Command::EditScene(Box::new(short)));
    h.run_steps(2);
    h.get_by_label("Run sweep").click();
    h.run_steps(1);
    wait_sweep(&mut h);
    assert!(
        matches!(h.state().research().sweep(), SweepState::Finished(_)),
        "{:?} {:?}",
        h.state().research().sweep(),
        h.state().message()
    );
    open(&mut h, "presets/three_points.ron");
    assert_ne!(h.state().scene().name, single.name);
    assert!(matches!(
        h.state().research().sweep(),
        SweepState::Finished(_)
    ));
    let named = format!("(scene “{}”)", single.name);
    assert!(h.query_by_label_contains(&named).is_some(), "{named}");
}

/// A scene edit clears a cancelled sweep's note (it speaks of the scene
/// before the edit), as another document does; finished results stay and
/// say they are of the scene as it was, until the scene is that one again.
#[test]
fn a_scene_edit_clears_a_cancelled_sweep_s_note_and_marks_results() {
    let mut h = cancelled_sweep();
    assert!(h.query_by_label_contains(CANCELLED).is_some());
    // a live edit (the speed): the run goes on, the note goes
    let mut faster = h.state().scene().clone();
    faster.speed_mps *= 1.1;
    h.state_mut().apply(Command::EditScene(Box::new(faster)));
    h.run_steps(2);
    assert!(
        h.query_by_label_contains(CANCELLED).is_none(),
        "the note of the sweep cancelled before the edit stays"
    );
    assert!(matches!(h.state().research().sweep(), SweepState::Idle));

    // finished results of the scene as it was
    let mut short = h.state().scene().clone();
    short.duration_s = short.ramp_s + 0.05;
    h.state_mut()
        .apply(Command::EditScene(Box::new(short.clone())));
    h.run_steps(2);
    h.get_by_label("Run sweep").click();
    h.run_steps(1);
    wait_sweep(&mut h);
    h.run_steps(2);
    assert!(matches!(
        h.state().research().sweep(),
        SweepState::Finished(_)
    ));
    assert!(h.query_by_label(OTHER_SCENE_NOTE).is_none());
    let mut edited = short.clone();
    edited.speed_mps *= 1.1;
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    h.run_steps(2);
    assert!(matches!(
        h.state().research().sweep(),
        SweepState::Finished(_)
    ));
    assert!(
        h.query_by_label(OTHER_SCENE_NOTE).is_some(),
        "results of the scene before the edit, not said"
    );
    h.state_mut().apply(Command::EditScene(Box::new(short)));
    h.run_steps(2);
    assert!(h.query_by_label(OTHER_SCENE_NOTE).is_none());
}

/// A short sweep of the three-points preset run to its end in the Sweep
/// view, in a window of `size`, with the mode bars or not.
fn finished_sweep(size: [f32; 2], mode_bars: bool) -> Harness<'static, App> {
    let mut scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    scene.duration_s = 0.05;
    let mut h = harness_sized(App::new(scene, None).unwrap(), size);
    h.run();
    h.state_mut().apply(Command::ShowModeBars(mode_bars));
    h.state_mut().apply(Command::ShowView(View::Sweep));
    h.run_steps(2);
    h.get_by_label("Run sweep").click();
    h.run_steps(1);
    wait_sweep(&mut h);
    h.run_steps(4);
    h
}

#[test]
fn the_sweep_plots_titles_stay_beside_their_frames() {
    let h = finished_sweep([1280.0, 720.0], true);
    let rotated = rotated_texts(&h);
    // the lowest text above the plots: the line naming the sweep
    let above = texts(&h)
        .into_iter()
        .filter(|(t, _)| t.contains("runs of speed V"))
        .map(|(_, r)| r.bottom())
        .fold(f32::NEG_INFINITY, f32::max);
    assert!(above.is_finite(), "no line naming the sweep");
    for (k, id) in PLOT_IDS.iter().enumerate() {
        let f = plot_frame(&h, id);
        let (text, r) = rotated
            .iter()
            .find(|(t, r)| {
                (t == Y_TITLES[k] || t == SHORT_Y_TITLES[k])
                    && r.right() <= f.left() + 0.5
                    && r.left() >= f.left() - 80.0
            })
            .unwrap_or_else(|| panic!("no y title of {id} beside {f:?} in {rotated:?}"));
        eprintln!("{id}: {text:?} at {r:?}, frame {f:?}");
        assert!(
            r.top() >= f.top() - 0.5 && r.bottom() <= f.bottom() + 0.5,
            "the title {text:?} of {id} spans {:.1}..{:.1} px, its frame {:.1}..{:.1} px",
            r.top(),
            r.bottom(),
            f.top(),
            f.bottom()
        );
        assert!(
            r.top() >= above,
            "{text:?} at {r:?} runs into the text above, to {above} px"
        );
    }
}

/// On a phone the four plots stack in one column inside the window (two
/// side by side ran off its right edge).
#[test]
fn on_a_phone_the_sweep_plots_stay_inside_the_window() {
    let size = [412.0, 915.0];
    let h = finished_sweep(size, false);
    let mut lefts = Vec::new();
    for id in PLOT_IDS {
        let f = plot_frame(&h, id);
        assert!(
            f.left() >= 0.0 && f.right() <= size[0],
            "{id}: frame {f:?} outside a {} px window",
            size[0]
        );
        assert!(f.width() >= 150.0, "{id}: frame {f:?} too narrow to read");
        lefts.push(f.left());
    }
    // one column: the frames one under another
    assert!(
        lefts.iter().all(|&l| (l - lefts[0]).abs() < 1.0),
        "{lefts:?}"
    );
}
