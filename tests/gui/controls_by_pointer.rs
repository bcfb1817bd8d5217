//! A first-time user's walk through the visualiser at a projector's
//! 1280 × 720, every control pressed with the pointer where it is painted:
//! a finished run restarts on Reset then Play (and on Play alone), the speed
//! list shows all its choices, classroom mode gives back the view and speed
//! it replaced, a refused value says what was typed and what is expected
//! without moving the fields beside it, and the file prompts work without a
//! desktop file dialog.

use crate::harness::{harness_sized, settle, texts, type_into};
use crate::support::temp_dir;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tirecontact::Scene;
use tirecontact::gui::Speed;
use tirecontact::gui::View;
use tirecontact::gui::{App, Command};

const SMALL: [f32; 2] = [1280.0, 720.0];

fn app_on(file: &str) -> App {
    let path = format!("{}/presets/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    App::new(Scene::parse(&text, &path).unwrap(), None).unwrap()
}

/// The default preset cut to `duration_s` (so that a run ends in a test).
fn short_default(duration_s: f64) -> App {
    let mut app = App::with_default_preset();
    let mut s = app.scene().clone();
    s.duration_s = duration_s;
    app.apply(Command::EditScene(Box::new(s)));
    assert_eq!(app.scene().duration_s, duration_s);
    app
}

/// The default preset cut to 0.01 s at 1280 x 720, played (Play clicked)
/// to its end.
fn finished_run() -> Harness<'static, App> {
    let mut h = harness_sized(short_default(0.01), SMALL);
    h.run();
    h.state_mut().apply(Command::SetSpeed(Speed::Max));
    h.get_by_label("Play").click();
    h.run();
    play_to_the_end(&mut h);
    h
}

/// Frames until the run pauses by itself (it finished).
fn play_to_the_end(h: &mut Harness<'_, App>) {
    for _ in 0..10_000 {
        if !h.state().time_control().is_playing() {
            break;
        }
        h.run_steps(1);
    }
    assert!(h.state().simulation().finished(), "the run did not finish");
    assert!(!h.state().time_control().is_playing());
}

#[test]
fn a_finished_run_restarts_on_reset_then_play_clicked_at_1280x720() {
    let mut h = finished_run();
    let end_s = h.state().simulation().time_s();
    assert!((end_s - 0.01).abs() < 1e-9, "{end_s}");
    // the message says how to go on
    let msg = h.state().message().expect("a run-complete message").clone();
    assert!(!msg.error);
    assert!(msg.text.contains("run complete"), "{}", msg.text);
    assert!(msg.text.contains("Play"), "{}", msg.text);

    // Reset: back to t = 0, the history emptied, still paused
    h.run();
    h.get_by_label("Reset").click();
    h.run();
    assert_eq!(h.state().simulation().time_s(), 0.0);
    assert_eq!(h.state().simulation().steps(), 0);
    assert_eq!(h.state().history().len(), 1);
    assert!(!h.state().time_control().is_playing());

    // Play: the run goes again from t = 0
    h.state_mut().apply(Command::SetSpeed(Speed::Factor(0.05)));
    h.run();
    h.get_by_label("Play").click();
    h.run_steps(3);
    assert!(h.state().time_control().is_playing());
    let t = h.state().simulation().time_s();
    assert!(t > 0.0 && t < 0.005, "t = {t} s");
}

#[test]
fn play_alone_on_a_finished_run_starts_it_again_from_zero() {
    let mut h = finished_run();
    h.state_mut().apply(Command::SetSpeed(Speed::Factor(0.05)));
    h.run();
    h.get_by_label("Play").click();
    h.run_steps(2);
    assert!(h.state().time_control().is_playing());
    let t = h.state().simulation().time_s();
    // 0.05x: under 0.001 s of simulated time per 1/60 s frame
    assert!(t > 0.0 && t < 0.003, "t = {t} s: the run did not restart");
}

/// Every painted text with the clip rectangle it was painted in.
fn clipped_texts(h: &Harness<'_, App>) -> Vec<(String, egui::Rect, egui::Rect)> {
    let mut out = Vec::new();
    for c in &h.output().shapes {
        let mut leaves = Vec::new();
        crate::harness::walk(&c.shape, &mut leaves);
        for s in leaves {
            if let egui::Shape::Text(t) = s {
                out.push((
                    t.galley.text().to_owned(),
                    t.visual_bounding_rect(),
                    c.clip_rect,
                ));
            }
        }
    }
    out
}

