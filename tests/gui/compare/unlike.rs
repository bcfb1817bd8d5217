//! A/B compare of unlike scenes: a pinned five-point run against a scene
//! of three points (one moved) says how the scenes differ and compares only
//! the points at the same place; the force plot's curves stay at or below
//! the ▼ clip line of the impacts.

use crate::harness::{advance, curves, harness_sized, settle, shapes};
use egui::epaint::{PathShape, Shape};
use egui_kittest::kittest::Queryable;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::compare_view::FORCE_PLOT_ID;
use tirecontact::gui::views::point_color;
use tirecontact::gui::views::time_plots::IMPACT_MARK_COLOR;
use tirecontact::gui::{App, Command, View};

#[test]
fn unlike_scenes_are_said_and_compared_only_where_they_match() {
    let paper = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = harness_sized(App::new(paper.clone(), None).unwrap(), [1600.0, 1000.0]);
    settle(&mut h);
    advance(&mut h, 8000);
    h.state_mut().apply(Command::ShowView(View::Compare));
    h.run_steps(2);
    h.get_by_label("Pin as reference").click();
    h.run_steps(2);
    assert!(h.state().research().pinned().is_some());

    let mut three = paper.clone();
    three.points = vec![paper.points[0], paper.points[2], paper.points[4]].into();
    three.points[2].x_m += 0.013;
    h.state_mut().apply(Command::EditScene(Box::new(three)));
    settle(&mut h);
    advance(&mut h, 8000);
    h.run_steps(4);

    assert!(
        h.query_by_label_contains("The reference has 5 points, this scene 3")
            .is_some(),
        "no word that the scenes differ"
    );
    assert!(
        h.query_by_label_contains("p0, p1 (reference p2)").is_some(),
        "the points compared are not named"
    );
    let d = h.state().research().difference().expect("a difference");
    assert_eq!(d.matched, [Some(0), Some(2), None]);
    assert!(d.du_m[2].is_empty());
    let rms = crate::harness::texts(&h)
        .into_iter()
        .map(|(t, _)| t)
        .find(|t| t.contains("RMS of current − reference"))
        .expect("an RMS line");
    assert!(rms.contains("p1:") && !rms.contains("p2:"), "{rms}");

    // the force plot: nothing drawn above the ▼ marks of clipped impacts
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(FORCE_PLOT_ID)).expect("force plot");
    let frame = *mem.transform().frame();
    let all = shapes(&h);
    let marks: Vec<f32> = all
        .iter()
        .filter_map(|s| match s {
            Shape::Path(PathShape {
                points,
                fill,
                closed: true,
                ..
            }) if *fill == IMPACT_MARK_COLOR && frame.contains(points[0]) => {
                Some(points.iter().map(|p| p.y).sum::<f32>() / points.len() as f32)
            }
            _ => None,
        })
        .collect();
    assert!(!marks.is_empty(), "the impacts are clipped and marked");
    let mark_top = marks.iter().copied().fold(f32::MAX, f32::min);
    let colors: Vec<egui::Color32> = (0..5)
        .flat_map(|i| [point_color(i), point_color(i).gamma_multiply(0.6)])
        .collect();
    let drawn: Vec<egui::Pos2> = curves(&h, &colors, 2)
        .into_iter()
        .flatten()
        .filter(|p| frame.contains(*p))
        .collect();
    assert!(!drawn.is_empty());
    let highest = drawn.iter().map(|p| p.y).fold(f32::MAX, f32::min);
    // (the mark's centroid sits a third of its height below the clip level)
    assert!(
        highest >= mark_top - 4.0,
        "a curve reaches y = {highest} px, above the ▼ marks at {mark_top} px"
    );
}

/// A reference with no point at the place of any current point: the view
/// says nothing is compared and draws no difference plots (they showed
/// empty axes over meaningless ranges).
#[test]
fn no_difference_plots_when_nothing_is_compared() {
    use tirecontact::gui::views::compare_view::FORCE_DIFF_PLOT_ID;
    let paper = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = harness_sized(App::new(paper.clone(), None).unwrap(), [1280.0, 720.0]);
    settle(&mut h);
    advance(&mut h, 2000);
    h.state_mut().apply(Command::ShowView(View::Compare));
    h.run_steps(2);
    h.get_by_label("Pin as reference").click();
    h.run_steps(2);
    assert!(
        PlotMemory::load(&h.ctx, egui::Id::unique(FORCE_DIFF_PLOT_ID)).is_some(),
        "the premise: difference plots shown against the run itself"
    );
    let mut moved = paper.clone();
    for p in moved.points.iter_mut() {
        p.x_m += 0.005;
    }
    h.state_mut().apply(Command::EditScene(Box::new(moved)));
    settle(&mut h);
    advance(&mut h, 2000);
    h.ctx.memory_mut(|m| m.data.clear());
    h.run_steps(4);
    assert!(h.query_by_label_contains("nothing is compared").is_some());
    assert!(
        PlotMemory::load(&h.ctx, egui::Id::unique(FORCE_DIFF_PLOT_ID)).is_none(),
        "a difference plot with nothing compared"
    );
}
