//! The visualiser driven headless with egui_kittest (no GPU): time control,
//! editing, refused values, broken presets, unsaved changes, export.

use crate::harness::{MemStorage, harness, settle, type_into};
use crate::support::temp_dir;
use egui_kittest::kittest::Queryable;
use tirecontact::Scene;
use tirecontact::gui::Discarding;
use tirecontact::gui::Speed;
use tirecontact::gui::{App, Command};

/// The single-mode preset (a modal tyre whose modes the tests edit).
fn single_mode_app() -> App {
    let text = include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/presets/single_mode.ron"
    ));
    App::new(Scene::parse(text, "presets/single_mode.ron").unwrap(), None).unwrap()
}

fn default_scene() -> Scene {
    Scene::parse(
        tirecontact::DEFAULT_PRESET,
        tirecontact::DEFAULT_PRESET_NAME,
    )
    .unwrap()
}

fn freq0(app: &App) -> f64 {
    app.modes()[0].freq_hz
}

#[test]
fn the_app_opens_on_the_paper_preset_one_click_from_playing() {
    let mut h = harness(App::with_default_preset());
    h.run();
    let scene = h.state().scene().clone();
    assert_eq!(scene, default_scene());
    assert!(matches!(scene.tyre, tirecontact::scene::Tyre::Ring { .. }));
    assert_eq!(scene.num_points(), 5);
    assert!(
        !h.state().modes().is_empty(),
        "the ring's modes are identified"
    );
    assert!(!h.state().is_dirty());
    // its 0.2 s run opens in slow motion, so that it lasts 4 s on screen
    assert_eq!(h.state().time_control().speed(), Speed::Factor(0.05));
    h.get_by_label("Play").click();
    h.run_steps(5);
    assert!(h.state().simulation().time_s() > 0.0);
}

#[test]
fn step_play_pause_and_reset_move_the_clock() {
    let mut h = harness(App::with_default_preset());
    h.run();
    let dt = h.state().scene().dt_s;
    assert_eq!(h.state().simulation().time_s(), 0.0);

    h.get_by_label("Step").click();
    h.run();
    assert!((h.state().simulation().time_s() - dt).abs() < 1e-15);

    h.key_press(egui::Key::ArrowRight);
    h.run();
    assert_eq!(h.state().simulation().steps(), 2);

    h.state_mut().apply(Command::Step(250));
    h.run();
    assert_eq!(h.state().simulation().steps(), 252);
    assert!(h.state().history().len() > 200);

    h.get_by_label("Play").click();
    h.run_steps(10);
    assert!(h.state().time_control().is_playing());
    let t_playing = h.state().simulation().time_s();
    assert!(
        t_playing > 252.0 * dt,
        "playing did not advance: {t_playing}"
    );
    // at 1x with 1/60 s frames, at most 1/60 s of simulated time per frame
    assert!(t_playing <= 252.0 * dt + 11.0 / 60.0 + 1e-9);

    h.key_press(egui::Key::Space);
    h.run();
    assert!(!h.state().time_control().is_playing());
    let t_paused = h.state().simulation().time_s();
    h.run_steps(3);
    assert_eq!(h.state().simulation().time_s(), t_paused);

    h.key_press(egui::Key::R);
    h.run();
    assert_eq!(h.state().simulation().time_s(), 0.0);
    assert_eq!(h.state().history().len(), 1);
}

#[test]
fn editing_a_field_changes_the_scene_and_restarts() {
    let mut h = harness(single_mode_app());
    h.run();
    h.state_mut().apply(Command::Step(10));
    h.run();
    type_into(&mut h, "tyre.modes[0].freq_hz", "120");
    assert_eq!(freq0(h.state()), 120.0);
    assert_eq!(h.state().simulation().problem().modes[0].freq_hz, 120.0);
    // a mode change restarts the run
    assert_eq!(h.state().simulation().steps(), 0);
    assert!(h.state().is_dirty());
    assert!(h.state().title().starts_with("* "));
}

/// A point's position across the tread is a field of the points table:
/// an edit restarts the run; on the ring tyre with rigid contact, a point
/// moved to another's `x` at a different `y` is refused with the reason.
#[test]
fn points_are_edited_across_the_tread() {
    let mut h = harness(App::with_default_preset());
    settle(&mut h);
    type_into(&mut h, "points[1].y_m", "0.04");
    assert_eq!(h.state().scene().points[1].y_m, 0.04);
    assert_eq!(h.state().simulation().problem().points[1].y_m, 0.04);
    assert!(h.state().is_dirty());
    settle(&mut h);
    type_into(&mut h, "points[1].x_m", "-0.05");
    assert_eq!(
        h.state().scene().points[1].x_m,
        -0.025,
        "the old value must be kept"
    );
    let reason = format!("{:?}", h.get_by_label_contains("refused"));
    assert!(
        reason.contains("share x_m = -0.05 m at different y_m")
            && reason.contains("does not depend on y"),
        "{reason}"
    );
}

