//! Save As: it offers the folder of the last file opened or saved (else the
//! working directory), its offered name is selected (typing replaces it),
//! and a save over a preset shipped with the app asks first.

use crate::harness::{harness_sized, settle};
use crate::support::temp_dir;
use egui_kittest::kittest::Queryable;
use tirecontact::Scene;
use tirecontact::gui::{App, Command};

fn save_as_offer(h: &mut egui_kittest::Harness<'_, App>) -> String {
    h.state_mut().apply(Command::SaveAsDialog);
    h.run_steps(2);
    let p = h
        .state()
        .file_prompt()
        .expect("no Save As prompt")
        .path
        .clone();
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    p
}

#[test]
fn save_as_offers_the_folder_of_the_last_file() {
    let tmp = temp_dir();
    let mut h = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    settle(&mut h);
    // no file yet: a bare name, in the working directory
    let offer = save_as_offer(&mut h);
    assert!(!offer.contains(std::path::MAIN_SEPARATOR), "{offer}");
    // saved into a folder, then a new scene: Save As offers that folder
    let dir = tmp.path().join("mine");
    std::fs::create_dir(&dir).unwrap();
    h.state_mut()
        .apply(Command::SavePath(dir.join("first.ron")));
    h.run_steps(2);
    assert!(dir.join("first.ron").is_file());
    h.state_mut().apply(Command::New);
    settle(&mut h);
    assert!(!h.state().scene().name.is_empty());
    let offer = save_as_offer(&mut h);
    assert_eq!(
        std::path::Path::new(&offer).parent(),
        Some(dir.as_path()),
        "{offer}"
    );
    // typing replaces the offered name (it is selected)
    h.state_mut().apply(Command::SaveAsDialog);
    h.run_steps(2);
    let typed = tmp.path().join("typed.ron").display().to_string();
    h.event(egui::Event::Text(typed.clone()));
    h.run_steps(1);
    assert_eq!(h.state().file_prompt().map(|p| p.path.clone()), Some(typed));
}

/// A folder named `presets` holding one of the shipped presets, with a
/// copy of `three_points.ron` in it.
fn shipped_copy(tmp: &std::path::Path) -> std::path::PathBuf {
    let presets = tmp.join("presets");
    std::fs::create_dir(&presets).unwrap();
    let file = presets.join("three_points.ron");
    std::fs::copy("presets/three_points.ron", &file).unwrap();
    file
}

#[test]
fn a_save_over_a_shipped_preset_asks_first() {
    let tmp = temp_dir();
    let file = shipped_copy(tmp.path());
    let before = std::fs::read_to_string(&file).unwrap();
    let mut h = harness_sized(App::with_default_preset(), [1600.0, 1000.0]);
    settle(&mut h);
    h.state_mut().apply(Command::OpenPath(file.clone()));
    settle(&mut h);
    assert_eq!(h.state().scene().num_points(), 3);
    let mut edited = h.state().scene().clone();
    edited.speed_mps *= 1.5;
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    settle(&mut h);
    // Save (to the opened file): the question, and the file untouched
    h.state_mut().apply(Command::Save);
    h.run_steps(2);
    assert!(h.state().prompt_open(), "no question before the overwrite");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), before);
    // Escape keeps the file
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    assert!(!h.state().prompt_open(), "Escape left the question open");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), before);
    assert!(h.state().is_dirty());
    // asked again, Overwrite writes it
    h.state_mut().apply(Command::Save);
    h.run_steps(2);
    h.state_mut().apply(Command::ConfirmOverwrite);
    h.run_steps(2);
    assert!(!h.state().is_dirty());
    let saved = Scene::load(&file).unwrap();
    assert_eq!(saved.speed_mps, h.state().scene().speed_mps);
    // a file elsewhere is saved without a question
    let other = tmp.path().join("other.ron");
    std::fs::copy(&file, &other).unwrap();
    h.state_mut().apply(Command::SavePath(other.clone()));
    h.run_steps(2);
    assert!(!h.state().prompt_open());
}

/// Save As from the question about a shipped preset offers the preset's
/// name in the user's folder (the home folder before any other), never the
/// shipped file: offered again, Enter asked the same question in a loop.
#[test]
fn save_as_from_the_shipped_question_offers_the_users_folder() {
    let tmp = temp_dir();
    let file = shipped_copy(tmp.path());
    let before = std::fs::read_to_string(&file).unwrap();
    let mut h = harness_sized(App::with_default_preset(), [1600.0, 1000.0]);
    settle(&mut h);
    let open_edit_save = |h: &mut egui_kittest::Harness<'_, App>| {
        h.state_mut().apply(Command::OpenPath(file.clone()));
        settle(h);
        let mut edited = h.state().scene().clone();
        edited.speed_mps *= 1.5;
        h.state_mut().apply(Command::EditScene(Box::new(edited)));
        settle(h);
        h.state_mut().apply(Command::Save);
        h.run_steps(2);
        assert!(h.state().prompt_open(), "no question before the overwrite");
        h.get_by_label("Save as…").click();
        h.run_steps(2);
        h.state()
            .file_prompt()
            .expect("no Save As prompt")
            .path
            .clone()
    };
    // nothing saved yet: the home folder
    let offer = open_edit_save(&mut h);
    assert_ne!(std::path::Path::new(&offer), file.as_path());
    if let Some(home) = std::env::home_dir() {
        assert_eq!(std::path::Path::new(&offer), home.join("three_points.ron"));
    }
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    // a scene saved into a folder of the user's: that folder, and Enter
    // saves there without a question
    let mine = tmp.path().join("mine");
    std::fs::create_dir(&mine).unwrap();
    h.state_mut()
        .apply(Command::SavePath(mine.join("first.ron")));
    h.run_steps(2);
    assert!(mine.join("first.ron").is_file());
    let offer = open_edit_save(&mut h);
    assert_eq!(std::path::Path::new(&offer), mine.join("three_points.ron"));
    h.key_press(egui::Key::Enter);
    h.run_steps(2);
    assert!(!h.state().prompt_open(), "a question after Enter");
    assert!(!h.state().is_dirty());
    assert_eq!(
        Scene::load(&mine.join("three_points.ron"))
            .unwrap()
            .speed_mps,
        h.state().scene().speed_mps
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), before);
}
