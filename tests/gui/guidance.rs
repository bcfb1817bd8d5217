//! What the app tells a first-time user at 1280 × 720: mistakes
//! pause the run and say what to do, the keys are listed in a Help menu,
//! an empty run is not exported as an empty figure, and a syntax error's
//! caret points at its column.

use crate::harness::{harness_sized, type_into};
use crate::support::temp_dir;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tirecontact::gui::Speed;
use tirecontact::gui::app::PAUSED_NOTE;
use tirecontact::gui::{App, Command};

const SMALL: [f32; 2] = [1280.0, 720.0];

/// The default preset, playing at 1280 × 720.
fn playing() -> Harness<'static, App> {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    h.get_by_label("Play").click();
    h.run_steps(2);
    assert!(h.state().time_control().is_playing());
    h
}

/// `crate::harness::type_into` for a window that keeps repainting (a playing run).
fn type_playing(h: &mut Harness<'_, App>, name: &str, text: &str) {
    h.get_by_label(name).focus();
    h.run_steps(1);
    h.get_by_label(name).set_text_value_accesskit(text);
    h.run_steps(1);
    h.key_press(egui::Key::Enter);
    h.run_steps(2);
}

fn banner(h: &Harness<'_, App>) -> String {
    h.state()
        .message()
        .map(|m| m.text.clone())
        .unwrap_or_default()
}

