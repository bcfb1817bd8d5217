//! The A/B compare view clips impact spikes like the time plots: with
//! "clip impact spikes" on (the default) its force axis is set by the force
//! without impacts (plus room for the legend above the clip level); off, by
//! the impulse / dt spikes.

use crate::harness::{advance, harness};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::analysis::compare::PinnedRun;
use tirecontact::gui::Quantity;
use tirecontact::gui::View;
use tirecontact::gui::research::compare::recording_without_impacts;
use tirecontact::gui::views::compare_view::{FORCE_DIFF_PLOT_ID, FORCE_PLOT_ID};
use tirecontact::gui::views::time_plots::clip_level;
use tirecontact::gui::{App, Command};
use tirecontact::scene::Tyre;

/// Lowest and highest y of the compare view's plot `id`, as drawn.
fn y_axis(h: &Harness<'_, App>, id: &str) -> (f64, f64) {
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(id)).expect("plot shown");
    let b = mem.bounds();
    (b.min()[1], b.max()[1])
}

/// Pixels of plot `id` between `level` and the axis top, the plot frame's
/// height and the height of its legend (its entries' span plus egui_plot's
/// padding: 4 px outside, 4 px inside the frame, above and below).
fn px_above(h: &Harness<'_, App>, id: &str, level: f64) -> (f32, f32, f32) {
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(id)).expect("plot shown");
    let tr = mem.transform();
    let frame = *tr.frame();
    let top = tr.position_from_point_y(mem.bounds().max()[1]);
    let entries: Vec<egui::Rect> = [
        "current run (solid)",
        "reference (dashed)",
        "current − reference",
        "impact (impulse / dt, clipped)",
    ]
    .iter()
    .flat_map(|l| h.get_all_by_label(l).map(|n| n.rect()).collect::<Vec<_>>())
    .filter(|r| frame.contains(r.center()))
    .collect();
    assert!(!entries.is_empty(), "no legend in {id}");
    let legend_h = entries.iter().map(|r| r.bottom()).fold(f32::MIN, f32::max)
        - entries.iter().map(|r| r.top()).fold(f32::MAX, f32::min)
        + 16.0;
    (
        tr.position_from_point_y(level) - top,
        frame.height(),
        legend_h,
    )
}

fn force_axis(h: &Harness<'_, App>) -> (f64, f64) {
    y_axis(h, FORCE_PLOT_ID)
}

fn range(ys: &[f64]) -> (f64, f64) {
    ys.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &y| {
            (lo.min(y), hi.max(y))
        })
}

/// Lowest and highest sample of `what` of point 0 over the whole history.
fn history_range(app: &App, what: Quantity) -> (f64, f64) {
    let h = app.history();
    (0..h.len())
        .map(|k| h.value(what, 0, k))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
            (lo.min(y), hi.max(y))
        })
}

