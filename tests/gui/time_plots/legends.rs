//! The time plots' legends keep off the newest samples: while following a
//! full window they sit right of them (the time axis runs on past the
//! window's end for them); before the window fills (samples on the left
//! only), at the right.

use crate::harness::{advance, harness};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::App;

/// Horizontal centres of the legend entries "point 0" of the four plots.
fn legend_x(h: &Harness<'_, App>) -> Vec<f32> {
    h.get_all_by_label("point 0")
        .map(|n| n.rect().center().x)
        .collect()
}

#[test]
fn the_legends_keep_off_the_newest_samples() {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    // 0.02 s of a 0.1 s window: samples on the left, legends on the right
    advance(&mut h, 2_000);
    h.run_steps(2);
    let xs = legend_x(&h);
    assert_eq!(xs.len(), 4, "one legend per plot: {xs:?}");
    let plot_mid = 0.5 * (h.ctx.content_rect().right() + 360.0);
    assert!(xs.iter().all(|&x| x > plot_mid), "{xs:?} vs {plot_mid}");
    // 0.15 s: the window is full and its newest samples are at its right
    // edge; the time axis runs on past them, and the legends are there
    advance(&mut h, 13_000);
    h.run_steps(2);
    let xs = legend_x(&h);
    assert_eq!(xs.len(), 4, "{xs:?}");
    let mem = egui_plot::PlotMemory::load(
        &h.ctx,
        egui::Id::unique(tirecontact::gui::views::time_plots::FORCE_PLOT_ID),
    )
    .expect("plot shown");
    let t_end = h.state().simulation().time_s();
    let newest_x = mem.transform().position_from_point_x(t_end);
    assert!(
        xs.iter().all(|&x| x > newest_x + 20.0),
        "{xs:?} vs the newest samples at {newest_x} px"
    );
}

/// The contact scheme's combo box says what the schemes are on hover.
#[test]
fn the_contact_scheme_explains_itself_on_hover() {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    assert!(
        h.query_by_label_contains("contact decided at step ends")
            .is_none()
    );
    // the grid's label, then the combo box of the same name
    let combo = h
        .get_all_by_label("contact scheme")
        .last()
        .expect("combo box");
    combo.hover();
    // tooltips show after a short delay
    for _ in 0..60 {
        h.run_steps(1);
    }
    assert!(
        h.query_by_label_contains("contact decided at step ends")
            .is_some(),
        "the tooltip names the schemes"
    );
}

fn small_harness(app: App) -> Harness<'static, App> {
    crate::harness::harness_sized(app, [1280.0, 720.0])
}

/// In a 1280 × 720 window the contact plot's lanes are closer than the
/// 20 px below which egui_plot hides y labels by default; the plot shows
/// them from `LANE_LABEL_SPACING` on, and the legends use smaller text.
#[test]
fn short_plots_keep_their_lane_labels_and_smaller_legends() {
    use egui_plot::PlotMemory;
    use tirecontact::gui::views::time_plots::{CONTACT_PLOT_ID, LANE_LABEL_SPACING};
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut small = small_harness(App::new(scene.clone(), None).unwrap());
    small.run();
    advance(&mut small, 200);
    small.run_steps(2);
    let mem = PlotMemory::load(&small.ctx, egui::Id::unique(CONTACT_PLOT_ID)).expect("plot shown");
    let lane_px = mem.transform().dpos_dvalue_y().abs() as f32;
    assert!(lane_px < 20.0, "the premise: lanes {lane_px} px apart");
    assert!(
        lane_px >= *LANE_LABEL_SPACING.end(),
        "lane labels fully shown from {} px: lanes {lane_px} px apart",
        LANE_LABEL_SPACING.end()
    );
    let entry_h = |h: &Harness<'_, App>| {
        h.get_all_by_label("point 0")
            .map(|n| n.rect().height())
            .fold(0.0f32, f32::max)
    };
    let mut big = harness(App::new(scene, None).unwrap());
    big.run();
    advance(&mut big, 200);
    big.run_steps(2);
    assert!(
        entry_h(&small) < entry_h(&big),
        "legend entries {} px (1280 × 720) vs {} px (1500 × 950)",
        entry_h(&small),
        entry_h(&big)
    );
}