/// A file `name` holding `text`, in a temporary folder of its own (both
/// removed on drop).
struct TempFile(std::path::PathBuf, #[allow(dead_code)] tempfile::TempDir);
impl TempFile {
    fn new(name: &str, text: &str) -> Self {
        let dir = temp_dir();
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        TempFile(p, dir)
    }
}

#[test]
fn a_refused_value_pauses_the_run_and_says_how_to_go_on() {
    let mut h = playing();
    type_playing(&mut h, "road.amplitude_m", "abc");
    assert!(!h.state().time_control().is_playing(), "still playing");
    let text = banner(&h);
    assert!(
        text.starts_with("road amplitude a (road.amplitude_m):"),
        "{text}"
    );
    assert!(text.contains("'abc'"), "{text}");
    assert!(text.contains("expected"), "{text}");
    assert!(text.ends_with(PAUSED_NOTE), "{text}");
    // a good value clears the refusal (the note went with it)
    type_into(&mut h, "road.amplitude_m", "2");
    assert!(!banner(&h).contains(PAUSED_NOTE), "{}", banner(&h));
    // refused while paused: nothing to say about the run
    type_into(&mut h, "road.wavelength_m", "0");
    let text = banner(&h);
    assert!(
        text.starts_with("road wavelength λ (road.wavelength_m):"),
        "{text}"
    );
    assert!(!text.contains(PAUSED_NOTE), "{text}");
}

/// A second refusal before the first is mended still says why the run is
/// paused (it replaced the first refusal's banner without the note, and the
/// run stood still unexplained).
#[test]
fn a_second_refusal_still_says_the_run_is_paused() {
    let mut h = playing();
    type_playing(&mut h, "road.amplitude_m", "abc");
    assert!(banner(&h).ends_with(PAUSED_NOTE), "{}", banner(&h));
    type_into(&mut h, "road.wavelength_m", "0");
    let text = banner(&h);
    assert!(
        text.starts_with("road wavelength λ (road.wavelength_m):"),
        "{text}"
    );
    assert!(text.ends_with(PAUSED_NOTE), "{text}");
    assert!(!h.state().time_control().is_playing(), "still paused");
}

#[test]
fn a_broken_preset_pauses_the_run_and_keeps_the_scene() {
    let mut h = playing();
    let before = h.state().scene().clone();
    let f = TempFile::new(
        "broken.ron",
        "Scene(\n    name: \"x\"\n    description: \"y\",\n)\n",
    );
    h.state_mut().apply(Command::OpenPath(f.0.clone()));
    crate::harness::settle(&mut h);
    assert!(!h.state().time_control().is_playing(), "still playing");
    assert_eq!(h.state().scene(), &before, "the scene was kept");
    let text = banner(&h);
    assert!(text.contains(PAUSED_NOTE), "{text}");
    // file:line:column of the missing comma's consequence
    let at = format!("{}:3:5", f.0.display());
    assert!(text.contains(&at), "{text}");
}

/// Paused, the same slip does not start the run either.
#[test]
fn a_refusal_while_paused_leaves_the_run_paused() {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    h.state_mut().apply(Command::SetSpeed(Speed::Max));
    type_into(&mut h, "speed_kmh", "-5");
    assert!(!h.state().time_control().is_playing());
    assert!(
        banner(&h).starts_with("speed V (speed_kmh):"),
        "{}",
        banner(&h)
    );
}

/// The text of every label (a label's text is its accesskit value) and
/// every other node's name.
fn all_texts(h: &Harness<'_, App>) -> Vec<String> {
    use egui_kittest::kittest::NodeT;
    h.query_all_by_label_contains("")
        .filter_map(|n| {
            let n = n.accesskit_node();
            n.value().or(n.label())
        })
        .collect()
}

#[test]
fn the_help_menu_lists_the_keys_and_they_do_what_it_says() {
    use tirecontact::gui::View;
    use tirecontact::gui::panels::help_menu::{FIRST_STEPS, SHORTCUTS};
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    h.get_by_label("Help").click();
    h.run();
    let shown = all_texts(&h);
    for (key, what) in SHORTCUTS {
        assert!(
            shown.iter().any(|t| t == key),
            "{key} not listed: {shown:?}"
        );
        assert!(shown.iter().any(|t| t == what), "{what} not listed");
    }
    for line in FIRST_STEPS {
        assert!(shown.iter().any(|t| t.ends_with(line)), "{line} not shown");
    }
    // the menu fits the 1280 x 720 window
    let r = h.get_by_label("Reopen the default scene").rect();
    assert!(r.max.y <= 720.0 && r.max.x <= 1280.0, "{r:?}");
    h.key_press(egui::Key::Escape);
    h.run();
    // what the list says of Space, 2 and R
    h.key_press(egui::Key::Space);
    h.run_steps(2);
    assert!(h.state().time_control().is_playing(), "Space did not play");
    h.key_press(egui::Key::Space);
    h.run_steps(2);
    assert!(
        !h.state().time_control().is_playing(),
        "Space did not pause"
    );
    assert!(h.state().simulation().steps() > 0);
    h.key_press(egui::Key::Num2);
    h.run();
    assert_eq!(h.state().view(), View::Scene);
    h.key_press(egui::Key::R);
    h.run();
    assert_eq!(h.state().simulation().steps(), 0, "R did not reset");
    // the digit keys listed are the views' keys, 1 to 8 in the views' order
    let digits: Vec<&str> = SHORTCUTS
        .iter()
        .flat_map(|(key, _)| key.split_whitespace())
        .filter(|k| k.parse::<u8>().is_ok())
        .collect();
    assert_eq!(digits, ["1", "2", "3", "4", "5", "6", "7", "8", "9"]);
    assert_eq!(digits.len(), View::ALL.len());
    let keys = [
        egui::Key::Num1,
        egui::Key::Num2,
        egui::Key::Num3,
        egui::Key::Num4,
        egui::Key::Num5,
        egui::Key::Num6,
        egui::Key::Num7,
        egui::Key::Num8,
        egui::Key::Num9,
    ];
    for (key, view) in keys.into_iter().zip(View::ALL) {
        h.key_press(key);
        // a research view's job repaints until it ends
        h.run_steps(2);
        assert_eq!(h.state().view(), view, "{key:?}");
    }
}

#[test]
fn reopen_the_default_scene_from_the_help_menu_after_an_edit() {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    let default = h.state().scene().clone();
    type_into(&mut h, "speed_kmh", "72");
    assert_ne!(h.state().scene(), &default);
    h.get_by_label("Help").click();
    h.run();
    h.get_by_label("Reopen the default scene").click();
    h.run();
    // unsaved edits: asked first
    assert!(h.state().pending_confirmation().is_some());
    h.get_by_label("Discard changes").click();
    h.run();
    assert_eq!(h.state().scene(), &default);
    assert!(!h.state().is_dirty());
}

/// Every control of the transport row and the road type list says on hover
/// what it does (the walk found "Space" as Play's whole tooltip, and none on
/// the N steps field or the road type list).
#[test]
fn the_transport_controls_and_the_road_type_explain_themselves() {
    for (control, says) in [
        ("Play", "play the run"),
        ("Step", "one solver step"),
        ("Step N", "solver steps"),
        ("N steps", "1 to 10 000 000"),
        ("Reset", "back to t = 0"),
        ("speed", "0.001x"),
        ("road type", "ISO 8608"),
    ] {
        let mut h = harness_sized(App::with_default_preset(), SMALL);
        h.run();
        h.get_all_by_label(control).last().unwrap().hover();
        h.run_steps(40);
        let shown = all_texts(&h);
        assert!(
            shown.iter().any(|t| t.contains(says)),
            "{control}: no tooltip saying {says:?}"
        );
    }
}

/// Exporting the plots before anything ran wrote an empty figure whose
/// time axis ran from -1 to 1 s; it now says what to do, in the dialog.
#[test]
fn an_empty_run_is_not_exported_as_an_empty_figure() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let path = dir.join("plots.png");
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    h.state_mut().apply(Command::ExportPngDialog);
    h.run();
    h.state_mut().apply(Command::ExportPng {
        path: path.clone(),
        width: 800,
        height: 600,
    });
    h.run();
    assert!(!path.exists(), "an empty figure was written");
    let shown = all_texts(&h);
    assert!(
        shown
            .iter()
            .any(|t| t.starts_with("Nothing to export yet") && t.contains("Press Play")),
        "{shown:?}"
    );
    // after some steps the same export writes the file
    h.state_mut().apply(Command::Step(200));
    h.run();
    h.state_mut().apply(Command::ExportPng {
        path: path.clone(),
        width: 800,
        height: 600,
    });
    h.run();
    assert!(path.exists(), "{:?}", h.state().message());
}

