//! The mode bars' vertical axis label fits beside the plot frame (egui_plot
//! centres it on the frame): a frame shorter than the label let it run up
//! over the "point i: u = …" line above the plot in classroom mode.

use egui_kittest::kittest::Queryable;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::classroom::{MODE_BARS_PLOT_ID, MODE_BARS_Y_LABEL};
use tirecontact::gui::{App, Command};

fn check(preset: &str, size: [f32; 2]) {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets")
        .join(preset);
    let app = App::new(Scene::load(&p).unwrap(), Some(p)).unwrap();
    let mut h = crate::harness::harness_sized(app, size);
    h.run_steps(2);
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(4);
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(MODE_BARS_PLOT_ID)).expect("bars shown");
    let frame = *mem.transform().frame();
    let font = egui::TextStyle::Body.resolve(&h.ctx.global_style());
    let label_w = h
        .ctx
        .fonts_mut(|f| f.layout_no_wrap(MODE_BARS_Y_LABEL.to_owned(), font, egui::Color32::WHITE))
        .size()
        .x;
    // the rotated label spans label_w about the frame's centre
    let top = frame.center().y - 0.5 * label_w;
    let line = h.get_by_label_contains("u = ").rect();
    assert!(
        top >= line.bottom() && label_w <= frame.height(),
        "{preset} at {size:?}: label {label_w} px high from y = {top}, frame {frame:?}, line above ends at {}",
        line.bottom()
    );
}

#[test]
fn the_mode_bars_axis_label_stays_beside_the_frame_in_classroom_mode() {
    // 13 modes (many mute rows) and 3 modes, at a projector's and a laptop's size
    for size in [[1280.0, 720.0], [1500.0, 950.0]] {
        check("paper.ron", size);
        check("guided_1a_soft_tyre.ron", size);
    }
}
