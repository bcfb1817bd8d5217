//! A preset's description is written for the scene as it was opened: after
//! an edit, the side panel and the classroom explanation say what changed
//! (with units), and a save adds it to the description, so that the saved
//! file's text does not describe a scene it no longer is.
#![cfg(feature = "gui")]

mod common;
use common::{harness, texts, type_into};
use tirecontact::Scene;
use tirecontact::gui::{App, Command};

fn three_points() -> App {
    let path = format!("{}/presets/three_points.ron", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    App::new(Scene::parse(&text, &path).unwrap(), None).unwrap()
}

fn shows(h: &egui_kittest::Harness<'_, App>, part: &str) -> bool {
    texts(h).iter().any(|(t, _)| t.contains(part))
}

#[test]
fn an_edit_is_said_under_the_description_and_saved_into_it() {
    let mut h = harness(three_points());
    h.run();
    let v0 = h.state().scene().speed_mps;
    assert!(!shows(&h, "Changed since opened or saved"));
    type_into(&mut h, "speed_mps", &format!("{}", 2.0 * v0));
    assert_eq!(h.state().scene().speed_mps, 2.0 * v0);
    let said = format!("speed {v0} -> {} m/s", 2.0 * v0);
    assert!(shows(&h, "Changed since opened or saved"), "no note");
    assert!(shows(&h, &said), "the note does not say {said:?}");

    // classroom mode says it under the large explanation too
    h.state_mut().apply(Command::SetClassroom(true));
    h.run();
    h.run();
    assert!(shows(&h, &said), "classroom explanation without the edit");
    h.state_mut().apply(Command::SetClassroom(false));
    h.run();

    let dir = std::env::temp_dir().join(format!("tc_edited_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("faster.ron");
    let before = h.state().scene().description.clone();
    h.state_mut().apply(Command::SavePath(path.clone()));
    h.run();
    assert!(!h.state().is_dirty());
    let saved = Scene::load(&path).unwrap();
    assert!(saved.description.starts_with(before.trim_end()));
    assert!(
        saved
            .description
            .ends_with(&format!("Edited from \"{}\": {said}.", saved.name)),
        "{:?}",
        saved.description
    );
    // the app's scene is the file's; the note is gone (nothing changed since)
    assert_eq!(h.state().scene().description, saved.description);
    h.run();
    assert!(!shows(&h, "Changed since opened or saved"));
    // a second save without edits adds nothing
    h.state_mut().apply(Command::SavePath(path.clone()));
    h.run();
    assert_eq!(Scene::load(&path).unwrap().description, saved.description);
    std::fs::remove_dir_all(dir).ok();
}
