//! Classroom mode at 1280 × 720: the scene plot is about 200 px high; its
//! legend (six entries in the top right corner) covered the tyre. The
//! legend is a row above the plot: every entry lies above the tyre's
//! painted line and markers. The phase labels never overlap each other
//! (read from the painted text shapes over the paper preset's run), and the
//! y title fits the plot's height.

use crate::harness::{advance, shapes};
use egui::epaint::{CircleShape, ColorMode, PathShape};
use egui::{Rect, Shape};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::views::scene_view::{
    CONTACT_NAME, DISPLACED_NAME, FLIGHT_NAME, ROAD_NAME_LEFT, SCENE_PLOT_ID, UNDEFORMED_NAME,
    displaced_tyre_color,
};
use tirecontact::gui::views::{CONTACT_COLOR, FLIGHT_COLOR};
use tirecontact::gui::{App, Command};

/// Bounds of the tyre as painted: its displaced line (one vertex per point,
/// 2 px, the theme's tyre colour) and the points' markers (7 px radius).
fn tyre_bounds(h: &Harness<'_, App>, points: usize) -> Rect {
    let tyre = displaced_tyre_color(&h.ctx.global_style().visuals);
    let frame = *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(SCENE_PLOT_ID))
        .expect("scene plot shown")
        .transform()
        .frame();
    let mut r = Rect::NOTHING;
    for s in shapes(h)
        .into_iter()
        .filter(|s| frame.contains_rect(s.visual_bounding_rect()))
    {
        match &s {
            Shape::Path(PathShape {
                points: p,
                closed: false,
                stroke,
                ..
            }) if p.len() == points && stroke.color == ColorMode::Solid(tyre) => {
                p.iter().for_each(|q| r.extend_with(*q));
            }
            Shape::Circle(CircleShape {
                center,
                radius,
                fill,
                ..
            }) if *radius >= 6.0 && (*fill == CONTACT_COLOR || *fill == FLIGHT_COLOR) => {
                r.extend_with(*center);
            }
            Shape::Path(PathShape {
                points: p,
                fill,
                closed: true,
                ..
            }) if *fill == FLIGHT_COLOR && p.len() == 4 => {
                p.iter().for_each(|q| r.extend_with(*q));
            }
            _ => {}
        }
    }
    r
}

/// Phase labels drawn in the plot ("p3: IMPACT"; the strip above the plot
/// lists them all on one line).
fn phase_labels(h: &Harness<'_, App>) -> Vec<(String, Rect)> {
    shapes(h)
        .iter()
        .filter_map(|s| match s {
            Shape::Text(t) => Some((t.galley.text().to_owned(), t.visual_bounding_rect())),
            _ => None,
        })
        .filter(|(t, _)| t.starts_with('p') && t.matches(": ").count() == 1 && !t.contains("  "))
        .collect()
}

