//! The fidelity view at 1280 × 720 (and 960 wide): its header (the relative
//! L2 error; the band and the pairs on the line under it, they made a strong
//! line running to the window's edge) is one line well inside the window,
//! and every other text stays inside it, wrapped where needed; with the ring
//! converted to a modal model and a mode removed too. Read from the painted
//! text shapes.

use crate::harness::wait_fidelity;
use egui_kittest::Harness;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::{App, Command};
use tirecontact::scene::Tyre;

fn inside(h: &Harness<'_, App>, w: f32, what: &str) {
    let all = crate::harness::texts(h);
    let header = all
        .iter()
        .find(|(t, _)| t.contains("relative L2 error"))
        .unwrap_or_else(|| panic!("{what}: no header"));
    // at 1280 px one line, well inside the window (it ran to 25 px of the
    // edge, with the band and the pairs on it)
    if w >= 1280.0 {
        let r = header.1;
        assert!(
            r.right() <= w - 200.0 && r.height() < 30.0,
            "{what}: the header {:?} is {r:?} in a {w} px window",
            header.0
        );
    }
    for (t, r) in all
        .iter()
        .filter(|(t, r)| !t.trim().is_empty() && r.is_finite())
    {
        assert!(
            r.right() <= w - 4.0,
            "{what}: {t:?} reaches x = {:.0} px of a {w} px window",
            r.right()
        );
    }
}

#[test]
fn the_fidelity_view_fits_1280_by_720() {
    for [w, hgt] in [[1280.0, 720.0], [960.0, 720.0]] {
        let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
        let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), [w, hgt]);
        h.run();
        h.state_mut().apply(Command::ShowView(View::Fidelity));
        h.run_steps(1);
        wait_fidelity(&mut h);
        h.run_steps(2);
        inside(&h, w, "ring");
        // as "Edit as a modal model" does, then the lowest mode removed
        let mut cut = h.state().scene().clone();
        let mut modes = h.state().modes().to_vec();
        modes.remove(0);
        cut.tyre = Tyre::Modal { modes };
        h.state_mut().apply(Command::EditScene(Box::new(cut)));
        h.run_steps(2);
        wait_fidelity(&mut h);
        h.run_steps(2);
        assert!(
            crate::harness::texts(&h)
                .iter()
                .any(|(t, _)| t.contains("12 modes in the modal sum")),
            "the mode was not removed"
        );
        inside(&h, w, "modal, a mode removed");
    }
}
