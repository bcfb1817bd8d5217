//! A phone-sized window (400 × 800): the editing panel hides behind a
//! button instead of covering the views, and comes back in their place.

use crate::harness::{harness_sized, settle, texts};
use egui_kittest::kittest::Queryable;
use tirecontact::gui::App;

#[test]
fn a_narrow_window_keeps_the_editing_panel_behind_a_button() {
    let mut h = harness_sized(App::with_default_preset(), [400.0, 800.0]);
    settle(&mut h);
    h.run_steps(2);
    // the views have the window: no field, the time plots' titles at the
    // left edge
    assert!(
        h.query_by_label("road.amplitude_m").is_none(),
        "the panel covers the views"
    );
    let leftmost = texts(&h)
        .iter()
        .filter(|(t, _)| t.contains("(mm") || t.contains("(N)"))
        .map(|(_, r)| r.left())
        .fold(f32::INFINITY, f32::min);
    assert!(leftmost < 60.0, "the views start at {leftmost} px");
    // the button shows the panel in their place, and back
    h.get_by_label("Edit the scene").click();
    h.run_steps(2);
    assert!(h.query_by_label("road.amplitude_m").is_some());
    h.get_by_label("Back to the views").click();
    h.run_steps(2);
    assert!(h.query_by_label("road.amplitude_m").is_none());
    // a view chosen from the View menu while editing comes in its place
    h.get_by_label("Edit the scene").click();
    h.run_steps(2);
    assert!(h.query_by_label("road.amplitude_m").is_some());
    h.get_by_label("View").click();
    h.run_steps(2);
    h.get_by_label("Time plots").click();
    h.run_steps(2);
    assert!(
        h.query_by_label("road.amplitude_m").is_none(),
        "the editing panel stayed over the chosen view"
    );
    // a wide window: the panel beside the views, as before
    let mut wide = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    settle(&mut wide);
    assert!(wide.query_by_label("road.amplitude_m").is_some());
    assert!(wide.query_by_label("Edit the scene").is_none());
}

/// Every control of a label `label` lies inside a `w × h` window.
fn inside(h: &egui_kittest::Harness<'_, App>, label: &str, [w, ht]: [f32; 2]) {
    let nodes: Vec<_> = h.query_all_by_label(label).collect();
    assert!(!nodes.is_empty(), "no {label}");
    for n in nodes {
        let r = n.rect();
        assert!(
            r.left() >= 0.0 && r.right() <= w && r.top() >= 0.0 && r.bottom() <= ht,
            "{label} at {r:?}: outside the {w} × {ht} window"
        );
    }
}

/// At phone size (400 × 800 logical px) the menu bar folds into Menu, View
/// and Help, and the transport row wraps: every control of both is inside
/// the window (the menu bar and the clock ran past its right edge).
#[test]
fn a_phone_window_shows_the_whole_menu_bar_and_transport() {
    let size = [400.0, 800.0];
    let mut h = harness_sized(App::with_default_preset(), size);
    settle(&mut h);
    h.run_steps(2);
    let texts = texts(&h);
    let clock = texts
        .iter()
        .find(|(t, _)| t.starts_with("t = "))
        .expect("the clock");
    assert!(clock.1.right() <= size[0], "the clock at {:?}", clock.1);
    for label in [
        "Help", "Play", "Step", "Step N", "N steps", "Reset", "speed", "Menu", "View",
    ] {
        inside(&h, label, size);
    }
    // the folded menus hold what the wide bar shows
    h.get_by_label("Menu").click();
    h.run_steps(2);
    for label in ["File", "Presets", "Guided tour", "Export"] {
        inside(&h, label, size);
    }
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    h.get_by_label("View").click();
    h.run_steps(2);
    for label in ["Classroom", "Time plots", "Mode bars"] {
        inside(&h, label, size);
    }
    // a wide window keeps the flat bar
    let mut wide = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    settle(&mut wide);
    assert!(wide.query_by_label("Menu").is_none());
    inside(&wide, "File", [1280.0, 720.0]);
    inside(&wide, "Help", [1280.0, 720.0]);
}

/// A message of several lines (a refused link's reason, at phone width)
/// unfolds in front of the view's top: the time plots' "follow latest"
/// row stays where it is with and without it, and its Dismiss is in the
/// window.
#[test]
fn a_long_banner_does_not_move_the_views_controls() {
    for size in [[400.0, 800.0], [1280.0, 720.0]] {
        let app = App::open_link("index.html#scene=v1.%%%", None);
        let text = app.message().unwrap().text.clone();
        let mut h = harness_sized(app, size);
        settle(&mut h);
        h.run_steps(2);
        let texts = texts(&h);
        let banner = texts
            .iter()
            .filter(|(t, _)| text.starts_with(t.as_str()) || t.contains("damaged"))
            .map(|(_, r)| *r)
            .reduce(|a, b| a.union(b))
            .expect("the banner");
        if size[0] < 700.0 {
            assert!(banner.height() > 20.0, "a banner of one line: {banner:?}");
        }
        let follow = h.get_by_label("follow latest").rect();
        let dismiss = h.get_by_label("Dismiss").rect();
        assert!(
            dismiss.right() <= size[0] && dismiss.bottom() <= size[1],
            "at {size:?} Dismiss at {dismiss:?}"
        );
        h.get_by_label("Dismiss").click();
        h.run();
        h.run();
        assert!(h.state().message().is_none());
        let after = h.get_by_label("follow latest").rect();
        assert!(
            (after.top() - follow.top()).abs() < 0.5,
            "at {size:?} the follow row moved {follow:?} -> {after:?}"
        );
    }
}

