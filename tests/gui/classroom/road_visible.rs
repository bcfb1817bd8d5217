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

/// The rule on the paper preset's figures: five points at x = −50…50 mm
/// preloaded by 3 mm over a 1 mm, 0.1 m sine, drawn over −110…110 mm (a
/// margin of 0.6 wavelengths), in the classroom's scene plot at 1280 × 720
/// (its frame about 769 × 237 px) and 1600 × 1000 (1015 × 427 px): the height
/// axis spans 15 mm (five times the largest height, 3 mm) and the road's
/// 2 mm peak to peak takes 13 % of it. Rounded down as in the normal view's
/// wider plot, the short plot took ×2 on a 37 mm axis (5 %).
#[test]
fn the_classroom_rule_gives_the_paper_roads_waves_an_eighth_of_the_axis() {
    use tirecontact::gui::views::scene_view::auto_exaggeration_for;
    let scene = crate::support::preset("paper");
    let hmax = scene
        .points
        .iter()
        .map(|p| p.h_m.abs())
        .fold(0.001, f64::max);
    assert_eq!(hmax, 0.003);
    let width_m = 0.22;
    let road_pp_m = 0.002;
    // the height axis (true m) of a frame at aspect 1: the road window,
    // widened by e / fit when rounded up, over the frame's shape, without
    // the exaggeration
    let axis_m = |frame: [f32; 2], round_up: bool| {
        let (e, fit) = auto_exaggeration_for(frame, width_m / hmax, round_up);
        let widen = (e / fit).max(1.0);
        (e, width_m * widen * f64::from(frame[1] / frame[0]) / e)
    };
    for frame in [[769.0, 237.0], [1015.0, 427.0]] {
        let (e, axis) = axis_m(frame, true);
        eprintln!("{frame:?}: x{e}, axis {:.1} mm", axis * 1e3);
        assert!((axis - 5.0 * hmax).abs() < 1e-12, "{frame:?}: {axis} m");
        assert!(road_pp_m / axis > 0.13, "{frame:?}: x{e}");
    }
    let (e, axis) = axis_m([769.0, 237.0], false);
    assert_eq!(e, 2.0);
    assert!(road_pp_m / axis < 0.06, "{}", road_pp_m / axis);
}
