//! A patch's row clicked in the patch view: the time plots draw its 16
//! points told apart (a colour ramp along the row when more than eight are
//! shown, the legend naming the first and the last), and the Plots PNG
//! holds the same points.

use crate::harness::{advance, harness_sized};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::jobs::export::time_figure;
use tirecontact::gui::{App, Command};
use tirecontact::output::figures::render_rgb_layout;

fn patch_app() -> egui_kittest::Harness<'static, App> {
    let preset = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/patch_chip_seal.ron");
    let scene = Scene::load(&preset).unwrap();
    let mut h = harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
    h.run();
    advance(&mut h, 2000);
    h
}

/// Points of row 2 (the patch presets number their points row by row).
fn row_2(h: &egui_kittest::Harness<'_, App>) -> Vec<usize> {
    let pts = &h.state().scene().points;
    let rows = tirecontact::gui::views::scene_view::rows_y_m(pts);
    (0..pts.len()).filter(|&i| pts[i].y_m == rows[2]).collect()
}

#[test]
fn a_clicked_row_exports_its_points() {
    let mut h = patch_app();
    let row = row_2(&h);
    assert_eq!(row.len(), 16);
    h.state_mut().apply(Command::ShowPoints(row.clone()));
    h.run();
    let app = h.state();
    let fig = time_figure(
        app.scene(),
        app.modes(),
        app.history(),
        &app.plot_options().shown,
        true,
    );
    let drawn: Vec<usize> = fig.panels[1]
        .series
        .iter()
        .filter_map(|s| s.color)
        .collect();
    assert_eq!(drawn.len(), row.len(), "{drawn:?}");
    // every line its own colour
    let mut colours = drawn.clone();
    colours.sort_unstable();
    colours.dedup();
    assert_eq!(colours.len(), row.len(), "colours repeat: {drawn:?}");
    // the legend names the row's first and last points
    let names: Vec<&str> = fig.panels[0]
        .series
        .iter()
        .map(|s| s.name.as_str())
        .filter(|n| !n.is_empty())
        .collect();
    let (first, last) = (row[0], row[row.len() - 1]);
    assert!(
        names.iter().any(|n| n.contains(&format!("point {first}")))
            && names.iter().any(|n| n.contains(&format!("point {last}"))),
        "{names:?}"
    );
    let (rgb, _) = render_rgb_layout(&fig, 1280, 720).unwrap();
    if let Some(dir) = std::env::var_os("TIRECONTACT_FIGURE_DIR") {
        image::RgbImage::from_raw(1280, 720, rgb)
            .unwrap()
            .save(Path::new(&dir).join("patch_row_plots.png"))
            .unwrap();
        let eight: Vec<bool> = (0..app.history().num_points()).map(|i| i < 8).collect();
        let fig = time_figure(app.scene(), app.modes(), app.history(), &eight, true);
        for (w, hgt) in [(1280, 720), (800, 600), (1600, 1000)] {
            let (rgb, _) = render_rgb_layout(&fig, w, hgt).unwrap();
            image::RgbImage::from_raw(w, hgt, rgb)
                .unwrap()
                .save(Path::new(&dir).join(format!("eight_{w}.png")))
                .unwrap();
        }
    }
}

#[test]
fn a_clicked_row_is_told_apart_in_the_time_plots() {
    let mut h = patch_app();
    let row = row_2(&h);
    h.state_mut().apply(Command::ShowPoints(row.clone()));
    h.run();
    let (first, last) = (row[0], row[row.len() - 1]);
    let texts = crate::harness::texts(&h);
    for name in [
        format!("point {first} (first of 16"),
        format!("point {last} (last)"),
    ] {
        assert!(
            texts.iter().any(|(t, _)| t.starts_with(&name)),
            "no legend entry {name:?}"
        );
    }
    // one colour per point, along the ramp
    let colours: Vec<egui::Color32> = row
        .iter()
        .map(|&i| tirecontact::gui::views::shown_point_color(&row, i))
        .collect();
    let mut distinct = colours.clone();
    distinct.sort_by_key(|c| c.to_array());
    distinct.dedup();
    assert_eq!(distinct.len(), row.len(), "{colours:?}");
    let strokes: Vec<egui::Color32> = crate::harness::shapes(&h)
        .iter()
        .filter_map(|s| match s {
            egui::Shape::Path(p) if p.points.len() > 10 => match p.stroke.color {
                egui::epaint::ColorMode::Solid(c) => Some(c),
                _ => None,
            },
            _ => None,
        })
        .collect();
    for c in &colours {
        assert!(strokes.contains(c), "no curve in {c:?}");
    }
}

#[test]
fn the_patch_view_exports_its_heat_map() {
    let mut h = patch_app();
    h.state_mut()
        .apply(Command::ShowView(tirecontact::gui::View::Patch));
    h.run();
    {
        use egui_kittest::kittest::Queryable;
        h.get_by_label(tirecontact::gui::views::patch_view::HEAT_MAP_PNG_BUTTON)
            .click();
    }
    h.run();
    assert!(h.state().prompt_open(), "no file prompt");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("heat.png");
    h.state_mut().apply(Command::ExportHeatMap(path.clone()));
    let bytes = std::fs::read(&path).expect("the heat map written");
    assert_eq!(&bytes[1..4], b"PNG");
    let m = h.state().message().unwrap();
    assert!(!m.error && m.text.starts_with("wrote"), "{m:?}");
    if let Some(dir) = std::env::var_os("TIRECONTACT_FIGURE_DIR") {
        std::fs::copy(&path, Path::new(&dir).join("heat_map.png")).unwrap();
    }
}
