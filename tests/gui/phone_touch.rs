//! Phone screens (390 × 844 and 360 × 740 logical px): the editing panel,
//! the Help menu and the time plots fit the width, buttons and menu rows
//! are fingertip targets, the layout stands still when the run plays, a
//! refused value's reason shows while editing, and classroom mode (a
//! presenter layout for wide screens) is not offered.

use crate::harness::{harness_sized, settle, texts, type_into};
use egui::accesskit::Role;
use egui_kittest::kittest::{NodeT, Queryable};
use tirecontact::gui::{App, Command};

const PHONES: [[f32; 2]; 2] = [[390.0, 844.0], [360.0, 740.0]];

fn phone(size: [f32; 2]) -> egui_kittest::Harness<'static, App> {
    let mut h = harness_sized(App::with_default_preset(), size);
    settle(&mut h);
    h.run_steps(2);
    h
}

/// The buttons of the frame, as (label, rect).
fn buttons(h: &egui_kittest::Harness<'_, App>) -> Vec<(String, egui::Rect)> {
    h.query_all_by_role(Role::Button)
        .map(|n| (n.accesskit_node().label().unwrap_or_default(), n.rect()))
        .collect()
}

#[test]
fn the_editing_panel_fits_a_phone_with_every_remove_button() {
    for size in PHONES {
        let mut h = phone(size);
        h.get_by_label("Edit the scene").click();
        h.run_steps(3);
        let all = buttons(&h);
        let removes: Vec<_> = all
            .iter()
            .filter(|(l, _)| l.starts_with("Remove"))
            .collect();
        assert!(!removes.is_empty(), "no Remove button at {size:?}");
        for (_, r) in &removes {
            assert!(r.height() >= 44.0, "at {size:?} a Remove button {r:?}");
        }
        for (label, r) in &all {
            assert!(
                r.left() >= 0.0 && r.right() <= size[0] + 0.5,
                "at {size:?} {label:?} at {r:?} is cut by the window's right edge"
            );
        }
        for (t, r) in texts(&h) {
            assert!(
                r.right() <= size[0] + 0.5,
                "at {size:?} {t:?} at {r:?} is cut"
            );
        }
    }
}

#[test]
fn buttons_and_menu_rows_are_fingertip_targets_on_a_phone_only() {
    for size in PHONES {
        let mut h = phone(size);
        for label in [
            "Play",
            "Step",
            "Reset",
            "Menu",
            "View",
            "Help",
            "Edit the scene",
        ] {
            let r = h.get_by_label(label).rect();
            assert!(
                r.height() >= 44.0,
                "at {size:?} {label} is {} px tall",
                r.height()
            );
        }
        h.get_by_label("Menu").click();
        h.run_steps(2);
        for label in ["File", "Presets", "Guided tour", "Export"] {
            let r = h.get_by_label(label).rect();
            assert!(
                r.height() >= 44.0,
                "at {size:?} the {label} row is {} px tall",
                r.height()
            );
        }
    }
    // the desktop keeps egui's compact rows
    let h = phone([1280.0, 720.0]);
    let r = h.get_by_label("Play").rect();
    assert!(
        r.height() < 30.0,
        "Play is {} px tall at 1280 px",
        r.height()
    );
}

#[test]
fn the_help_menu_fits_a_phone_and_scrolls_to_its_end() {
    for size in PHONES {
        let mut h = phone(size);
        h.get_by_label("Help").click();
        h.run_steps(3);
        let shown = texts(&h);
        let first = shown
            .iter()
            .find(|(t, _)| t.starts_with("• Play (Space)"))
            .expect("the Help menu's first step");
        for (t, r) in &shown {
            assert!(
                r.right() <= size[0] + 0.5,
                "at {size:?} {t:?} at {r:?} is cut"
            );
        }
        assert!(first.1.left() >= 0.0);
        // its last button is in the window, or reached by scrolling it
        let reopen = h.get_by_label("Reopen the default scene");
        reopen.scroll_to_me();
        h.run_steps(3);
        let r = h.get_by_label("Reopen the default scene").rect();
        assert!(
            r.bottom() <= size[1] && r.top() >= 0.0,
            "at {size:?} the menu's last button at {r:?}"
        );
        // and it works there
        let mut faster = h.state().scene().clone();
        faster.speed_mps *= 2.0;
        h.state_mut().apply(Command::EditScene(Box::new(faster)));
        h.run();
        h.get_by_label("Reopen the default scene").click();
        h.run_steps(2);
        assert!(h.state().pending_confirmation().is_some(), "at {size:?}");
    }
}

