//! An edit that needs the ring tyre identified again (a contact point
//! moved) or a ring preset opened does not stop the window: the edit waits
//! for the identification on a thread of its own while frames go on and the
//! current run keeps stepping, then applies with the modes of the new
//! positions (as `Scene::modes` identifies them). Files are read there too:
//! an opened preset, a measured road.

use crate::harness::harness_sized;
use crate::support::temp_dir;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::gui::{App, Command};
use tirecontact::{ModeCache, Scene};

/// Frames (at most `limit`) until no identification waits; how many.
fn frames_until_identified(h: &mut egui_kittest::Harness<'_, App>, limit: usize) -> usize {
    let mut frames = 0;
    while h.state().identifying() && frames < limit {
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.step();
        frames += 1;
    }
    frames
}

#[test]
fn a_moved_point_of_a_ring_tyre_is_identified_off_the_ui_thread() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = harness_sized(App::new(scene.clone(), None).unwrap(), [1280.0, 720.0]);
    h.state_mut().apply(Command::Play);
    h.run_steps(3);
    let steps_before = h.state().simulation().steps();
    assert!(steps_before > 0, "the run plays");

    // point 0 moved by 5 mm: positions never identified before
    let mut edited = scene.clone();
    edited.points[0].x_m += 0.005;
    assert!(
        !h.state().has_modes_for(&edited),
        "a new identification is needed"
    );
    h.state_mut()
        .apply(Command::EditScene(Box::new(edited.clone())));
    // the command returned with the edit waiting, the old scene running
    assert!(
        h.state().identifying(),
        "the edit waits for its identification"
    );
    assert_eq!(h.state().scene().points, scene.points);
    let waiting = h
        .state()
        .message()
        .map(|m| m.text.clone())
        .unwrap_or_default();
    assert!(
        waiting.contains("Identifying the tyre's modes"),
        "{waiting}"
    );
    // meanwhile the fields take no edit (one would be built on the old
    // points and drop the waiting one)
    h.step();
    if h.state().identifying() {
        use egui_kittest::kittest::{NodeT, Queryable};
        assert!(
            h.get_by_label("road.amplitude_m")
                .accesskit_node()
                .is_disabled()
        );
    }

    let frames = frames_until_identified(&mut h, 20_000);
    assert!(
        !h.state().identifying(),
        "identified within {frames} frames"
    );
    // applied: the new points, the run restarted, modes of the new positions
    assert_eq!(h.state().scene().points, edited.points);
    let fresh = |s: &Scene| ModeCache::new().modes(s).unwrap();
    assert_eq!(h.state().modes(), fresh(&edited).as_slice());
    assert_ne!(h.state().modes(), fresh(&scene).as_slice());
    let shown = h
        .state()
        .message()
        .map(|m| m.text.clone())
        .unwrap_or_default();
    assert!(
        !shown.contains("Identifying"),
        "the waiting note is gone: {shown}"
    );
    // and it keeps playing from the restart, the fields editable again
    h.run_steps(3);
    assert!(h.state().time_control().is_playing());
    use egui_kittest::kittest::{NodeT, Queryable};
    assert!(
        !h.get_by_label("road.amplitude_m")
            .accesskit_node()
            .is_disabled()
    );
}

#[test]
fn the_current_run_goes_on_while_a_ring_is_identified() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = harness_sized(App::new(scene.clone(), None).unwrap(), [1280.0, 720.0]);
    h.state_mut().apply(Command::Play);
    h.run_steps(2);
    let mut edited = scene.clone();
    edited.points[4].x_m -= 0.0035;
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    let t0 = h.state().simulation().time_s();
    // a few frames while the thread works: the old run advances
    h.step();
    h.step();
    if h.state().identifying() {
        assert!(
            h.state().simulation().time_s() > t0,
            "the run stood still while the ring was identified"
        );
    }
    frames_until_identified(&mut h, 20_000);
    assert!(!h.state().identifying());
}

