//! The status bar names the document: a built-in preset by its name (not
//! "unsaved scene"), "unsaved changes" only after an edit.
#![cfg(feature = "gui")]

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