#[test]
fn the_speed_list_shows_every_choice_without_scrolling() {
    for (size, classroom) in [(SMALL, false), (SMALL, true), ([1600.0, 1000.0], false)] {
        let mut h = harness_sized(App::with_default_preset(), size);
        h.state_mut().apply(Command::SetClassroom(classroom));
        h.run();
        h.run();
        h.get(
            egui_kittest::kittest::by()
                .label("speed")
                .role(egui::accesskit::Role::ComboBox),
        )
        .click();
        h.run();
        h.run();
        let shown = clipped_texts(&h);
        for want in ["0.001x real time", "10x real time", "as fast as possible"] {
            let (_, r, clip) = shown
                .iter()
                .find(|(t, _, _)| t == want)
                .unwrap_or_else(|| panic!("{want} not painted ({size:?})"));
            assert!(
                clip.contains_rect(*r),
                "{want} at {r:?} is cut by its list ({clip:?}, {size:?}, classroom {classroom})"
            );
        }
    }
}

#[test]
fn classroom_mode_and_back_gives_the_view_and_speed_it_replaced() {
    let mut h = harness_sized(app_on("single_mode.ron"), SMALL);
    h.run();
    let speed = h.state().time_control().speed();
    assert_eq!(speed, Speed::Factor(0.25));
    assert_eq!(h.state().view(), View::TimePlots);
    h.get_by_label("Classroom").click();
    h.run();
    h.run();
    assert!(h.state().classroom());
    assert_eq!(h.state().view(), View::Scene);
    assert_eq!(h.state().time_control().speed(), Speed::Factor(0.05));
    h.get_by_label("Classroom").click();
    h.run();
    h.run();
    assert!(!h.state().classroom());
    assert_eq!(h.state().view(), View::TimePlots);
    assert_eq!(h.state().time_control().speed(), speed);
    assert!(h.query_by_label("u (mm, up)").is_some() || !texts(&h).is_empty());

    // a speed chosen in classroom mode is kept when it ends
    h.state_mut().apply(Command::SetClassroom(true));
    h.run();
    h.state_mut().apply(Command::SetSpeed(Speed::Factor(0.1)));
    h.state_mut().apply(Command::SetClassroom(false));
    h.run();
    assert_eq!(h.state().time_control().speed(), Speed::Factor(0.1));
}

const FREQ: &str = "tyre.modes[0].freq_hz";
const DAMP: &str = "tyre.modes[0].damping_ratio";

#[test]
fn a_refused_mode_value_names_what_was_typed_and_what_is_expected_in_place() {
    let mut h = harness_sized(app_on("single_mode.ron"), SMALL);
    h.run();
    h.run();
    let scene = h.state().scene().clone();
    let damp_at = h.get_by_label(DAMP).rect();
    let dup_at = h.get_by_label("Duplicate").rect();
    // what is below the refused field keeps its place (a reason under the
    // field added a row, gone as the value was fixed: the next click missed)
    let add_at = h.get_by_label("Add mode").rect();
    for (field, typed, says) in [
        (FREQ, "0", ["frequency > 0 Hz", "got 0 Hz", "keeps 100 Hz"]),
        (DAMP, "-0.1", ["damping", "got -0.1", "keeps 0.05"]),
        (
            DAMP,
            "abc",
            ["'abc' is not a number", "expected", "keeps 0.05"],
        ),
        (
            FREQ,
            "-5",
            ["frequency > 0 Hz", "got -5 Hz", "keeps 100 Hz"],
        ),
    ] {
        type_into(&mut h, field, typed);
        // the banner names the field, the value typed and what is expected
        let m = h.state().message().expect("a refusal message").clone();
        assert!(m.error);
        // by its label, then its path
        assert!(m.text.contains(&format!("({field}):")), "{}", m.text);
        for s in says {
            assert!(
                m.text.contains(s),
                "{field} = {typed}: the message does not say '{s}': {}",
                m.text
            );
        }
        assert!(h.query_all_by_label("not applied").count() >= 1);
        // the long reason wraps in the banner: Dismiss stays in the window
        let dismiss = h.get_by_label("Dismiss").rect();
        assert!(
            dismiss.right() <= SMALL[0] - 4.0,
            "{field} = {typed}: Dismiss at {dismiss:?} is off the window"
        );
        // nothing is lost: the scene keeps its values, the run its state
        assert_eq!(h.state().scene(), &scene, "{field} = {typed}");
        assert!(!h.state().is_dirty());
        // the reason is under the field: the fields right of it stay put
        // (beside it, it pushed them, the buttons and the plots 240 px right)
        let d = h.get_by_label(DAMP).rect();
        assert!(
            (d.left() - damp_at.left()).abs() < 0.5,
            "{field} = {typed}: the damping field moved from {damp_at:?} to {d:?}"
        );
        let b = h.get_by_label("Duplicate").rect();
        assert!(
            (b.left() - dup_at.left()).abs() < 60.0,
            "{field} = {typed}: Duplicate moved from {dup_at:?} to {b:?}"
        );
        let a = h.get_by_label("Add mode").rect();
        assert!(
            (a.top() - add_at.top()).abs() < 0.5,
            "{field} = {typed}: Add mode moved from {add_at:?} to {a:?}"
        );
    }
    // a good value clears the reason and applies
    type_into(&mut h, FREQ, "120");
    type_into(&mut h, DAMP, "0.1");
    assert_eq!(h.state().modes()[0].freq_hz, 120.0);
    assert_eq!(h.state().modes()[0].damping_ratio, 0.1);
    assert!(
        h.query_all_by_label("not applied").count() == 0,
        "a mark stayed after a good value"
    );
    assert!((h.get_by_label("Add mode").rect().top() - add_at.top()).abs() < 0.5);
    assert_eq!(h.state().message(), None, "the refusal stayed up");
}