#[test]
fn an_identification_that_fails_refuses_the_edit_and_keeps_the_scene() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = harness_sized(App::new(scene.clone(), None).unwrap(), [1280.0, 720.0]);
    // a band below the ring's lowest mode (47 Hz): LSCE finds no mode there
    let mut edited = scene.clone();
    if let tirecontact::scene::Tyre::Ring { identification, .. } = &mut edited.tyre {
        identification.band_hz = (0.0, 20.0);
    }
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    assert!(
        h.state().identifying(),
        "valid options: identified on the thread"
    );
    frames_until_identified(&mut h, 20_000);
    assert_eq!(h.state().scene(), &scene, "the scene is kept");
    let m = h.state().message().expect("a message");
    assert!(
        m.error && m.text.contains("no physical pole pair"),
        "{}",
        m.text
    );
}

#[test]
fn a_ring_preset_opened_is_identified_off_the_ui_thread() {
    let text = std::fs::read_to_string("presets/paper.ron").unwrap();
    let changed = text.replace("damping_ratio: 0.05,", "damping_ratio: 0.061,");
    assert_ne!(changed, text);
    let tmp = temp_dir();
    let dir = tmp.path();
    let path = dir.join("damped.ron");
    std::fs::write(&path, &changed).unwrap();
    let want = Scene::load(&path).unwrap();

    let mut h = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    assert!(!h.state().has_modes_for(&want));
    h.state_mut().apply(Command::OpenPath(path.clone()));
    assert!(
        h.state().identifying(),
        "the file waits for its identification"
    );
    assert_ne!(
        h.state().scene(),
        &want,
        "the current scene stays meanwhile"
    );
    frames_until_identified(&mut h, 20_000);
    assert_eq!(h.state().scene(), &want);
    assert_eq!(
        h.state().modes(),
        ModeCache::new().modes(&want).unwrap().as_slice()
    );
    assert!(!h.state().is_dirty(), "opened, not edited");
    let m = h
        .state()
        .message()
        .map(|m| m.text.clone())
        .unwrap_or_default();
    assert!(m.starts_with("opened"), "{m}");
}

/// A preset opened and a measured road chosen are read on the preparation
/// thread: the app waits for them (the current scene and run go on), then
/// applies them; a file that cannot be read is refused then, the scene kept.
#[test]
fn preset_and_road_files_are_read_off_the_ui_thread() {
    let tmp = temp_dir();
    let mut h = harness_sized(
        App::new(
            Scene::load(Path::new("presets/single_mode.ron")).unwrap(),
            None,
        )
        .unwrap(),
        [1280.0, 720.0],
    );
    h.run();
    let before = h.state().scene().clone();
    h.state_mut()
        .apply(Command::OpenPath("presets/three_points.ron".into()));
    assert!(
        h.state().identifying(),
        "the preset is read by the UI thread"
    );
    assert_eq!(
        h.state().scene(),
        &before,
        "the current scene stays meanwhile"
    );
    crate::harness::settle(&mut h);
    assert_eq!(h.state().scene().num_points(), 3);

    // a live road edit to a measured profile: read off the UI thread, then
    // applied live (the run is not restarted)
    h.state_mut().apply(Command::Step(200));
    h.run();
    let road = tmp.path().join("road.csv");
    std::fs::write(&road, "x_m,z_m\n-10,0\n0,0.001\n10,0\n").unwrap();
    let mut s = h.state().scene().clone();
    s.road = tirecontact::model::road::Road::Measured {
        file: road.clone(),
        looped: false,
    };
    let old_road = h.state().scene().road.clone();
    h.state_mut().apply(Command::EditScene(Box::new(s.clone())));
    assert!(
        h.state().identifying(),
        "the road file is read by the UI thread"
    );
    assert_eq!(h.state().scene().road, old_road, "the old road meanwhile");
    crate::harness::settle(&mut h);
    assert_eq!(h.state().scene().road, s.road);
    assert_eq!(
        *h.state().simulation().problem().road,
        tirecontact::scene::load_road(&s.road, s.base_dir.as_deref()).unwrap()
    );
    assert_eq!(
        h.state().simulation().steps(),
        200,
        "a live edit, no restart"
    );

    // a road file that is not there: refused when read, the scene kept
    let kept = h.state().scene().clone();
    let mut gone = kept.clone();
    gone.road = tirecontact::model::road::Road::Measured {
        file: tmp.path().join("missing.csv"),
        looped: false,
    };
    h.state_mut().apply(Command::EditScene(Box::new(gone)));
    crate::harness::settle(&mut h);
    assert_eq!(h.state().scene(), &kept);
    let m = h.state().message().expect("a refusal");
    assert!(m.error && m.text.contains("missing.csv"), "{}", m.text);
}