#[test]
fn classroom_scene_legend_keeps_off_the_tyre_and_phase_labels_do_not_overlap() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let points = scene.points.len();
    let steps = (scene.duration_s / scene.dt_s).round() as u64;
    for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
        let mut h = crate::harness::harness_sized(App::new(scene.clone(), None).unwrap(), size);
        h.run();
        h.state_mut().apply(Command::ShowView(View::Scene));
        h.state_mut().apply(Command::SetClassroom(true));
        h.run_steps(2);
        let mut checked_labels = 0;
        let mut most = 0;
        let chunk = 250;
        for _ in 0..steps / chunk {
            advance(&mut h, chunk);
            h.run_steps(1);
            let tyre = tyre_bounds(&h, points);
            assert!(tyre.is_positive(), "{size:?}: no tyre painted");
            for name in [
                ROAD_NAME_LEFT,
                UNDEFORMED_NAME,
                DISPLACED_NAME,
                CONTACT_NAME,
                FLIGHT_NAME,
            ] {
                let e = h.get_by_label(name).rect();
                assert!(
                    e.bottom() <= tyre.top() - 7.0,
                    "{size:?} t = {} s: legend entry {name:?} at {e:?} over the tyre at {tyre:?}",
                    h.state().simulation().time_s()
                );
            }
            let labels = phase_labels(&h);
            most = most.max(labels.len());
            for (i, (a, ra)) in labels.iter().enumerate() {
                for (b, rb) in &labels[i + 1..] {
                    assert!(
                        !ra.intersects(*rb),
                        "{size:?} t = {} s: {a:?} at {ra:?} overlaps {b:?} at {rb:?}",
                        h.state().simulation().time_s()
                    );
                    checked_labels += 1;
                }
            }
        }
        // the y title fits the plot's height (it ran past a short plot)
        let frame = *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(SCENE_PLOT_ID))
            .expect("scene plot shown")
            .transform()
            .frame();
        let (title, r) = shapes(&h)
            .iter()
            .find_map(|s| match s {
                Shape::Text(t)
                    if t.angle != 0.0
                        && t.galley.text().contains("height (mm)")
                        && t.visual_bounding_rect().right() <= frame.left() =>
                {
                    Some((t.galley.text().to_owned(), t.visual_bounding_rect()))
                }
                _ => None,
            })
            .expect("the scene plot's y title");
        eprintln!("{size:?}: y title {title:?} spans {r:?}, the plot {frame:?}");
        assert!(
            r.top() >= frame.top() - 0.5 && r.bottom() <= frame.bottom() + 0.5,
            "{size:?}: y title {title:?} at {r:?} past the plot {frame:?}"
        );
        eprintln!("{size:?}: {checked_labels} pairs of phase labels checked, up to {most} at once");
        assert!(
            checked_labels > 0,
            "{size:?}: never two phase labels at once"
        );
    }
}

/// The classroom scene legend is one row at 1280 × 720, in the classroom's
/// type scale (at least 20 px: its small text, 15 px, was too small from
/// the back of a room), its entries' short names where the full ones do
/// not fit one row; as large as the row has room for at 1600 px.
#[test]
fn the_classroom_scene_legend_is_one_row_as_large_as_it_fits() {
    use tirecontact::gui::views::scene_legend::ROW_MIN_PX;
    for (preset, size_px, least) in [
        ("paper.ron", [1280.0, 720.0], 1.0),
        ("three_points.ron", [1280.0, 720.0], 1.0),
        ("paper.ron", [1600.0, 1000.0], 1.0),
    ] {
        let scene =
            tirecontact::Scene::load(&std::path::Path::new("presets").join(preset)).unwrap();
        let mut h = crate::harness::harness_sized(
            tirecontact::gui::App::new(scene, None).unwrap(),
            size_px,
        );
        h.state_mut()
            .apply(tirecontact::gui::Command::SetClassroom(true));
        h.run_steps(4);
        crate::harness::advance(&mut h, 1_000);
        h.run_steps(4);
        // each entry's full or short name
        let names = [
            ("road (moving left)", "road (to left)"),
            ("undeformed tyre", "undeformed"),
            ("in contact", "in contact"),
            ("contact force (N)", "force (N)"),
        ];
        let mut found = Vec::new();
        for s in crate::harness::shapes(&h) {
            if let egui::Shape::Text(t) = s
                && names
                    .iter()
                    .any(|(a, b)| *a == t.galley.text() || *b == t.galley.text())
            {
                let size = t.galley.job.sections[0].format.font_id.size;
                found.push((t.galley.text().to_owned(), size, t.visual_bounding_rect()));
            }
        }
        assert_eq!(found.len(), names.len(), "{preset}: {found:?}");
        // (tops: a name with parentheses reaches lower)
        let y = found[0].2.top();
        for (name, size, r) in &found {
            assert!(
                *size >= least * ROW_MIN_PX - 1e-3,
                "{preset}: {name} in {size} px text"
            );
            assert!((r.top() - y).abs() < 2.0, "{preset}: two rows {found:?}");
            assert!(r.right() <= size_px[0], "{preset}: {name} cut at {r:?}");
        }
    }
}
