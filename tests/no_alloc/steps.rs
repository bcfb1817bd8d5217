//! Zero heap allocations per step once a simulation is built, for both
//! contact schemes and through located impacts and releases.

use crate::allocations_in;
use tirecontact::SceneSimulation;

#[test]
fn steps_do_not_allocate() {
    // "Compliant": tread springs (override the scheme; landings and
    // releases located in the step as the "Located" scheme's are)
    for scheme in ["Located", "Paper", "Compliant"] {
        let text = std::fs::read_to_string("presets/three_points.ron")
            .unwrap()
            .replace(
                "contact_scheme: Located",
                &if scheme == "Compliant" {
                    "contact: Compliant(stiffness_n_m: [3e6])".to_string()
                } else {
                    format!("contact_scheme: {scheme}")
                },
            );
        let scene = tirecontact::Scene::parse(&text, "three_points").unwrap();
        let mut sim = tirecontact::Simulation::from_scene(&scene).unwrap();
        // warm up: the first event sizes the scratch tables
        for _ in 0..5000 {
            sim.step().unwrap();
        }
        let events_before = sim.stats().events;
        let allocs = allocations_in(|| {
            for _ in 0..20000 {
                sim.step().unwrap();
            }
        });
        let events = sim.stats().events - events_before;
        assert_eq!(
            allocs, 0,
            "{scheme}: {allocs} allocations in 20000 steps ({events} events)"
        );
        if scheme == "Located" {
            assert!(
                events > 50,
                "the window must contain located events: {events}"
            );
        }
        if scheme == "Compliant" {
            assert!(
                events > 20,
                "the window must contain located landings and releases: {events}"
            );
        }
    }
}

#[test]
fn threaded_steps_do_not_allocate() {
    // every kernel split over 2 threads (a large compliant set: updated
    // inverse, GMRES sub-steps), on a rough road
    let mut scene = tirecontact::analysis::bench::scaling::scaling_scene(
        60,
        40,
        tirecontact::analysis::bench::scaling::Regime::Tread,
    );
    scene.road = tirecontact::model::road::Road::Sine {
        amplitude_m: 5e-4,
        wavelength_m: 0.03,
    };
    scene.ramp_s = 1e-3;
    // (the methods of large sets from 2 points on the road: every step's
    // set takes them, the rows projected ahead included)
    let options = tirecontact::SolverOptions {
        threads: 2,
        parallel_from_madds: 1,
        large_set_from: 2,
        ..tirecontact::SolverOptions::default()
    };
    let mut sim = tirecontact::Simulation::from_scene_with(&scene, options).unwrap();
    for _ in 0..500 {
        sim.step().unwrap();
    }
    let (calls, events) = (sim.threaded_kernel_calls(), sim.stats().events);
    let allocs = allocations_in(|| {
        for _ in 0..2000 {
            sim.step().unwrap();
        }
    });
    assert_eq!(allocs, 0, "{allocs} allocations in 2000 threaded steps");
    assert!(sim.threaded_kernel_calls() > calls + 2000);
    assert!(
        sim.stats().events > events,
        "the window must contain events"
    );
}