/// An FE tyre's file is read on the preparation thread: opening its
/// preset waits off the UI thread, then the side panel shows the file, the
/// nodes and the modes read; a damping edit restarts the run with it; a
/// file that is not there is refused when read, naming it, the scene kept.
#[test]
fn an_fe_tyre_is_read_off_the_ui_thread() {
    let mut h = harness_sized(
        App::new(
            Scene::load(Path::new("presets/single_mode.ron")).unwrap(),
            None,
        )
        .unwrap(),
        [1280.0, 720.0],
    );
    h.run();
    h.state_mut()
        .apply(Command::OpenPath("presets/fe_plate.ron".into()));
    assert!(
        h.state().identifying(),
        "the FE file is read by the UI thread"
    );
    crate::harness::settle(&mut h);
    assert_eq!(h.state().scene().num_points(), 15);
    assert_eq!(h.state().simulation().problem().num_points(), 15);
    h.get_by_label("fe_plate.uff");
    h.get_by_label("41 from 123.321 Hz to 399.963 Hz");
    // a damping edit: restart with the new ratio
    let mut s = h.state().scene().clone();
    let tirecontact::scene::Tyre::FeModes { damping, .. } = &mut s.tyre else {
        panic!("not an FE tyre");
    };
    *damping = tirecontact::readers::fe_modes::FeDamping::Ratio(0.02);
    h.state_mut().apply(Command::EditScene(Box::new(s.clone())));
    crate::harness::settle(&mut h);
    assert_eq!(h.state().scene().tyre, s.tyre);
    // a file that is not there
    let kept = h.state().scene().clone();
    let mut gone = kept.clone();
    if let tirecontact::scene::Tyre::FeModes { file, .. } = &mut gone.tyre {
        *file = "missing_fe.uff".into();
    }
    h.state_mut().apply(Command::EditScene(Box::new(gone)));
    crate::harness::settle(&mut h);
    assert_eq!(h.state().scene(), &kept);
    let m = h.state().message().expect("a refusal");
    assert!(m.error && m.text.contains("missing_fe.uff"), "{}", m.text);
}

/// While an edit waits for its ring's identification, a progress line says
/// what the preparation is doing, and its Cancel stops it: the current
/// scene is kept and no edit applies later.
#[test]
fn a_preparation_shows_its_progress_and_can_be_cancelled() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = harness_sized(App::new(scene.clone(), None).unwrap(), [1280.0, 720.0]);
    h.run_steps(2);
    let mut edited = scene.clone();
    edited.points[0].x_m += 0.004;
    h.state_mut()
        .apply(Command::EditScene(Box::new(edited.clone())));
    assert!(h.state().identifying());
    h.step();
    let (doing, fraction) = h.state().preparation_progress().expect("a preparation");
    assert!(!doing.is_empty() && (0.0..=1.0).contains(&fraction));
    assert!(
        h.query_by_label_contains("Preparing the scene:").is_some(),
        "no progress line"
    );
    // Cancel stays in place while the stage's text changes length
    let at = h.get_by_label("Cancel").rect();
    for _ in 0..2 {
        h.step();
        assert_eq!(h.get_by_label("Cancel").rect(), at, "Cancel moved");
    }
    h.get_by_label("Cancel").click();
    h.run_steps(3);
    assert!(!h.state().identifying(), "the preparation goes on");
    assert!(h.state().preparation_progress().is_none());
    assert!(h.query_by_label_contains("Preparing the scene:").is_none());
    assert_eq!(
        h.state().scene().points,
        scene.points,
        "the current scene is kept"
    );
    let m = h.state().message().unwrap();
    assert!(m.text.contains("Cancelled"), "{m:?}");
    // nothing applies later
    for _ in 0..20 {
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.step();
    }
    assert_eq!(h.state().scene().points, scene.points);
}
