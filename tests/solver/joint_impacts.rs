//! Impacts solved as one complementarity problem over every point at the
//! road (method §4.4, "Several events at one instant") against the
//! impacts of one point at a time: complementarity at every step end, the
//! same momentum delivered to the tyre, and far fewer events where many
//! fine-spaced rigid points land on a ramp.

use proptest::prelude::*;
use tirecontact::analysis::bench::scaling::{Regime, scaling_scene};
use tirecontact::model::road::Road;
use tirecontact::{PreparedModel, Scene, Simulation, SolverOptions};

/// A rigid footprint of `p` points `spacing_m` apart on `k` modes, rolling
/// onto a sine road of `amplitude_m` and `wavelength_m` over the 0.01 s
/// ramp, for `duration_s`.
fn footprint(
    p: usize,
    k: usize,
    spacing_m: f64,
    amplitude_m: f64,
    wavelength_m: f64,
    duration_s: f64,
) -> Scene {
    let mut scene = scaling_scene(p, k, Regime::Rigid);
    for pt in &mut scene.points {
        pt.x_m *= spacing_m / 0.005;
    }
    scene.road = Road::Sine {
        amplitude_m,
        wavelength_m,
    };
    scene.duration_s = duration_s;
    scene
}

/// What a run gives: the momentum delivered to the tyre per window of
/// `window` steps (N·s, the sum of the step-mean forces times `dt`), the
/// worst step-mean force below zero against the largest (both N), the
/// worst gap below the road at a step end (m) and the events.
struct Run {
    momentum_ns: Vec<f64>,
    min_force_n: f64,
    max_force_n: f64,
    min_gap_m: f64,
    events: u64,
}

fn run(scene: &Scene, joint_impacts: bool, window: u64) -> Run {
    let model = PreparedModel::of(scene).unwrap();
    let options = SolverOptions {
        joint_impacts,
        ..SolverOptions::default()
    };
    let mut sim = Simulation::new(&model, options).unwrap();
    let dt = sim.dt_s();
    let mut out = Run {
        momentum_ns: vec![],
        min_force_n: 0.0,
        max_force_n: 0.0,
        min_gap_m: 0.0,
        events: 0,
    };
    let mut acc = 0.0;
    while !sim.finished() {
        sim.step().unwrap();
        for (i, &q) in sim.force_n().iter().enumerate() {
            acc += q * dt;
            out.min_force_n = out.min_force_n.min(q);
            out.max_force_n = out.max_force_n.max(q);
            out.min_gap_m = out.min_gap_m.min(sim.gap_m(i));
        }
        if sim.steps().is_multiple_of(window) {
            out.momentum_ns.push(acc);
            acc = 0.0;
        }
    }
    out.events = sim.stats().events;
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Over generated rigid footprints (20 to 120 points 1 to 5 mm apart,
    /// 20 to 120 modes, a rough road, the ramp), joint impacts keep every
    /// step-mean force >= -1e-9 of the largest and every gap at a step end
    /// above -1e-9 m, and deliver the momentum of the one-by-one impacts
    /// per window of 1 ms to 1 % of the largest window's.
    #[test]
    fn joint_impacts_keep_complementarity_and_agree(
        p in 20usize..=120,
        k in 20usize..=120,
        spacing_mm in 1.0f64..5.0,
        amplitude_mm in 0.1f64..0.5,
        wavelength_mm in 20.0f64..100.0,
    ) {
        let scene = footprint(p, k, spacing_mm * 1e-3, amplitude_mm * 1e-3, wavelength_mm * 1e-3, 0.006);
        let window = 100;
        let joint = run(&scene, true, window);
        let single = run(&scene, false, window);
        let tol_q = 1e-9 * joint.max_force_n.max(1.0);
        prop_assert!(joint.min_force_n >= -tol_q, "force {} of {}", joint.min_force_n, joint.max_force_n);
        prop_assert!(joint.min_gap_m >= -1e-9, "gap {}", joint.min_gap_m);
        let largest = single.momentum_ns.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let worst = joint
            .momentum_ns
            .iter()
            .zip(&single.momentum_ns)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        eprintln!(
            "P {p} K {k} spacing {spacing_mm:.2} mm: events {} / {}; momentum difference {:.2e} of {largest:.3e} N s; min force {:.1e} N; min gap {:.1e} m",
            joint.events, single.events, worst / largest, joint.min_force_n, joint.min_gap_m
        );
        prop_assert!(worst <= 1e-2 * largest, "momentum {worst} of {largest}");
    }
}

/// The rigid footprint of 120 points on 400 modes: over the first 100
/// steps of its ramp, joint impacts take fewer than a quarter of the events of
/// the one-by-one impacts (66 against 641 when written).
#[test]
fn joint_impacts_take_fewer_events_on_a_rigid_ramp() {
    let mut scene = scaling_scene(120, 400, Regime::Rigid);
    scene.duration_s = 100.0 * scene.dt_s;
    let joint = run(&scene, true, 100);
    let single = run(&scene, false, 100);
    eprintln!(
        "events: joint {}, one by one {}",
        joint.events, single.events
    );
    assert!(
        4 * joint.events < single.events,
        "joint {} one by one {}",
        joint.events,
        single.events
    );
}
