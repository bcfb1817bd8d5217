//! The exported PNG figure of the time plots follows "clip impact spikes":
//! on, its force panel is cut at the clip level (a margin above the force
//! without impacts of its windows) with the clipped samples as dots; off,
//! the impulse / dt spikes set its range. Both contact schemes.

use crate::harness::{advance, harness};
use crate::support::temp_dir;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::jobs::export::{CLIPPED_IMPACTS, time_figure};
use tirecontact::gui::views::time_plots::clip_level;
use tirecontact::gui::{App, Command};
use tirecontact::gui::{History, Quantity};
use tirecontact::output::figures::{Figure, Series};
use tirecontact::output::record::{PLOT_SAMPLES, Recording};
use tirecontact::scene::ContactScheme;

/// Range of `values`.
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
        (lo.min(y), hi.max(y))
    })
}

/// The windows the exported figure draws: the history's samples merged to
/// at most the command line's figure samples, the t = 0 sample on its own.
fn windows(h: &History) -> Recording {
    let rec = h.to_recording();
    assert_eq!(rec.len(), h.len());
    // the recording holds what the history holds
    for i in 0..h.num_points() {
        for k in 0..h.len() {
            let smooth = rec.q_n[i][k] - rec.q_impact_n[i][k];
            let want = h.value(Quantity::ForceWithoutImpacts, i, k);
            assert!((smooth - want).abs() <= 1e-6 * (1.0 + want.abs()));
        }
    }
    let merged = rec.merged_after_start((rec.len() - 1).div_ceil(PLOT_SAMPLES as usize));
    assert!(merged.len() <= 1 + PLOT_SAMPLES as usize);
    merged
}

fn force_panel(fig: &Figure) -> &tirecontact::output::figures::Panel {
    fig.panels
        .iter()
        .find(|p| p.title.starts_with("Contact force"))
        .expect("a force panel")
}

fn highest(series: &[&Series]) -> f64 {
    series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .fold(f64::NEG_INFINITY, f64::max)
}

fn check(preset: &str, scheme: ContactScheme, steps: u64) {
    let mut scene = Scene::load(Path::new(&format!("presets/{preset}.ron"))).unwrap();
    scene.contact_scheme = scheme;
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    advance(&mut h, steps);
    let app = h.state();
    let hist = app.history();
    let shown = vec![true; hist.num_points()];
    let rec = windows(hist);
    let raw = range(rec.q_n.iter().flatten().copied());
    let smooth = rec
        .q_n
        .iter()
        .flatten()
        .zip(rec.q_impact_n.iter().flatten())
        .map(|(q, qi)| q - qi);
    let top = clip_level(range(smooth));
    assert!(
        raw.1 > 5.0 * top,
        "{preset}: the run has impact spikes: {} N vs {top} N",
        raw.1
    );

    let fig = time_figure(app.scene(), app.modes(), hist, &shown, true);
    let panel = force_panel(&fig);
    let (dots, lines): (Vec<&Series>, Vec<&Series>) =
        panel.series.iter().partition(|s| s.name == CLIPPED_IMPACTS);
    assert_eq!(lines.len(), hist.num_points());
    assert_eq!(dots.len(), 1, "{preset}: clipped impacts are marked");
    assert!(!dots[0].points.is_empty());
    assert!(
        dots[0]
            .points
            .iter()
            .all(|p| (p.1 - top).abs() <= 1e-9 * top),
        "{preset}: the dots sit at the clip level {top} N"
    );
    let hi = highest(&lines);
    assert!(
        (hi - top).abs() <= 1e-9 * top,
        "{preset}: force lines reach {hi} N, clip level {top} N"
    );
    // said by the dots' legend entry, not again in the panel title
    assert!(!panel.title.contains("clipped"), "{}", panel.title);

    let fig = time_figure(app.scene(), app.modes(), hist, &shown, false);
    let panel = force_panel(&fig);
    assert!(panel.series.iter().all(|s| s.name != CLIPPED_IMPACTS));
    let all: Vec<&Series> = panel.series.iter().collect();
    assert_eq!(
        highest(&all),
        raw.1,
        "{preset}: unclipped, the spikes are drawn"
    );

    // the app's export writes the figure (clip on by default)
    let tmp = temp_dir();
    let path = tmp.path().join(format!("export_clip_{preset}.png"));
    h.state_mut().apply(Command::ExportPng {
        path: path.clone(),
        width: 800,
        height: 600,
    });
    let bytes = std::fs::read(&path).expect("PNG written");
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn the_exported_force_panel_clips_located_impacts() {
    check("three_points", ContactScheme::Located, 15_000);
}

#[test]
fn the_exported_force_panel_clips_the_paper_schemes_landings() {
    check("paper", ContactScheme::Paper, 12_000);
}

#[test]
fn the_exported_contact_lanes_are_named_after_their_points() {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    advance(&mut h, 200);
    let app = h.state();
    let hist = app.history();
    // point 1 hidden: lanes 0, 1 are points 0 and 2
    let shown = vec![true, false, true];
    let fig = time_figure(app.scene(), app.modes(), hist, &shown, true);
    let lanes = fig
        .panels
        .iter()
        .find(|p| p.title.starts_with("Contact state"))
        .expect("a contact panel");
    assert_eq!(lanes.y_names, ["p0", "p2"]);
    // the other panels keep numeric ticks
    assert!(
        fig.panels
            .iter()
            .filter(|p| !p.title.starts_with("Contact state"))
            .all(|p| p.y_names.is_empty())
    );
    // one legend of the points, in the first panel (same colours in all)
    let named = |p: &tirecontact::output::figures::Panel| {
        p.series
            .iter()
            .filter(|s| s.name.starts_with("point "))
            .count()
    };
    assert_eq!(named(&fig.panels[0]), 2);
    assert!(fig.panels[1..].iter().all(|p| named(p) == 0));
}
