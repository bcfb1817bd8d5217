//! Classroom mode, mode bars with mute/solo, random road and compliant
//! contact controls, and animation export, driven headless with egui_kittest.

use crate::support::temp_dir;
mod clip;
mod events;
mod fit;
mod label_gap;
mod labels;
mod legend;
mod mode_bar_colours;
mod mode_bars_fit;
mod mode_bars_layout;
mod panel;
pub(crate) mod patch_rows;
mod phone_back;
mod picker_contrast;
mod road_visible;
mod scene_ticks;
mod steady_plot;
mod theme;
mod time_ticks;
mod type_scale;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::{Path, PathBuf};
use tirecontact::Scene;
use tirecontact::gui::classroom::FONT_SCALE;
use tirecontact::gui::{App, Command};
use tirecontact::model::road::{Road, RoadClass};
use tirecontact::output::animation::{FrameSettings, frame_path};
use tirecontact::scene::{Contact, Tyre};
use tirecontact::solver::phase::ContactPhase;

fn preset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets")
        .join(name)
}

fn app_on(name: &str) -> App {
    let p = preset(name);
    App::new(Scene::load(&p).unwrap(), Some(p)).unwrap()
}

fn harness(app: App, size: [f32; 2]) -> Harness<'static, App> {
    crate::harness::harness_sized(app, size)
}

fn body_size(h: &Harness<'_, App>) -> f32 {
    h.ctx.global_style().text_styles[&egui::TextStyle::Body].size
}

#[test]
fn classroom_toggle_scales_fonts_and_switches_to_the_presenter_layout() {
    let mut h = harness(app_on("single_mode.ron"), [1280.0, 720.0]);
    h.run();
    let normal = body_size(&h);
    assert!(
        h.query_by_label("road type").is_some(),
        "editing panel shown"
    );
    assert!(h.query_by_label_contains("contact phase").is_none());

    h.get_by_label("Classroom").click();
    h.run();
    h.run();
    assert!(h.state().classroom());
    let big = body_size(&h);
    assert!(
        (big / normal - FONT_SCALE).abs() < 1e-4,
        "{normal} -> {big}"
    );
    assert!(
        h.query_by_label("road type").is_none(),
        "editing panel hidden"
    );
    assert!(h.query_by_label_contains("contact phase").is_some());
    assert!(h.query_by_label("Mode contributions").is_some());
    // slow motion
    assert_eq!(
        h.state().time_control().speed(),
        tirecontact::gui::Speed::Factor(0.05)
    );

    h.get_by_label("Classroom").click();
    h.run();
    h.run();
    assert!(!h.state().classroom());
    assert_eq!(body_size(&h), normal);
    assert!(h.query_by_label("road type").is_some());

    // choosing another view leaves classroom mode (the views' tabs folded
    // into the View menu where classroom mode's large text leaves no room)
    h.state_mut().apply(Command::SetClassroom(true));
    h.run();
    if h.query_by_label("Time plots").is_none() {
        h.get_by_label("View").click();
        h.run();
    }
    h.get_by_label("Time plots").click();
    h.run();
    h.run();
    assert!(!h.state().classroom());
    assert_eq!(body_size(&h), normal);
}

#[test]
fn a_phase_label_appears_when_the_point_impacts() {
    let mut h = harness(app_on("single_mode.ron"), [1280.0, 720.0]);
    h.state_mut().apply(Command::SetClassroom(true));
    h.run();
    assert!(h.query_by_label("p0: free flight").is_some());
    // step until the first impact (the contact flag rises)
    let mut steps = 0;
    while !h.state().simulation().in_contact()[0] {
        h.state_mut().apply(Command::Step(1));
        h.run();
        steps += 1;
        assert!(steps < 20_000, "no impact");
    }
    let t = h.state().simulation().time_s();
    assert_eq!(h.state().phases().phase(0, t), ContactPhase::Impact);
    assert_eq!(h.state().phases().impacts(0), 1);
    assert!(
        h.query_by_label("p0: IMPACT").is_some(),
        "impact label not shown after {steps} steps"
    );
}

