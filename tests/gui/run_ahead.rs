//! "As fast as possible" on the desktop: the run steps on a thread of its
//! own between frames ([`App::frame`]), and gives the run the frames' own
//! steps give.

use crate::harness::MAX_RUN_FRAMES;
use crate::support::preset;
use egui_kittest::Harness;
use tirecontact::Scene;
use tirecontact::gui::{App, Command, Quantity, Speed};

fn playing_at_max(scene: &Scene) -> App {
    let mut app = App::new(scene.clone(), None).unwrap();
    app.apply(Command::SetSpeed(Speed::Max));
    app.apply(Command::Play);
    app
}

/// The harness running eframe's frame (`lent`) or only the UI's (`App::show`).
fn harness(app: App, lent: bool) -> Harness<'static, App> {
    let b = Harness::builder()
        .with_size([1500.0, 950.0])
        .with_step_dt(1.0 / 60.0)
        .with_max_steps(MAX_RUN_FRAMES);
    if lent {
        b.build_ui_state(|ui, app: &mut App| app.frame(ui), app)
    } else {
        b.build_ui_state(|ui, app: &mut App| app.show(ui), app)
    }
}

/// Frames until the run has ended; the run taken back after each.
fn play_to_end(h: &mut Harness<'_, App>) -> usize {
    let mut frames = 0;
    loop {
        h.run_steps(1);
        frames += 1;
        h.state_mut().reclaim_run();
        if h.state().simulation().finished() {
            return frames;
        }
        assert!(frames < 100_000, "the run makes no progress");
    }
}

/// Stepped between frames or in them, a run is the same to the bit: its
/// histories, its forces and its step count, on a small scene and a patch.
#[test]
fn a_run_stepped_between_frames_is_the_run_stepped_in_them() {
    for (name, steps) in [("three_points", 3000.0), ("patch_texture", 300.0)] {
        let mut scene = preset(name);
        scene.duration_s = steps * scene.dt_s;
        let mut lent = harness(playing_at_max(&scene), true);
        let mut framed = harness(playing_at_max(&scene), false);
        play_to_end(&mut lent);
        play_to_end(&mut framed);
        let (a, b) = (lent.state(), framed.state());
        assert_eq!(a.simulation().steps(), b.simulation().steps(), "{name}");
        assert_eq!(a.history().times(), b.history().times(), "{name}");
        for i in 0..scene.num_points() {
            for what in [Quantity::Displacement, Quantity::Force, Quantity::Gap] {
                let ha = a
                    .history()
                    .decimated(what, i, 0.0, scene.duration_s, 1 << 20, 1.0);
                let hb = b
                    .history()
                    .decimated(what, i, 0.0, scene.duration_s, 1 << 20, 1.0);
                assert_eq!(ha, hb, "{name}: point {i}, {what:?}");
            }
            assert_eq!(
                a.simulation().force_n()[i].to_bits(),
                b.simulation().force_n()[i].to_bits(),
                "{name}: point {i}"
            );
        }
    }
}

/// Paused, or at a chosen speed, the run stays with the app between
/// frames; played as fast as possible, it goes on between them, and a
/// pause stops it at once.
#[test]
fn only_a_run_as_fast_as_possible_is_lent() {
    let mut scene = preset("three_points");
    scene.duration_s = 1.0;
    let mut app = App::new(scene.clone(), None).unwrap();
    app.apply(Command::SetSpeed(Speed::Factor(0.01)));
    app.apply(Command::Play);
    let mut h = harness(app, true);
    h.run_steps(3);
    // (without taking it back: the app holds the scene's own run)
    assert!(!h.state().run_is_lent());
    assert_eq!(h.state().simulation().num_points(), scene.num_points());
    let at_speed = h.state().simulation().steps();
    assert!(at_speed > 0);

    // the first frame at full speed steps in the frame, then lends the run
    h.state_mut().apply(Command::SetSpeed(Speed::Max));
    h.run_steps(1);
    assert!(h.state().run_is_lent());
    h.state_mut().reclaim_run();
    assert!(!h.state().run_is_lent());
    let s1 = h.state().simulation().steps();
    // the next frames take no steps of their own: the steps come from the
    // time between frames (a few 20 ms waits, however loaded the machine)
    let mut s2 = s1;
    for _ in 0..100 {
        h.run_steps(1);
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.state_mut().reclaim_run();
        s2 = h.state().simulation().steps();
        if s2 > s1 + 100 {
            break;
        }
    }
    assert!(
        s2 > s1 + 100,
        "the time between frames took no steps: {s1} -> {s2}"
    );
    assert!(h.state().time_control().is_playing());

    h.state_mut().apply(Command::Pause);
    h.run_steps(2);
    assert!(!h.state().run_is_lent());
    let paused = h.state().simulation().steps();
    std::thread::sleep(std::time::Duration::from_millis(20));
    h.run_steps(2);
    assert_eq!(h.state().simulation().steps(), paused);
    assert_eq!(h.state().simulation().num_points(), scene.num_points());
    assert!(!h.state().time_control().is_playing());
}
