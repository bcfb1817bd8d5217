//! Legends that sat over curves: classroom mode's plot of one point (its
//! legend fixed top left, over the curve) and the A/B compare view at
//! 1280 × 720 (the displacement legend over the left part of the plot).
//! Measured on the painted shapes: the length (px) of the curves (strokes in
//! the points' colours) inside the legend's box (its entries' widgets plus
//! egui_plot's frame margins), against the curves' length in the frame.

use crate::harness::{advance, curves, ink};
use egui::{Color32, Pos2, Rect};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::classroom::CLASSROOM_PLOT_ID;
use tirecontact::gui::views::compare_view::{
    CURRENT, DISPLACEMENT_PLOT_ID, FORCE_PLOT_ID, REFERENCE,
};
use tirecontact::gui::views::point_color;
use tirecontact::gui::views::time_plots::IMPACT_LABEL;
use tirecontact::gui::{App, Command};

fn frame_of(h: &Harness<'_, App>, id: &str) -> Rect {
    *PlotMemory::load(&h.ctx, egui::Id::unique(id))
        .unwrap_or_else(|| panic!("plot {id} shown"))
        .transform()
        .frame()
}

/// The legend box in `near`: its entries named `names` in egui_plot's
/// legend frame (8 px margins left and right, 4 px above and below), and
/// the entries found.
fn legend_box(h: &Harness<'_, App>, near: Rect, names: &[String]) -> Option<(Rect, Vec<String>)> {
    let found: Vec<(String, Rect)> = names
        .iter()
        .flat_map(|n| {
            h.query_all_by_label(n)
                .map(|node| (n.clone(), node.rect()))
                .collect::<Vec<_>>()
        })
        .filter(|(_, r)| near.contains(r.center()))
        .collect();
    let r = found.iter().map(|(_, r)| *r).reduce(|a, b| a.union(b))?;
    Some((
        r.expand2(egui::vec2(8.0, 4.0)),
        found.into_iter().map(|(n, _)| n).collect(),
    ))
}

/// Asserts that the legend of plot `id` (its entries in `near`, the frame
/// when `None`) covers at most 2 px of the curves drawn in its frame (and
/// that there are curves); returns the entries found.
fn check(
    h: &Harness<'_, App>,
    id: &str,
    near: Option<Rect>,
    names: &[String],
    colors: &[Color32],
    what: &str,
) -> Vec<String> {
    let frame = frame_of(h, id);
    let (legend, found) =
        legend_box(h, near.unwrap_or(frame), names).unwrap_or_else(|| panic!("{what}: no legend"));
    let in_frame: Vec<Vec<Pos2>> = curves(h, colors, 2)
        .into_iter()
        .filter(|c| c.iter().all(|p| frame.expand(2.0).contains(*p)))
        .collect();
    let total = ink(frame, &in_frame);
    let under = ink(legend, &in_frame);
    eprintln!(
        "{what}: legend {:.0}x{:.0} px at ({:.0}, {:.0}) in a frame {:.0}x{:.0} px at ({:.0}, {:.0}); {under:.1} px of {total:.0} px of curves under it",
        legend.width(),
        legend.height(),
        legend.left(),
        legend.top(),
        frame.width(),
        frame.height(),
        frame.left(),
        frame.top(),
    );
    assert!(
        total > 0.5 * frame.width(),
        "{what}: the curves are drawn ({total} px)"
    );
    assert!(
        under <= 2.0,
        "{what}: {under:.1} px of curves under the legend {legend:?}"
    );
    found
}

fn names(points: usize) -> Vec<String> {
    let mut n: Vec<String> = (0..points).map(|i| format!("point {i}")).collect();
    n.push(IMPACT_LABEL.to_owned());
    n
}