#[test]
fn muting_a_mode_changes_the_scene_and_the_bars_and_unmuting_restores_it() {
    let mut h = harness(app_on("guided_1a_soft_tyre.ron"), [1280.0, 720.0]);
    h.state_mut().apply(Command::SetClassroom(true));
    h.run();
    let original = h.state().scene().tyre.clone();
    h.state_mut().apply(Command::Step(3000));
    h.run();
    let mut c = vec![0.0; 3];
    h.state().simulation().mode_displacement_m(0, &mut c);
    assert!(c[1].abs() > 0.0, "mode 1 contributes before muting");

    h.state_mut().apply(Command::Play);
    h.step();
    h.get_all_by_label("Mute").nth(1).unwrap().click();
    h.step();
    h.step();
    assert!(
        h.state().time_control().is_playing(),
        "keeps playing after the restart"
    );
    h.state_mut().apply(Command::Pause);
    h.state_mut().apply(Command::Reset);
    h.run();
    let Tyre::Modal { modes } = &h.state().scene().tyre else {
        panic!("modal tyre expected")
    };
    assert!(
        modes[1]
            .residue_matrix()
            .iter()
            .flatten()
            .all(|a| *a == 0.0)
    );
    assert!(modes[0].residue_matrix()[0][0] > 0.0);
    assert_eq!(h.state().mutes().unwrap().muted, [false, true, false]);
    assert_eq!(h.state().simulation().time_s(), 0.0, "the run restarted");
    assert!(
        h.query_by_label("muted").is_some(),
        "the user sees the mute"
    );
    h.state_mut().apply(Command::Step(3000));
    h.run();
    h.state().simulation().mode_displacement_m(0, &mut c);
    assert_eq!(c[1], 0.0);
    assert!(c[0].abs() > 0.0);

    // un-toggling brings the tyre back exactly
    h.get_all_by_label("Mute").nth(1).unwrap().click();
    h.run();
    assert!(h.state().mutes().is_none());
    assert_eq!(h.state().scene().tyre, original);
    assert!(h.query_by_label("muted").is_none());

    // solo: every other mode muted; again: all back
    h.get_all_by_label("Solo").nth(2).unwrap().click();
    h.run();
    assert_eq!(h.state().mutes().unwrap().muted, [true, true, false]);
    h.get_all_by_label("Solo").nth(2).unwrap().click();
    h.run();
    assert_eq!(h.state().scene().tyre, original);
}

#[test]
fn muting_below_the_rank_of_rigid_contact_is_refused_with_the_reason() {
    let mut h = harness(app_on("three_points.ron"), [1280.0, 720.0]);
    h.state_mut().apply(Command::ShowModeBars(true));
    h.run();
    let before = h.state().scene().clone();
    h.get_all_by_label("Mute").next().unwrap().click();
    h.run();
    let m = h.state().message().unwrap();
    // said plainly, naming what was clicked, with the ways out at hand
    // (buttons beside the mode bars, not a panel classroom mode hides)
    assert!(
        m.error
            && m.text.starts_with("Mute of mode 0 not applied")
            && m.text.contains("move each of the 3 points on its own")
            && m.text.contains("keep more modes playing"),
        "{m:?}"
    );
    assert_eq!(h.state().scene(), &before);
    // Solo says Solo
    h.get_all_by_label("Solo").nth(1).unwrap().click();
    h.run();
    let m = h.state().message().unwrap();
    assert!(m.text.starts_with("Solo of mode 1 not applied"), "{m:?}");
    // "Keep the modes playing" closes the note, nothing changes
    h.get_by_label("Keep the modes playing").click();
    h.run();
    assert!(h.query_by_label("Use compliant contact").is_none());
    assert!(h.state().message().is_none(), "the refusal's banner stays");
    assert_eq!(h.state().scene(), &before);
    // "Use compliant contact": the solo applies with a tread spring
    h.get_all_by_label("Solo").nth(1).unwrap().click();
    h.run();
    h.get_by_label("Use compliant contact").click();
    h.run();
    assert!(!h.state().scene().contact.is_rigid(), "still rigid");
    assert_eq!(h.state().mutes().unwrap().muted, [true, false, true]);
    assert!(h.query_by_label("Use compliant contact").is_none());
    // the solo applied: its refusal's banner gone with its cause
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
}

