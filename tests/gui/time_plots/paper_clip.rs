//! "clip impact spikes" with the paper's contact scheme (`contact_scheme:
//! Paper`), which locates no impacts: its landing steps are the impacts
//! (rule of `output::impacts::paper_impact_n`, unit-tested there), so the force plot fits the rolling
//! force and marks the first-contact spikes ▼, as it does for located impacts.

use crate::harness::{advance, harness};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::SceneSimulation;
use tirecontact::gui::views::time_plots::{FORCE_PLOT_ID, clip_level};
use tirecontact::gui::{App, Command};
use tirecontact::gui::{History, Quantity};
use tirecontact::scene::ContactScheme;
use tirecontact::{Scene, Simulation};

fn paper_scene(scheme: ContactScheme) -> Scene {
    let mut scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    scene.contact_scheme = scheme;
    scene
}

/// Highest step-mean force per point, after the ramp (`from` steps on),
/// of the paper scheme's history, raw and without impacts (N).
fn paper_maxima(steps: usize, from: usize) -> (Vec<f64>, Vec<f64>) {
    let scene = paper_scene(ContactScheme::Paper);
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let p = sim.num_points();
    let mut h = History::new(p, 1 << 24);
    h.record_initial(&sim);
    for _ in 0..steps {
        sim.step().unwrap();
        h.after_step(&sim);
    }
    assert_eq!(h.stride(), 1);
    let max = |what| {
        (0..p)
            .map(|i| {
                (from..h.len())
                    .map(|k| h.value(what, i, k))
                    .fold(0.0, f64::max)
            })
            .collect::<Vec<f64>>()
    };
    (max(Quantity::Force), max(Quantity::ForceWithoutImpacts))
}

/// The paper scheme's force without impacts has the rolling force's range
/// that the located scheme (which reports its impacts' impulses) gives the
/// same scene: an independent reference, within 10 %.
#[test]
fn paper_force_without_impacts_matches_the_located_schemes() {
    let (steps, from) = (12_000, 6_000);
    let (raw, smooth) = paper_maxima(steps, from);
    let scene = paper_scene(ContactScheme::Located);
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let p = sim.num_points();
    let mut located = vec![0.0f64; p];
    for k in 1..=steps {
        sim.step().unwrap();
        if k >= from {
            for (i, m) in located.iter_mut().enumerate() {
                let q = sim.force_n()[i] - sim.impact_impulse_ns()[i] / sim.dt_s();
                *m = m.max(q);
            }
        }
    }
    for i in 0..p {
        assert!(
            raw[i] > 10.0 * located[i],
            "point {i}: the paper scheme spikes at landings: {} N vs {} N",
            raw[i],
            located[i]
        );
        assert!(
            (smooth[i] - located[i]).abs() <= 0.1 * located[i],
            "point {i}: paper without impacts {} N vs located {} N",
            smooth[i],
            located[i]
        );
    }
}

fn force_axis(h: &Harness<'_, App>) -> (f64, f64) {
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(FORCE_PLOT_ID)).expect("plot shown");
    let b = mem.bounds();
    (b.min()[1], b.max()[1])
}

/// Range of `what` over the samples of all points at times `t >= t0`.
fn range_since(app: &App, what: Quantity, t0: f64) -> (f64, f64) {
    let h = app.history();
    let from = h.times().partition_point(|&t| t < t0);
    (0..h.num_points())
        .flat_map(|i| (from..h.len()).map(move |k| h.value(what, i, k)))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
            (lo.min(y), hi.max(y))
        })
}

#[test]
fn the_time_plots_clip_the_paper_schemes_first_contact_spikes() {
    let mut h = harness(App::new(paper_scene(ContactScheme::Located), None).unwrap());
    h.run();
    // switched in the contact panel (a restart)
    h.state_mut().apply(Command::EditScene(Box::new(paper_scene(
        ContactScheme::Paper,
    ))));
    h.run_steps(1);
    assert_eq!(h.state().scene().contact_scheme, ContactScheme::Paper);
    advance(&mut h, 12_000);
    h.run_steps(4);

    // the followed window: the latest 0.1 s
    let t_end = h.state().history().last_time().unwrap();
    let t0 = t_end - 0.1;
    let raw = range_since(h.state(), Quantity::Force, t0);
    let smooth = range_since(h.state(), Quantity::ForceWithoutImpacts, t0);
    let top = clip_level(smooth);
    assert!(
        raw.1 > 10.0 * top,
        "the window holds landing spikes: {} N vs {top} N",
        raw.1
    );
    let (lo, hi) = force_axis(&h);
    assert!(hi >= smooth.1, "axis top {hi} N below the rolling force");
    assert!(
        hi <= top + 0.1 * (top - lo),
        "axis top {hi} N beyond the clip level {top} N (spikes {} N)",
        raw.1
    );
    assert!(
        h.query_by_label_contains("impact (impulse / dt, clipped)")
            .is_some(),
        "clipped landings are marked in the legend"
    );

    // not clipped: the spikes set the axis, nothing is marked
    h.get_by_label("clip impact spikes").click();
    h.run_steps(4);
    let (_, hi) = force_axis(&h);
    assert!(hi >= raw.1, "axis top {hi} N below the spike {} N", raw.1);
    assert!(
        h.query_by_label_contains("impact (impulse / dt, clipped)")
            .is_none()
    );
}
