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
    assert!(text.starts_with("points along:"), "{text}");
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
            && edits.contains("spacing across Δy 20 -> 25 mm")
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

/// A patch of a thousand points (50 along × 20 across) is set up on a
/// background thread: every frame while it is built stays short, the
/// banner says what is being done, and the run restarts on it after.
#[test]
fn a_thousand_point_patch_is_set_up_without_blocking_the_frames() {
    let mut h = patch_app();
    // 20 rows 5 mm apart fit the 16 cm wide belt; a patch of more than
    // 100 points is set up off the UI thread, for as many frames as that
    // takes: typed without running the frames to rest
    let type_then_settle = |h: &mut egui_kittest::Harness<'static, App>, name: &str, text: &str| {
        h.get_by_label(name).focus();
        h.run_steps(2);
        h.get_by_label(name).set_text_value_accesskit(text);
        h.run_steps(2);
        h.key_press(egui::Key::Enter);
        settle(h);
    };
    type_then_settle(&mut h, "points.spacing_m.1", "5");
    type_then_settle(&mut h, "points.across", "20");
    assert_eq!(
        h.state().scene().points.len(),
        320,
        "{:?}",
        h.state().message()
    );
    h.get_by_label("points.along").focus();
    h.run();
    h.get_by_label("points.along")
        .set_text_value_accesskit("50");
    h.run();
    h.key_press(egui::Key::Enter);
    let mut frames = 0;
    let mut slowest_s: f64 = 0.0;
    let mut said = false;
    let started = std::time::Instant::now();
    loop {
        let t = std::time::Instant::now();
        h.run_steps(1);
        slowest_s = slowest_s.max(t.elapsed().as_secs_f64());
        frames += 1;
        said |= h
            .state()
            .message()
            .is_some_and(|m| m.text.contains("Setting up the solver for the 1000 points"));
        if frames > 3 && !h.state().identifying() {
            break;
        }
        assert!(started.elapsed().as_secs() < 300, "the set-up never ended");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let total_s = started.elapsed().as_secs_f64();
    assert_eq!(h.state().scene().points.len(), 1000);
    assert_eq!(h.state().simulation().num_points(), 1000);
    assert!(said, "the banner did not say what was set up");
    eprintln!("set-up {total_s:.2} s over {frames} frames, slowest frame {slowest_s:.3} s");
    // the frames went on during the set-up: none held the whole of it
    // (set up inside a frame, one frame took all of it), and many were drawn
    assert!(
        slowest_s < 0.5 * total_s && frames >= 10,
        "a frame took {slowest_s:.3} s of a {total_s:.2} s set-up ({frames} frames)"
    );
}

/// The colour bar's caption and its labels: the caption clear of the top
/// label (at least 4 px between their painted boxes).
#[test]
fn the_colour_bar_caption_does_not_crowd_its_top_label() {
    use tirecontact::gui::views::patch_view::COLOUR_BAR_CAPTION;
    let mut h = patch_app();
    advance(&mut h, 2000);
    h.run_steps(2);
    let texts = crate::harness::texts(&h);
    let caption = texts
        .iter()
        .find(|(t, _)| t == COLOUR_BAR_CAPTION)
        .map(|(_, r)| *r)
        .expect("the caption");
    // the bar's labels: texts below the caption, overlapping it across
    let labels: Vec<_> = texts
        .iter()
        .filter(|(t, r)| {
            t != COLOUR_BAR_CAPTION
                && r.left() < caption.right() + 40.0
                && r.right() > caption.left() - 10.0
                && r.top() < caption.bottom() + 200.0
                && r.top() > caption.top() - 5.0
        })
        .collect();
    assert!(!labels.is_empty(), "no colour bar labels near {caption:?}");
    for (t, r) in labels {
        assert!(
            r.top() >= caption.bottom() + 4.0,
            "label {t:?} at {r:?} crowds the caption at {caption:?}"
        );
    }
}

/// The plate tyre's parameters are edited in the side panel as the other
/// tyres' are: a value out of range is refused naming the field, the value
/// and the range; a good one restarts the run on the new plate.
#[test]
fn the_plate_is_edited_in_the_side_panel() {
    use tirecontact::scene::Tyre;
    let width = |h: &egui_kittest::Harness<'_, App>| match &h.state().scene().tyre {
        Tyre::Plate { plate } => plate.width_m,
        t => panic!("not a plate: {t:?}"),
    };
    let mut h = patch_app();
    let before = width(&h);
    type_into(&mut h, "tyre.plate.width_m", "20");
    settle(&mut h);
    let b = banner(&h);
    assert!(
        b.contains("plate width W") && b.contains("got 20 m") && b.contains("from 0.001 to 10 m"),
        "{b}"
    );
    assert_eq!(width(&h), before);
    advance(&mut h, 5);
    type_into(&mut h, "tyre.plate.width_m", "0.2");
    settle(&mut h);
    assert_eq!(width(&h), 0.2);
    assert_eq!(h.state().simulation().steps(), 0, "the run restarted");
}

/// An OpenCRG road in the side panel: the file's `u` and `v` ranges and
/// grid, its absolute height (the mean road plane, the `h` datum) and the
/// strip the run travels, each computed here from the file as read and
/// the scene's points, speed and duration.
#[test]
fn a_crg_road_shows_its_file_ranges_height_and_travelled_strip() {
    let scene = Scene::load(Path::new("presets/patch_belgian_block.ron")).unwrap();
    let crg =
        tirecontact::readers::crg::read_crg(Path::new("presets/roads/belgian_block.crg")).unwrap();
    let Road::Crg {
        u_start_m: Some(u0),
        v_offset_m: v0,
        ..
    } = scene.road.clone()
    else {
        panic!("the preset starts at a given u")
    };
    let xs: Vec<f64> = scene.points.iter().map(|p| p.x_m).collect();
    let ys: Vec<f64> = scene.points.iter().map(|p| p.y_m).collect();
    let lo = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (xa, xb, ya, yb) = (lo(&xs), hi(&xs), lo(&ys), hi(&ys));
    let travel = scene.speed_mps * scene.duration_s;
    let mut h = harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
    settle(&mut h);
    let expected = [
        format!(
            "u {:.3} m to {:.3} m, v {:.3} m to {:.3} m",
            crg.u_first_m,
            crg.u_last_m(),
            crg.v_m[0],
            crg.v_m[crg.v_m.len() - 1]
        ),
        format!(
            "Δu {:.2} mm, Δv {:.2} mm",
            crg.u_inc_m * 1e3,
            (crg.v_m[1] - crg.v_m[0]) * 1e3
        ),
        format!("mean road plane at {:.4} m (h datum)", crg.mean_height_m()),
        format!(
            "travelled strip: u {:.3} m to {:.3} m",
            u0 + xa,
            u0 + xb + travel
        ),
        format!(
            "v {:.3} m to {:.3} m (v offset {v0:.3} m)",
            v0 + ya,
            v0 + yb
        ),
    ];
    for text in &expected {
        assert!(
            h.query_by_label_contains(text).is_some(),
            "the road panel does not say `{text}`"
        );
    }
    assert!(
        h.query_by_label_contains("OpenCRG road roads/belgian_block.crg")
            .is_some()
    );
}
