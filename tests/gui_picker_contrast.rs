//! The classroom's point picker stays readable when a point is selected:
//! its text contrasts with the selection's fill (WCAG contrast ratio ≥ 3,
//! the level for large or bold text) in the dark and the light theme.
#![cfg(feature = "gui")]

mod common;
use common::contrast;
use egui::Visuals;
use tirecontact::gui::classroom::picker_color;
use tirecontact::gui::views::point_color;

#[test]
fn a_selected_point_reads_on_the_selection_fill() {
    // the premise: point 0's colour on the dark selection fill is unreadable
    let dark = Visuals::dark();
    assert!(contrast(point_color(0), dark.selection.bg_fill) < 2.0);
    for (theme, v) in [("dark", Visuals::dark()), ("light", Visuals::light())] {
        for i in 0..24 {
            let c = contrast(picker_color(&v, i, true), v.selection.bg_fill);
            assert!(
                c >= 3.0,
                "{theme} theme, point {i} selected: contrast {c:.2}"
            );
        }
        // unselected, each point keeps its colour (the plots' colour key)
        for i in 0..24 {
            assert_eq!(picker_color(&v, i, false), point_color(i));
        }
    }
}

/// The marks of clipped impacts are seen on the plot background of both
/// themes (WCAG contrast ≥ 3 for graphics).
#[test]
fn impact_marks_read_on_dark_and_light_plots() {
    use tirecontact::gui::views::time_plots::IMPACT_MARK_COLOR;
    for (theme, v) in [("dark", Visuals::dark()), ("light", Visuals::light())] {
        let c = contrast(IMPACT_MARK_COLOR, v.extreme_bg_color);
        assert!(c >= 3.0, "{theme} theme: contrast {c:.2}");
    }
}
