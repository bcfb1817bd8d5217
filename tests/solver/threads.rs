//! The kernels' threads (`SolverOptions::threads`): a run on 2 or 3
//! threads must give every output of every step bit for bit as on one,
//! through contact, landings, releases, large active sets (their updated
//! inverse and GMRES sub-steps) and both contact laws. With
//! `parallel_from_madds: 1` every kernel call is split, the smallest
//! included (ranges of uneven and empty lengths); with the default, the
//! split kernels are those of a large scene.

use tirecontact::analysis::bench::scaling::{Regime, patch_scene, scaling_scene};
use tirecontact::model::road::Road;
use tirecontact::solver::simulation::RunStats;
use tirecontact::{PreparedModel, Scene, Simulation, SolverOptions};

/// Runs `scene` for `steps` steps on 1 thread and on each of `counts`,
/// comparing displacement, velocity, force, impact impulses and contact
/// after every step and the statistics at the end; returns the
/// one-thread run's statistics.
fn compare(scene: &Scene, steps: u64, counts: &[usize], parallel_from_madds: usize) -> RunStats {
    let model = PreparedModel::of(scene).unwrap();
    let options = |threads| SolverOptions {
        threads,
        parallel_from_madds,
        ..SolverOptions::default()
    };
    let mut one = model.simulation(options(1)).unwrap();
    let mut many: Vec<Simulation> = counts
        .iter()
        .map(|&n| model.simulation(options(n)).unwrap())
        .collect();
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    for step in 0..steps {
        let r1 = one.step().unwrap();
        for (sim, &n) in many.iter_mut().zip(counts) {
            let r = sim.step().unwrap();
            let at = format!("{}, {n} threads, step {step}", scene.name);
            assert_eq!(r, r1, "{at}: step report");
            assert_eq!(
                bits(sim.displacement_m()),
                bits(one.displacement_m()),
                "{at}: u"
            );
            assert_eq!(
                bits(sim.velocity_mps()),
                bits(one.velocity_mps()),
                "{at}: v"
            );
            assert_eq!(bits(sim.force_n()), bits(one.force_n()), "{at}: force");
            assert_eq!(
                bits(sim.impact_impulse_ns()),
                bits(one.impact_impulse_ns()),
                "{at}: impulses"
            );
            assert_eq!(sim.in_contact(), one.in_contact(), "{at}: contact");
        }
    }
    assert_eq!(one.threads(), 1);
    assert_eq!(one.threaded_kernel_calls(), 0);
    for (sim, &n) in many.iter().zip(counts) {
        assert_eq!(sim.stats(), one.stats(), "{}, {n} threads", scene.name);
        assert_eq!(sim.threads(), n);
        // the threads did run: set-up tables and per-step kernels
        assert!(
            sim.threaded_kernel_calls() > steps,
            "{}, {n} threads: {} threaded calls",
            scene.name,
            sim.threaded_kernel_calls()
        );
    }
    one.stats().clone()
}

/// `scene` on a rough road (points land and leave inside steps), the
/// ramp shortened to `ramp_s`.
fn rough(mut scene: Scene, ramp_s: f64) -> Scene {
    scene.road = Road::Sine {
        amplitude_m: 5e-4,
        wavelength_m: 0.03,
    };
    scene.ramp_s = ramp_s;
    scene
}

#[test]
fn a_patch_on_tread_springs_is_bit_identical_on_2_and_3_threads() {
    // 200 points (10 across), 100 modes; large sets from 24 points on the road
    let scene = rough(patch_scene(20, 10, 100, Regime::Tread), 1e-3);
    let st = compare(&scene, 400, &[2, 3], 1);
    // every path ran: landings and releases, bordered updates, GMRES
    assert!(st.events > 0 && st.contact_updates > 0, "{st:?}");
    assert!(
        st.krylov_applications > 0 && st.factorisations > 0,
        "{st:?}"
    );
}

#[test]
fn rigid_contact_is_bit_identical_on_2_and_3_threads() {
    let scene = rough(scaling_scene(120, 60, Regime::Rigid), 1e-3);
    let st = compare(&scene, 400, &[2, 3], 1);
    assert!(st.events > 0 && st.steady_steps > 0, "{st:?}");
}

#[test]
fn a_large_scene_with_the_default_split_is_bit_identical_on_2_threads() {
    // P K = 60 000: the projection, the forces and the updated inverse's
    // products are split at the default threshold
    let scene = scaling_scene(300, 200, Regime::Tread);
    let st = compare(&scene, 300, &[2], tirecontact::base::threads::PARALLEL_FROM);
    assert!(st.contact_steps.iter().any(|&c| c > 0), "{st:?}");
}
