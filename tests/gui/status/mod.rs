//! The status bar names the document: a built-in preset by its name (not
//! "unsaved scene"), "unsaved changes" only after an edit.

mod fit;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tirecontact::gui::{App, Command};

#[test]
fn the_default_preset_is_named_in_the_status_bar_until_edited() {
    let app = App::with_default_preset();
    let name = app.scene().name.clone();
    let mut h = Harness::builder()
        .with_size([1500.0, 950.0])
        .build_ui_state(|ui, app: &mut App| app.show(ui), app);
    h.run_steps(2);
    assert!(
        h.query_by_label(&format!("{name} (built-in preset)"))
            .is_some()
    );
    assert!(h.query_by_label_contains("unsaved").is_none());
    assert!(
        !h.state().title().contains("unsaved"),
        "{}",
        h.state().title()
    );

    let mut edited = h.state().scene().clone();
    edited.duration_s *= 2.0;
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    h.run_steps(2);
    assert!(
        h.query_by_label_contains("(unsaved changes)").is_some(),
        "an edit is marked"
    );
}

/// The frame rate is shown while playing only: paused, frames come only on
/// input and the last rate measured (or the 0 before any) would be stale.
#[test]
fn the_frame_rate_is_shown_while_playing_only() {
    let mut app = App::with_default_preset();
    let mut scene = app.scene().clone();
    scene.duration_s = 100.0; // plays for the whole test
    app.apply(Command::EditScene(Box::new(scene)));
    let mut h = Harness::builder()
        .with_size([1500.0, 950.0])
        .build_ui_state(|ui, app: &mut App| app.show(ui), app);
    h.run_steps(2);
    assert!(h.query_by_label("– fps").is_some(), "paused at the start");
    assert!(h.query_by_label("0 fps").is_none());
    h.state_mut().apply(Command::Play);
    // a rate is measured over a second of wall time
    let measured = |h: &Harness<'_, App>| {
        use egui_kittest::kittest::NodeT;
        h.query_by_label_contains(" fps")
            .and_then(|n| {
                let a = n.accesskit_node();
                a.label().or_else(|| a.value())
            })
            .is_some_and(|t| t.starts_with(|c: char| c.is_ascii_digit()))
    };
    let start = std::time::Instant::now();
    while !measured(&h) && start.elapsed().as_secs_f64() < 20.0 {
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    assert!(measured(&h), "a rate while playing");
    h.state_mut().apply(Command::Pause);
    h.run_steps(2);
    assert!(h.query_by_label("– fps").is_some(), "paused again");
}
