//! The time plots' curves are solid polylines. egui_plot draws a line with
//! two samples in one pixel column as a band of vertical thickness the
//! stroke's width: a steep stretch then thinned to nothing, and every curve
//! of the paper preset looked dashed (dashes mean the reference run in A/B
//! compare). The min/max decimation already gives at most two samples per
//! column, so the curves are drawn as paths, every sample joined.

use crate::harness::{advance, harness_sized, shapes};
use egui::epaint::{ColorMode, PathShape, Shape};
use tirecontact::gui::views::point_color;
use tirecontact::gui::{App, Command, View};

#[test]
fn every_time_plot_curve_is_one_solid_path_at_both_window_sizes() {
    for size in [[1600.0, 1000.0], [1280.0, 720.0]] {
        let mut h = harness_sized(App::with_default_preset(), size);
        h.state_mut().apply(Command::ShowView(View::TimePlots));
        // past the ramp, through many landings and releases
        advance(&mut h, 6000);
        h.run_steps(2);
        let colors: Vec<egui::Color32> = (0..5).map(point_color).collect();
        let all = shapes(&h);
        let bands = all
            .iter()
            .filter(|s| matches!(s, Shape::Band(b) if colors.contains(&b.fill)))
            .count();
        assert_eq!(bands, 0, "{size:?}: {bands} curves drawn as bands");
        // each point's curve in each of the three line plots (displacement,
        // force, gap): one open path of many joined samples
        for (i, c) in colors.iter().enumerate() {
            let paths: Vec<usize> = all
                .iter()
                .filter_map(|s| match s {
                    Shape::Path(PathShape {
                        points,
                        stroke,
                        closed: false,
                        ..
                    }) if matches!(stroke.color, ColorMode::Solid(k) if k == *c) => {
                        Some(points.len())
                    }
                    _ => None,
                })
                .filter(|n| *n >= 100)
                .collect();
            assert!(
                paths.len() >= 3,
                "{size:?}: point {i} has {} long solid paths ({paths:?})",
                paths.len()
            );
        }
    }
}
