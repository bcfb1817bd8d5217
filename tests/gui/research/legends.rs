//! The legends of the spectra, sweep and compare views keep off the curves:
//! measured in pixels as the length of the drawn curves (the plot lines as
//! egui shapes) under the legend entries, against the same length under a
//! legend-sized box in each corner.

use crate::harness::{advance, harness};
use egui::epaint::{PathShape, Shape};
use egui::{Pos2, Rect};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::SweepState;
use tirecontact::gui::View;
use tirecontact::gui::views::legend_place::length_inside;
use tirecontact::gui::{App, Command};
use tirecontact::scene::Tyre;

fn collect(shape: &Shape, out: &mut Vec<Vec<Pos2>>) {
    match shape {
        Shape::Vec(v) => v.iter().for_each(|s| collect(s, out)),
        // curves; not the 3-point impact markers
        Shape::Path(PathShape { points, closed, .. }) if points.len() > 3 && !closed => {
            out.push(points.clone())
        }
        // dense curves: egui_plot draws them as min/max bands
        Shape::Band(b) => {
            out.push(b.points.iter().map(|p| Pos2::new(p.x, p.y.min)).collect());
            out.push(b.points.iter().map(|p| Pos2::new(p.x, p.y.max)).collect());
            for p in &b.points {
                out.push(vec![Pos2::new(p.x, p.y.min), Pos2::new(p.x, p.y.max)]);
            }
        }
        _ => {}
    }
}

/// The polylines drawn on the last frame (the plots' curves).
fn curves(h: &Harness<'_, App>) -> Vec<Vec<Pos2>> {
    let mut out = Vec::new();
    for c in &h.output().shapes {
        collect(&c.shape, &mut out);
    }
    out
}

/// Rectangles of the legend entries named `labels`.
fn entries(h: &Harness<'_, App>, labels: &[&str]) -> Vec<Rect> {
    labels
        .iter()
        .flat_map(|l| h.get_all_by_label(l).map(|n| n.rect()).collect::<Vec<_>>())
        .collect()
}

/// Curve length (px) under the legend entries.
fn ink_under(h: &Harness<'_, App>, labels: &[&str]) -> (f32, usize) {
    let c = curves(h);
    let e = entries(h, labels);
    let per: Vec<f32> = e.iter().map(|r| length_inside(*r, &c)).collect();
    eprintln!("ink per entry (px): {per:?}");
    (per.iter().sum(), e.len())
}

fn settle(h: &mut Harness<'_, App>) {
    // the corner is chosen from the curves of the frame before
    h.run_steps(4);
}

/// The spectra's one legend is a row above the three plots, at both
/// window sizes; the markers' labels are small text that does not overlap.
#[test]
fn spectra_legends_keep_off_the_curves() {
    for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
        let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
        let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), size);
        h.run();
        advance(&mut h, 12_000);
        h.state_mut().apply(Command::ShowView(View::Spectra));
        settle(&mut h);
        let labels = [
            "point 0",
            "point 1",
            "point 2",
            "total: sum of all points",
            "road n·V/λ",
            "modal frequencies",
        ];
        let (ink, n) = ink_under(&h, &labels);
        assert_eq!(n, labels.len(), "{size:?}: legend entries found: {n}");
        assert!(ink <= 0.5, "{size:?}: {ink} px of curve under the legends");
        // all above the curves
        let top_curve = curves(&h)
            .iter()
            .flatten()
            .map(|p| p.y)
            .fold(f32::MAX, f32::min);
        for r in entries(&h, &labels) {
            assert!(
                r.bottom() <= top_curve,
                "{size:?}: entry {r:?} below a curve at {top_curve}"
            );
        }
        // the markers' labels: apart, and no smaller than the small text
        let marks: Vec<(String, Rect, f32)> = h
            .output()
            .shapes
            .iter()
            .filter_map(|c| match &c.shape {
                Shape::Text(t) => {
                    let s = t.galley.text().to_owned();
                    let px = t
                        .galley
                        .job
                        .sections
                        .first()
                        .map_or(0.0, |s| s.format.font_id.size);
                    (s.contains("V/λ") || (s.starts_with('f') && s[1..].parse::<u32>().is_ok()))
                        .then(|| (s, t.visual_bounding_rect(), px))
                }
                _ => None,
            })
            .collect();
        assert!(
            marks.iter().any(|m| m.0.starts_with("V/λ ")),
            "{size:?}: {marks:?}"
        );
        for (i, a) in marks.iter().enumerate() {
            assert!(a.2 >= 11.0, "{size:?}: {:?} in {} px", a.0, a.2);
            for b in &marks[i + 1..] {
                assert!(!a.1.intersects(b.1), "{size:?}: {:?} over {:?}", a.0, b.0);
            }
        }
    }
}

