//! The animation-frames export's messages: its start replaces an earlier
//! message (a refusal stayed up during the export), and a cancelled export
//! says where the frames written so far are, as information (not an error).

use crate::harness::{harness_sized, settle};
use crate::support::temp_dir;
use tirecontact::gui::{App, Command};
use tirecontact::output::animation::FrameSettings;

#[test]
fn the_export_replaces_old_messages_and_a_cancel_says_where_the_frames_are() {
    let tmp = temp_dir();
    let dir = tmp.path().join("frames");
    let mut h = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    settle(&mut h);
    h.state_mut().apply(Command::FieldRefused {
        field: "speed".into(),
        text: "speed V: -3 refused".into(),
    });
    h.run_steps(2);
    assert!(h.state().message().is_some_and(|m| m.error));
    h.state_mut().apply(Command::ExportFrames {
        dir: dir.clone(),
        settings: FrameSettings {
            t0_s: 0.0,
            t1_s: 0.2,
            fps: 25.0,
            slow_motion: 20.0,
            width: 320,
            height: 200,
        },
        clear_old: false,
    });
    let m = h.state().message().expect("no message").clone();
    assert!(
        !m.error && m.text.contains("exporting 100 animation frames"),
        "the refusal stayed up: {m:?}"
    );
    h.state_mut().apply(Command::CancelFrames);
    let r = h.state_mut().wait_frames_export().expect("no export");
    assert!(r.is_err(), "finished before the cancel: {r:?}");
    let m = h.state().message().unwrap();
    // asked for: information, not an error
    assert!(!m.error, "a cancel shown as an error: {m:?}");
    let at = std::path::absolute(&dir).unwrap();
    assert!(
        m.text.contains("written so far stay in") && m.text.contains(&at.display().to_string()),
        "{m:?}"
    );
}