#[test]
fn the_classroom_plot_legend_covers_no_curve() {
    for (preset, point) in [("single_mode.ron", 0), ("paper.ron", 2)] {
        let scene = Scene::load(&Path::new("presets").join(preset)).unwrap();
        let steps = (scene.duration_s / scene.dt_s).round() as u64;
        for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
            let mut h = crate::harness::harness_sized(App::new(scene.clone(), None).unwrap(), size);
            h.state_mut().apply(Command::SetClassroom(true));
            h.run_steps(4);
            if point > 0 {
                h.get_by_label(&point.to_string()).click();
                h.run_steps(2);
            }
            let points = h.state().simulation().num_points();
            let colors: Vec<Color32> = (0..points).map(point_color).collect();
            for (when, n) in [("mid-run", steps / 2), ("after the run", steps - steps / 2)] {
                advance(&mut h, n);
                for quantity in ["contact force", "displacement"] {
                    h.get_by_label(quantity).click();
                    h.run_steps(4);
                    // the legend is the plot's: in it or in the row above
                    let frame = frame_of(&h, CLASSROOM_PLOT_ID);
                    let near = Rect::from_min_max(frame.min - egui::vec2(100.0, 80.0), frame.max);
                    let found = check(
                        &h,
                        CLASSROOM_PLOT_ID,
                        Some(near),
                        &names(points),
                        &colors,
                        &format!("classroom {preset} {size:?} {when}, {quantity} of point {point}"),
                    );
                    assert!(found.contains(&format!("point {point}")), "{found:?}");
                    if quantity == "contact force" && preset == "paper.ron" {
                        assert!(found.contains(&IMPACT_LABEL.to_owned()), "{found:?}");
                    }
                }
            }
        }
    }
}

#[test]
fn the_compare_legends_cover_no_curve() {
    // a run pinned, then the same run again, checked as it grows
    let runs: [(&str, u64, &[u64]); 4] = [
        ("three_points.ron", 12_000, &[1_000, 3_000]),
        ("paper.ron", 20_000, &[2_000, 4_000, 6_000, 8_000]),
        ("single_mode.ron", 100_000, &[5_000, 20_000, 75_000]),
        ("random_road.ron", 50_000, &[5_000, 20_000, 25_000]),
    ];
    for (preset, first, stages) in runs {
        let scene = Scene::load(&Path::new("presets").join(preset)).unwrap();
        for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
            let mut h = crate::harness::harness_sized(App::new(scene.clone(), None).unwrap(), size);
            h.run();
            advance(&mut h, first);
            h.state_mut().apply(Command::ShowView(View::Compare));
            h.run_steps(2);
            h.get_by_label("Pin as reference").click();
            h.run_steps(2);
            h.state_mut().apply(Command::Reset);
            h.run_steps(2);
            let points = h.state().simulation().num_points();
            // current runs in the points' colours, the reference dimmed
            let colors: Vec<Color32> = (0..points)
                .flat_map(|i| [point_color(i), point_color(i).gamma_multiply(0.6)])
                .collect();
            let names: Vec<String> = [CURRENT, REFERENCE, IMPACT_LABEL]
                .iter()
                .map(|s| s.to_string())
                .collect();
            // the same run as it grows, then a faster one (a live edit:
            // current and reference differ) to its end
            let mut plan: Vec<(u64, bool)> = stages.iter().map(|&n| (n, false)).collect();
            plan.push((first, true));
            for (n, edit) in plan {
                if edit {
                    let mut faster = h.state().scene().clone();
                    faster.speed_mps *= 1.3;
                    h.state_mut().apply(Command::EditScene(Box::new(faster)));
                    h.state_mut().apply(Command::Reset);
                    h.run();
                }
                let n = n.min(first - h.state().simulation().steps());
                advance(&mut h, n);
                h.run();
                let t_ms = h.state().simulation().time_s() * 1e3;
                for clip in ["clipped", "not clipped"] {
                    for (id, plot) in [
                        (DISPLACEMENT_PLOT_ID, "displacement"),
                        (FORCE_PLOT_ID, "force"),
                    ] {
                        check(
                            &h,
                            id,
                            None,
                            &names,
                            &colors,
                            &format!("compare {preset} {size:?} at {t_ms:.0} ms, {plot}, {clip}"),
                        );
                    }
                    h.get_by_label("clip impact spikes").click();
                    h.run();
                }
            }
        }
    }
}
