//! The contact plot draws one lane per shown point, raised while the point
//! is in contact. On a patch preset at 1280 × 720 (then eight lanes about
//! 10 px apart, now the sixteen points of a row) a raised lane touched the
//! next lane's floor: the lanes overlapped
//! by a stroke (1.8 px apart, closed by anti-aliasing). The painted lanes
//! keep at least 3 px (two strokes) of clear background between the ink of
//! neighbouring lanes at both window sizes.

use crate::harness::{advance, harness_sized, shapes};
use egui::epaint::{ColorMode, PathShape, Shape};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::shown_point_color;
use tirecontact::gui::views::time_plots::CONTACT_PLOT_ID;
use tirecontact::gui::{App, Command, View};

/// Clear px wanted between the ink of two neighbouring lanes.
const CLEAR_PX: f32 = 3.0;

#[test]
fn neighbouring_contact_lanes_never_overlap() {
    for preset in ["paper.ron", "patch_texture.ron", "patch_chip_seal.ron"] {
        for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
            let scene = Scene::load(&Path::new("presets").join(preset)).unwrap();
            let mut h = harness_sized(App::new(scene, None).unwrap(), size);
            h.state_mut().apply(Command::ShowView(View::TimePlots));
            h.run_steps(2);
            advance(&mut h, 6000);
            h.run_steps(2);
            let frame = *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(CONTACT_PLOT_ID))
                .expect("contact plot shown")
                .transform()
                .frame();
            // each lane's ink: its paths' vertical extent and half a stroke
            let shown = h.state().plot_options().shown.clone();
            let shown_idx: Vec<usize> = (0..shown.len()).filter(|&i| shown[i]).collect();
            let mut lanes: Vec<(usize, f32, f32)> = Vec::new();
            for (lane, &i) in shown_idx.iter().enumerate() {
                let c = shown_point_color(&shown_idx, i);
                let (mut top, mut bottom) = (f32::INFINITY, f32::NEG_INFINITY);
                for s in shapes(&h) {
                    if let Shape::Path(PathShape {
                        points,
                        stroke,
                        closed: false,
                        ..
                    }) = &s
                        && stroke.color == ColorMode::Solid(c)
                        && points.iter().all(|p| frame.contains(*p))
                    {
                        for p in points {
                            top = top.min(p.y - 0.5 * stroke.width);
                            bottom = bottom.max(p.y + 0.5 * stroke.width);
                        }
                    }
                }
                assert!(
                    top < bottom,
                    "{preset} {size:?}: lane of point {i} not painted"
                );
                lanes.push((lane, top, bottom));
            }
            assert!(lanes.len() >= 3, "{preset} {size:?}: {} lanes", lanes.len());
            for w in lanes.windows(2) {
                // lane k + 1 is drawn above lane k
                let ((_, low_top, _), (_, _, high_bottom)) = (w[0], w[1]);
                let clear = low_top - high_bottom;
                eprintln!(
                    "{preset} {size:?}: lanes {} and {} {clear:.1} px apart",
                    w[0].0, w[1].0
                );
                assert!(
                    clear >= CLEAR_PX,
                    "{preset} {size:?}: lanes {} and {} overlap ({clear:.2} px clear)",
                    w[0].0,
                    w[1].0
                );
            }
        }
    }
}