#[test]
fn a_refused_text_does_not_outlive_its_document() {
    // single_mode's and three_points' first modes are both 5 % damped
    let mut h = harness_sized(app_on("single_mode.ron"), SMALL);
    h.run();
    type_into(&mut h, DAMP, "-0.1");
    assert_eq!(h.query_all_by_label("not applied").count(), 1);
    let path = format!("{}/presets/three_points.ron", env!("CARGO_MANIFEST_DIR"));
    h.state_mut().apply(Command::OpenPath(path.into()));
    h.run();
    h.run();
    assert_eq!(h.state().modes()[0].damping_ratio, 0.05);
    assert_eq!(h.query_all_by_label("not applied").count(), 0);
    assert_eq!(
        h.get_by_label(DAMP).value().as_deref(),
        Some("0.05"),
        "the old document's refused text is still in the field"
    );
}

/// A refusal's reason stays in the banner when the run ends meanwhile (its
/// field is still marked "not applied"; "run complete" used to replace it).
#[test]
fn a_refusal_stays_up_when_the_run_completes() {
    let mut app = app_on("single_mode.ron");
    let mut s = app.scene().clone();
    s.duration_s = 0.01;
    app.apply(Command::EditScene(Box::new(s)));
    let mut h = harness_sized(app, SMALL);
    h.run();
    type_into(&mut h, DAMP, "-0.1");
    let refusal = h.state().message().expect("a refusal").clone();
    assert!(
        refusal.error && refusal.text.contains("got -0.1"),
        "{}",
        refusal.text
    );
    h.state_mut().apply(Command::SetSpeed(Speed::Max));
    h.state_mut().apply(Command::Play);
    play_to_the_end(&mut h);
    assert!(h.state().simulation().finished());
    assert_eq!(
        h.state().message(),
        Some(&refusal),
        "the reason was replaced"
    );
    // the kept value typed back: the mark and the reason go, nothing changes
    type_into(&mut h, DAMP, "0.05");
    assert_eq!(h.query_all_by_label("not applied").count(), 0);
    assert_eq!(h.state().message(), None, "the refusal stayed up");
    assert_eq!(h.state().modes()[0].damping_ratio, 0.05);
    // without a refusal, the end of the run is said
    type_into(&mut h, DAMP, "0.06");
    h.state_mut().apply(Command::Play);
    play_to_the_end(&mut h);
    let m = h.state().message().expect("a run-complete message");
    assert!(m.text.contains("run complete"), "{}", m.text);
}

