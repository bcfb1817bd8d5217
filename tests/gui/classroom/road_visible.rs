//! Classroom mode on the paper preset: the automatic exaggeration makes
//! the 1 mm road's waves and the tyre's displacement visible (it chose ×2
//! on a −20…15 mm axis, where both looked flat), as large as in the normal
//! scene view at least.

use super::{app_on, harness};
use tirecontact::gui::views::scene_view::SCENE_PLOT_ID;
use tirecontact::gui::{Command, View};

/// The scene plot's exaggeration, and the road's peak to peak (px) for an
/// amplitude of `amplitude_m`.
fn road_px(h: &egui_kittest::Harness<'_, tirecontact::gui::App>, amplitude_m: f64) -> (f64, f64) {
    let mem = egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(SCENE_PLOT_ID))
        .expect("scene plot shown");
    let t = mem.transform();
    let e = h.state().scene_options().exaggeration;
    let per_px = t.dvalue_dpos()[1].abs();
    (e, 2.0 * amplitude_m * e / per_px)
}

#[test]
fn the_classroom_scene_shows_the_paper_roads_waves() {
    for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
        let mut h = harness(app_on("paper.ron"), size);
        h.run();
        h.state_mut().apply(Command::ShowView(View::Scene));
        h.run_steps(3);
        let (e_normal, px_normal) = road_px(&h, 0.001);
        h.state_mut().apply(Command::SetClassroom(true));
        h.run_steps(3);
        let (e, px) = road_px(&h, 0.001);
        let frame_h = egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(SCENE_PLOT_ID))
            .unwrap()
            .transform()
            .frame()
            .height();
        eprintln!(
            "{size:?}: normal x{e_normal} {px_normal:.0} px; classroom x{e} {px:.0} px of {frame_h}"
        );
        assert!(
            px >= 0.08 * f64::from(frame_h),
            "{size:?}: the road's waves {px:.0} px of a {frame_h} px plot at x{e}"
        );
        assert!(
            e >= e_normal,
            "{size:?}: x{e} in classroom, x{e_normal} in the normal view"
        );
    }
}
