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

/// Types `text` as a keyboard does: per character its key goes down, the
/// character is entered, the key goes up (so a prompt that did not take
/// the keyboard lets `r` reset the run and digits switch the view).
fn keystrokes(h: &mut egui_kittest::Harness<'_, App>, text: &str) {
    for c in text.chars() {
        let key = egui::Key::from_name(&c.to_uppercase().to_string());
        let ev = |pressed| egui::Event::Key {
            key: key.expect("a letter or digit"),
            physical_key: None,
            pressed,
            repeat: false,
            modifiers: egui::Modifiers::NONE,
        };
        h.event(ev(true));
        h.event(egui::Event::Text(c.to_string()));
        h.event(ev(false));
        h.run_steps(1);
    }
    h.run_steps(1);
}

/// The text of the field named `name` (its accessible value).
fn field_text(h: &egui_kittest::Harness<'_, App>, name: &str) -> Option<String> {
    h.query_by_label(name).and_then(|n| n.value())
}

/// Every prompt (the file prompts of Open, Save As, the exports and the
/// research tools; the PNG and the animation-frames dialogs; the
/// unsaved-changes question): it takes the keyboard when it opens, with
/// its offered text selected (what is typed replaces it and fires no
/// shortcut), Escape closes it, and Enter confirms it.
#[test]
fn every_prompt_takes_the_keyboard_enter_confirms_and_escape_cancels() {
    use tirecontact::gui::ResearchCommand as R;
    let tmp = temp_dir();
    let mut h = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    settle(&mut h);
    let view = h.state().view();
    // what, how it opens, its text field, the file Enter confirms
    let prompts: Vec<(&str, Command, &str, &str)> = vec![
        ("open", Command::OpenDialog, "file path", ""),
        ("save as", Command::SaveAsDialog, "file path", "saved.ron"),
        (
            "CSV export",
            Command::ExportCsvDialog,
            "file path",
            "run.csv",
        ),
        (
            "PNG export",
            Command::ExportPngDialog,
            "PNG file path",
            "plots.png",
        ),
        (
            "animation frames",
            Command::ExportFramesDialog,
            "frames folder",
            "frames",
        ),
        (
            "sweep CSV",
            Command::Research(R::ExportSweepCsvDialog),
            "file path",
            "s.csv",
        ),
        (
            "sweep PNG",
            Command::Research(R::ExportSweepPngDialog),
            "file path",
            "s.png",
        ),
        (
            "pinned CSV",
            Command::Research(R::ExportPinnedCsvDialog),
            "file path",
            "p.csv",
        ),
        (
            "modal preset",
            Command::Research(R::WorkbenchSaveDialog),
            "file path",
            "m.ron",
        ),
    ];
    for (what, open, field, file) in &prompts {
        // a run under way: a stray `r` would reset it, `2` show the scene
        h.state_mut().apply(Command::Step(40));
        h.run_steps(3);
        let steps = h.state().simulation().steps();
        // typed at once: replaces the offered text, no shortcut fires
        h.state_mut().apply(open.clone());
        h.run_steps(2);
        assert!(h.state().prompt_open(), "{what}: no prompt");
        keystrokes(&mut h, "r2");
        assert_eq!(
            field_text(&h, field).as_deref(),
            Some("r2"),
            "{what}: the typed keys did not replace the offered text"
        );
        assert_eq!(h.state().view(), view, "{what}: `2` switched the view");
        assert!(
            h.state().simulation().steps() >= steps,
            "{what}: `r` reset the run"
        );
        // Escape cancels
        h.key_press(egui::Key::Escape);
        h.run_steps(2);
        assert!(!h.state().prompt_open(), "{what}: Escape left it open");
        assert!(field_text(&h, field).is_none(), "{what}: still shown");
        // Enter confirms (a path in the temporary folder)
        h.state_mut().apply(open.clone());
        h.run_steps(2);
        let target = if *what == "open" {
            "presets/three_points.ron".to_string()
        } else {
            tmp.path().join(file).display().to_string()
        };
        h.event(egui::Event::Text(target.clone()));
        h.run_steps(1);
        assert_eq!(field_text(&h, field), Some(target.clone()), "{what}");
        h.key_press(egui::Key::Enter);
        h.run_steps(3);
        assert!(!h.state().prompt_open(), "{what}: Enter did not confirm");
        if *what == "animation frames" {
            assert!(h.state().exporting_frames(), "Enter started no export");
            h.state_mut().apply(Command::CancelFrames);
            let _ = h.state_mut().wait_frames_export();
        }
        settle(&mut h);
        if ["save as", "PNG export"].contains(what) {
            assert!(
                std::path::Path::new(&target).exists(),
                "{what}: not written"
            );
        }
    }
    assert_eq!(h.state().scene().num_points(), 3, "Open did not open");

    // the unsaved-changes question: Escape keeps the changes
    let mut edited = h.state().scene().clone();
    edited.speed_mps *= 1.5;
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    settle(&mut h);
    assert!(h.state().is_dirty());
    h.state_mut().apply(Command::New);
    h.run_steps(2);
    assert!(h.state().pending_confirmation().is_some(), "no question");
    keystrokes(&mut h, "r2");
    assert_eq!(h.state().view(), view, "`2` switched the view under it");
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    assert!(
        h.state().pending_confirmation().is_none(),
        "Escape left the question open"
    );
    assert!(h.state().is_dirty(), "Escape discarded the changes");
}

/// After a refused path (a folder) Enter shows why in the prompt and the
/// path field keeps the keyboard: retyping edits the path, not the run.
#[test]
fn a_refused_path_keeps_the_keyboard_in_the_prompt() {
    let tmp = temp_dir();
    let mut h = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    settle(&mut h);
    h.state_mut().apply(Command::Step(40));
    h.run_steps(3);
    let steps = h.state().simulation().steps();
    let view = h.state().view();
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::O);
    h.run_steps(2);
    let folder = tmp.path().display().to_string();
    h.event(egui::Event::Text(folder.clone()));
    h.run_steps(1);
    h.key_press(egui::Key::Enter);
    h.run_steps(3);
    let p = h.state().file_prompt().expect("a folder closed the prompt");
    assert!(p.note.as_deref().is_some_and(|n| n.contains("is a folder")));
    keystrokes(&mut h, "r2");
    assert_eq!(
        h.state().file_prompt().map(|p| p.path.clone()),
        Some(format!("{folder}r2")),
        "the retyped keys went elsewhere"
    );
    assert_eq!(h.state().view(), view, "`2` switched the view");
    assert!(h.state().simulation().steps() >= steps, "`r` reset the run");
}

/// Save As into a folder that does not exist is refused in the prompt,
/// which stays open with the path as typed and says why; nothing is
/// written and the scene stays unsaved.
#[test]
fn save_as_into_a_missing_folder_keeps_the_prompt_and_the_path() {
    let tmp = temp_dir();
    let mut h = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    settle(&mut h);
    h.state_mut().apply(Command::SaveAsDialog);
    h.run_steps(2);
    let typed = tmp
        .path()
        .join("nodir")
        .join("p1.ron")
        .display()
        .to_string();
    h.event(egui::Event::Text(typed.clone()));
    h.run_steps(1);
    h.key_press(egui::Key::Enter);
    h.run_steps(3);
    let p = h
        .state()
        .file_prompt()
        .expect("a missing folder closed the prompt");
    assert_eq!(p.path, typed);
    assert!(
        p.note.as_deref().is_some_and(|n| n.contains("no folder")),
        "{:?}",
        p.note
    );
    assert!(!tmp.path().join("nodir").exists());
}