/// The caret under a quoted source line points at the error's column: the
/// banner draws the excerpt in monospace (in the body font the caret sat
/// under the blanks before the field).
#[test]
fn the_caret_of_a_syntax_error_points_at_its_column() {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    let f = TempFile::new(
        "caret.ron",
        "Scene(\n    name: \"x\"\n    description: \"y\",\n)\n",
    );
    h.state_mut().apply(Command::OpenPath(f.0.clone()));
    h.run();
    let mut found = false;
    for s in crate::harness::shapes(&h) {
        let egui::Shape::Text(t) = s else { continue };
        if !t.galley.text().contains("Cannot open this preset") {
            continue;
        }
        // the row quoting line 3 and the caret row below it
        let rows: Vec<(f32, Vec<(char, f32)>)> = t
            .galley
            .rows
            .iter()
            .map(|r| {
                (
                    r.pos.y,
                    r.row
                        .glyphs
                        .iter()
                        .map(|g| (g.chr, r.pos.x + g.pos.x))
                        .collect(),
                )
            })
            .collect();
        let text_of = |g: &[(char, f32)]| g.iter().map(|c| c.0).collect::<String>();
        let quoted = rows
            .iter()
            .position(|(_, g)| text_of(g).trim_start().starts_with("3 |"))
            .expect("no quoted line");
        let d_x = rows[quoted].1.iter().find(|c| c.0 == 'd').unwrap().1;
        let caret_x = rows[quoted + 1]
            .1
            .iter()
            .find(|c| c.0 == '^')
            .expect("no caret below")
            .1;
        assert!(
            (caret_x - d_x).abs() < 1.0,
            "caret at x = {caret_x}, column 5 ('d') at x = {d_x}"
        );
        found = true;
    }
    assert!(found, "no banner");
}

/// At 1280 × 720 the scene view's header keeps each label whole on a row:
/// "ramping in" was cut after "ramping", its value on the next row.
#[test]
fn the_scene_header_keeps_its_labels_whole_at_1280_by_720() {
    use tirecontact::gui::View;
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.state_mut().apply(Command::ShowView(View::Scene));
    h.run();
    let t = crate::harness::texts(&h);
    let ramp = t
        .iter()
        .find(|(s, _)| s.contains("ramping in"))
        .expect("no ramp label at t = 0");
    let rows = crate::harness::shapes(&h)
        .into_iter()
        .find_map(|s| match s {
            egui::Shape::Text(t) if t.galley.text() == ramp.0 => Some(t.galley.rows.len()),
            _ => None,
        })
        .unwrap();
    assert_eq!(rows, 1, "{:?} wrapped", ramp.0);
    assert!(ramp.1.max.x <= SMALL[0], "{ramp:?} past the window");
    let header = t
        .iter()
        .find(|(s, _)| s.contains("points in contact"))
        .unwrap();
    assert!(header.1.max.x <= SMALL[0], "{header:?} past the window");
    assert!(ramp.0.contains(" %"), "{}", ramp.0);
    // past the ramp the label says so in the same place: the header keeps
    // its rows (and the plot its top) when the ramp ends
    let ramp_steps = (h.state().scene().ramp_s / h.state().scene().dt_s).ceil() as u64;
    crate::harness::advance(&mut h, ramp_steps + 10);
    h.run();
    let after = crate::harness::texts(&h)
        .into_iter()
        .find(|(t, _)| t == "road and preload in full")
        .expect("no label past the ramp");
    assert!(
        (after.1.center().y - ramp.1.center().y).abs() < 0.5,
        "moved from {:?} to {:?}",
        ramp.1,
        after.1
    );
}