/// With the mode bars open in a 1280 × 720 window the time plots are about
/// 470 px wide (less the strip past the window's end for the legends): 0.01 s
/// ticks of the 0.1 s window are closer than the 60 px below which egui_plot
/// hides x labels by default (one label was left). The time axes step 1-2-5
/// and label steps from `TIME_LABEL_SPACING` on: read the time labels painted
/// under the force plot.
#[test]
fn narrow_time_plots_keep_their_time_labels() {
    use egui::{Rect, Shape};
    use egui_plot::PlotMemory;
    use tirecontact::gui::views::time_plots::{FORCE_PLOT_ID, TIME_LABEL_SPACING};
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = small_harness(App::new(scene, None).unwrap());
    h.run();
    h.state_mut()
        .apply(tirecontact::gui::Command::ShowModeBars(true));
    advance(&mut h, 12_000);
    h.run_steps(2);
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(FORCE_PLOT_ID)).expect("plot shown");
    let frame = *mem.transform().frame();
    let tick_px = (0.01 * mem.transform().dpos_dvalue_x()) as f32;
    assert!(
        tick_px < 60.0,
        "the premise: 0.01 s ticks {tick_px} px apart"
    );
    fn walk(s: &Shape, out: &mut Vec<(String, Rect)>) {
        match s {
            Shape::Vec(v) => v.iter().for_each(|s| walk(s, out)),
            Shape::Text(t) => out.push((t.galley.text().to_owned(), t.visual_bounding_rect())),
            _ => {}
        }
    }
    let mut texts = Vec::new();
    for c in &h.output().shapes {
        walk(&c.shape, &mut texts);
    }
    // time labels: numbers just under the frame, inside its width
    let mut labels: Vec<(f64, f32)> = texts
        .iter()
        .filter(|(_, r)| {
            r.top() >= frame.bottom() - 1.0
                && r.top() <= frame.bottom() + 20.0
                && frame.x_range().contains(r.center().x)
        })
        .filter_map(|(t, r)| t.parse::<f64>().ok().map(|v| (v, r.center().x)))
        .collect();
    labels.sort_by(|a, b| a.1.total_cmp(&b.1));
    eprintln!("frame {frame:?}, time labels {labels:?}");
    assert!(labels.len() >= 3, "time labels {labels:?}");
    for w in labels.windows(2) {
        let (a, b) = (w[0], w[1]);
        assert!(b.0 > a.0, "time labels increase: {labels:?}");
        assert!(
            b.1 - a.1 >= *TIME_LABEL_SPACING.end() - 0.5,
            "time labels fully shown from {} px: {labels:?}",
            TIME_LABEL_SPACING.end()
        );
        // at the drawn scale
        let px = (b.0 - a.0) * mem.transform().dpos_dvalue_x();
        assert!(((b.1 - a.1) as f64 - px).abs() < 1.0, "{labels:?}");
    }
}

/// At 1280 × 720 the time plots are short and their legends take the small
/// text: at least 11 px (egui's 9 px could not be read).
#[test]
fn short_plots_legends_are_legible() {
    let mut h = crate::harness::harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    h.run();
    advance(&mut h, 500);
    h.run_steps(2);
    let sizes: Vec<f32> = crate::harness::shapes(&h)
        .iter()
        .filter_map(|s| match s {
            egui::Shape::Text(t) if t.galley.text() == "point 0" => {
                t.galley.job.sections.first().map(|s| s.format.font_id.size)
            }
            _ => None,
        })
        .collect();
    assert!(sizes.len() >= 4, "{sizes:?}");
    assert!(
        sizes.iter().all(|&px| px >= 11.0),
        "legend text {sizes:?} px"
    );
}

/// In the smallest window (900 × 600) with the editing panel and the mode
/// bars both open, the side panels give way and the time plots keep a
/// readable width (they were squeezed to about 120 px, their legends over
/// the curves).
#[test]
fn side_panels_leave_the_time_plots_room_in_a_small_window() {
    use egui_plot::PlotMemory;
    use tirecontact::gui::views::time_plots::FORCE_PLOT_ID;
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), [900.0, 600.0]);
    h.run();
    h.state_mut()
        .apply(tirecontact::gui::Command::ShowModeBars(true));
    advance(&mut h, 2_000);
    h.run_steps(2);
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(FORCE_PLOT_ID)).expect("plot shown");
    let frame = *mem.transform().frame();
    assert!(
        frame.width() >= 250.0 && frame.right() <= 900.0,
        "force plot {frame:?} in a 900 px window"
    );
    assert!(
        h.get_all_by_label("Mute").count() > 0,
        "the mode bars are shown"
    );
}

/// A patch's legend ("point 0 (first of 16, colours along the ramp)") beside
/// the mode bars at 1280 × 800: the strip past the window's end it needed
/// took half of each time plot, the curves squeezed into the other half.
/// Wider than `MAX_LEGEND_STRIP` of the frame, it goes to one row above the
/// four plots, as on a phone: the newest samples stay in the right part of
/// the frame, and the legend's first name is still shown.
#[test]
fn a_wide_legend_leaves_the_curves_most_of_the_plot() {
    use egui_plot::PlotMemory;
    use tirecontact::gui::views::time_plots::{FORCE_PLOT_ID, MAX_LEGEND_STRIP};
    let scene = Scene::load(Path::new("presets/patch_chip_seal.ron")).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), [1280.0, 800.0]);
    h.run();
    h.state_mut()
        .apply(tirecontact::gui::Command::ShowModeBars(true));
    // past the 0.1 s window: the followed window is full
    advance(&mut h, 12_000);
    h.run_steps(3);
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(FORCE_PLOT_ID)).expect("plot shown");
    let frame = *mem.transform().frame();
    let t_end = h.state().simulation().time_s();
    let newest_x = mem.transform().position_from_point_x(t_end);
    let share = (newest_x - frame.left()) / frame.width();
    assert!(
        share >= 1.0 - MAX_LEGEND_STRIP,
        "the curves end at {newest_x} px, {share:.2} of the force plot {frame:?}"
    );
    // the first and the last names, side by side (the unnamed points
    // between them laid empty labels that put the two over each other)
    let first = h.get_by_label_contains("first of 16").rect();
    let last = h.get_by_label_contains("(last)").rect();
    assert!(
        !first.intersects(last),
        "the shared legend's names overlap: {first:?} and {last:?}"
    );
}
