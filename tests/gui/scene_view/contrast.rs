//! The scene view's displaced tyre line is seen in both themes: its fixed
//! dark grey (60, 60, 60) was barely visible on the dark theme's plot
//! background. Its colour follows the theme, with WCAG contrast ≥ 4.5
//! against the plot background (egui_plot fills it with `extreme_bg_color`);
//! read from the painted line in the dark and the light theme.

use crate::harness::{contrast, shapes};
use egui::epaint::{ColorMode, PathShape, Shape};
use egui::{Color32, Theme, Visuals};
use egui_kittest::Harness;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::views::scene_view::displaced_tyre_color;
use tirecontact::gui::{App, Command};

/// Colours of the painted open polylines 2 px wide with one vertex per point
/// (the displaced tyre's line; the road has hundreds, the undeformed
/// tyre's line is dashed into segments).
fn tyre_line_colors(h: &Harness<'_, App>, points: usize) -> Vec<Color32> {
    shapes(h)
        .into_iter()
        .filter_map(|s| match s {
            Shape::Path(PathShape {
                points: p,
                closed: false,
                stroke,
                ..
            }) if p.len() == points && (stroke.width - 2.0).abs() < 1e-3 => match stroke.color {
                ColorMode::Solid(c) => Some(c),
                _ => None,
            },
            _ => None,
        })
        .collect()
}

#[test]
fn the_displaced_tyre_reads_on_dark_and_light_plots() {
    // the premise: the old colour on the dark plot background
    let old = Color32::from_rgb(60, 60, 60);
    assert!(contrast(old, Visuals::dark().extreme_bg_color) < 3.0);
    for (theme, v) in [("dark", Visuals::dark()), ("light", Visuals::light())] {
        let c = contrast(displaced_tyre_color(&v), v.extreme_bg_color);
        eprintln!("{theme} theme: contrast {c:.2}");
        assert!(c >= 4.5, "{theme} theme: contrast {c:.2}");
    }
    // as painted, in each theme
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let points = scene.points.len();
    for theme in [Theme::Dark, Theme::Light] {
        let mut h = Harness::builder()
            .with_size([1600.0, 1000.0])
            .with_step_dt(1.0 / 60.0)
            .with_theme(theme)
            .build_ui_state(
                |ui, app: &mut App| app.show(ui),
                App::new(scene.clone(), None).unwrap(),
            );
        h.run();
        h.state_mut().apply(Command::ShowView(View::Scene));
        h.run_steps(2);
        let visuals = h.ctx.global_style().visuals.clone();
        assert_eq!(visuals.dark_mode, theme == Theme::Dark, "{theme:?}");
        let expected = displaced_tyre_color(&visuals);
        let colors = tyre_line_colors(&h, points);
        eprintln!("{theme:?}: lines {colors:?}, expected {expected:?}");
        assert!(
            colors.contains(&expected),
            "{theme:?}: no line in {expected:?} among {colors:?}"
        );
        let c = contrast(expected, visuals.extreme_bg_color);
        assert!(c >= 4.5, "{theme:?}: contrast {c:.2}");
    }
}
