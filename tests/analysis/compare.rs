//! A/B comparison: the difference of a run against a pinned run.

use std::path::Path;
use tirecontact::SceneSimulation;
use tirecontact::analysis::compare::PinnedRun;
use tirecontact::output::record::Recording;
use tirecontact::{Scene, Simulation};

fn record(scene: &Scene) -> Recording {
    let mut sim = Simulation::from_scene(scene).unwrap();
    let mut rec = Recording::new(scene.num_points(), scene.num_steps(), 500);
    while !sim.finished() {
        sim.step().unwrap();
        rec.after_step(&sim);
    }
    rec
}

#[test]
fn pinned_run_difference() {
    let mut scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    scene.duration_s = 0.05;
    let a = record(&scene);
    let pin = PinnedRun::new("A", &scene, 3, &a);
    // against itself: zero on every sample
    let d = pin.difference(&scene.points, &a);
    assert_eq!(d.t_s, a.t_s);
    assert!(d.rms_du_m.iter().chain(&d.rms_dq_n).all(|&x| x == 0.0));
    // the pin survives a parameter change; the difference is the direct one
    scene.speed_mps = 14.0;
    let b = record(&scene);
    assert_eq!(pin.scene.speed_mps, 12.0);
    let d = pin.difference(&scene.points, &b);
    assert_eq!(d.t_s, b.t_s, "same time grid: every sample compared");
    for i in 0..3 {
        for k in (0..b.t_s.len()).step_by(37) {
            assert_eq!(d.du_m[i][k], b.u_m[i][k] - a.u_m[i][k]);
            assert_eq!(d.dq_n[i][k], b.q_n[i][k] - a.q_n[i][k]);
        }
        assert!(d.rms_du_m[i] > 0.0);
    }
    // the export: a header and one row per sample
    let mut csv = Vec::new();
    pin.write_csv(&mut csv).unwrap();
    let text = String::from_utf8(csv).unwrap();
    assert!(text.starts_with("t_s,u0_m,u1_m,u2_m,q0_N,q1_N,q2_N\n"));
    assert_eq!(text.lines().count(), a.t_s.len() + 1);
}

/// Runs of unlike scenes are compared only at the points at the same place,
/// and what differs (points, step, modes) is said.
#[test]
fn unlike_scenes_are_compared_only_where_they_match() {
    let mut five = Scene::load(Path::new("presets/paper.ron")).unwrap();
    five.duration_s = 0.02;
    let a = record(&five);
    let pin = PinnedRun::new("A", &five, 13, &a);
    assert!(pin.unlike(&five, 13).is_empty(), "a scene is like itself");
    // another speed and another road: said, with their values
    let mut faster = five.clone();
    faster.speed_mps = five.speed_mps + 5.0;
    let said = pin.unlike(&faster, 13);
    assert_eq!(said.len(), 1, "{said:?}");
    assert!(
        said[0].contains("excited differently")
            && said[0].contains(&format!(
                "speed V {} -> {} m/s",
                five.speed_mps,
                five.speed_mps + 5.0
            )),
        "{said:?}"
    );
    let mut rough = five.clone();
    rough.road = tirecontact::model::road::Road::Random {
        class: tirecontact::model::road::RoadClass::C,
        seed: 1,
        length_m: 100.0,
        min_wavenumber_cpm: 1.0,
        max_wavenumber_cpm: 20.0,
    };
    let said = pin.unlike(&rough, 13).join(" ");
    assert!(said.contains("road") && said.contains("random"), "{said}");
    // three of the five points, in another order, and a finer step
    let mut three = five.clone();
    three.points = vec![five.points[3], five.points[0], five.points[4]].into();
    three.points[2].x_m += 0.01; // moved: no counterpart
    three.dt_s = five.dt_s / 2.0;
    let b = record(&three);
    let d = pin.difference(&three.points, &b);
    assert_eq!(d.matched, [Some(3), Some(0), None]);
    for k in (0..d.t_s.len()).step_by(53) {
        let t = d.t_s[k];
        // the current sample k' at t, the pinned sample at t (both grids
        // hold t when it is on the coarser one)
        let kb = b.t_s.iter().position(|&x| x == t).unwrap();
        if let Some(ka) = a.t_s.iter().position(|&x| x == t) {
            assert_eq!(d.du_m[0][k], b.u_m[0][kb] - a.u_m[3][ka]);
            assert_eq!(d.du_m[1][k], b.u_m[1][kb] - a.u_m[0][ka]);
        }
    }
    assert!(d.du_m[2].is_empty() && d.rms_dq_n[2].is_nan());
    assert!(d.rms_du_m[..2].iter().all(|x| x.is_finite()));
    let said = pin.unlike(&three, 12).join("\n");
    for part in [
        "The reference has 5 points, this scene 3",
        "compared only at the 2 points at the same place: p0 (reference p3), p1 (reference p0)",
        "Time step 10 µs in the reference, 5 µs here",
        "13 modes, this one 12 modes",
    ] {
        assert!(said.contains(part), "{part:?} not in {said}");
    }
    // a point moved across the tread is at another place
    let mut across = five.points.clone();
    across[1].y_m = 0.02;
    assert_eq!(
        pin.matched(&across),
        [Some(0), None, Some(2), Some(3), Some(4)]
    );
    // nothing at the same place: nothing compared, and said
    let mut apart = five.clone();
    for p in &mut apart.points {
        p.x_m += 1.0;
    }
    assert!(pin.unlike(&apart, 13)[0].contains("nothing is compared"));
    let d = pin.difference(&apart.points, &a);
    assert!(d.matched.iter().all(Option::is_none));
    assert!(d.du_m.iter().all(Vec::is_empty));
}
