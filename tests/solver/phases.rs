//! The contact phase of each point (free flight, impact, contact,
//! release) read from runs.

use tirecontact::identify::SceneSimulation;
use tirecontact::solver::phase::*;
use tirecontact::{Scene, Simulation};

#[test]
fn the_table_of_phases() {
    use ContactPhase::*;
    assert_eq!(classify(false, false, false), FreeFlight);
    assert_eq!(classify(false, true, false), Impact);
    assert_eq!(classify(false, true, true), Impact);
    assert_eq!(classify(false, false, true), Impact);
    assert_eq!(classify(true, true, true), InContact);
    assert_eq!(classify(true, false, false), Release);
}

#[test]
fn events_are_held_then_the_steady_phase_shows() {
    let mut t = PhaseTracker::new(2, 0.01);
    t.after_step(0.001, &[false, false], &[0.0, 0.0]);
    assert_eq!(t.phase(0, 0.001), ContactPhase::FreeFlight);
    t.after_step(0.002, &[true, false], &[5.0, 0.0]);
    assert_eq!(t.phase(0, 0.002), ContactPhase::Impact);
    assert_eq!(t.phase(1, 0.002), ContactPhase::FreeFlight);
    t.after_step(0.003, &[true, false], &[5.0, 0.0]);
    assert_eq!(t.phase(0, 0.011), ContactPhase::Impact);
    assert_eq!(t.phase(0, 0.0125), ContactPhase::InContact);
    t.after_step(0.02, &[false, false], &[0.0, 0.0]);
    assert_eq!(t.phase(0, 0.02), ContactPhase::Release);
    assert_eq!(t.phase(0, 0.031), ContactPhase::FreeFlight);
    assert_eq!((t.impacts(0), t.releases(0)), (1, 1));
    // out-of-range point: free flight, no panic
    assert_eq!(t.phase(9, 0.0), ContactPhase::FreeFlight);
}

/// Played at the classroom's slow motion, the paper preset's points
/// land and leave every few milliseconds: the four phases must each be
/// shown a visible share of the run, not only IMPACT and RELEASE.
#[test]
fn every_phase_is_shown_for_a_share_of_a_fast_bouncing_run() {
    for (preset, text) in [
        (
            "paper",
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/paper.ron")),
        ),
        (
            "three_points",
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/three_points.ron"
            )),
        ),
    ] {
        let mut scene = Scene::parse(text, preset).unwrap();
        scene.duration_s = scene.duration_s.min(0.15);
        let p = scene.num_points();
        // 0.6 s of wall time at 0.05x and at 0.01x
        for hold_s in [0.6 * 0.05, 0.6 * 0.01] {
            let mut sim = Simulation::from_scene(&scene).unwrap();
            let mut tr = PhaseTracker::new(p, hold_s);
            let mut shown = [0u64; 4];
            let mut total = 0u64;
            while !sim.finished() {
                sim.step().unwrap();
                tr.after_step(sim.time_s(), sim.in_contact(), sim.force_n());
                if sim.time_s() < scene.ramp_s {
                    continue;
                }
                for i in 0..p {
                    let k = match tr.phase(i, sim.time_s()) {
                        ContactPhase::FreeFlight => 0,
                        ContactPhase::Impact => 1,
                        ContactPhase::InContact => 2,
                        ContactPhase::Release => 3,
                    };
                    shown[k] += 1;
                    total += 1;
                }
            }
            let share: Vec<f64> = shown.iter().map(|&n| n as f64 / total as f64).collect();
            for (k, name) in ["free flight", "impact", "in contact", "release"]
                .iter()
                .enumerate()
            {
                assert!(
                    share[k] >= 0.05,
                    "{preset}, hold {hold_s} s: {name} shown {:.3} of the run ({share:?})",
                    share[k]
                );
            }
        }
    }
}

/// Over a run, impacts and releases alternate per point, and counting
/// the contact flag's rising edges independently gives the same impacts
/// (bounces inside a step excepted, counted separately).
#[test]
fn impacts_match_rising_edges_of_the_contact_flag() {
    let scene = Scene::parse(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/three_points.ron"
        )),
        "three",
    )
    .unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let mut tr = PhaseTracker::new(3, 0.0);
    let mut prev = [false; 3];
    let mut rising = [0u64; 3];
    let mut bounces = [0u64; 3];
    for _ in 0..20_000 {
        sim.step().unwrap();
        for i in 0..3 {
            let c = sim.in_contact()[i];
            rising[i] += u64::from(!prev[i] && c);
            bounces[i] += u64::from(!prev[i] && !c && sim.force_n()[i] > 0.0);
            prev[i] = c;
        }
        tr.after_step(sim.time_s(), sim.in_contact(), sim.force_n());
    }
    for i in 0..3 {
        assert!(rising[i] > 0, "point {i} never landed");
        assert_eq!(tr.impacts(i), rising[i] + bounces[i]);
        let open = u64::from(prev[i]);
        assert_eq!(tr.releases(i) + open, rising[i]);
    }
}
