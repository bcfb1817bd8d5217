//! The status bar stays in one row inside the window: in classroom mode at
//! 1280 × 720 with unsaved changes its full texts (a preset opened by its
//! absolute path, 15 000 steps) run past the right edge, so the labels take
//! their short texts (full text on hover); in the normal layout at
//! 1500 × 950 they are shown whole.

use crate::harness::advance;
use egui::Rect;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::{App, Command};

fn harness(size: [f32; 2], classroom: bool) -> Harness<'static, App> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/guided_1a_soft_tyre.ron");
    let app = App::new(Scene::load(&p).unwrap(), Some(p)).unwrap();
    let mut h = crate::harness::harness_sized(app, size);
    h.run();
    if classroom {
        h.state_mut().apply(Command::SetClassroom(true));
        h.run_steps(2);
    }
    let mut edited = h.state().scene().clone();
    edited.duration_s *= 2.0;
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    h.run_steps(1);
    advance(&mut h, 15_000);
    h.run_steps(2);
    h
}

/// The status bar's labels: document, run, history, frame rate (those
/// inside the bar and painted: the side panel's rows scrolled out of sight
/// under it are in the accessibility tree too).
fn status_labels(h: &Harness<'_, App>) -> Vec<(String, Rect)> {
    let fps = h.get_by_label_contains(" fps");
    let y = fps.rect().center().y;
    let bar = h.state().status_bar_rect().expand(1.0);
    // (painted where the node is: a widget out of its panel's sight is
    // not; an elided text keeps its start)
    let painted = crate::harness::texts(h);
    let shown = |text: &str, r: Rect| {
        let start: String = text.chars().take(4).collect();
        painted
            .iter()
            .any(|(t, p)| p.intersects(r) && t.starts_with(&start))
    };
    let mut v: Vec<(String, Rect)> = h
        .query_all_by(|n| n.role() == egui::accesskit::Role::Label)
        .filter(|n| n.rect().top() <= y && n.rect().bottom() >= y)
        .filter(|n| bar.contains_rect(n.rect()))
        .map(|n| {
            let a = n.accesskit_node();
            let text = a.label().or_else(|| a.value()).unwrap_or_default();
            (text, n.rect())
        })
        .filter(|(text, r)| shown(text, *r))
        .collect();
    v.sort_by(|a, b| a.1.left().total_cmp(&b.1.left()));
    v
}

fn check_one_row_inside(h: &Harness<'_, App>, width: f32) -> Vec<(String, Rect)> {
    let labels = status_labels(h);
    eprintln!("{width} px: {labels:?}");
    assert!(labels.len() >= 4, "{labels:?}");
    let top = labels[0].1.top();
    for (text, r) in &labels {
        assert!(
            r.right() <= width && r.left() >= 0.0,
            "{text:?} ends at {} px, window {width} px",
            r.right()
        );
        assert!((r.top() - top).abs() <= 4.0, "{text:?} not in one row");
    }
    for w in labels.windows(2) {
        assert!(
            w[0].1.right() <= w[1].1.left(),
            "{:?} overlaps {:?}",
            w[0],
            w[1]
        );
    }
    labels
}

#[test]
fn the_classroom_status_bar_fits_a_1280_px_window_in_one_row() {
    let h = harness([1280.0, 720.0], true);
    let labels = check_one_row_inside(&h, 1280.0);
    let has = |s: &str| labels.iter().any(|(t, _)| t.contains(s));
    assert!(has("history:"), "{labels:?}");
    assert!(has("guided_1a_soft_tyre.ron"), "{labels:?}");
    assert!(has("unsaved"), "{labels:?}");
    // the full history text is kept for the hover
    let full = tirecontact::gui::chrome::status_bar::history_text(
        h.state().history().len(),
        h.state().history().stride(),
    );
    assert!(h.query_by_label(&full).is_none(), "shortened: {labels:?}");
}

#[test]
fn a_shortened_label_shows_its_full_text_on_hover() {
    let mut h = harness([1280.0, 720.0], true);
    let full = tirecontact::gui::chrome::status_bar::history_text(
        h.state().history().len(),
        h.state().history().stride(),
    );
    assert!(h.query_by_label(&full).is_none(), "shortened");
    h.get_by_label_contains("history:").hover();
    h.run_steps(60);
    let found: Vec<String> = h
        .query_all_by_label_contains("history")
        .map(|n| format!("{n:?}"))
        .collect();
    assert!(
        h.query_by_label(&full).is_some(),
        "no hover text {full:?}: {found:?}"
    );
}

#[test]
fn a_1600_px_classroom_status_bar_stays_in_one_row() {
    let h = harness([1600.0, 1000.0], true);
    check_one_row_inside(&h, 1600.0);
}

#[test]
fn wide_windows_show_the_full_texts() {
    {
        let size = [1500.0, 950.0];
        let h = harness(size, false);
        let labels = check_one_row_inside(&h, size[0]);
        let full = tirecontact::gui::chrome::status_bar::history_text(
            h.state().history().len(),
            h.state().history().stride(),
        );
        assert!(
            labels.iter().any(|(t, _)| *t == full),
            "{size:?}: {labels:?}"
        );
        assert!(
            labels.iter().any(|(t, _)| t.ends_with("(unsaved changes)")),
            "{size:?}: {labels:?}"
        );
    }
}
