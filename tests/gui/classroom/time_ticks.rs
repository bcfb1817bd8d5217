//! The classroom's point plot draws no time label cut by the frame's edge:
//! "0.1" was left of 0.17 s at the right edge while the run played (a label
//! centred on a tick closer to the edge than half its width).

use crate::harness::{advance, texts};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::classroom::CLASSROOM_PLOT_ID;
use tirecontact::gui::{App, Command};

#[test]
fn no_time_label_is_cut_by_the_frame() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
    h.run();
    h.state_mut().apply(Command::ShowView(View::Scene));
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(2);
    let mut near_edge = 0;
    // moments of the run: the window's end at 0.1 s, then on in 2.5 ms
    // steps, so that ticks pass the frame's edges
    advance(&mut h, 10_000);
    for _ in 0..40 {
        advance(&mut h, 250);
        h.run_steps(2);
        let frame = *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(CLASSROOM_PLOT_ID))
            .expect("point plot shown")
            .transform()
            .frame();
        let all = texts(&h);
        let axis = all
            .iter()
            .find(|(t, _)| t == "time t (s)")
            .expect("time axis label")
            .1;
        for (t, r) in all.iter().filter(|(t, r)| {
            t.parse::<f64>().is_ok() && r.top() >= frame.bottom() && r.bottom() <= axis.top() + 1.0
        }) {
            assert!(
                r.left() >= frame.left() - 0.5 && r.right() <= frame.right() + 0.5,
                "t = {} s: time label {t:?} over x {:.1}..{:.1}, the frame spans {:.1}..{:.1}",
                h.state().simulation().time_s(),
                r.left(),
                r.right(),
                frame.left(),
                frame.right()
            );
            if r.right() > frame.right() - 40.0 {
                near_edge += 1;
            }
        }
    }
    // the check saw labels close to the edge, not only ones far from it
    assert!(
        near_edge > 0,
        "no time label came near the frame's right edge"
    );
}
