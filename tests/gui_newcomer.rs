//! A first-time user's five minutes at 1280 × 720 (session 10): mistakes
//! pause the run and say what to do, the keys are listed in a Help menu,
//! an empty run is not exported as an empty figure, and a syntax error's
//! caret points at its column.
#![cfg(feature = "gui")]

mod common;
use common::{harness_sized, type_into};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tirecontact::gui::app::PAUSED_NOTE;
use tirecontact::gui::time_control::Speed;
use tirecontact::gui::{App, Command};

const SMALL: [f32; 2] = [1280.0, 720.0];

/// The default preset, playing at 1280 × 720.
fn playing() -> Harness<'static, App> {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    h.get_by_label("Play").click();
    h.run_steps(2);
    assert!(h.state().time_control().is_playing());
    h
}

/// `common::type_into` for a window that keeps repainting (a playing run).
fn type_playing(h: &mut Harness<'_, App>, name: &str, text: &str) {
    h.get_by_label(name).focus();
    h.run_steps(1);
    h.get_by_label(name).set_text_value_accesskit(text);
    h.run_steps(1);
    h.key_press(egui::Key::Enter);
    h.run_steps(2);
}

fn banner(h: &Harness<'_, App>) -> String {
    h.state()
        .message()
        .map(|m| m.text.clone())
        .unwrap_or_default()
}

/// A temporary file holding `text` (removed on drop).
struct TempFile(std::path::PathBuf);
impl TempFile {
    fn new(name: &str, text: &str) -> Self {
        let p = std::env::temp_dir().join(format!(
            "tirecontact_newcomer_{}_{name}",
            std::process::id()
        ));
        std::fs::write(&p, text).unwrap();
        TempFile(p)
    }
}
impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

#[test]
fn a_refused_value_pauses_the_run_and_says_how_to_go_on() {
    let mut h = playing();
    type_playing(&mut h, "road.amplitude_m", "abc");
    assert!(!h.state().time_control().is_playing(), "still playing");
    let text = banner(&h);
    assert!(text.starts_with("road.amplitude_m:"), "{text}");
    assert!(text.contains("'abc'"), "{text}");
    assert!(text.contains("expected"), "{text}");
    assert!(text.ends_with(PAUSED_NOTE), "{text}");
    // a good value clears the refusal (the note went with it)
    type_into(&mut h, "road.amplitude_m", "2");
    assert!(!banner(&h).contains(PAUSED_NOTE), "{}", banner(&h));
    // refused while paused: nothing to say about the run
    type_into(&mut h, "road.wavelength_m", "0");
    let text = banner(&h);
    assert!(text.starts_with("road.wavelength_m:"), "{text}");
    assert!(!text.contains(PAUSED_NOTE), "{text}");
}

#[test]
fn a_broken_preset_pauses_the_run_and_keeps_the_scene() {
    let mut h = playing();
    let before = h.state().scene().clone();
    let f = TempFile::new(
        "broken.ron",
        "Scene(\n    name: \"x\"\n    description: \"y\",\n)\n",
    );
    h.state_mut().apply(Command::OpenPath(f.0.clone()));
    h.run_steps(1);
    assert!(!h.state().time_control().is_playing(), "still playing");
    assert_eq!(h.state().scene(), &before, "the scene was kept");
    let text = banner(&h);
    assert!(text.contains(PAUSED_NOTE), "{text}");
    // file:line:column of the missing comma's consequence
    let at = format!("{}:3:5", f.0.display());
    assert!(text.contains(&at), "{text}");
}

/// Paused, the same slip does not start the run either.
#[test]
fn a_refusal_while_paused_leaves_the_run_paused() {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    h.state_mut().apply(Command::SetSpeed(Speed::Max));
    type_into(&mut h, "speed_kmh", "-5");
    assert!(!h.state().time_control().is_playing());
    assert!(banner(&h).starts_with("speed_kmh:"), "{}", banner(&h));
}
