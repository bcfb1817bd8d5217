//! A/B comparison: the difference of a run against a pinned run.

use std::path::Path;
use tirecontact::compare::PinnedRun;
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
    let pin = PinnedRun::new("A", &scene, &a);
    // against itself: zero on every sample
    let d = pin.difference(&a);
    assert_eq!(d.t_s, a.t_s);
    assert!(d.rms_du_m.iter().chain(&d.rms_dq_n).all(|&x| x == 0.0));
    // the pin survives a parameter change; the difference is the direct one
    scene.speed_mps = 14.0;
    let b = record(&scene);
    assert_eq!(pin.scene.speed_mps, 12.0);
    let d = pin.difference(&b);
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
