//! The patch view's plots read as figures: the total force and the contact
//! area against time carry y numbers at several values with their units in
//! the titles (the total force plot showed only its 0), time numbers and
//! title below; the heat map's axes are in mm; no two of the view's texts
//! overlap. At 1280 × 720 and 1600 × 1000, on the three patch presets.

use crate::harness::{advance, harness_sized, settle, texts};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::patch_view::{
    CONTACT_AREA_PLOT_ID, CONTACT_AREA_TITLE, TOTAL_FORCE_PLOT_ID, TOTAL_FORCE_TITLE,
};
use tirecontact::gui::{App, Command, View};

/// A tick label's value (`1 000` grouped, `−` or `-`).
fn number(t: &str) -> Option<f64> {
    t.replace([' ', '\u{2009}'], "")
        .replace('−', "-")
        .parse()
        .ok()
}

#[test]
fn the_patch_plots_have_numbered_axes_with_units() {
    for preset in [
        "patch_texture.ron",
        "patch_wheel_path.ron",
        "patch_chip_seal.ron",
    ] {
        for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
            let scene = Scene::load(&Path::new("presets").join(preset)).unwrap();
            let mut h = harness_sized(App::new(scene, None).unwrap(), size);
            settle(&mut h);
            h.state_mut().apply(Command::ShowView(View::Patch));
            settle(&mut h);
            advance(&mut h, 4000);
            h.run_steps(3);
            let all = texts(&h);
            for (id, title) in [
                (TOTAL_FORCE_PLOT_ID, TOTAL_FORCE_TITLE),
                (CONTACT_AREA_PLOT_ID, CONTACT_AREA_TITLE),
            ] {
                let frame = *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(id))
                    .unwrap_or_else(|| panic!("{preset}: plot {id} shown"))
                    .transform()
                    .frame();
                // y numbers: left of the frame, within its height
                let ys: Vec<f64> = all
                    .iter()
                    .filter(|(_, r)| {
                        r.right() <= frame.left() + 1.0
                            && r.center().y >= frame.top() - 1.0
                            && r.center().y <= frame.bottom() + 1.0
                    })
                    .filter_map(|(t, _)| number(t))
                    .collect();
                assert!(
                    ys.len() >= 3,
                    "{preset} {size:?}: {title}: y numbers {ys:?} (frame {frame:?})"
                );
                // time numbers below the frame
                let xs = all
                    .iter()
                    .filter(|(t, r)| {
                        r.top() >= frame.bottom() - 1.0
                            && r.top() <= frame.bottom() + 30.0
                            && r.center().x >= frame.left()
                            && r.center().x <= frame.right()
                            && number(t).is_some()
                    })
                    .count();
                assert!(xs >= 3, "{preset} {size:?}: {title}: {xs} time numbers");
                for want in [title, "time t (s)"] {
                    assert!(
                        all.iter().any(|(t, r)| t == want
                            && r.top() >= frame.top() - 60.0
                            && r.bottom() <= frame.bottom() + 60.0),
                        "{preset} {size:?}: no {want:?} beside the plot {id}"
                    );
                }
            }
            // the heat map's axes in mm
            for want in ["y (mm)", "along the rolling direction x (mm)"] {
                assert!(
                    all.iter().any(|(t, _)| t == want),
                    "{preset} {size:?}: no heat map axis title {want:?}"
                );
            }
            // no two texts of the view overlap (the heat map's row labels
            // among them)
            let view: Vec<&(String, egui::Rect)> = all
                .iter()
                .filter(|(t, r)| !t.trim().is_empty() && r.left() > 0.3 * size[0])
                .collect();
            for (i, (a, ra)) in view.iter().enumerate() {
                for (b, rb) in &view[i + 1..] {
                    assert!(
                        !ra.shrink(0.5).intersects(rb.shrink(0.5)),
                        "{preset} {size:?}: {a:?} at {ra:?} overlaps {b:?} at {rb:?}"
                    );
                }
            }
        }
    }
}