#[test]
fn live_edits_keep_the_run_going() {
    let mut h = harness(App::with_default_preset());
    h.run();
    h.state_mut().apply(Command::Step(10));
    h.run();
    type_into(&mut h, "speed_kmh", "36");
    assert!((h.state().scene().speed_mps - 10.0).abs() < 1e-12);
    assert!((h.state().simulation().problem().speed_mps - 10.0).abs() < 1e-12);
    assert_eq!(
        h.state().simulation().steps(),
        10,
        "a speed change must not restart"
    );
    type_into(&mut h, "road.amplitude_m", "3");
    assert_eq!(h.state().simulation().steps(), 10);
    // the running simulation samples the edited road
    match &*h.state().simulation().problem().road {
        tirecontact::model::road::RoadProfile::Harmonics(h) => {
            assert!((h[0].amplitude_m - 0.003).abs() < 1e-15)
        }
        r => panic!("unexpected road {r:?}"),
    }
}

#[test]
fn a_bad_value_is_refused_at_the_field_with_the_reason() {
    let mut h = harness(single_mode_app());
    h.run();
    type_into(&mut h, "tyre.modes[0].freq_hz", "-5");
    assert_eq!(freq0(h.state()), 100.0, "the old value must be kept");
    let reason = h.get_by_label_contains("refused");
    let text = format!("{reason:?}");
    assert!(text.contains("frequency > 0 Hz"), "{text}");
    assert!(!h.state().is_dirty());

    type_into(&mut h, "tyre.modes[0].damping_ratio", "abc");
    assert_eq!(h.state().modes()[0].damping_ratio, 0.05);
    assert!(h.query_by_label_contains("is not a number").is_some());
}

#[test]
fn a_broken_preset_shows_its_error_and_keeps_the_scene() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let syntax = dir.join("syntax.ron");
    std::fs::write(
        &syntax,
        "Scene(\n  name: \"x\",\n  tyre: Modal(modes: [\n  oops\n",
    )
    .unwrap();
    let mut h = harness(App::with_default_preset());
    h.run();
    let before = h.state().scene().clone();
    h.state_mut().apply(Command::OpenPath(syntax.clone()));
    h.run();
    assert_eq!(h.state().scene(), &before);
    let msg = h.state().message().cloned().unwrap();
    assert!(msg.error);
    assert!(msg.text.contains("syntax.ron:4:"), "{}", msg.text);
    assert!(h.query_by_label_contains("current scene is kept").is_some());

    let invalid = dir.join("invalid.ron");
    let text = tirecontact::DEFAULT_PRESET.replace("dt_s: 1e-5", "dt_s: -1e-5");
    std::fs::write(&invalid, text).unwrap();
    h.state_mut().apply(Command::OpenPath(invalid));
    h.run();
    assert_eq!(h.state().scene(), &before);
    assert!(h.state().message().unwrap().text.contains("dt_s = -1e-5"));
}

#[test]
fn unsaved_changes_are_confirmed_before_they_are_dropped() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let mut h = harness(single_mode_app());
    h.run();
    type_into(&mut h, "tyre.modes[0].freq_hz", "150");
    assert!(h.state().is_dirty());
    h.state_mut().apply(Command::New);
    h.run();
    assert_eq!(h.state().pending_confirmation(), Some(&Discarding::New));
    h.get_by_label("Cancel").click();
    h.run();
    assert_eq!(freq0(h.state()), 150.0);
    assert!(h.state().pending_confirmation().is_none());

    h.state_mut().apply(Command::New);
    h.run();
    h.get_by_label("Discard changes").click();
    settle(&mut h);
    assert_eq!(h.state().scene(), &default_scene());
    assert!(!h.state().is_dirty());
    // back to a modal scene to edit its first mode
    h.state_mut()
        .apply(Command::OpenPath("presets/single_mode.ron".into()));
    h.run();
    assert_eq!(freq0(h.state()), 100.0);

    // save, reopen: not dirty, same scene
    type_into(&mut h, "tyre.modes[0].freq_hz", "130");
    let path = dir.join("saved.ron");
    h.state_mut().apply(Command::SavePath(path.clone()));
    h.run();
    assert!(!h.state().is_dirty());
    assert_eq!(
        tirecontact::ModeCache::new()
            .modes(&Scene::load(&path).unwrap())
            .unwrap()[0]
            .freq_hz,
        130.0
    );
    h.state_mut().apply(Command::OpenPath(path));
    h.run();
    assert!(h.state().pending_confirmation().is_none());
    assert_eq!(freq0(h.state()), 130.0);
}

