//! A preset's description is written for the scene as it was opened: after
//! an edit, the side panel and the classroom explanation say what changed
//! (with units), and a save adds it to the description, so that the saved
//! file's text does not describe a scene it no longer is.

use crate::harness::{harness, texts, type_into};
use crate::support::temp_dir;
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
    let said = format!("speed V {v0} -> {} m/s", 2.0 * v0);
    assert!(shows(&h, "Changed since opened or saved"), "no note");
    assert!(shows(&h, &said), "the note does not say {said:?}");

    // classroom mode says it under the large explanation too
    h.state_mut().apply(Command::SetClassroom(true));
    h.run();
    h.run();
    assert!(shows(&h, &said), "classroom explanation without the edit");
    h.state_mut().apply(Command::SetClassroom(false));
    h.run();

    let tmp = temp_dir();
    let dir = tmp.path();
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
}

#[test]
fn name_and_description_are_edited_in_place_without_a_restart() {
    let mut h = harness(three_points());
    h.run();
    h.state_mut().apply(Command::Play);
    crate::harness::advance(&mut h, 50);
    let steps = h.state().simulation().steps();
    assert!(steps >= 50);
    // the section opens on a click on its header
    use egui_kittest::kittest::Queryable;
    h.get_by_label("Name and description").click();
    h.run();
    type_into(&mut h, "scene.name", "  Fast three points  ");
    assert_eq!(h.state().scene().name, "Fast three points");
    assert!(h.state().title().contains("Fast three points"));
    assert!(
        h.state().simulation().steps() >= steps,
        "renaming restarted the run"
    );
    // an empty name is refused, the old one kept, and the banner says so
    type_into(&mut h, "scene.name", "   ");
    assert_eq!(h.state().scene().name, "Fast three points");
    let msg = h
        .state()
        .message()
        .map(|m| m.text.clone())
        .unwrap_or_default();
    assert!(
        msg.contains("scene.name") && msg.contains("empty"),
        "{msg:?}"
    );

    // a speed edit, then a description written for it: the text is the
    // user's, so no note under it and nothing added on save
    let v0 = h.state().scene().speed_mps;
    type_into(&mut h, "speed_mps", &format!("{}", 2.0 * v0));
    assert!(shows(&h, "Changed since opened or saved"));
    h.get_by_label("scene.description").focus();
    h.run();
    h.get_by_label("scene.description")
        .set_text_value_accesskit("Three points at twice the speed.");
    h.run();
    // focus leaves the multi-line field on a click elsewhere
    h.get_by_label("scene.name").focus();
    h.run();
    h.run();
    assert_eq!(
        h.state().scene().description,
        "Three points at twice the speed."
    );
    assert!(!shows(&h, "Changed since opened or saved"));
    let tmp = temp_dir();
    let dir = tmp.path();
    let path = dir.join("fast.ron");
    h.state_mut().apply(Command::SavePath(path.clone()));
    h.run();
    let saved = Scene::load(&path).unwrap();
    assert_eq!(saved.name, "Fast three points");
    assert_eq!(saved.description, "Three points at twice the speed.");
}

#[test]
fn an_open_description_field_is_not_repeated_above_it() {
    let mut h = harness(three_points());
    h.run();
    let description = h.state().scene().description.clone();
    let count = |h: &egui_kittest::Harness<'_, App>| {
        texts(h)
            .iter()
            .filter(|(t, _)| t.as_str() == description.as_str())
            .count()
    };
    assert_eq!(count(&h), 1, "the description under the scene's name");
    use egui_kittest::kittest::Queryable;
    h.get_by_label("Name and description").click();
    h.run();
    h.run();
    assert_eq!(count(&h), 1, "shown in its field and again above it");
    h.get_by_label("Name and description").click();
    h.run();
    h.run();
    assert_eq!(count(&h), 1, "closed again: the description above");
}

/// A ring tyre made a modal model, then detuned and given one more mode:
/// the note, the unsaved-changes question and the saved description list
/// the mode edits against the identified modes, not only "ring -> modal".
#[test]
fn mode_edits_after_edit_as_a_modal_model_are_listed() {
    use crate::harness::{harness_sized, settle};
    use egui_kittest::kittest::Queryable;
    let mut h = harness_sized(App::with_default_preset(), [1280.0, 1600.0]);
    settle(&mut h);
    let n = h.state().modes().len();
    let (f0, z0) = (
        h.state().modes()[0].freq_hz,
        h.state().modes()[0].damping_ratio,
    );
    h.get_by_label("Edit as a modal model").click();
    settle(&mut h);
    type_into(&mut h, "tyre.modes[0].freq_hz", "45");
    type_into(&mut h, "tyre.modes[0].damping_ratio", "0.02");
    h.get_by_label("Add mode").click();
    settle(&mut h);
    assert_eq!(h.state().modes().len(), n + 1);
    let edits = h.state().edits();
    let want = [
        format!("tyre ring -> modal model of its {n} identified modes"),
        format!("mode 0 frequency {} -> 45 Hz", short(f0)),
        format!("mode 0 damping ratio {} -> 0.02", short(z0)),
    ];
    for w in &want {
        assert!(edits.contains(w), "{w:?} not in {edits:?}");
    }
    assert!(
        edits
            .iter()
            .any(|e| e.starts_with(&format!("mode {n} (")) && e.ends_with("added")),
        "{edits:?}"
    );
    assert!(shows(&h, &want[1]), "the side panel's note");
    // a new scene asks first, listing them
    h.state_mut().apply(Command::New);
    h.run_steps(2);
    assert!(h.state().pending_confirmation().is_some());
    assert!(shows(&h, &want[2]), "the unsaved-changes question");
    h.get_by_label("Cancel").click();
    h.run_steps(2);
    // saved into the description
    let tmp = temp_dir();
    let path = tmp.path().join("detuned.ron");
    h.state_mut().apply(Command::SavePath(path.clone()));
    h.run();
    let saved = Scene::load(&path).unwrap();
    assert!(
        saved.description.contains(&want[1]),
        "{}",
        saved.description
    );
}

/// `x` to four significant digits, as the edit list writes it.
fn short(x: f64) -> String {
    let r: f64 = format!("{x:.3e}").parse().unwrap();
    format!("{r}")
}