#[test]
fn save_as_open_and_csv_work_by_typing_the_path() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let file = dir.join("edited.ron");
    let mut h = harness_sized(app_on("single_mode.ron"), SMALL);
    h.run();
    let mut s = h.state().scene().clone();
    s.duration_s = 0.5;
    h.state_mut().apply(Command::EditScene(Box::new(s)));
    h.run();
    assert!(h.state().is_dirty());

    // the keyboard path: Ctrl+S on a scene without a file asks for one
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h.run();
    h.run();
    let prompt = h.state().file_prompt().expect("a save prompt").clone();
    assert_eq!(prompt.path, "single_mode_on_a_sine_road.ron");
    // an empty path is refused with what to do
    h.get_by_label("file path").set_text_value_accesskit("  ");
    h.run();
    h.get_by_label("Save").click();
    h.run();
    h.run();
    let note = h.state().file_prompt().and_then(|p| p.note.clone());
    assert!(
        note.as_deref()
            .is_some_and(|n| n.contains("Type a file path")),
        "{note:?}"
    );
    // Escape cancels the prompt, and nothing is saved
    h.key_press(egui::Key::Escape);
    h.run();
    h.run();
    assert!(
        h.state().file_prompt().is_none(),
        "Escape left the prompt open"
    );
    assert!(h.state().is_dirty());
    assert!(!file.exists());
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h.run();
    h.run();
    assert!(h.state().file_prompt().is_some());
    // a typed path saves, confirmed with Enter
    h.get_by_label("file path")
        .set_text_value_accesskit(&file.display().to_string());
    h.run();
    h.key_press(egui::Key::Enter);
    h.run();
    h.run();
    assert!(h.state().file_prompt().is_none());
    assert!(!h.state().is_dirty(), "{:?}", h.state().message());
    assert_eq!(Scene::load(&file).unwrap().duration_s, 0.5);

    // a folder that does not exist: the prompt stays, its note names it
    h.state_mut().apply(Command::SaveAsDialog);
    h.run();
    let bad = dir.join("no_such_folder").join("x.ron");
    h.get_by_label("file path")
        .set_text_value_accesskit(&bad.display().to_string());
    h.run();
    h.get_by_label("Save").click();
    h.run();
    let prompt = h.state().file_prompt().expect("the prompt closed");
    assert_eq!(prompt.path, bad.display().to_string());
    let note = prompt.note.clone().unwrap_or_default();
    assert!(note.contains("no_such_folder"), "{note}");
    h.key_press(egui::Key::Escape);
    h.run();
    h.run();
    assert!(h.state().file_prompt().is_none());

    // File > Open… (Ctrl+O) with a typed path opens it
    h.state_mut().apply(Command::New);
    settle(&mut h);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::O);
    h.run();
    h.run();
    h.get_by_label("file path")
        .set_text_value_accesskit(&file.display().to_string());
    h.run();
    h.get_by_label("Open").click();
    h.run();
    h.run();
    assert_eq!(h.state().scene().duration_s, 0.5);
    assert_eq!(h.state().title(), h.state().title().replace("* ", ""));

    // Export > Run as CSV… with the prompt's own name, in the folder typed
    h.state_mut().apply(Command::Step(50));
    h.run();
    h.state_mut().apply(Command::ExportCsvDialog);
    h.run();
    let csv = dir.join("run.csv");
    h.get_by_label("file path")
        .set_text_value_accesskit(&csv.display().to_string());
    h.run();
    h.get_by_label("Export CSV").click();
    // the export runs on a thread with a spinner: frames, not `run`
    h.run_steps(2);
    assert!(h.state().file_prompt().is_none());
    // still running, or (a short run on a busy machine) already ended and
    // reported in the banner by one of those frames
    match h.state_mut().wait_csv_export() {
        Some(r) => assert!(r.is_ok(), "{r:?}"),
        None => {
            let m = h.state().message().expect("the export's end said");
            assert!(!m.error && m.text.starts_with("wrote"), "{m:?}");
        }
    }
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.lines().count() > 50, "{} lines", text.lines().count());
}

#[test]
fn the_pinned_run_exports_to_a_typed_path() {
    use tirecontact::gui::ResearchCommand;
    let tmp = temp_dir();
    let dir = tmp.path();
    let csv = dir.join("reference.csv");
    let mut h = harness_sized(app_on("single_mode.ron"), SMALL);
    h.run();
    h.state_mut().apply(Command::Step(200));
    h.run();
    h.state_mut()
        .apply(Command::Research(ResearchCommand::PinReference));
    h.state_mut()
        .apply(Command::Research(ResearchCommand::ExportPinnedCsvDialog));
    h.run();
    let prompt = h.state().file_prompt().expect("an export prompt").clone();
    assert_eq!(prompt.path, "reference.csv");
    h.get_by_label("file path")
        .set_text_value_accesskit(&csv.display().to_string());
    h.run();
    h.get_by_label("Export CSV").click();
    h.run();
    assert!(h.state().file_prompt().is_none());
    let m = h.state().message().expect("a message").clone();
    assert!(!m.error, "{}", m.text);
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.lines().count() > 100, "{} lines", text.lines().count());
}

