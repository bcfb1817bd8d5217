//! Undo and redo of scene edits: by the keys, the File menu and the buttons
//! beside the edits; a live edit and one that restarts the run; the fields
//! show the scene given back; the unsaved marker follows; a new document
//! starts with nothing to undo.

use crate::harness::{harness, texts, type_into};
use egui_kittest::kittest::{NodeT, Queryable};
use tirecontact::Scene;
use tirecontact::gui::{App, Command};

fn three_points_scene() -> Scene {
    let path = format!("{}/presets/three_points.ron", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    Scene::parse(&text, &path).unwrap()
}

fn three_points() -> App {
    App::new(three_points_scene(), None).unwrap()
}

/// The text the field `name` shows.
fn shown(h: &egui_kittest::Harness<'_, App>, name: &str) -> String {
    h.get_by_label(name).value().unwrap_or_default()
}

fn ctrl(h: &mut egui_kittest::Harness<'_, App>, shift: bool, key: egui::Key) {
    let m = if shift {
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT
    } else {
        egui::Modifiers::COMMAND
    };
    h.key_press_modifiers(m, key);
    h.run();
    h.run();
}

#[test]
fn the_keys_take_edits_back_and_make_them_again() {
    let mut h = harness(three_points());
    h.run();
    let v0 = h.state().scene().speed_mps;
    let dt0 = h.state().scene().dt_s;
    assert!(!h.state().is_dirty());
    // a live edit (speed), then one that restarts the run (time step)
    type_into(&mut h, "speed_mps", &format!("{}", 2.0 * v0));
    // (the field is in µs)
    type_into(&mut h, "dt_s", &format!("{}", dt0 * 1e6 / 2.0));
    let dt1 = h.state().scene().dt_s;
    assert!((dt1 - dt0 / 2.0).abs() < 1e-12, "{dt1}");
    // (Enter took the focus off the field: the keys are the app's)

    ctrl(&mut h, false, egui::Key::Z);
    assert_eq!(h.state().scene().dt_s, dt0, "Ctrl+Z: the time step back");
    assert_eq!(h.state().scene().speed_mps, 2.0 * v0, "only the last edit");
    assert_eq!(
        h.state().simulation().dt_s(),
        dt0,
        "the run restarted on it"
    );
    let field_s = shown(&h, "dt_s").parse::<f64>().unwrap() * 1e-6;
    assert!((field_s - dt0).abs() < 1e-12, "the field shows {field_s} s");

    ctrl(&mut h, false, egui::Key::Z);
    assert_eq!(h.state().scene().speed_mps, v0);
    assert_eq!(shown(&h, "speed_mps").parse::<f64>().unwrap(), v0);
    assert!(!h.state().is_dirty(), "every edit undone: nothing unsaved");

    // nothing left to undo: the scene stays
    ctrl(&mut h, false, egui::Key::Z);
    assert_eq!(h.state().scene().speed_mps, v0);

    ctrl(&mut h, true, egui::Key::Z);
    assert_eq!(h.state().scene().speed_mps, 2.0 * v0, "Ctrl+Shift+Z redoes");
    ctrl(&mut h, false, egui::Key::Y);
    assert_eq!(h.state().scene().dt_s, dt1, "and Ctrl+Y");
    assert!(h.state().is_dirty());
}

#[test]
fn the_menu_and_the_buttons_say_what_they_would_change() {
    let mut h = harness(three_points());
    h.run();
    // before any edit: Undo disabled in the File menu and beside the edits
    h.get_by_label("File").click();
    h.run();
    let undos: Vec<bool> = h
        .query_all_by_label_contains("Undo")
        .map(|n| n.accesskit_node().is_disabled())
        .collect();
    assert!(undos.len() == 2 && undos.iter().all(|&d| d), "{undos:?}");
    h.key_press(egui::Key::Escape);
    h.run();
    let v0 = h.state().scene().speed_mps;
    type_into(&mut h, "speed_mps", &format!("{}", 3.0 * v0));
    let said = format!("Undo speed V {v0} -> {} m/s", 3.0 * v0);
    h.get_by_label("File").click();
    h.run();
    assert!(
        texts(&h).iter().any(|(t, _)| t == &said),
        "the File menu does not say {said:?}"
    );
    h.get_by_label_contains(&said).click();
    h.run();
    h.run();
    assert_eq!(h.state().scene().speed_mps, v0, "the menu's Undo");
    // the buttons beside the edits: Redo now
    let redo = h
        .query_all_by_label_contains("Redo")
        .find(|n| !n.accesskit_node().is_disabled())
        .expect("an enabled Redo beside the edits");
    redo.click();
    h.run();
    h.run();
    assert_eq!(h.state().scene().speed_mps, 3.0 * v0, "the button's Redo");
}

#[test]
fn a_new_document_has_nothing_to_undo() {
    let mut h = harness(three_points());
    h.run();
    let v0 = h.state().scene().speed_mps;
    type_into(&mut h, "speed_mps", &format!("{}", 2.0 * v0));
    h.state_mut().apply(Command::OpenPreset(0));
    h.run();
    h.state_mut().apply(Command::ConfirmDiscard);
    h.run();
    let opened = h.state().scene().clone();
    h.state_mut().apply(Command::Undo);
    h.run();
    assert_eq!(
        *h.state().scene(),
        opened,
        "the edit of the other file stays there"
    );
}

/// A mute is a scene edit: undone and redone with the mode bars' marks
/// (the tyre with zeroed modes came back with no mode marked muted, and
/// un-muting could not give the original back).
#[test]
fn mutes_are_undone_and_redone_with_their_marks() {
    // (tread springs: a mute of rigid contact is refused)
    let mut scene = three_points_scene();
    scene.contact = tirecontact::scene::Contact::Compliant {
        stiffness_n_m: vec![2.0e5],
    };
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    let original = h.state().scene().tyre.clone();
    h.state_mut().apply(Command::ToggleMute(0));
    h.run();
    h.state_mut().apply(Command::ToggleMute(1));
    h.run();
    let muted = |h: &egui_kittest::Harness<'_, App>| h.state().mutes().map(|m| m.muted.clone());
    assert_eq!(muted(&h), Some(vec![true, true, false]));
    h.state_mut().apply(Command::Undo);
    h.run();
    assert_eq!(
        muted(&h),
        Some(vec![true, false, false]),
        "the second mute undone"
    );
    assert_eq!(
        h.state().mutes().map(|m| &m.tyre),
        Some(&h.state().scene().tyre),
        "the marks are those of the tyre"
    );
    h.state_mut().apply(Command::Undo);
    h.run();
    assert_eq!(muted(&h), None);
    assert_eq!(h.state().scene().tyre, original);
    h.state_mut().apply(Command::Redo);
    h.run();
    assert_eq!(
        muted(&h),
        Some(vec![true, false, false]),
        "the first mute again"
    );
    // and un-muting gives the original tyre back
    h.state_mut().apply(Command::UnmuteAll);
    h.run();
    assert_eq!(h.state().scene().tyre, original);
}

/// Undo and redo past a Save As into another folder keep the document's
/// folder (relative road files are read from it): the scene given back is
/// the edit's, its folder where the document is saved now.
#[test]
fn undo_past_a_save_as_keeps_the_folder_of_the_document() {
    let tmp = crate::support::temp_dir();
    let (old_dir, new_dir) = (tmp.path().join("old"), tmp.path().join("new"));
    std::fs::create_dir(&old_dir).unwrap();
    std::fs::create_dir(&new_dir).unwrap();
    let mut scene = three_points_scene();
    scene.base_dir = Some(old_dir.clone());
    let mut h = harness(App::new(scene.clone(), None).unwrap());
    h.run();
    let mut faster = scene.clone();
    faster.speed_mps *= 2.0;
    h.state_mut().apply(Command::EditScene(Box::new(faster)));
    h.run();
    h.state_mut()
        .apply(Command::SavePath(new_dir.join("moved.ron")));
    h.run_steps(2);
    assert_eq!(
        h.state().scene().base_dir.as_deref(),
        Some(new_dir.as_path())
    );

    h.state_mut().apply(Command::Undo);
    h.run_steps(2);
    assert_eq!(
        h.state().scene().speed_mps,
        scene.speed_mps,
        "the edit undone"
    );
    assert_eq!(
        h.state().scene().base_dir.as_deref(),
        Some(new_dir.as_path()),
        "the undo brought back the folder of before the Save As"
    );
    h.state_mut().apply(Command::Redo);
    h.run_steps(2);
    assert_eq!(h.state().scene().speed_mps, 2.0 * scene.speed_mps, "redone");
    assert_eq!(
        h.state().scene().base_dir.as_deref(),
        Some(new_dir.as_path())
    );
    // the undo and the redo moved along the stacks (no new edit of their own)
    assert!(!h.state().is_dirty(), "the saved scene, redone");
}

/// A save writes the edits into the description; an undo past the save
/// takes back the edit and keeps the description the save wrote (it gave
/// back the text of before the save, the saved lines gone without a
/// word), and a second save adds the undone change after them. A redo
/// gives back the saved scene.
#[test]
fn undo_past_a_save_keeps_the_description_it_wrote() {
    let tmp = crate::support::temp_dir();
    let path = tmp.path().join("faster.ron");
    let mut h = harness(three_points());
    h.run();
    let v0 = h.state().scene().speed_mps;
    let opened = h.state().scene().description.clone();
    type_into(&mut h, "speed_mps", &format!("{}", 2.0 * v0));
    h.state_mut().apply(Command::SavePath(path.clone()));
    h.run_steps(2);
    let saved = Scene::load(&path).unwrap().description;
    assert_ne!(
        saved, opened,
        "the save wrote the edit into the description"
    );
    assert_eq!(h.state().scene().description, saved);

    ctrl(&mut h, false, egui::Key::Z);
    assert_eq!(h.state().scene().speed_mps, v0, "the edit undone");
    assert_eq!(
        h.state().scene().description,
        saved,
        "the undo took back the description the save wrote"
    );
    assert!(h.state().is_dirty(), "the undone edit is unsaved");
    // saved again: the text of the first save, then the undone change
    h.state_mut().apply(Command::SavePath(path.clone()));
    h.run_steps(2);
    let again = Scene::load(&path).unwrap().description;
    let undone = format!("speed V {} -> {v0} m/s", 2.0 * v0);
    assert!(
        again.starts_with(saved.trim_end()) && again.contains(&undone),
        "{again:?}"
    );

    ctrl(&mut h, true, egui::Key::Z);
    assert_eq!(h.state().scene().speed_mps, 2.0 * v0, "redone");
    assert_eq!(h.state().scene().description, again);
}
