//! File prompts used from the keyboard alone: a prompt takes the keyboard
//! when it opens (what is typed goes to the path, never to the single-key
//! shortcuts), Enter confirms and Escape cancels in every prompt.

use crate::harness::{harness_sized, settle};
use crate::support::temp_dir;
use egui_kittest::kittest::Queryable;
use tirecontact::Scene;
use tirecontact::gui::{App, Command, View};

/// Types `text` as keyboard input to whatever has the focus (no click).
fn type_keys(h: &mut egui_kittest::Harness<'_, App>, text: &str) {
    h.event(egui::Event::Text(text.to_owned()));
    h.run_steps(2);
}

#[test]
fn a_path_typed_after_ctrl_o_opens_the_scene_and_fires_no_shortcut() {
    let mut h = harness_sized(App::with_default_preset(), [1600.0, 1000.0]);
    settle(&mut h);
    // a run under way: a stray `r` would reset it, digits would switch views
    h.state_mut().apply(Command::Step(50));
    h.run_steps(3);
    let steps = h.state().simulation().steps();
    assert!(steps > 0);
    let view = h.state().view();
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::O);
    h.run_steps(2);
    assert!(h.state().file_prompt().is_some(), "no file prompt");
    // "presets/three_points.ron" holds an `r` and digits would be in other
    // names; the shortcuts must not see them
    type_keys(&mut h, "presets/three_points.ron");
    assert_eq!(
        h.state().file_prompt().map(|p| p.path.as_str()),
        Some("presets/three_points.ron"),
        "the typed text went elsewhere"
    );
    assert_eq!(h.state().view(), view, "a digit switched the view");
    assert!(h.state().simulation().steps() >= steps, "`r` reset the run");
    h.key_press(egui::Key::Enter);
    settle(&mut h);
    assert!(h.state().file_prompt().is_none(), "Enter did not confirm");
    assert_eq!(h.state().scene().num_points(), 3, "the preset did not open");
}

#[test]
fn digits_typed_into_save_as_stay_in_the_path() {
    let tmp = temp_dir();
    let file = tmp.path().join("run2.ron");
    let mut h = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    settle(&mut h);
    h.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::S,
    );
    h.run_steps(2);
    let p = h.state().file_prompt().expect("no Save As prompt");
    // the prompt offers a name; select it all and type over it
    assert!(!p.path.is_empty());
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    type_keys(&mut h, &file.display().to_string());
    assert_eq!(
        h.state().view(),
        View::TimePlots,
        "a digit switched the view"
    );
    h.key_press(egui::Key::Enter);
    h.run_steps(3);
    assert!(h.state().file_prompt().is_none());
    assert_eq!(
        Scene::load(&file).unwrap().num_points(),
        h.state().scene().num_points()
    );
}

#[test]
fn enter_writes_the_png_and_escape_closes_its_dialog() {
    let tmp = temp_dir();
    let png = tmp.path().join("plots.png");
    let mut h = harness_sized(App::with_default_preset(), [1600.0, 1000.0]);
    settle(&mut h);
    h.state_mut().apply(Command::Step(300));
    h.run_steps(3);
    h.state_mut().apply(Command::ExportPngDialog);
    h.run_steps(2);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    type_keys(&mut h, &png.display().to_string());
    h.key_press(egui::Key::Enter);
    h.run_steps(3);
    let bytes = std::fs::read(&png).expect("Enter wrote no PNG");
    assert_eq!(&bytes[1..4], b"PNG");

    h.state_mut().apply(Command::ExportPngDialog);
    h.run_steps(2);
    assert!(h.query_by_label("PNG file path").is_some(), "no PNG dialog");
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    assert!(
        h.query_by_label("PNG file path").is_none(),
        "Escape left the PNG dialog open"
    );
}
