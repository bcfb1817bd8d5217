//! The contact patch edited in the side panel: a `Grid(...)` scene's
//! counts, spacings and preload restart the run with the grid form kept
//! (listed in the edits); a texture road's fields apply live; refusals
//! name the field's label and the values it accepts.

use crate::harness::{advance, harness_sized, settle, type_into};
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::{App, Command, View};
use tirecontact::model::road::Road;
use tirecontact::scene::points::Preload;

fn patch_app() -> egui_kittest::Harness<'static, App> {
    let scene = Scene::load(Path::new("presets/patch_texture.ron")).unwrap();
    let mut h = harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
    settle(&mut h);
    h.state_mut().apply(Command::ShowView(View::Patch));
    settle(&mut h);
    h
}

fn banner(h: &egui_kittest::Harness<'_, App>) -> String {
    h.state()
        .message()
        .map(|m| m.text.clone())
        .unwrap_or_default()
}

#[test]
fn the_grid_is_edited_in_the_side_panel_and_keeps_its_form() {
    let mut h = patch_app();
    assert!(h.query_by_label("points.along").is_some(), "no grid fields");
    assert!(
        h.query_by_label("points[0].x_m").is_none(),
        "a grid's 96 points are listed one by one"
    );
    advance(&mut h, 5);
    // points along: the run restarts on the new grid, still a Grid(...)
    type_into(&mut h, "points.along", "20");
    settle(&mut h);
    let s = h.state().scene();
    let g = *s.points.grid().expect("the grid form kept");
    assert_eq!((g.along, g.across), (20, 6));
    assert_eq!(s.points.len(), 120);
    assert_eq!(h.state().simulation().steps(), 0, "the run restarted");
    // the footprint's length (mm): the points' heights follow it
    type_into(&mut h, "points.preload.length_m", "200");
    settle(&mut h);
    let g = *h.state().scene().points.grid().unwrap();
    assert_eq!(
        g.preload,
        Preload::Parabolic {
            depth_m: 0.001,
            length_m: 0.2
        }
    );
    let p0 = h.state().scene().points[0];
    let u = 2.0 * p0.x_m / 0.2;
    assert!((p0.h_m + 0.001 * (1.0 - u * u)).abs() < 1e-15, "{p0:?}");
    // none along: refused, naming the label and the range
    type_into(&mut h, "points.along", "0");
    let text = banner(&h);
    assert!(text.starts_with("points along (points.along):"), "{text}");
    assert!(text.contains("1 to 2000 points along"), "{text}");
    assert_eq!(h.state().scene().points.grid().unwrap().along, 20);
    // too many in all: the room left at 6 rows across
    type_into(&mut h, "points.along", "400");
    let text = banner(&h);
    assert!(
        text.contains("at most 2000 points in all: 1 to 333 along"),
        "{text}"
    );
    assert_eq!(h.state().scene().points.len(), 120);
    // a spacing of 0: refused, naming its label
    type_into(&mut h, "points.spacing_m.1", "0");
    let text = banner(&h);
    assert!(
        text.starts_with("spacing across Δy (points.spacing_m.1):"),
        "{text}"
    );
    // the edits are listed
    type_into(&mut h, "points.spacing_m.1", "25");
    settle(&mut h);
    assert_eq!(h.state().scene().points.grid().unwrap().spacing_m.1, 0.025);
    let edits = h.state().edits().join("; ");
    assert!(
        edits.contains("patch grid 16 × 6 -> 20 × 6 points")
            && edits.contains("patch spacing across 20 -> 25 mm")
            && edits.contains("patch preload"),
        "{edits}"
    );
}

#[test]
fn a_texture_is_edited_live_and_refusals_name_the_field() {
    let mut h = patch_app();
    advance(&mut h, 5);
    // the period across (mm): applied to the running simulation
    type_into(&mut h, "road.width_m", "300");
    settle(&mut h);
    match &h.state().scene().road {
        Road::Texture { width_m, .. } => assert!((width_m - 0.3).abs() < 1e-12),
        r => panic!("{r:?}"),
    }
    assert_eq!(
        h.state().simulation().steps(),
        5,
        "a road edit applies live"
    );
    // a band upside down: refused, naming the label
    type_into(&mut h, "road.max_wavenumber_cpm", "5");
    let text = banner(&h);
    assert!(
        text.starts_with("highest wavenumber n (road.max_wavenumber_cpm):"),
        "{text}"
    );
    match &h.state().scene().road {
        Road::Texture {
            max_wavenumber_cpm, ..
        } => assert_eq!(*max_wavenumber_cpm, 200.0),
        r => panic!("{r:?}"),
    }
}