/// "Edit the scene" and the views below it stay where they are when the
/// transport row's "paused" becomes "running at …x real time".
#[test]
fn the_layout_stands_still_when_the_run_plays_on_a_phone() {
    for size in PHONES {
        let mut h = phone(size);
        let paused = h.get_by_label("Edit the scene").rect();
        h.state_mut().apply(Command::TogglePlay);
        h.run_steps(20);
        assert!(
            texts(&h).iter().any(|(t, _)| t.starts_with("running at")),
            "not running"
        );
        let playing = h.get_by_label("Edit the scene").rect();
        assert_eq!(playing, paused, "at {size:?}");
        h.state_mut().apply(Command::TogglePlay);
    }
}

/// The four time plots share one legend row above them: their curves have
/// the width (the legends' strip took 60 to 70 % of it).
#[test]
fn the_time_plots_give_a_phone_their_width() {
    for size in PHONES {
        let h = phone(size);
        let shown = texts(&h);
        let entries: Vec<_> = shown.iter().filter(|(t, _)| t == "point 0").collect();
        assert_eq!(entries.len(), 1, "at {size:?}: {entries:?}");
        // the time axis is labelled on to the right of the window
        let rightmost_tick = shown
            .iter()
            .filter(|(t, r)| t.parse::<f64>().is_ok() && r.bottom() > 0.6 * size[1])
            .map(|(_, r)| r.right())
            .fold(0.0f32, f32::max);
        assert!(
            rightmost_tick > 0.75 * size[0],
            "at {size:?} the last time label ends at {rightmost_tick} px"
        );
    }
}

/// All four time plots are on a phone's screen: the last plot's time axis
/// title ends above the status bar (at 360 × 740 the contact plot was
/// behind it).
#[test]
fn the_four_time_plots_fit_above_the_status_bar_on_a_phone() {
    for size in PHONES {
        let h = phone(size);
        let shown = texts(&h);
        let axis = shown
            .iter()
            .filter(|(t, _)| t == "time t (s)")
            .map(|(_, r)| r.bottom())
            .fold(0.0f32, f32::max);
        let status_top = shown
            .iter()
            .filter(|(t, _)| t.contains(" steps · "))
            .map(|(_, r)| r.top())
            .fold(f32::INFINITY, f32::min);
        assert!(axis > 0.0, "at {size:?} no time axis title is drawn");
        assert!(
            status_top.is_finite(),
            "at {size:?} no status bar text found"
        );
        assert!(
            axis <= status_top,
            "at {size:?} the last plot's time axis ends at {axis} px, below the status bar's top at {status_top} px"
        );
    }
}

/// A refused value's reason shows in the editing panel (the views' banner
/// is hidden behind it, and a hover text cannot be reached by touch).
#[test]
fn a_refused_value_says_why_while_editing_on_a_phone() {
    let mut h = phone(PHONES[0]);
    h.get_by_label("Edit the scene").click();
    h.run_steps(3);
    type_into(&mut h, "speed_mps", "-5");
    h.run_steps(2);
    let shown = texts(&h);
    assert!(
        shown
            .iter()
            .any(|(t, r)| t.contains("refused") && r.bottom() <= PHONES[0][1]),
        "no reason in view: {:?}",
        shown.iter().map(|(t, _)| t).collect::<Vec<_>>()
    );
    assert!(h.query_by_label("Back to the views").is_some());
}

/// The mode bars, which need room beside the view, are not offered on a
/// phone (the toggle showed them on while no bars were drawn).
#[test]
fn mode_bars_are_not_offered_on_a_phone() {
    let mut h = phone(PHONES[0]);
    h.state_mut().apply(Command::ShowModeBars(true));
    h.run_steps(2);
    h.get_by_label("View").click();
    h.run_steps(2);
    assert!(
        h.get_by_label("Mode bars").accesskit_node().is_disabled(),
        "Mode bars offered at 390 px"
    );
    assert_eq!(h.query_all_by_label("Mute").count(), 0);
}

/// Classroom mode is not offered on a phone, and a session that left it on
/// opens in the normal layout there.
#[test]
fn classroom_mode_is_not_offered_on_a_phone() {
    let mut h = phone(PHONES[0]);
    h.get_by_label("View").click();
    h.run_steps(2);
    assert!(
        h.get_by_label("Classroom").accesskit_node().is_disabled(),
        "Classroom offered at 390 px"
    );
    h.key_press(egui::Key::Escape);
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(3);
    assert!(h.query_by_label("Edit the scene").is_some());
    assert!(!h.state().classroom());
}