/// A message of several lines covers the top of the view only for a
/// while: it folds to its first line after `BANNER_UNFOLDED_S`, uncovering
/// the time plots' "follow latest" row; "More" unfolds it and "Less" folds
/// it again, and the message stays until dismissed.
#[test]
fn a_long_banner_folds_and_uncovers_the_view() {
    use tirecontact::gui::chrome::dialogs::BANNER_UNFOLDED_S;
    let size = [400.0, 800.0];
    let app = App::open_link("index.html#scene=v1.%%%", None);
    let text = app.message().unwrap().text.clone();
    let mut h = harness_sized(app, size);
    settle(&mut h);
    h.run_steps(2);
    let banner = |h: &egui_kittest::Harness<'_, App>| {
        texts(h)
            .into_iter()
            .filter(|(t, _)| !t.is_empty() && text.starts_with(t.as_str()))
            .map(|(_, r)| r)
            .reduce(|a, b| a.union(b))
            .expect("the banner")
    };
    let follow = h.get_by_label("follow latest").rect();
    let whole = banner(&h);
    assert!(
        whole.bottom() > follow.top(),
        "the unfolded banner {whole:?} does not reach the follow row {follow:?}"
    );
    assert!(h.query_by_label("Less").is_some(), "no way to fold it");
    // (the harness steps 1/60 s a frame)
    h.run_steps((BANNER_UNFOLDED_S * 60.0) as usize + 10);
    let folded = banner(&h);
    assert!(
        folded.bottom() <= follow.top() && folded.height() < 0.5 * whole.height(),
        "folded banner {folded:?} (was {whole:?}), follow row {follow:?}"
    );
    assert!(h.state().message().is_some(), "the message is kept");
    h.get_by_label("More").click();
    h.run_steps(2);
    let again = banner(&h);
    assert!(
        (again.height() - whole.height()).abs() < 1.0,
        "{again:?} vs {whole:?}"
    );
    h.get_by_label("Less").click();
    h.run_steps(2);
    assert!(banner(&h).bottom() <= follow.top());
    assert!(h.query_by_label("More").is_some());
}

/// A scene opened from a link says so in the status bar, with its name
/// (not "built-in preset").
#[test]
fn a_scene_from_a_link_says_so_in_the_status_bar() {
    let scene = tirecontact::Scene::load(std::path::Path::new("presets/three_points.ron")).unwrap();
    let link = tirecontact::scene::share::link(&scene, "index.html").unwrap();
    let mut h = harness_sized(App::open_link(&link, None), [1280.0, 720.0]);
    settle(&mut h);
    let texts = texts(&h);
    let label = format!("{} (from a link)", scene.name);
    assert!(
        texts.iter().any(|(t, _)| *t == label),
        "no {label:?} in {:?}",
        texts.iter().map(|(t, _)| t).collect::<Vec<_>>()
    );
    assert!(!texts.iter().any(|(t, _)| t.contains("built-in preset")));
    assert!(h.state().title().contains("(from a link)"));
}

/// At phone size every view's text lies inside the window (the scene
/// view's one-row header widened the page past its right edge, cutting
/// the plot, its legend and the status bar).
#[test]
fn a_phone_window_keeps_every_view_inside_it() {
    use tirecontact::gui::{Command, View};
    let size = [400.0, 800.0];
    for view in [View::TimePlots, View::Scene, View::Patch] {
        let mut h = harness_sized(App::with_default_preset(), size);
        h.state_mut().apply(Command::ShowView(view));
        crate::harness::advance(&mut h, 3000);
        settle(&mut h);
        h.run_steps(2);
        let past: Vec<_> = texts(&h)
            .into_iter()
            .filter(|(t, r)| !t.trim().is_empty() && r.right() > size[0] + 0.5)
            .collect();
        assert!(past.is_empty(), "{view:?}: past the right edge: {past:?}");
    }
}

/// Where the flat menu bar does not fit (900 × 600 in a research view,
/// classroom mode at 1280 × 720) its view items fold into a View menu and
/// Help stays in the window; a wide window keeps them on the bar.
#[test]
fn the_menu_bar_folds_its_view_items_where_they_do_not_fit() {
    use tirecontact::gui::{Command, View};
    let mut small = harness_sized(App::with_default_preset(), [900.0, 600.0]);
    settle(&mut small);
    small.state_mut().apply(Command::ShowView(View::Workbench));
    small.run_steps(3);
    inside(&small, "Help", [900.0, 600.0]);
    assert!(small.query_by_label("View").is_some(), "no View menu");
    let mut class = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    class.state_mut().apply(Command::SetClassroom(true));
    settle(&mut class);
    class.run_steps(3);
    inside(&class, "Help", [1280.0, 720.0]);
    inside(&class, "Classroom", [1280.0, 720.0]);
    let mut wide = harness_sized(App::with_default_preset(), [1600.0, 1000.0]);
    settle(&mut wide);
    wide.run_steps(3);
    assert!(
        wide.query_by_label("View").is_none(),
        "view items folded at 1600 px"
    );
    assert!(wide.query_by_label("Mode bars").is_some());
    inside(&wide, "Help", [1600.0, 1000.0]);
}
