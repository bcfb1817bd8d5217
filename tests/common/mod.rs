//! Shared kittest set-up of the GUI tests (`mod common;` in each).
#![allow(dead_code)]

use egui_kittest::Harness;
use tirecontact::gui::{App, Command};

/// The app in a 1500 × 950 window stepped at 60 frames per second.
pub fn harness(app: App) -> Harness<'static, App> {
    harness_sized(app, [1500.0, 950.0])
}

/// The app in a window of `size` (points) stepped at 60 frames per second.
pub fn harness_sized(app: App, size: [f32; 2]) -> Harness<'static, App> {
    Harness::builder()
        .with_size(size)
        .with_step_dt(1.0 / 60.0)
        .build_ui_state(|ui, app: &mut App| app.show(ui), app)
}

/// Takes `n` solver steps (over as many frames as the step budget needs).
pub fn advance(h: &mut Harness<'_, App>, n: u64) {
    let target = h.state().simulation().steps() + n;
    h.state_mut().apply(Command::Step(n));
    for _ in 0..100_000 {
        if h.state().simulation().steps() >= target {
            break;
        }
        h.run_steps(1);
    }
    assert_eq!(h.state().simulation().steps(), target);
}

/// WCAG relative luminance of an sRGB colour.
pub fn luminance(c: egui::Color32) -> f64 {
    let lin = |v: u8| {
        let v = f64::from(v) / 255.0;
        if v <= 0.03928 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * lin(c.r()) + 0.7152 * lin(c.g()) + 0.0722 * lin(c.b())
}

/// WCAG contrast ratio of two colours (1 to 21).
pub fn contrast(a: egui::Color32, b: egui::Color32) -> f64 {
    let (la, lb) = (luminance(a), luminance(b));
    (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
}
