//! Share shows its link in a selectable text field, to copy by hand where
//! there is no clipboard; the window takes the keys until it is closed.

use crate::harness::harness;
use crate::support::preset;
use egui_kittest::kittest::Queryable;
use tirecontact::gui::chrome::dialogs::LINK_FIELD;
use tirecontact::gui::{App, Command};

#[test]
fn share_shows_its_link_to_copy_by_hand() {
    let mut h = harness(App::new(preset("three_points"), None).unwrap());
    h.run();
    assert!(h.query_by_label(LINK_FIELD).is_none());
    h.state_mut().apply(Command::Share);
    h.run();
    let link = h.state().shared_link().expect("no link").to_string();
    assert!(link.contains("#scene="), "{link}");
    let field = h.get_by_label(LINK_FIELD);
    assert_eq!(field.value().as_deref(), Some(link.as_str()));
    // Space is the window's, not Play's
    h.key_press(egui::Key::Space);
    h.run_steps(2);
    assert!(!h.state().time_control().is_playing());
    // Escape closes it; the link stays the app's
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    assert!(h.query_by_label(LINK_FIELD).is_none());
    assert!(!h.state().prompt_open());
    assert_eq!(h.state().shared_link(), Some(link.as_str()));
}
