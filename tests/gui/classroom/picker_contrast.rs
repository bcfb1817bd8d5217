//! The classroom's point picker stays readable when a point is selected:
//! its text contrasts with the selection's fill (WCAG contrast ratio ≥ 3,
//! the level for large or bold text) in the dark and the light theme.

use crate::harness::contrast;
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
        // where it reads on the panel, else the least darkening (light
        // theme) or lightening (dark theme) toward the text colour that does
        for i in 0..24 {
            let c = picker_color(&v, i, false);
            let own = contrast(point_color(i), v.panel_fill);
            if own >= 3.0 {
                assert_eq!(c, point_color(i), "{theme} theme, point {i}");
            } else {
                let got = contrast(c, v.panel_fill);
                assert!(
                    (3.0..4.0).contains(&got),
                    "{theme} theme, point {i}: contrast {got:.2} (own colour {own:.2})"
                );
            }
        }
    }
    // the premise of the mixing: point 4's sky blue on the light panel
    assert!(contrast(point_color(4), Visuals::light().panel_fill) < 3.0);
}

/// The points' checkbox labels over the time plots read on the light
/// theme's panel (classroom mode is light): painted in a colour of WCAG
/// contrast >= 3 with the panel.
#[test]
fn point_labels_over_the_plots_read_in_the_light_theme() {
    use crate::harness::{harness, shapes};
    let mut h = harness(tirecontact::gui::App::with_default_preset());
    h.ctx.set_visuals(Visuals::light());
    h.run();
    h.run();
    let bg = Visuals::light().panel_fill;
    let mut seen = 0;
    for s in shapes(&h) {
        if let egui::Shape::Text(t) = s {
            let text = t.galley.text();
            if text.len() == 1 && text.chars().all(|c| c.is_ascii_digit()) {
                for sec in &t.galley.job.sections {
                    let c = sec.format.color;
                    // (a label in a colour of its own: not the theme's text)
                    if c != egui::Color32::PLACEHOLDER && c != t.fallback_color {
                        let k = contrast(c, bg);
                        assert!(k >= 3.0, "label {text:?} colour {c:?}: contrast {k:.2}");
                        seen += 1;
                    }
                }
            }
        }
    }
    assert!(seen >= 5, "found {seen} coloured point labels");
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