#[test]
fn export_writes_a_png_of_the_requested_size_that_is_not_blank() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let mut h = harness(App::with_default_preset());
    h.run();
    h.state_mut().apply(Command::Step(3000));
    h.run();
    let path = dir.join("plots.png");
    h.state_mut().apply(Command::ExportPng {
        path: path.clone(),
        width: 900,
        height: 700,
    });
    h.run();
    assert!(
        !h.state().message().unwrap().error,
        "{:?}",
        h.state().message()
    );
    let img = image::open(&path).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (900, 700));
    let non_white = img.pixels().filter(|p| p.0 != [255, 255, 255]).count();
    let frac = non_white as f64 / (900.0 * 700.0);
    assert!(frac > 0.01, "image looks blank: {frac}");
    // the data lines are drawn in the palette's first colour
    let c0 = tirecontact::output::figures::PALETTE[0];
    assert!(
        img.pixels().any(|p| p.0 == [c0.0, c0.1, c0.2]),
        "no series drawn"
    );

    // a bad size is refused with a message, nothing panics
    h.state_mut().apply(Command::ExportPng {
        path: dir.join("tiny.png"),
        width: 10,
        height: 10,
    });
    assert!(h.state().message().unwrap().error);
}

#[test]
fn csv_export_matches_the_run_including_live_edits() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let mut h = harness(single_mode_app());
    h.run();
    h.state_mut().apply(Command::Step(200));
    h.run();
    type_into(&mut h, "speed_mps", "25");
    h.state_mut().apply(Command::Step(100));
    h.run();
    let u_now = h.state().simulation().displacement_m()[0];
    let path = dir.join("run.csv");
    h.state_mut().apply(Command::ExportCsv(path.clone()));
    let r = h.state_mut().wait_csv_export().unwrap();
    assert!(r.is_ok(), "{r:?}");
    let text = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "t_s,u0_m,v0_mps,q0_N,gap0_m,contact0");
    assert_eq!(lines.len(), 1 + 301);
    let last_u: f64 = lines[301].split(',').nth(1).unwrap().parse().unwrap();
    assert!(
        (last_u - u_now).abs() <= 1e-9 * u_now.abs().max(1e-12),
        "{last_u} vs {u_now}"
    );
}

#[test]
fn a_solver_error_pauses_the_run_and_shows_the_message() {
    // a measured road 0.1 m long, not looped, at 10 m/s: out of range after 10 ms
    let tmp = temp_dir();
    let dir = tmp.path();
    let road = dir.join("road.csv");
    std::fs::write(&road, "x_m,z_m\n0.0,0.0\n0.05,0.001\n0.1,0.0\n").unwrap();
    let text = format!(
        r#"Scene(
        name: "short road",
        tyre: Modal(modes: [Mode(freq_hz: 100.0, damping_ratio: 0.05, residue: [[0.1]])]),
        points: [Point(x_m: 0.0, h_m: -0.001)],
        road: Measured(file: "{}"),
        speed_mps: 10.0,
        ramp_s: 0.002,
        dt_s: 1e-5,
        duration_s: 0.05,
    )"#,
        road.display()
    );
    let scene = Scene::parse(&text, "short road").unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    // a 0.05 s run opens in slow motion (watchable); play it at real time
    h.state_mut().apply(Command::SetSpeed(Speed::Factor(1.0)));
    h.state_mut().apply(Command::Play);
    h.run_steps(30);
    assert!(!h.state().time_control().is_playing(), "the run must pause");
    let msg = h.state().message().cloned().unwrap();
    assert!(
        msg.error && msg.text.contains("outside its extent"),
        "{}",
        msg.text
    );
    let t = h.state().simulation().time_s();
    assert!((0.009..0.0101).contains(&t), "{t}");
    assert!(h.query_by_label_contains("Solver error").is_some());
}

#[test]
fn views_switch_and_render() {
    let mut h = harness(App::with_default_preset());
    h.run();
    h.state_mut().apply(Command::Step(2000));
    h.run();
    h.get_by_label("Scene view").click();
    h.run();
    assert!(h.query_by_label_contains("vertical exaggeration").is_some());
    h.get_by_label("Green functions").click();
    h.run();
    assert!(h.query_by_label("receiving point i").is_some());
    h.get_by_label("Time plots").click();
    h.run();
    assert!(h.query_by_label("follow latest").is_some());
}

