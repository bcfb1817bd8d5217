//! Classroom mode in a window narrowed to a phone's width and widened
//! again: the phone gets its layout (classroom mode off, fingertip-sized
//! targets), and the wide window gets back the desktop's sizes and
//! classroom mode, as before it was narrowed.

use crate::harness::{MemStorage, harness_sized, settle};
use egui_kittest::Harness;
use tirecontact::gui::{App, Command, View};

/// What sizes the controls and text: the interaction height, the buttons'
/// padding and the body and small text sizes (px).
fn sizes(h: &Harness<'_, App>) -> [f32; 4] {
    let s = h.ctx.global_style();
    let text = |t: egui::TextStyle| s.text_styles.get(&t).map_or(0.0, |f| f.size);
    [
        s.spacing.interact_size.y,
        s.spacing.button_padding.y,
        text(egui::TextStyle::Body),
        text(egui::TextStyle::Small),
    ]
}

/// Whether two sets of sizes agree (to rounding of the scalings).
fn same(a: [f32; 4], b: [f32; 4]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-3)
}

#[test]
fn widening_a_phone_window_restores_the_desktop_and_classroom_mode() {
    let desktop = [1280.0, 720.0];
    let mut h = harness_sized(App::with_default_preset(), desktop);
    settle(&mut h);
    h.run_steps(2);
    let plain = sizes(&h);
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(3);
    assert!(h.state().classroom());
    let classroom = sizes(&h);
    assert!(classroom[2] > plain[2], "{classroom:?} vs {plain:?}");

    h.set_size(egui::vec2(412.0, 915.0));
    h.run_steps(3);
    assert!(!h.state().classroom(), "classroom mode on a phone");
    let phone = sizes(&h);
    // a fingertip's target: 44 px
    assert!(phone[0] >= 44.0, "{phone:?}");
    assert!(
        same(
            [0.0, 0.0, phone[2], phone[3]],
            [0.0, 0.0, plain[2], plain[3]]
        ),
        "the phone's text: {phone:?} vs {plain:?}"
    );

    h.set_size(egui::vec2(desktop[0], desktop[1]));
    h.run_steps(3);
    assert!(h.state().classroom(), "classroom mode not restored");
    assert_eq!(h.state().view(), View::Scene);
    assert!(
        same(sizes(&h), classroom),
        "the desktop's classroom sizes: {:?} vs {classroom:?}",
        sizes(&h)
    );
    h.state_mut().apply(Command::SetClassroom(false));
    h.run_steps(3);
    assert!(
        same(sizes(&h), plain),
        "the desktop's sizes after classroom mode: {:?} vs {plain:?}",
        sizes(&h)
    );

    // a view chosen on the phone stays when the window widens
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(3);
    h.set_size(egui::vec2(412.0, 915.0));
    h.run_steps(3);
    h.state_mut().apply(Command::ShowView(View::TimePlots));
    h.run_steps(3);
    h.set_size(egui::vec2(desktop[0], desktop[1]));
    h.run_steps(3);
    assert!(!h.state().classroom());
    assert_eq!(h.state().view(), View::TimePlots);
    assert!(same(sizes(&h), plain), "{:?} vs {plain:?}", sizes(&h));
}

/// A session closed at a phone's width keeps the classroom mode the user
/// chose: set aside on the phone, it comes back at the next start in a
/// wide window; a view chosen on the phone ends it, and the session says so.
#[test]
fn a_session_closed_at_a_phone_s_width_keeps_classroom_mode() {
    use eframe::App as _;
    let desktop = [1280.0, 720.0];
    let mut h = harness_sized(App::with_default_preset(), desktop);
    settle(&mut h);
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(3);
    h.set_size(egui::vec2(412.0, 915.0));
    h.run_steps(3);
    assert!(!h.state().classroom(), "classroom mode on a phone");
    let mut storage = MemStorage::default();
    h.state_mut().save(&mut storage);
    let restored = App::restore(Some(&storage));
    assert!(
        restored.classroom(),
        "the next start lost the classroom mode set aside on the phone"
    );
    assert_eq!(restored.view(), View::Scene);
    let mut again = harness_sized(restored, desktop);
    settle(&mut again);
    again.run_steps(3);
    assert!(again.state().classroom());

    // a view chosen on the phone: classroom mode is over
    h.state_mut().apply(Command::ShowView(View::TimePlots));
    h.run_steps(3);
    let mut storage = MemStorage::default();
    h.state_mut().save(&mut storage);
    assert!(!App::restore(Some(&storage)).classroom());
}
