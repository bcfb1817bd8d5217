//! Leaving classroom mode gives back the theme the user had, and the
//! message banner does not move the views' plots (it overlays them).

use super::{app_on, harness};
use crate::harness::MemStorage;
use egui_kittest::kittest::Queryable;
use tirecontact::gui::Command;

#[test]
fn leaving_classroom_gives_back_the_users_theme() {
    for start in [egui::Theme::Dark, egui::Theme::Light] {
        let mut h = harness(app_on("single_mode.ron"), [1280.0, 720.0]);
        h.ctx.set_theme(start);
        h.run();
        assert_eq!(h.ctx.theme(), start);
        h.get_by_label("Classroom").click();
        h.run();
        h.run();
        assert!(h.state().classroom());
        assert_eq!(h.ctx.theme(), egui::Theme::Light, "classroom is light");
        h.state_mut().apply(Command::SetClassroom(false));
        h.run();
        h.run();
        assert!(!h.state().classroom());
        assert_eq!(h.ctx.theme(), start, "the theme was not given back");
        assert_eq!(
            h.ctx.global_style().visuals.dark_mode,
            start == egui::Theme::Dark
        );
    }
}

/// eframe's storage in memory.
/// A session that ended in classroom mode: egui keeps the theme preference
/// between runs (classroom mode's light one), and leaving classroom mode in
/// the next run gives back the user's dark theme.
#[test]
fn a_session_that_ended_in_classroom_gives_back_the_users_theme() {
    let mut h = harness(app_on("single_mode.ron"), [1280.0, 720.0]);
    h.ctx.set_theme(egui::ThemePreference::Dark);
    h.run();
    h.state_mut().apply(Command::SetClassroom(true));
    h.run();
    h.run();
    let mut storage = MemStorage::default();
    eframe::App::save(h.state_mut(), &mut storage);
    // the next run: egui's options come back with the light preference
    let app = tirecontact::gui::App::restore(Some(&storage));
    assert!(app.classroom(), "classroom mode restored");
    let mut h = harness(app, [1280.0, 720.0]);
    h.ctx.set_theme(egui::ThemePreference::Light);
    h.run();
    h.run();
    assert_eq!(h.ctx.theme(), egui::Theme::Light);
    h.state_mut().apply(Command::SetClassroom(false));
    h.run();
    h.run();
    assert_eq!(h.ctx.theme(), egui::Theme::Dark, "the light theme stayed");
}

/// Top (px) of the time plots' force plot frame.
fn force_plot_top(h: &egui_kittest::Harness<'_, tirecontact::gui::App>) -> f32 {
    egui_plot::PlotMemory::load(
        &h.ctx,
        egui::Id::unique(tirecontact::gui::views::time_plots::FORCE_PLOT_ID),
    )
    .expect("plot shown")
    .transform()
    .frame()
    .top()
}

/// A message banner appearing and clearing leaves the plots where they
/// were, of one line or of several (which unfold in front of the view's
/// top, their Dismiss at hand) (1280 × 720 and 1600 × 1000).
#[test]
fn banners_do_not_move_the_plots() {
    for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
        let mut h = harness(app_on("three_points.ron"), size);
        h.run();
        h.state_mut().apply(Command::DismissMessage);
        h.run();
        h.run();
        assert!(h.state().message().is_none());
        let clear = force_plot_top(&h);
        let refused = |text: &str| Command::FieldRefused {
            field: "speed".into(),
            text: text.into(),
        };
        h.state_mut()
            .apply(refused("speed V: -3 refused, expected > 0 km/h"));
        h.run();
        h.run();
        assert!(h.state().message().is_some());
        assert!(
            (force_plot_top(&h) - clear).abs() < 0.5,
            "{size:?}: a one-line banner moved the plots {clear} -> {}",
            force_plot_top(&h)
        );
        h.state_mut().apply(refused(
            "a long reason\nover several lines\nthat the banner wraps\nand more",
        ));
        h.run();
        h.run();
        // a longer one as well: the plots stay, the whole text shown
        assert!(
            (force_plot_top(&h) - clear).abs() < 0.5,
            "{size:?}: a four-line banner moved the plots {clear} -> {}",
            force_plot_top(&h)
        );
        let banner = h.get_by_label_contains("over several lines").rect();
        assert!(banner.height() > 50.0, "{size:?}: {banner:?}");
        h.get_by_label("Dismiss").click();
        h.run();
        h.run();
        assert!(
            h.state().message().is_none(),
            "{size:?}: Dismiss out of reach"
        );
        h.run();
        h.run();
        assert!((force_plot_top(&h) - clear).abs() < 0.5);
    }
}

/// In classroom mode (larger text) too, the banner neither moves the
/// view nor covers its first row.
#[test]
fn the_classroom_banner_keeps_to_its_strip() {
    let mut h = harness(app_on("three_points.ron"), [1280.0, 720.0]);
    h.run();
    h.state_mut().apply(Command::SetClassroom(true));
    h.run();
    h.run();
    let row_top = |h: &egui_kittest::Harness<'_, tirecontact::gui::App>| {
        h.get_by_label_contains("contact phase").rect().top()
    };
    let clear = row_top(&h);
    h.state_mut().apply(Command::FieldRefused {
        field: "speed".into(),
        text: "opened presets/three_points.ron".into(),
    });
    h.run();
    h.run();
    assert!(
        (row_top(&h) - clear).abs() < 0.5,
        "the banner moved the view"
    );
    let dismiss = h.get_by_label("Dismiss").rect();
    assert!(
        dismiss.bottom() < clear,
        "the banner ({dismiss:?}) covers the view's first row at {clear}"
    );
}
