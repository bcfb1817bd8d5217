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

/// Before the first step: the time axes run from 0 to the run's duration
/// and the colour bar says there is no force yet (it ran 0 to 1e-9 N, the
/// axes -0.5 to 0.5 s). Early in the run the contact area counts only the
/// points carrying force: with no force there is no area (it showed about
/// 105 cm² at 0 N, every point touching the road while the preload ramps
/// in).
#[test]
fn the_patch_view_starts_empty_and_counts_only_loaded_points() {
    use tirecontact::gui::views::patch_view::NO_FORCE_YET;
    for preset in [
        "patch_texture.ron",
        "patch_wheel_path.ron",
        "patch_chip_seal.ron",
    ] {
        let scene = Scene::load(&Path::new("presets").join(preset)).unwrap();
        let duration_s = scene.duration_s;
        let mut h = harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
        settle(&mut h);
        h.state_mut().apply(Command::ShowView(View::Patch));
        settle(&mut h);
        h.run_steps(3);
        let all = texts(&h);
        let (_, label) = all
            .iter()
            .find(|(t, _)| t == NO_FORCE_YET)
            .unwrap_or_else(|| panic!("{preset}: no {NO_FORCE_YET:?} in {all:?}"));
        assert!(label.right() <= 1280.0, "{preset}: cut off at {label:?}");
        assert!(
            !all.iter()
                .any(|(t, _)| t.contains("e-9") || t.contains("1e-")),
            "{preset}: {all:?}"
        );
        for id in [TOTAL_FORCE_PLOT_ID, CONTACT_AREA_PLOT_ID] {
            let mem = egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(id))
                .unwrap_or_else(|| panic!("{preset}: plot {id} shown"));
            let b = *mem.transform().bounds();
            assert!(
                b.min()[0] >= -0.1 * duration_s && b.max()[0] >= duration_s,
                "{preset}: {id} time axis {:?} for a run of {duration_s} s",
                b.range_x()
            );
            // a force and an area are never negative: before the first
            // force, 0 to 1, not around 0
            assert!(
                b.min()[1] == 0.0 && b.max()[1] >= 1.0,
                "{preset}: {id} value axis {:?} before any force",
                b.range_y()
            );
        }
        // a few steps in: the header's area is the loaded points' cells
        advance(&mut h, 20);
        h.run_steps(2);
        let sim = h.state().simulation();
        let total: f64 = sim.force_n().iter().sum();
        let header = texts(&h)
            .into_iter()
            .map(|(t, _)| t)
            .find(|t| t.contains("contact area"))
            .expect("the header");
        if total == 0.0 {
            assert!(header.contains("contact area 0 cm²"), "{preset}: {header}");
        }
        let carrying = sim.force_n().iter().filter(|&&f| f > 0.0).count();
        assert!(
            header.contains(&format!("({carrying} of ")),
            "{preset}: {header}"
        );
    }
}

/// The header's figures to three significant digits with their units (it
/// read "cell 6.0 × 20.0 mm", "438.6 N"); the points carrying force and
/// those in contact at the step's end both said where they differ (the
/// status bar's "11 in contact" stood beside "13 carrying force").
#[test]
fn the_patch_header_rounds_to_meaningful_digits() {
    use tirecontact::gui::views::patch_view::header_text;
    assert_eq!(
        header_text(0.090_37, 438.62, 22.8e-4, (19, 19, 96), (0.006, 0.02)),
        "t = 0.0904 s: total force 439 N, contact area 22.8 cm² (19 of 96 points in contact and carrying force, cell 6 × 20 mm)"
    );
    assert_eq!(
        header_text(0.0, 0.0, 0.0, (0, 0, 96), (0.002_5, 0.03)),
        "t = 0 s: total force 0 N, contact area 0 cm² (0 of 96 points in contact and carrying force, cell 2.5 × 30 mm)"
    );
    assert!(
        header_text(0.05, 300.0, 1e-3, (13, 11, 96), (0.006, 0.02)).contains(
            "13 of 96 points carrying force over the last step, 11 in contact at its end"
        )
    );
    // a small force keeps its digits
    assert!(
        header_text(1e-5, 0.012_34, 1e-4, (3, 3, 96), (0.006, 0.02))
            .contains("total force 0.0123 N")
    );
}

/// The status bar and the patch view count the same points at the same
/// instant: the header's points in contact are the status bar's.
#[test]
fn the_patch_header_and_the_status_bar_agree_on_the_points_in_contact() {
    let path = format!("{}/presets/patch_chip_seal.ron", env!("CARGO_MANIFEST_DIR"));
    let app = tirecontact::gui::App::new(
        tirecontact::Scene::load(std::path::Path::new(&path)).unwrap(),
        None,
    )
    .unwrap();
    let mut h = crate::harness::harness(app);
    h.run();
    h.state_mut().apply(tirecontact::gui::Command::ShowView(
        tirecontact::gui::View::Patch,
    ));
    // through the ramp and some rolling steps, until a step releases a point
    let mut seen = false;
    for _ in 0..60 {
        crate::harness::advance(&mut h, 200);
        h.run_steps(1);
        let texts = crate::harness::texts(&h);
        let status = texts
            .iter()
            .find_map(|(t, _)| {
                t.strip_suffix(" in contact")
                    .and_then(|s| s.rsplit(' ').next())
            })
            .and_then(|n| n.parse::<usize>().ok())
            .expect("the status bar's count");
        let header = texts
            .iter()
            .find(|(t, _)| t.starts_with("t = ") && t.contains("points"))
            .map(|(t, _)| t.clone())
            .expect("the patch header");
        let said = if header.contains("at its end") {
            seen = true;
            format!(", {status} in contact at its end")
        } else {
            format!("({status} of 96 points in contact")
        };
        assert!(header.contains(&said), "status {status}: {header}");
        if seen {
            break;
        }
    }
    assert!(
        seen,
        "no step released a point inside it: both counts never differed"
    );
}

/// The heat map export is offered for a patch only: for a scene of one row
/// of points it is disabled, saying why, before any file is asked for.
#[test]
fn the_heat_map_export_is_offered_for_a_patch_only() {
    use egui_kittest::kittest::{NodeT, Queryable};
    for (preset, offered) in [
        ("presets/paper.ron", false),
        ("presets/patch_texture.ron", true),
    ] {
        let scene = tirecontact::Scene::load(std::path::Path::new(preset)).unwrap();
        let mut h = crate::harness::harness_sized(
            tirecontact::gui::App::new(scene, None).unwrap(),
            [1280.0, 720.0],
        );
        h.run_steps(2);
        h.get_by_label("Export").click();
        h.run_steps(2);
        let item = h.get_by_label("Contact patch heat map (PNG)…");
        assert_eq!(!item.accesskit_node().is_disabled(), offered, "{preset}");
    }
}