#[test]
fn file_names_offered_read_like_the_scene_name() {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    h.state_mut().apply(Command::SaveAsDialog);
    h.run();
    let p = h.state().file_prompt().expect("a save prompt").path.clone();
    // "Paper: ring tyre, five points, sine road"
    assert_eq!(p, "paper_ring_tyre_five_points_sine_road.ron");
}

#[test]
fn the_png_export_takes_a_typed_path() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let png = dir.join("plots.png");
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    h.state_mut().apply(Command::Step(300));
    h.run();
    h.state_mut().apply(Command::ExportPngDialog);
    h.run();
    h.get_by_label("1200x900").click();
    h.run();
    h.get_by_label("PNG file path")
        .set_text_value_accesskit(&png.display().to_string());
    h.run();
    h.get_by_label("Export PNG").click();
    h.run();
    h.run();
    let m = h.state().message().expect("a message").clone();
    assert!(!m.error, "{}", m.text);
    let img = image_size(&png);
    assert_eq!(img, (1200, 900));
}

/// Width and height of a PNG from its IHDR chunk.
fn image_size(p: &std::path::Path) -> (u32, u32) {
    let b = std::fs::read(p).unwrap();
    assert_eq!(&b[1..4], b"PNG");
    let be = |i: usize| u32::from_be_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
    (be(16), be(20))
}

/// "Save first" in the unsaved-changes question saves, then does what the
/// user asked for (it used to save and drop the request).
#[test]
fn save_first_saves_then_does_the_held_action() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let file = dir.join("kept.ron");
    // copies to open (a save must never reach the shipped presets)
    let (three, one) = (dir.join("three.ron"), dir.join("one.ron"));
    for (from, to) in [("three_points.ron", &three), ("single_mode.ron", &one)] {
        std::fs::copy(format!("{}/presets/{from}", env!("CARGO_MANIFEST_DIR")), to).unwrap();
    }
    let mut h = harness_sized(app_on("single_mode.ron"), SMALL);
    h.run();
    let edited = |h: &mut Harness<'_, App>, d: f64| {
        let mut s = h.state().scene().clone();
        s.duration_s = d;
        h.state_mut().apply(Command::EditScene(Box::new(s)));
        h.run();
        assert!(h.state().is_dirty());
    };
    // a scene without a file: the prompt asks for one, the preset opens after
    edited(&mut h, 0.5);
    h.state_mut().apply(Command::OpenPath(three.clone()));
    h.run();
    h.get_by_label("Save first").click();
    h.run();
    h.run();
    assert!(h.state().file_prompt().is_some(), "no file prompt");
    h.get_by_label("file path")
        .set_text_value_accesskit(&file.display().to_string());
    h.run();
    h.get_by_label("Save").click();
    h.run();
    h.run();
    assert_eq!(Scene::load(&file).unwrap().duration_s, 0.5);
    assert_eq!(h.state().scene().num_points(), 3, "the preset did not open");
    assert!(!h.state().is_dirty());
    // the banner says the save as well as what opened (the opening's
    // message alone took the save's place)
    let said = |h: &Harness<'_, App>| {
        h.state()
            .message()
            .map(|m| m.text.clone())
            .unwrap_or_default()
    };
    let m = said(&h);
    assert!(
        m.contains(&format!("saved {}", file.display())) && m.contains("opened"),
        "{m}"
    );

    // a cancelled prompt keeps the scene and its edits (a scene without a
    // file: the built-in default)
    h.state_mut().apply(Command::New);
    settle(&mut h);
    edited(&mut h, 0.25);
    h.state_mut().apply(Command::OpenPath(one.clone()));
    h.run();
    h.get_by_label("Save first").click();
    h.run();
    h.run();
    h.get_by_label("Cancel").click();
    h.run();
    h.run();
    assert_eq!(h.state().scene().duration_s, 0.25);
    assert!(h.state().is_dirty());
    let default = Scene::parse(tirecontact::DEFAULT_PRESET, "default").unwrap();
    assert_eq!(h.state().scene().name, default.name, "the held action ran");

    // a scene with its file: saved there at once, then the preset opens
    h.state_mut().apply(Command::SavePath(file.clone()));
    h.run();
    edited(&mut h, 0.125);
    h.state_mut().apply(Command::OpenPath(one.clone()));
    h.run();
    h.get_by_label("Save first").click();
    h.run();
    h.run();
    assert_eq!(Scene::load(&file).unwrap().duration_s, 0.125);
    assert_eq!(h.state().scene().num_points(), 1, "the preset did not open");
    let m = said(&h);
    assert!(
        m.starts_with(&format!("saved {}, then", file.display())),
        "{m}"
    );
}