#[test]
fn choosing_a_random_road_class_in_the_panel_changes_the_road() {
    let mut h = harness(app_on("random_road.ron"), [1500.0, 950.0]);
    h.run();
    h.state_mut().apply(Command::Step(100));
    h.run();
    h.get_by_label("road class").click();
    h.run();
    h.get_by_label("E (very poor)").click();
    h.run();
    let Road::Random { class, seed, .. } = h.state().scene().road.clone() else {
        panic!("random road expected")
    };
    assert_eq!(class, RoadClass::E);
    assert_eq!(seed, 2026);
    // live: the running simulation samples the new road, no restart
    assert_eq!(
        *h.state().simulation().problem().road,
        tirecontact::scene::load_road(&h.state().scene().road, None).unwrap()
    );
    assert_eq!(h.state().simulation().steps(), 100);
    // a new seed regenerates it
    h.get_by_label("new road").click();
    h.run();
    let Road::Random { seed, .. } = h.state().scene().road.clone() else {
        panic!()
    };
    assert_eq!(seed, 2027);
    // a bad band is refused at the field, with the reason
    let name = "road.max_wavenumber_cpm";
    h.get_by_label(name).focus();
    h.run();
    h.get_by_label(name).set_text_value_accesskit("0.5");
    h.run();
    h.key_press(egui::Key::Enter);
    h.run();
    assert!(h.query_by_label_contains("refused: expected").is_some());
    let Road::Random {
        max_wavenumber_cpm, ..
    } = h.state().scene().road.clone()
    else {
        panic!()
    };
    assert_eq!(max_wavenumber_cpm, 20.0);
}

#[test]
fn the_compliant_switch_edits_the_contact_and_restarts() {
    let mut h = harness(app_on("single_mode.ron"), [1500.0, 950.0]);
    h.run();
    h.state_mut().apply(Command::Step(100));
    h.run();
    h.get_by_label("Compliant").click();
    h.run();
    assert_eq!(
        h.state().scene().contact,
        Contact::Compliant {
            stiffness_n_m: vec![2e6]
        }
    );
    assert_eq!(
        h.state().simulation().problem().contact,
        h.state().scene().contact
    );
    assert_eq!(h.state().simulation().steps(), 0, "restarted");
    // 5 kN/mm = 5e6 N/m
    let name = "contact.stiffness_n_m[0]";
    for (text, expect) in [("-1", 2e6), ("5", 5e6)] {
        crate::harness::type_into(&mut h, name, text);
        let Contact::Compliant { stiffness_n_m } = h.state().scene().contact.clone() else {
            panic!()
        };
        assert!(
            (stiffness_n_m[0] - expect).abs() < 1e-6,
            "{text}: {stiffness_n_m:?}"
        );
        if text == "-1" {
            assert!(h.query_by_label_contains("refused: expected").is_some());
        }
    }
    h.get_by_label("Rigid").click();
    h.run();
    assert_eq!(h.state().scene().contact, Contact::Rigid);
}