/// On a phone a row of text alone is as high as its text, while buttons
/// keep their fingertip height: `ui.horizontal` takes the touch target's
/// 44 px as every row's least height, so the transport's "paused" line and
/// the status bar were button rows with their text in the middle, and the
/// message banner's strip (kept whether or not a message shows) left an
/// empty band under "Edit the scene". Measured from the nodes' and texts'
/// rects, in units of the "paused" line's text height.
#[test]
fn rows_of_text_are_as_high_as_their_text_on_a_phone() {
    for size in PHONES {
        let h = phone(size);
        let rect = |label: &str| {
            h.query_all_by_label(label)
                .next()
                .unwrap_or_else(|| panic!("no {label} at {size:?}"))
                .rect()
        };
        let paused = rect("paused");
        let edit = rect("Edit the scene");
        let follow = rect("follow latest");
        let line = paused.height();
        assert!(edit.height() >= 44.0, "at {size:?} Edit the scene {edit:?}");
        // under "paused": half an item spacing, the top panel's margin and
        // edge, and the button panel's margin
        let under_paused = edit.top() - paused.bottom();
        assert!(
            under_paused <= line,
            "at {size:?} {under_paused} px under the paused line ({line} px of text)"
        );
        // between "Edit the scene" and the view's first row: the banner's
        // strip (a line and its margins) and the panels' edges, less than
        // a second strip
        let band = follow.top() - edit.bottom();
        assert!(
            band <= 2.0 * (line + 12.0),
            "at {size:?} a {band} px band under Edit the scene (lines of {line} px)"
        );
        // the status bar: its line of text and its panel's margins
        let status_top = crate::harness::status_top(&h);
        assert!(
            size[1] - status_top <= 2.0 * line,
            "at {size:?} the status bar's text starts {} px above the window's bottom",
            size[1] - status_top
        );
    }
}

/// In the phone's editing panel a row of text alone (the "Tags:" line, a
/// section's heading, a table's header) is as high as its text, while the
/// fields, lists and buttons beside them keep their fingertip height.
/// `ui.horizontal` and egui's grids take the touch target's 44 px as every
/// row's least height: there the text sat in the middle of a 44 px row.
/// A line of text `line` px high centred in a row of R px leaves
/// (R - line) / 2 besides the item spacing to its neighbour: at most a
/// quarter of a line for a row at most a line and a half high.
#[test]
fn the_phone_editors_rows_of_text_are_as_high_as_their_text() {
    use std::path::Path;
    for size in PHONES {
        for preset in ["paper.ron", "three_points.ron"] {
            let p = Path::new("presets").join(preset);
            let app = App::new(tirecontact::Scene::load(&p).unwrap(), Some(p)).unwrap();
            let mut h = harness_sized(app, size);
            settle(&mut h);
            h.get_by_label("Edit the scene").click();
            h.run_steps(3);
            let style = h.ctx.global_style();
            let spacing = style.spacing.item_spacing.y;
            let body = style.text_styles[&egui::TextStyle::Body].clone();
            let line = h.ctx.fonts_mut(|f| f.row_height(&body));
            let rect = |h: &egui_kittest::Harness<'_, App>, label: &str| {
                h.query_all_by_label(label)
                    .next()
                    .unwrap_or_else(|| panic!("no {label} at {size:?} in {preset}"))
                    .rect()
            };
            // the "Tags:" line, its wrapped row as high as the label's node
            let tags = rect(&h, "Tags:");
            assert!(
                tags.height() <= 1.5 * line,
                "at {size:?} in {preset}: the Tags row is {tags:?} ({line} px lines)"
            );
            // a heading or header above a row of fields or lists
            let mut pairs = vec![("Road", "road type")];
            if preset == "three_points.ron" {
                pairs.push(("damping ratio", "tyre.modes[0].damping_ratio"));
            }
            let check = |h: &egui_kittest::Harness<'_, App>, text: &str, next: &str| {
                let t = rect(h, text);
                let n = rect(h, next);
                assert!(n.height() >= 44.0, "at {size:?} {next} is {n:?}");
                let gap = n.top() - t.bottom();
                assert!(
                    gap <= spacing + 0.25 * line,
                    "at {size:?} in {preset}: {gap} px between {text:?} and {next} \
                     ({line} px lines, item spacing {spacing} px)"
                );
            };
            for (text, next) in pairs {
                check(&h, text, next);
            }
            // further down: the contact section's heading above Rigid
            h.get_by_label("Rigid").scroll_to_me();
            h.run_steps(3);
            check(&h, "Contact", "Rigid");
        }
    }
}