#[test]
fn the_compare_force_axis_fits_the_force_without_impacts_when_clipping() {
    let scene = Scene::load(Path::new("presets/single_mode.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    advance(&mut h, 20_000);
    h.state_mut().apply(Command::ShowView(View::Compare));
    h.run_steps(2);
    h.get_by_label("Pin as reference").click();
    h.run_steps(4);
    assert!(h.state().research().pinned().is_some());

    let (_, raw_hi) = history_range(h.state(), Quantity::Force);
    let smooth = history_range(h.state(), Quantity::ForceWithoutImpacts);
    let top = clip_level(smooth);
    assert!(
        raw_hi > 5.0 * top,
        "the run has impact spikes: {raw_hi} N vs {top} N"
    );
    // clipped: the axis reaches the clip level (the ▼ marks) and no further
    // than room for the legend above it plus egui_plot's margin: far below
    // the spikes
    let (lo, hi) = force_axis(&h);
    assert!(hi >= top, "axis top {hi} N below the clip level {top} N");
    let (above_px, frame_px, legend_px) = px_above(&h, FORCE_PLOT_ID, top);
    eprintln!(
        "clip level {top} N, axis top {hi} N, spikes {raw_hi} N: {above_px} px above the clip level for a legend {legend_px} px high in a {frame_px} px plot"
    );
    assert!(
        above_px <= legend_px + 6.0 + 0.1 * frame_px,
        "axis top {hi} N, {above_px} px above the clip level {top} N (legend {legend_px} px)"
    );
    assert!(hi < 0.5 * raw_hi, "axis top {hi} N vs spikes {raw_hi} N");
    assert!(
        lo <= smooth.0,
        "{lo} N above the lowest force {} N",
        smooth.0
    );
    assert!(
        h.query_by_label_contains("impact (impulse / dt, clipped)")
            .is_some(),
        "clipped impacts are marked in the legend"
    );

    // not clipped: the spikes set the axis
    h.get_by_label("clip impact spikes").click();
    h.run_steps(4);
    let (_, hi) = force_axis(&h);
    assert!(hi >= raw_hi, "axis top {hi} N below the spike {raw_hi} N");
    assert!(
        h.query_by_label_contains("impact (impulse / dt, clipped)")
            .is_none()
    );
}

/// The force difference current − reference is clipped at both edges by the
/// difference of the forces without impacts (impacts of either run make
/// spikes of either sign).
#[test]
fn the_compare_force_difference_is_clipped_at_both_edges() {
    let scene = Scene::load(Path::new("presets/single_mode.ron")).unwrap();
    let mut h = harness(App::new(scene.clone(), None).unwrap());
    h.run();
    advance(&mut h, 20_000);
    h.state_mut().apply(Command::ShowView(View::Compare));
    h.run_steps(2);
    h.get_by_label("Pin as reference").click();
    h.run_steps(2);
    let pin = PinnedRun::new("a", &scene, 1, &h.state().history().to_recording());
    let pin_smooth = PinnedRun::new(
        "a",
        &scene,
        1,
        &recording_without_impacts(h.state().history()),
    );
    let mut edited = scene.clone();
    if let Tyre::Modal { modes } = &mut edited.tyre {
        modes[0].freq_hz *= 1.1;
    }
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    h.run_steps(1);
    advance(&mut h, 20_000);
    h.run_steps(4);

    let raw = range(
        &pin.difference(&scene.points, &h.state().history().to_recording())
            .dq_n[0],
    );
    let smooth = range(
        &pin_smooth
            .difference(
                &scene.points,
                &recording_without_impacts(h.state().history()),
            )
            .dq_n[0],
    );
    let (top, bottom) = (clip_level(smooth), -clip_level((-smooth.1, -smooth.0)));
    assert!(
        raw.1 > 2.0 * top && raw.0 < 2.0 * bottom,
        "impacts make spikes of both signs: {raw:?} vs {bottom}..{top} N"
    );
    let (lo, hi) = y_axis(&h, FORCE_DIFF_PLOT_ID);
    let margin = 0.1 * (top - bottom);
    // room for the legend above the upper clip level, far below the spikes
    let (above_px, frame_px, legend_px) = px_above(&h, FORCE_DIFF_PLOT_ID, top);
    eprintln!(
        "difference: clip {bottom}..{top} N, axis {lo}..{hi} N, spikes {raw:?} N: {above_px} px above for a legend {legend_px} px high in a {frame_px} px plot"
    );
    assert!(hi >= top, "{hi} vs {top} N");
    assert!(
        above_px <= legend_px + 6.0 + 0.1 * frame_px,
        "axis top {hi} N, {above_px} px above the clip level {top} N (legend {legend_px} px)"
    );
    assert!(hi < 0.5 * raw.1, "axis top {hi} N vs spikes {} N", raw.1);
    assert!(lo <= bottom && lo >= bottom - margin, "{lo} vs {bottom} N");

    // the RMS line is of the force the plot draws: without impacts here
    let rms_of = |d: &[f64]| (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt();
    let diff_smooth = pin_smooth.difference(
        &scene.points,
        &recording_without_impacts(h.state().history()),
    );
    let want = rms_of(&diff_smooth.dq_n[0]);
    let (text, got) = rms_line(&h);
    assert!(text.contains("force without impacts"), "{text}");
    assert!(
        (got - want).abs() <= 1e-3 * want && got <= smooth.1.max(-smooth.0),
        "RMS {got} N shown, {want} N of the force without impacts (its difference within {smooth:?} N): {text}"
    );

    h.get_by_label("clip impact spikes").click();
    h.run_steps(4);
    let (lo, hi) = y_axis(&h, FORCE_DIFF_PLOT_ID);
    assert!(hi >= raw.1 && lo <= raw.0, "{lo}..{hi} vs {raw:?} N");
    // unclipped: the RMS of the whole force, its spikes included
    let diff_raw = pin.difference(&scene.points, &h.state().history().to_recording());
    let want = rms_of(&diff_raw.dq_n[0]);
    let (text, got) = rms_line(&h);
    assert!(text.contains("force with impacts"), "{text}");
    assert!(
        (got - want).abs() <= 1e-3 * want,
        "RMS {got} N shown, {want} N: {text}"
    );
}

/// The compare view's RMS line and its force RMS of point 0 (N).
fn rms_line(h: &Harness<'_, App>) -> (String, f64) {
    let text = crate::harness::texts(h)
        .into_iter()
        .map(|(t, _)| t)
        .find(|t| t.contains("RMS of current − reference"))
        .expect("an RMS line");
    let value = text
        .split("p0: ")
        .nth(1)
        .and_then(|rest| rest.split(" N").next())
        .and_then(|v| v.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no force RMS of p0 in {text}"));
    (text, value)
}
