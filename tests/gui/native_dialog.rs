//! The desktop's file dialog runs on its own thread: while it is open the
//! window keeps drawing (rfd's dialogs block their caller, and called from
//! the UI they froze the app until the user answered). The dialog here is
//! a stand-in that answers only when the test lets it.

use crate::harness::harness_sized;
use egui_kittest::kittest::Queryable;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};
use tirecontact::gui::chrome::native_dialog::{self, Kind, Request};
use tirecontact::gui::{App, Command};

static ANSWER_NOW: AtomicBool = AtomicBool::new(false);
static ANSWERED: AtomicBool = AtomicBool::new(false);

/// A dialog the user takes a while to answer (until the test says, at
/// most 10 s).
fn slow_dialog(r: &Request) -> Option<PathBuf> {
    let start = Instant::now();
    while !ANSWER_NOW.load(Ordering::SeqCst) && start.elapsed() < Duration::from_secs(10) {
        std::thread::sleep(Duration::from_millis(2));
    }
    ANSWERED.store(true, Ordering::SeqCst);
    assert_eq!(r.kind, Kind::Save);
    assert_eq!(r.filter.as_ref().map(|f| f.1.as_str()), Some("ron"));
    Some(PathBuf::from("/tmp/chosen_in_the_dialog.ron"))
}

#[test]
fn the_window_keeps_drawing_while_the_file_dialog_is_open() {
    native_dialog::set_backend(slow_dialog);
    let mut h = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    h.run();
    h.state_mut().apply(Command::SaveAsDialog);
    h.run();
    let offered = h.state().file_prompt().expect("a save prompt").path.clone();
    h.get_by_label("Choose…").click();
    // frames go on while the dialog is open (its spinner keeps repainting),
    // and so does the run
    h.run_steps(2);
    h.state_mut().apply(Command::Step(10));
    h.run_steps(5);
    assert!(
        !ANSWERED.load(Ordering::SeqCst),
        "the frame waited for the dialog"
    );
    assert!(
        h.state().simulation().steps() >= 10,
        "no steps while the dialog was open"
    );
    assert_eq!(
        h.state().file_prompt().map(|p| p.path.clone()),
        Some(offered)
    );
    // the user answers: the path field takes the chosen file
    ANSWER_NOW.store(true, Ordering::SeqCst);
    let start = Instant::now();
    while h.state().file_prompt().map(|p| p.path.as_str()) != Some("/tmp/chosen_in_the_dialog.ron")
        && start.elapsed() < Duration::from_secs(10)
    {
        std::thread::sleep(Duration::from_millis(5));
        h.run_steps(1);
    }
    assert_eq!(
        h.state().file_prompt().map(|p| p.path.clone()).as_deref(),
        Some("/tmp/chosen_in_the_dialog.ron")
    );
    assert!(ANSWERED.load(Ordering::SeqCst));
}