#[test]
fn every_shipped_preset_opens() {
    let mut h = harness(App::with_default_preset());
    h.run();
    for (k, (_, file, text)) in tirecontact::gui::model::presets::SHIPPED.iter().enumerate() {
        let expected = Scene::parse(text, file).unwrap();
        h.state_mut().apply(Command::OpenPreset(k));
        h.run();
        assert_eq!(h.state().scene(), &expected, "{:?}", h.state().message());
        assert!(!h.state().modes().is_empty());
        h.state_mut().apply(Command::Step(20));
        h.run();
        assert_eq!(h.state().simulation().steps(), 20);
    }
}

#[test]
fn the_last_session_is_restored() {
    use eframe::App as _;
    use eframe::Storage as _;
    let mut h = harness(single_mode_app());
    h.run();
    type_into(&mut h, "tyre.modes[0].freq_hz", "140");
    let mut storage = MemStorage::default();
    h.state_mut().save(&mut storage);
    let restored = App::restore(Some(&storage));
    assert_eq!(restored.scene(), h.state().scene());
    assert!(restored.is_dirty(), "unsaved edits stay marked as unsaved");
    // nothing stored, or garbage: the default preset
    assert_eq!(App::restore(None).scene(), &default_scene());
    storage.set_string("tirecontact.session", "not ron".to_string());
    assert_eq!(App::restore(Some(&storage)).scene(), &default_scene());
}

/// A minimised window stops simulating (and asking for frames) and resumes
/// where it was when shown again.
#[test]
fn a_minimised_window_does_not_simulate() {
    let mut h = harness(single_mode_app());
    h.run();
    h.state_mut().apply(Command::Play);
    h.run_steps(3);
    let t_playing = h.state().simulation().time_s();
    assert!(t_playing > 0.0);
    let id = egui::ViewportId::ROOT;
    h.input_mut().viewports.entry(id).or_default().minimized = Some(true);
    h.run_steps(5);
    assert_eq!(h.state().simulation().time_s(), t_playing);
    assert!(
        h.state().time_control().is_playing(),
        "still playing, only hidden"
    );
    h.input_mut().viewports.entry(id).or_default().minimized = Some(false);
    h.run_steps(3);
    assert!(h.state().simulation().time_s() > t_playing);
}

/// A new duration re-chooses the playback speed when the old one was the
/// automatic choice or would play the new run in a blink (a 0.002 s run at
/// 0.25x ended in 8 ms); a chosen speed that still plays it long enough
/// stays.
#[test]
fn a_new_duration_rechooses_a_speed_that_would_end_in_a_blink() {
    let mut h = harness(App::new(default_scene(), None).unwrap());
    h.run();
    let with_duration = |h: &mut egui_kittest::Harness<'_, App>, d: f64| {
        let mut s = h.state().scene().clone();
        s.duration_s = d;
        h.state_mut().apply(Command::EditScene(Box::new(s)));
        h.run_steps(2);
        assert_eq!(h.state().scene().duration_s, d);
        h.state().time_control().speed()
    };
    // the automatic choice follows the duration
    assert_eq!(
        h.state().time_control().speed(),
        Speed::watchable(h.state().scene().duration_s)
    );
    assert_eq!(with_duration(&mut h, 2.0), Speed::watchable(2.0));
    // chosen by hand: kept while the run lasts 4 s or more at it
    h.state_mut().apply(Command::SetSpeed(Speed::Factor(0.25)));
    assert_eq!(with_duration(&mut h, 1.5), Speed::Factor(0.25));
    // ... and re-chosen when the run would end in 8 ms
    let s = with_duration(&mut h, 0.002);
    assert_eq!(s, Speed::watchable(0.002));
    let Speed::Factor(f) = s else { panic!("{s:?}") };
    assert!(0.002 / f >= 2.0, "the run plays {} s", 0.002 / f);
}

/// An FE tyre's 15 points are all shown when it opens (points 0–7 were).
#[test]
fn an_fe_tyre_opens_with_every_point_shown() {
    let path = std::path::PathBuf::from("presets/fe_plate.ron");
    let scene = Scene::load(&path).unwrap();
    assert_eq!(scene.num_points(), 15);
    let mut h = harness(App::new(scene, Some(path)).unwrap());
    h.run();
    let shown = &h.state().plot_options().shown;
    assert_eq!(shown.len(), 15);
    assert!(shown.iter().all(|&s| s), "{shown:?}");
}
