//! The A/B compare view clips impact spikes like the time plots: with
//! "clip impact spikes" on (the default) its force axis is set by the force
//! without impacts; off, by the impulse / dt spikes.
#![cfg(feature = "gui")]

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::command::View;
use tirecontact::gui::history::Quantity;
use tirecontact::gui::views::compare_view::FORCE_PLOT_ID;
use tirecontact::gui::views::time_plots::clip_level;
use tirecontact::gui::{App, Command};

fn harness(app: App) -> Harness<'static, App> {
    Harness::builder()
        .with_size([1500.0, 950.0])
        .with_step_dt(1.0 / 60.0)
        .build_ui_state(|ui, app: &mut App| app.show(ui), app)
}

/// Takes `n` solver steps (over as many frames as the step budget needs).
fn advance(h: &mut Harness<'_, App>, n: u64) {
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

/// Lowest and highest y of the compare view's force plot, as drawn.
fn force_axis(h: &Harness<'_, App>) -> (f64, f64) {
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(FORCE_PLOT_ID)).expect("force plot shown");
    let b = mem.bounds();
    (b.min()[1], b.max()[1])
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

    let (raw_lo, raw_hi) = history_range(h.state(), Quantity::Force);
    let smooth = history_range(h.state(), Quantity::ForceWithoutImpacts);
    let top = clip_level(smooth);
    assert!(
        raw_hi > 5.0 * top,
        "the run has impact spikes: {raw_hi} N vs {top} N"
    );
    // clipped: the axis reaches the clip level (the ▼ marks) and no further
    // than egui_plot's margin beyond it
    let (lo, hi) = force_axis(&h);
    let span = top - raw_lo.min(smooth.0);
    assert!(hi >= top, "axis top {hi} N below the clip level {top} N");
    assert!(
        hi <= top + 0.1 * span,
        "axis top {hi} N beyond the clip level {top} N"
    );
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
