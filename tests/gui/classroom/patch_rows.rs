//! On a patch preset the classroom's side view draws one row across the
//! tread in full and the others faded behind it, says which row of how
//! many it shows, and a top view beside it draws every point at a place of
//! its own: the rows share their x, and drawn alike they lay 96 points on
//! 16 places.

use crate::harness::{advance, shapes, texts};
use egui::epaint::{CircleShape, PathShape, Shape};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::classroom::{TOP_VIEW_DOT_PX, top_view_caption};
use tirecontact::gui::views::scene_view::{FADED_ROW_COLOR, FADED_ROW_MARKER_PX, SCENE_PLOT_ID};
use tirecontact::gui::views::{CONTACT_COLOR, FLIGHT_COLOR};
use tirecontact::gui::{App, Command, View};

/// Centres of the full-size markers (7 px: discs on the road, diamonds in
/// flight) and of the faded rows' markers inside `frame`.
pub(crate) fn markers(shapes: &[Shape], frame: egui::Rect) -> (Vec<egui::Pos2>, Vec<egui::Pos2>) {
    let (mut full, mut faded) = (Vec::new(), Vec::new());
    for s in shapes {
        match s {
            Shape::Circle(CircleShape {
                center,
                radius,
                fill,
                ..
            }) if frame.contains(*center) => {
                if *fill == CONTACT_COLOR && (*radius - 7.0).abs() < 0.01 {
                    full.push(*center);
                } else if *fill == FADED_ROW_COLOR && (*radius - FADED_ROW_MARKER_PX).abs() < 0.01 {
                    faded.push(*center);
                }
            }
            Shape::Path(PathShape {
                points,
                closed: true,
                fill,
                ..
            }) if points.len() == 4 && *fill == FLIGHT_COLOR => {
                let c = egui::Pos2::new(
                    points.iter().map(|p| p.x).sum::<f32>() / 4.0,
                    points.iter().map(|p| p.y).sum::<f32>() / 4.0,
                );
                // a 7 px diamond: its corners 7 px from its centre
                if frame.contains(c) && (points[0].distance(c) - 7.0).abs() < 0.05 {
                    full.push(c);
                }
            }
            _ => {}
        }
    }
    (full, faded)
}

/// The font size (px) of the painted text `text`.
fn font_px(h: &egui_kittest::Harness<'_, App>, text: &str) -> f32 {
    shapes(h)
        .iter()
        .find_map(|s| match s {
            Shape::Text(t) if t.galley.text() == text => {
                t.galley.job.sections.first().map(|s| s.format.font_id.size)
            }
            _ => None,
        })
        .unwrap_or(0.0)
}

#[test]
fn a_patch_shows_one_row_in_full_and_names_it() {
    let preset = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/patch_texture.ron");
    let scene = Scene::load(&preset).unwrap();
    let n = scene.points.len();
    let rows = tirecontact::gui::views::scene_view::rows_y_m(&scene.points);
    assert_eq!((n, rows.len()), (96, 6));
    let along = n / rows.len();
    let row0: Vec<f64> = scene
        .points
        .iter()
        .filter(|p| p.y_m == scene.points[0].y_m)
        .map(|p| p.x_m)
        .collect();
    assert_eq!(row0.len(), along);
    for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
        let mut h = crate::harness::harness_sized(App::new(scene.clone(), None).unwrap(), size);
        h.run();
        h.state_mut().apply(Command::ShowView(View::Scene));
        h.state_mut().apply(Command::SetClassroom(true));
        h.run_steps(2);
        // into the run: some points on the road, some in flight
        advance(&mut h, 3000);
        h.run_steps(2);
        let frame = *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(SCENE_PLOT_ID))
            .expect("scene plot shown")
            .transform()
            .frame();
        let (full, faded) = markers(&shapes(&h), frame);
        // one row in full (point 0's), at as many places as it has points
        assert_eq!(full.len(), along, "{size:?}: full markers {full:?}");
        let mut xs: Vec<f32> = full.iter().map(|p| p.x).collect();
        xs.sort_by(f32::total_cmp);
        assert!(
            xs.windows(2).all(|w| w[1] - w[0] > 3.0),
            "{size:?}: full markers share a place: {xs:?}"
        );
        // the road window zoomed to the patch: it spans most of the plot
        let spread = xs.last().copied().unwrap_or(0.0) - xs.first().copied().unwrap_or(0.0);
        assert!(
            spread > 0.5 * frame.width(),
            "{size:?}: patch {spread} px of {} px",
            frame.width()
        );
        // the other rows faded, every one of their points drawn
        assert_eq!(faded.len(), n - along, "{size:?}");
        let all = texts(&h);
        let named = all
            .iter()
            .find(|(t, _)| t.contains(&format!("row 1 of {} across the tread", rows.len())))
            .unwrap_or_else(|| panic!("{size:?}: no row named in {all:?}"));
        assert!(named.0.contains("the other 5 faded"), "{named:?}");
        // classroom size: at least 20 px
        assert!(font_px(&h, &named.0) >= 20.0, "{named:?}");
        // the top view: every point at a place of its own, the rows apart
        let caption = top_view_caption(rows.len());
        let (_, cap) = all
            .iter()
            .find(|(t, _)| *t == caption)
            .unwrap_or_else(|| panic!("{size:?}: no {caption:?} in {all:?}"));
        assert!(font_px(&h, &caption) >= 20.0, "{caption:?}");
        // beside the plot, covering neither the road nor the phase labels
        assert!(
            cap.left() > frame.right(),
            "{size:?}: top view at {cap:?} over the plot {frame:?}"
        );
        let dots: Vec<egui::Pos2> = shapes(&h)
            .iter()
            .filter_map(|s| match s {
                Shape::Circle(c)
                    if (c.fill == CONTACT_COLOR || c.fill == FLIGHT_COLOR)
                        && c.radius <= TOP_VIEW_DOT_PX
                        && c.center.y > cap.bottom() =>
                {
                    Some(c.center)
                }
                _ => None,
            })
            .collect();
        assert_eq!(dots.len(), n, "{size:?}");
        for (i, a) in dots.iter().enumerate() {
            for b in &dots[..i] {
                assert!(a.distance(*b) >= 4.0, "{size:?}: dots at {a:?} and {b:?}");
            }
        }
        let mut ys: Vec<f32> = dots.iter().map(|p| p.y).collect();
        ys.sort_by(f32::total_cmp);
        ys.dedup_by(|a, b| (*a - *b).abs() < 0.5);
        assert_eq!(ys.len(), rows.len(), "{size:?}: rows at {ys:?}");
    }
}