#[test]
fn compare_legends_keep_off_the_curves() {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    advance(&mut h, 12_000);
    h.state_mut().apply(Command::ShowView(View::Compare));
    h.run_steps(2);
    h.get_by_label("Pin as reference").click();
    h.run_steps(2);
    advance(&mut h, 4_000);
    // the curves fill the whole run: the legends go above them; on a
    // clipped force axis above the clip level (was 520 px of curve under
    // the force legend's entries, in its emptiest corner)
    h.get_by_label("clip impact spikes").click();
    settle(&mut h);
    let labels = ["current run (solid)", "reference (dashed)"];
    let (ink, n) = ink_under(&h, &labels);
    assert_eq!(n, 4, "legend entries found: {n}");
    eprintln!("compare: {ink:.0} px of curve under {n} legend entries");
    assert!(ink <= 10.0, "{ink} px of curve under the legends");
    h.get_by_label("clip impact spikes").click();
    settle(&mut h);
    let clipped = [
        "current run (solid)",
        "reference (dashed)",
        "impact (impulse / dt, clipped)",
    ];
    let (ink, n) = ink_under(&h, &clipped);
    assert_eq!(n, 5, "legend entries found: {n}");
    eprintln!("compare, clipped: {ink:.0} px of curve under {n} legend entries");
    assert!(ink <= 10.0, "{ink} px of curve under the clipped legends");
    // the difference plots (shown by default) get curves and legends once
    // the run differs from the reference: clipped, after an edit
    let mut edited = h.state().scene().clone();
    if let Tyre::Modal { modes } = &mut edited.tyre {
        modes[0].freq_hz *= 1.1;
    }
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    h.run_steps(1);
    advance(&mut h, 16_000);
    settle(&mut h);
    let (ink, n) = ink_under(&h, &[clipped.as_slice(), &["current − reference"]].concat());
    assert!(n >= 8, "legend entries found: {n}");
    eprintln!("compare with differences, clipped: {ink:.0} px of curve under {n} legend entries");
    assert!(ink <= 10.0, "{ink} px of curve under the legends");
}

#[test]
fn sweep_legends_keep_off_the_curves() {
    let mut scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    scene.duration_s = 0.05;
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    h.state_mut().apply(Command::ShowView(View::Sweep));
    h.run_steps(2);
    h.get_by_label("Run sweep").click();
    h.run_steps(2);
    for _ in 0..20_000 {
        if !h.state().research().sweep().is_running() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.run_steps(1);
    }
    assert!(matches!(
        h.state().research().sweep(),
        SweepState::Finished(_)
    ));
    settle(&mut h);
    let labels = ["point 0", "point 1", "point 2"];
    let (ink, n) = ink_under(&h, &labels);
    assert!(n >= 9, "legend entries found: {n}");
    eprintln!("sweep: {ink:.0} px of curve under {n} legend entries");
    assert!(ink <= 10.0, "{ink} px of curve under the legends");
    // every legend reads first to last downwards in every corner, as the
    // PNG's do: a bottom corner's legend stacked them upwards
    use egui_plot::Corner;
    use tirecontact::gui::views::{legend_place, sweep_view::PLOT_IDS};
    let bands = [
        "315 Hz band",
        "500 Hz band",
        "800 Hz band",
        "1250 Hz band",
        "2000 Hz band",
    ];
    for corner in [
        Corner::LeftBottom,
        Corner::RightBottom,
        Corner::LeftTop,
        Corner::RightTop,
    ] {
        for id in PLOT_IDS {
            legend_place::set_corner(&h.ctx, egui::Id::unique(id), corner);
        }
        h.run_steps(1);
        let tops = |labels: &[&str]| -> Vec<Vec<f32>> {
            labels
                .iter()
                .map(|l| h.get_all_by_label(l).map(|n| n.rect().top()).collect())
                .collect()
        };
        let points = tops(&labels);
        assert_eq!(points[0].len(), 3, "{corner:?}: point legends {points:?}");
        for k in 0..3 {
            // the three point legends, each in its own plot, left to right
            // and top to bottom alike for every label
            assert!(
                points[0][k] < points[1][k] && points[1][k] < points[2][k],
                "{corner:?}: legend {k} reads point 0..2 at y {:?}",
                points.iter().map(|p| p[k]).collect::<Vec<_>>()
            );
        }
        let b: Vec<f32> = tops(&bands).iter().map(|t| t[0]).collect();
        assert!(
            b.windows(2).all(|w| w[0] < w[1]),
            "{corner:?}: bands at y {b:?}"
        );
    }
}
