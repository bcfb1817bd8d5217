//! The A/B compare view in small windows (900 × 600, a phone's 412 × 915):
//! its four plots keep a readable height and the view scrolls with the
//! mouse wheel until the last plot and its time axis end above the status
//! bar; the displacement difference's axis shows at least two labelled
//! ticks, and a difference that is (nearly) constant, as of a run compared
//! with itself, gets an axis of a few micrometres (egui_plot gave a flat
//! line an axis as high as the time axis is wide).

use crate::harness::{advance, harness_sized, plot_frame, status_top, texts, wheel};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::compare_view::{
    DISPLACEMENT_DIFF_PLOT_ID, DISPLACEMENT_PLOT_ID, FORCE_DIFF_PLOT_ID, FORCE_PLOT_ID,
    MIN_HALF_SPAN_MM, MIN_PLOT_PX,
};
use tirecontact::gui::{App, Command, View};
use tirecontact::scene::Tyre;

const PLOTS: [&str; 4] = [
    DISPLACEMENT_PLOT_ID,
    FORCE_PLOT_ID,
    DISPLACEMENT_DIFF_PLOT_ID,
    FORCE_DIFF_PLOT_ID,
];

/// A run of three_points pinned, then (`edit`) the scene with its first
/// mode 10 % higher run again: four plots (without the edit, the
/// differences are zero).
fn compare(size: [f32; 2], edit: bool) -> Harness<'static, App> {
    let mut scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    scene.duration_s = 0.03;
    let mut h = harness_sized(App::new(scene.clone(), None).unwrap(), size);
    h.run();
    advance(&mut h, 3000);
    h.state_mut().apply(Command::ShowView(View::Compare));
    h.run_steps(2);
    h.get_by_label("Pin as reference").click();
    h.run_steps(2);
    if edit {
        let mut edited = scene.clone();
        if let Tyre::Modal { modes } = &mut edited.tyre {
            modes[0].freq_hz *= 1.1;
        }
        h.state_mut().apply(Command::EditScene(Box::new(edited)));
        h.run_steps(1);
        advance(&mut h, 3000);
    }
    h.run_steps(4);
    h
}

/// The numbers painted left of `frame` beside it (its y tick labels).
fn y_ticks(h: &Harness<'_, App>, frame: egui::Rect) -> Vec<String> {
    texts(h)
        .into_iter()
        .filter(|(t, r)| {
            t.replace('−', "-").trim().parse::<f64>().is_ok()
                && r.right() <= frame.left() + 1.0
                && r.right() >= frame.left() - 20.0
                && r.center().y >= frame.top()
                && r.center().y <= frame.bottom()
        })
        .map(|(t, _)| t)
        .collect()
}

#[test]
fn the_compare_plots_keep_their_height_and_the_view_scrolls_to_the_last() {
    for size in [[900.0, 600.0], [412.0, 915.0]] {
        let mut h = compare(size, true);
        let bottom = status_top(&h);
        for id in PLOTS {
            let f = plot_frame(&h, id);
            eprintln!("{size:?}: {id} frame {f:?}");
            assert!(
                f.height() >= 0.6 * MIN_PLOT_PX,
                "{size:?}: the frame of {id} is {:.0} px high",
                f.height()
            );
        }
        let first = plot_frame(&h, PLOTS[0]);
        wheel(&mut h, first.center(), -400.0, 8);
        let last = plot_frame(&h, PLOTS[3]);
        let axis = texts(&h)
            .into_iter()
            .filter(|(t, _)| t == "time t (s)")
            .map(|(_, r)| r.bottom())
            .fold(f32::NEG_INFINITY, f32::max);
        assert!(
            last.top() >= 0.0 && axis.is_finite() && axis <= bottom,
            "{size:?}: scrolled to its end, the last plot {last:?} with its time axis down to {axis} px, the status bar at {bottom} px"
        );
    }
}

#[test]
fn the_displacement_difference_axis_shows_two_ticks() {
    for size in [[900.0, 600.0], [412.0, 915.0], [1280.0, 720.0]] {
        for edit in [true, false] {
            let mut h = compare(size, edit);
            let f = plot_frame(&h, DISPLACEMENT_DIFF_PLOT_ID);
            if f.bottom() > status_top(&h) {
                let first = plot_frame(&h, PLOTS[0]);
                wheel(&mut h, first.center(), -400.0, 8);
            }
            let f = plot_frame(&h, DISPLACEMENT_DIFF_PLOT_ID);
            assert!(f.bottom() <= status_top(&h), "{size:?}: Δu at {f:?}");
            let ticks = y_ticks(&h, f);
            eprintln!("{size:?} edited {edit}: Δu ticks {ticks:?} beside {f:?}");
            assert!(
                ticks.len() >= 2,
                "{size:?} (edited: {edit}): the Δu axis shows {ticks:?}"
            );
            if !edit {
                let b = *egui_plot::PlotMemory::load(
                    &h.ctx,
                    egui::Id::unique(DISPLACEMENT_DIFF_PLOT_ID),
                )
                .unwrap()
                .bounds();
                let (lo, hi) = (b.min()[1], b.max()[1]);
                assert!(
                    lo <= -MIN_HALF_SPAN_MM
                        && hi >= MIN_HALF_SPAN_MM
                        && hi - lo <= 2.5 * MIN_HALF_SPAN_MM,
                    "{size:?}: a zero difference on an axis {lo}..{hi} mm"
                );
            }
        }
    }
}

/// Labelled marks (egui_plot labels a step more than 20 px apart) of a
/// value axis over `bounds` drawn `px` high.
fn labelled(bounds: (f64, f64), px: f64) -> Vec<f64> {
    let range = bounds.1 - bounds.0;
    tirecontact::gui::views::nice_marks(
        egui_plot::GridInput {
            bounds,
            base_step_size: 8.0 * range / px,
        },
        30.0,
        tirecontact::gui::views::Y_SHOWN_PX,
    )
    .into_iter()
    .filter(|m| m.step_size * px / range > 20.0 && m.value >= bounds.0 && m.value <= bounds.1)
    .map(|m| m.value)
    .collect()
}

/// The value axes of the compare view's plots (frames of 105 px and more:
/// the plots' least height) label at least two ticks whatever their range:
/// a labelled step of more than half the axis left one label
/// (−0.22..0.49 mm in 105 px: only 0).
#[test]
fn value_axes_label_at_least_two_ticks() {
    let l = labelled((-0.22, 0.49), 105.0);
    assert!(l.len() >= 2, "{l:?}");
    for px in [105.0, 125.0, 150.0, 200.0, 400.0] {
        for k in 0..400 {
            // spans over three decades, at every offset
            let span = 10f64.powf(-3.0 + 3.0 * f64::from(k % 40) / 40.0);
            let lo = -span * f64::from(k / 40) / 10.0;
            let l = labelled((lo, lo + span), px);
            assert!(l.len() >= 2, "{lo}..{} at {px} px: labels {l:?}", lo + span);
        }
    }
}