#[test]
fn animation_export_writes_n_frames_of_the_right_size() {
    let tmp = temp_dir();
    let dir = tmp.path().join("frames");
    let mut h = harness(app_on("three_points.ron"), [1280.0, 720.0]);
    h.run();
    let settings = FrameSettings {
        t0_s: 0.05,
        t1_s: 0.07,
        fps: 25.0,
        slow_motion: 20.0,
        width: 400,
        height: 300,
    };
    let n = 10; // 0.02 s × 20 × 25 fps
    h.state_mut().apply(Command::ExportFrames {
        dir: dir.clone(),
        settings,
        clear_old: false,
    });
    assert!(h.state().exporting_frames());
    h.step(); // the progress window shows while it runs
    assert_eq!(h.state_mut().wait_frames_export(), Some(Ok(n)));
    let files = std::fs::read_dir(&dir).unwrap().count();
    assert_eq!(files as u64, n);
    for k in [0, n - 1] {
        let img = image::open(frame_path(&dir, k)).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (400, 300));
        let non_white = img.pixels().filter(|p| p.0 != [255, 255, 255]).count();
        assert!(non_white as f64 > 0.02 * 400.0 * 300.0, "frame {k} blank");
        // road fill and contact/flight markers are drawn
        assert!(
            img.pixels()
                .any(|p| p.0 == [213, 94, 0] || p.0 == [0, 158, 115])
        );
    }
    // frames differ: the road moves
    let a = image::open(frame_path(&dir, 0)).unwrap().to_rgb8();
    let b = image::open(frame_path(&dir, n - 1)).unwrap().to_rgb8();
    assert_ne!(a.as_raw(), b.as_raw());
    // where they went is said
    let m = h.state().message().unwrap();
    assert!(
        !m.error && m.text.contains(&format!("into {}", dir.display())),
        "{m:?}"
    );
    // bad settings are refused with the field named
    h.state_mut().apply(Command::ExportFrames {
        dir: dir.clone(),
        settings: FrameSettings {
            fps: -1.0,
            ..settings
        },
        clear_old: false,
    });
    let m = h.state().message().unwrap();
    assert!(m.error && m.text.contains("fps = -1"), "{m:?}");
    // a shorter export into the same folder: refused (the old scene's last
    // frames would stay behind and mix), unless the old frames are cleared
    let shorter = FrameSettings {
        t1_s: 0.06,
        ..settings
    };
    h.state_mut().apply(Command::ExportFrames {
        dir: dir.clone(),
        settings: shorter,
        clear_old: false,
    });
    assert!(!h.state().exporting_frames());
    let m = h.state().message().unwrap();
    assert!(
        m.error
            && m.text
                .contains("already holds 10 frames of an earlier export"),
        "{m:?}"
    );
    assert_eq!(std::fs::read_dir(&dir).unwrap().count() as u64, n);
    h.state_mut().apply(Command::ExportFrames {
        dir: dir.clone(),
        settings: shorter,
        clear_old: true,
    });
    assert_eq!(h.state_mut().wait_frames_export(), Some(Ok(5)));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 5);
}

#[test]
fn every_guided_preset_opens_from_the_menu() {
    let mut h = harness(app_on("single_mode.ron"), [1280.0, 720.0]);
    h.run();
    for (k, (_, file, _)) in tirecontact::gui::model::presets::GUIDED.iter().enumerate() {
        h.state_mut().apply(Command::OpenGuided(k));
        h.run();
        let m = h.state().message().unwrap();
        assert!(!m.error, "{file}: {m:?}");
        assert!(!h.state().scene().description.is_empty());
    }
}

#[test]
fn muting_a_ring_tyre_mode_uses_its_identified_modes_and_unmuting_gives_the_ring_back() {
    let mut h = harness(app_on("paper.ron"), [1280.0, 720.0]);
    h.state_mut().apply(Command::ShowModeBars(true));
    h.run();
    assert!(matches!(h.state().scene().tyre, Tyre::Ring { .. }));
    let n = h.state().modes().len();
    assert!(n > 5, "{n} identified modes");
    let identified = h.state().modes().to_vec();
    h.state_mut().apply(Command::ToggleMute(n - 1));
    h.run();
    let m = h.state().message();
    assert!(m.is_none_or(|m| !m.error), "{m:?}");
    let Tyre::Modal { modes } = &h.state().scene().tyre else {
        panic!("muting turns the ring into its identified modes")
    };
    assert_eq!(modes.len(), n);
    assert_eq!(modes[0], identified[0]);
    assert!(
        modes[n - 1]
            .residue_matrix()
            .iter()
            .flatten()
            .all(|a| *a == 0.0)
    );
    h.state_mut().apply(Command::UnmuteAll);
    h.run();
    assert!(matches!(h.state().scene().tyre, Tyre::Ring { .. }));
    assert!(h.state().mutes().is_none());
}
