//! The scene plot at the window sizes of a laptop and a projector
//! (1280 × 720, 1920 × 1080): in the normal view its x axis shows numbers
//! clear of its title from the first frame (a view opened while paused has
//! no second frame); in classroom mode the plot keeps most of its height
//! (the phase strip, the header and the legend one row each), shows its
//! height labels and spreads the road over its width.

use crate::harness::{advance, harness_sized, shapes, texts};
use egui::Rect;
use egui_kittest::Harness;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::scene_view::{ROAD_COLOR, SCENE_PLOT_ID};
use tirecontact::gui::{App, Command, View};

const SIZES: [[f32; 2]; 2] = [[1280.0, 720.0], [1920.0, 1080.0]];

fn frame(h: &Harness<'_, App>) -> Rect {
    *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(SCENE_PLOT_ID))
        .expect("scene plot shown")
        .transform()
        .frame()
}

/// The numbers painted under the frame (x tick labels) and beside it (y).
fn tick_numbers(h: &Harness<'_, App>, f: Rect) -> (Vec<Rect>, Vec<Rect>) {
    let number = |t: &str| t.replace('−', "-").trim().parse::<f64>().is_ok();
    let all = texts(h);
    let x = all
        .iter()
        .filter(|(t, r)| number(t) && r.top() >= f.bottom() - 1.0 && r.top() <= f.bottom() + 40.0)
        .filter(|(_, r)| r.center().x >= f.left() - 20.0 && r.center().x <= f.right() + 20.0)
        .map(|(_, r)| *r)
        .collect();
    let y = all
        .iter()
        .filter(|(t, r)| number(t) && r.right() <= f.left() + 1.0 && r.right() >= f.left() - 14.0)
        .filter(|(_, r)| r.center().y >= f.top() - 1.0 && r.center().y <= f.bottom() + 1.0)
        .map(|(_, r)| *r)
        .collect();
    (x, y)
}

fn paper(size: [f32; 2]) -> Harness<'static, App> {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    harness_sized(App::new(scene, None).unwrap(), size)
}

#[test]
fn the_scene_views_x_axis_shows_numbers_under_its_title_from_the_first_frame() {
    for size in SIZES {
        let mut h = paper(size);
        h.run();
        advance(&mut h, 2000);
        h.run();
        // opened while paused: one frame, no input to bring a second
        h.state_mut().apply(Command::ShowView(View::Scene));
        h.run_steps(1);
        let f = frame(&h);
        let (x, _) = tick_numbers(&h, f);
        assert!(x.len() >= 3, "{size:?}: {} x tick labels", x.len());
        let title = texts(&h)
            .into_iter()
            .find(|(t, _)| t.starts_with("position along the contact line"))
            .expect("the x title")
            .1;
        for r in &x {
            assert!(
                !r.intersects(title),
                "{size:?}: tick label {r:?} under the title {title:?}"
            );
        }
    }
}

#[test]
fn the_classroom_scene_keeps_its_height_and_spreads_the_road() {
    for size in SIZES {
        let mut h = paper(size);
        h.run();
        h.state_mut().apply(Command::SetClassroom(true));
        h.run_steps(3);
        // in the ramp (its "ramping in" note shown) and after it
        for steps in [2000, 8000] {
            advance(&mut h, steps);
            h.run_steps(2);
            let f = frame(&h);
            let at = format!("{size:?} at {} steps", h.state().simulation().steps());
            eprintln!("{at}: scene frame {:.0} x {:.0} px", f.width(), f.height());
            assert!(
                f.height() >= 0.3 * size[1],
                "{at}: scene plot {:.0} px high",
                f.height()
            );
            let (_, y) = tick_numbers(&h, f);
            assert!(y.len() >= 3, "{at}: {} height labels", y.len());
            // the phase strip on one row
            let all = texts(&h);
            let strip: Vec<Rect> = all
                .iter()
                .filter(|(t, _)| {
                    t.starts_with('p')
                        && t.contains(": ")
                        && t[1..]
                            .split(':')
                            .next()
                            .is_some_and(|n| n.parse::<u32>().is_ok())
                })
                .map(|(_, r)| *r)
                .filter(|r| r.bottom() <= f.top())
                .collect();
            assert_eq!(strip.len(), 5, "{at}: phase strip {strip:?}");
            assert!(
                strip
                    .iter()
                    .all(|r| (r.center().y - strip[0].center().y).abs() < 2.0),
                "{at}: the phase strip wraps: {strip:?}"
            );
            // the header on one row
            let row_of = |prefix: &str| {
                all.iter()
                    .find(|(t, _)| {
                        t.starts_with(prefix) || (prefix == "force (N)" && t.ends_with(prefix))
                    })
                    .unwrap_or_else(|| panic!("{at}: no {prefix:?}"))
                    .1
                    .center()
                    .y
            };
            assert!(
                (row_of("heights ×") - row_of("V = ")).abs() < 2.0,
                "{at}: the header wraps"
            );
            // the legend on one row
            assert!(
                (row_of("road (") - row_of("force (N)")).abs() < 2.0,
                "{at}: the legend wraps"
            );
            // the road's line spans most of the plot's width
            let road: Vec<f32> = shapes(&h)
                .iter()
                .filter_map(|s| match s {
                    egui::Shape::Path(p)
                        if !p.closed
                            && matches!(p.stroke.color, egui::epaint::ColorMode::Solid(c) if c == ROAD_COLOR) =>
                    {
                        Some(p.points.iter().map(|q| q.x).collect::<Vec<f32>>())
                    }
                    _ => None,
                })
                .flatten()
                .filter(|x| *x >= f.left() && *x <= f.right())
                .collect();
            let lo = road.iter().copied().fold(f32::MAX, f32::min);
            let hi = road.iter().copied().fold(f32::MIN, f32::max);
            assert!(
                hi - lo >= 0.6 * f.width(),
                "{at}: the road spans {:.0} of {:.0} px",
                hi - lo,
                f.width()
            );
        }
    }
}