/// Quitting (or opening another scene) with unsaved edits asks first and
/// says which edits would be lost.
#[test]
fn the_unsaved_changes_question_names_the_changes() {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    type_into(&mut h, "speed_kmh", "72");
    type_into(&mut h, "road.amplitude_m", "2");
    h.state_mut().apply(Command::Quit);
    h.run();
    assert!(h.state().pending_confirmation().is_some());
    let shown = all_texts(&h);
    let line = shown
        .iter()
        .find(|t| t.starts_with("Changed: "))
        .unwrap_or_else(|| panic!("no list of changes: {shown:?}"));
    assert!(line.contains("speed V 10 -> 20 m/s"), "{line}");
    assert!(line.contains("road amplitude a 1 -> 2 mm"), "{line}");
    h.get_by_label("Cancel").click();
    h.run();
    assert!(h.state().pending_confirmation().is_none());
    assert!(h.state().is_dirty(), "the edits were kept");
}

/// The PNG export dialog says where a relative path goes and has a Cancel
/// button, as the open and save prompts do.
#[test]
fn the_png_dialog_says_where_a_relative_path_goes_and_cancels() {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    h.state_mut().apply(Command::ExportPngDialog);
    h.run();
    let cwd = std::env::current_dir().unwrap().display().to_string();
    let shown = all_texts(&h);
    assert!(
        shown
            .iter()
            .any(|t| t == &format!("A relative path is in {cwd}.")),
        "{shown:?}"
    );
    h.get_by_label("Cancel").click();
    h.run();
    assert!(h.query_by_label("Export PNG").is_none(), "still open");
}

/// The fields stay where they are when edits are made: the note of the
/// edits above them grew at the first edit and moved every field down by
/// two lines, under the pointer.
#[test]
fn edits_do_not_move_the_fields_under_the_pointer() {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    let at = |h: &Harness<'_, App>| {
        (
            h.get_by_label("road.wavelength_m").rect(),
            h.get_by_label("ramp_s").rect(),
        )
    };
    let before = at(&h);
    assert!(
        all_texts(&h)
            .iter()
            .any(|t| t == tirecontact::gui::panels::edits_box::NO_EDITS),
        "no placeholder"
    );
    type_into(&mut h, "speed_kmh", "72");
    assert!(!h.state().edits().is_empty());
    assert_eq!(at(&h), before, "moved by the first edit");
    type_into(&mut h, "road.amplitude_m", "2");
    type_into(&mut h, "ramp_s", "0.06");
    type_into(&mut h, "duration_s", "0.3");
    assert_eq!(h.state().edits().len(), 4, "{:?}", h.state().edits());
    assert_eq!(at(&h), before, "moved by more edits");
}

/// Every time plot's legend reads point 0 first, wherever it sits: egui_plot
/// stacks a bottom corner's legend upwards, and the force plot's legend
/// read "point 4 … point 0" whenever its curves sent it to a bottom corner.
#[test]
fn a_legend_in_a_bottom_corner_still_reads_point_0_first() {
    let mut h = harness_sized(App::with_default_preset(), SMALL);
    h.run();
    crate::harness::advance(&mut h, 500);
    h.run();
    let k = 1usize; // the force plot
    let key =
        egui::Id::unique(("tirecontact.time_plots.legend", k)).with("tirecontact.legend_corner");
    h.ctx
        .data_mut(|d| d.insert_temp(key, egui_plot::Corner::RightBottom));
    h.run_steps(1);
    let ys = |name: &str| {
        let mut v: Vec<f32> = crate::harness::texts(&h)
            .into_iter()
            .filter(|(t, _)| t == name)
            .map(|(_, r)| r.center().y)
            .collect();
        v.sort_by(f32::total_cmp);
        v
    };
    let (first, last) = (ys("point 0"), ys("point 4"));
    assert_eq!(first.len(), 4, "{first:?}");
    assert_eq!(last.len(), 4, "{last:?}");
    for (plot, (a, b)) in first.iter().zip(&last).enumerate() {
        assert!(a < b, "plot {plot}: point 0 at y = {a}, point 4 at y = {b}");
    }
}
