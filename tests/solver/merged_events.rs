//! Events of tread springs in one full-step solve (method §4.6, "Events
//! in one solve") against the sub-steps they replace, on a shortened
//! chip-seal patch: stones under single points, landings and releases in
//! most steps.

use crate::support::Gap;
use tirecontact::scene::{PointGrid, Points, Preload, Scene, Tyre};
use tirecontact::{PreparedModel, SolverOptions};

/// The chip-seal preset on a grid of 8 × 3 points, its plate's modes up
/// to 900 Hz, from `t = 0` with a ramp of 5 ms, to `duration_s`.
fn small_chip_seal(duration_s: f64) -> Scene {
    let mut scene = Scene::load(std::path::Path::new("presets/patch_chip_seal.ron")).unwrap();
    scene.points = Points::from_grid(PointGrid {
        along: 8,
        across: 3,
        spacing_m: (0.008, 0.02),
        preload: Preload::Parabolic {
            depth_m: 0.001,
            length_m: 0.07,
        },
    });
    if let Tyre::Plate { plate } = &mut scene.tyre {
        plate.max_freq_hz = 900.0;
    }
    scene.ramp_s = 0.005;
    scene.duration_s = duration_s;
    scene
}

fn merged(on: bool) -> SolverOptions {
    SolverOptions {
        merged_events: on,
        ..SolverOptions::default()
    }
}

/// Merged events with direct solves of every set size (no kept inverse,
/// no GMRES sub-steps).
fn direct_solves() -> SolverOptions {
    SolverOptions {
        large_set_from: usize::MAX,
        compliant_large_set_from: usize::MAX,
        iterative_sub_from: usize::MAX,
        ..merged(true)
    }
}

/// Displacements of every point at the times `0, every·dt, …` (m), and
/// the run's statistics.
fn run(
    scene: &Scene,
    dt_s: f64,
    every: u64,
    options: SolverOptions,
) -> (Vec<Vec<f64>>, tirecontact::solver::simulation::RunStats) {
    let mut scene = scene.clone();
    scene.dt_s = dt_s;
    let model = PreparedModel::of(&scene).unwrap();
    let mut sim = model.simulation(options).unwrap();
    let mut out = Vec::new();
    let mut n = 0u64;
    while !sim.finished() {
        sim.step().unwrap();
        n += 1;
        if n.is_multiple_of(every) {
            out.push(sim.displacement_m().to_vec());
        }
    }
    (out, sim.stats().clone())
}

/// Largest difference of two histories over the largest value (m/m).
fn rel_diff(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let mut gap = Gap::default();
    for (x, y) in a.iter().zip(b) {
        gap.add(x, y);
    }
    gap.relative()
}

/// The merged step differs from the sub-steps by `O(dt²)`: halving `dt`
/// divides their difference by about four, and each is as close to a
/// reference (the sub-steps at a quarter of the finest step) as the other
/// to within a factor of two. Most event steps are merged.
#[test]
fn merged_events_converge_to_the_sub_steps_as_dt_squared() {
    let scene = small_chip_seal(0.012);
    let dts = [4e-5, 2e-5, 1e-5];
    let finest = dts[2] / 4.0;
    let (reference, _) = run(&scene, finest, 16, merged(false));
    let mut diffs = Vec::new();
    for (n, &dt) in dts.iter().enumerate() {
        // (every run sampled at the coarsest step's times)
        let every = 1 << n;
        let (a, sa) = run(&scene, dt, every, merged(true));
        let (b, sb) = run(&scene, dt, every, merged(false));
        let d = rel_diff(&a, &b);
        let (ea, eb) = (rel_diff(&a, &reference), rel_diff(&b, &reference));
        eprintln!(
            "dt = {dt:e} s: merged vs sub-steps {d:.3e}; error merged {ea:.3e}, sub-steps {eb:.3e}; \
             events {} / {}, merged steps {} of {}",
            sa.events, sb.events, sa.merged_steps, sa.steps
        );
        assert!(sa.merged_steps > 0 && sb.merged_steps == 0, "{sa:?} {sb:?}");
        assert!(ea < 2.0 * eb + 1e-9, "dt = {dt}: {ea:e} vs {eb:e}");
        diffs.push(d);
    }
    for pair in diffs.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!(order > 1.7, "order {order:.2}: {diffs:?}");
    }
}

/// The bordered solve through the trial's factorisation and a fresh
/// factorisation of the merged system agree to round-off, step by step;
/// the step-mean forces never pull.
#[test]
fn bordered_merged_solves_agree_with_fresh_factorisations() {
    let scene = small_chip_seal(0.02);
    let model = PreparedModel::of(&scene).unwrap();
    // (direct solves of every set size in both: the large sets' kept
    // inverse is a reuse too)
    let direct = direct_solves();
    let mut a = model.simulation(direct).unwrap();
    let fresh = SolverOptions {
        reuse_factorisation: false,
        ..direct
    };
    let mut b = model.simulation(fresh).unwrap();
    let (mut u, mut lowest, mut q_max) = (Gap::default(), 0.0f64, 0.0f64);
    while !a.finished() {
        a.step().unwrap();
        b.step().unwrap();
        u.add(a.displacement_m(), b.displacement_m());
        for &q in a.force_n() {
            (lowest, q_max) = (lowest.min(q), q_max.max(q));
        }
    }
    let st = a.stats();
    eprintln!(
        "u differs by {:.2e} of {:.2e} m; {} merged steps, {} events; forces {lowest:.2e} to {q_max:.2e} N",
        u.diff, u.max, st.merged_steps, st.events
    );
    assert!(st.merged_steps > 200, "{st:?}");
    assert!(u.relative() <= 1e-9, "{u:?}");
    assert!(lowest >= -1e-9 * q_max, "{lowest} N");
}

/// A large set's merged step, bordered through the kept inverse of its
/// trial (`large_set_from` lowered so that every set of the patch takes the
/// large-set methods), agrees with the direct solves step by step.
#[test]
fn merged_steps_through_the_kept_inverse_agree_with_direct_solves() {
    let scene = small_chip_seal(0.02);
    let model = PreparedModel::of(&scene).unwrap();
    let direct = direct_solves();
    let kept = SolverOptions {
        large_set_from: 2,
        ..merged(true)
    };
    let mut a = model.simulation(kept).unwrap();
    let mut b = model.simulation(direct).unwrap();
    let mut u = Gap::default();
    while !a.finished() {
        a.step().unwrap();
        b.step().unwrap();
        u.add(a.displacement_m(), b.displacement_m());
    }
    let (sa, sb) = (a.stats(), b.stats());
    eprintln!(
        "u differs by {:.2e} of {:.2e} m; merged steps {} and {}, events {} and {}",
        u.diff, u.max, sa.merged_steps, sb.merged_steps, sa.events, sb.events
    );
    assert!(sa.merged_steps > 200, "{sa:?}");
    assert!(
        sa.merged_steps.abs_diff(sb.merged_steps) <= sb.merged_steps / 50,
        "{sa:?} {sb:?}"
    );
    assert!(u.relative() <= 1e-9, "{u:?}");
}
