//! The mode bars' Mute and Solo buttons in small desktop windows, beside
//! the views and in classroom mode: each one lies inside the window, or is
//! brought into it by scrolling to it, and a click on it mutes or solos its
//! mode.

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tirecontact::gui::{App, Command};

/// Every `label` button of the mode bars, scrolled to, lies inside the
/// `w × h` window (above the status bar, which covers the window's bottom).
fn each_reachable(h: &mut Harness<'static, App>, label: &str, [w, ht]: [f32; 2], what: &str) {
    let n = h.query_all_by_label(label).count();
    assert!(n >= 3, "{what}: {n} {label} buttons");
    for k in 0..n {
        h.get_all_by_label(label).nth(k).unwrap().scroll_to_me();
        h.run_steps(3);
        let bottom = crate::harness::status_top(h);
        let r = h.get_all_by_label(label).nth(k).unwrap().rect();
        assert!(
            r.left() >= 0.0 && r.right() <= w && r.top() >= 0.0 && r.bottom() <= bottom.min(ht),
            "{what}: {label} {k} at {r:?}, the window {w} × {ht} (status bar from {bottom})"
        );
    }
}

/// The app on `preset` in a `size` window with the mode bars beside the views.
fn bars(preset: &str, size: [f32; 2]) -> Harness<'static, App> {
    let mut h = crate::harness::harness_sized(super::app_on(preset), size);
    crate::harness::settle(&mut h);
    h.state_mut().apply(Command::ShowModeBars(true));
    h.run_steps(4);
    h
}

#[test]
fn the_mode_bars_buttons_lie_in_small_desktop_windows() {
    for size in [
        [720.0, 600.0],
        [900.0, 600.0],
        [1024.0, 768.0],
        [1280.0, 720.0],
    ] {
        for preset in ["guided_1a_soft_tyre.ron", "paper.ron"] {
            let what = format!("{preset} at {size:?}");
            let mut h = bars(preset, size);
            each_reachable(&mut h, "Mute", size, &what);
            each_reachable(&mut h, "Solo", size, &what);
        }
        // a click on the last Solo, scrolled to, solos its mode
        let mut h = bars("guided_1a_soft_tyre.ron", size);
        each_reachable(&mut h, "Solo", size, "guided_1a_soft_tyre.ron");
        h.get_all_by_label("Solo").nth(2).unwrap().click();
        h.run_steps(3);
        assert_eq!(
            h.state().mutes().map(|m| m.muted.clone()),
            Some(vec![true, true, false]),
            "{size:?}: the click on Solo 2"
        );
    }
}

#[test]
fn classroom_mode_keeps_the_mute_rows_reachable_in_small_windows() {
    for size in [[720.0, 600.0], [900.0, 600.0], [1280.0, 720.0]] {
        for preset in ["guided_1a_soft_tyre.ron", "three_points.ron", "paper.ron"] {
            let what = format!("classroom, {preset} at {size:?}");
            let mut h = crate::harness::harness_sized(super::app_on(preset), size);
            crate::harness::settle(&mut h);
            h.state_mut().apply(Command::SetClassroom(true));
            h.run_steps(4);
            each_reachable(&mut h, "Mute", size, &what);
            each_reachable(&mut h, "Solo", size, &what);
        }
        // scrolled to, the last Mute takes a click
        let mut h = crate::harness::harness_sized(super::app_on("guided_1a_soft_tyre.ron"), size);
        crate::harness::settle(&mut h);
        h.state_mut().apply(Command::SetClassroom(true));
        h.run_steps(4);
        each_reachable(&mut h, "Mute", size, "classroom");
        h.get_all_by_label("Mute").nth(2).unwrap().click();
        h.run_steps(3);
        assert_eq!(
            h.state().mutes().map(|m| m.muted.clone()),
            Some(vec![false, false, true]),
            "classroom at {size:?}: the click on Mute 2"
        );
    }
}
