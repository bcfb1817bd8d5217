//! The residue rank cut (`SolverOptions::rank_tolerance`): what it drops,
//! and what that costs, against the exact-rank factorisation as control.

use tirecontact::SceneSimulation;
use tirecontact::model::convolution::{EXACT_RANK_TOLERANCE, ModalBasis};
use tirecontact::scene::Mode;
use tirecontact::{IDENTIFIED_RANK_TOLERANCE, Scene, Simulation, SolverOptions};

/// `Σ_r σ_r e_r e_rᵀ` with orthonormal `e_r` built from a rotation (3 points).
fn residue(sigmas: [f64; 3]) -> Vec<Vec<f64>> {
    let (c, s) = (0.6f64, 0.8f64);
    let e = [
        [c, s, 0.0],
        [-s * 0.6, c * 0.6, 0.8],
        [s * 0.8, -c * 0.8, 0.6],
    ];
    (0..3)
        .map(|i| {
            (0..3)
                .map(|j| (0..3).map(|r| sigmas[r] * e[r][i] * e[r][j]).sum())
                .collect()
        })
        .collect()
}

fn mode(sigmas: [f64; 3]) -> Mode {
    Mode {
        freq_hz: 80.0,
        damping_ratio: 0.05,
        residue: residue(sigmas),
        shape: Vec::new(),
    }
}

#[test]
fn terms_below_the_cut_are_dropped_and_the_rest_kept() {
    // a genuine third term at 1e-3 stays; noise at 1e-7 goes
    let kept =
        ModalBasis::with_rank_tolerance(&[mode([2.0, 1.0, 2e-3])], 3, IDENTIFIED_RANK_TOLERANCE)
            .unwrap();
    assert_eq!(kept.num_states(), 3);
    let cut =
        ModalBasis::with_rank_tolerance(&[mode([2.0, 1.0, 2e-7])], 3, IDENTIFIED_RANK_TOLERANCE)
            .unwrap();
    assert_eq!(cut.num_states(), 2);
    let exact = ModalBasis::new(&[mode([2.0, 1.0, 2e-7])], 3).unwrap();
    assert_eq!(exact.num_states(), 3);
    // the truncated residue (its velocity jump Σ A) differs from the exact
    // one by the dropped singular value at most (2-norm <= Frobenius)
    let (a, b) = (cut.velocity_jump(), exact.velocity_jump());
    let diff: f64 = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!(
        diff <= 2e-7 * (1.0 + 1e-9) && diff > 1e-7,
        "dropped part {diff:e}"
    );
    // a tolerance below round-off is clamped to the exact cut
    let clamped = ModalBasis::with_rank_tolerance(&[mode([2.0, 1.0, 2e-7])], 3, 0.0).unwrap();
    assert_eq!(clamped.num_states(), 3);
}

#[test]
fn paper_preset_keeps_the_ring_pairs_and_its_results() {
    let mut scene = Scene::load(std::path::Path::new("presets/paper.ron")).unwrap();
    scene.duration_s = 0.12;
    let exact_opts = SolverOptions {
        rank_tolerance: Some(EXACT_RANK_TOLERANCE),
        ..SolverOptions::default()
    };
    let mut cut = Simulation::from_scene(&scene).unwrap();
    let mut exact = Simulation::from_scene_with(&scene, exact_opts).unwrap();
    // the ring's modes come in cos/sin pairs: rank 2 each (13 modes)
    let modes = tirecontact::ModeCache::new().modes(&scene).unwrap().len();
    assert_eq!(cut.num_states(), 2 * modes);
    assert!(exact.num_states() > cut.num_states());
    let (mut du, mut umax, mut dq, mut qmax) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    while !cut.finished() {
        cut.step().unwrap();
        exact.step().unwrap();
        for i in 0..scene.num_points() {
            let (a, b) = (cut.displacement_m()[i], exact.displacement_m()[i]);
            du = du.max((a - b).abs());
            umax = umax.max(b.abs());
            // forces without the impact impulses (impulse / dt would
            // amplify a sub-step shift of a landing)
            let qa = cut.force_n()[i] - cut.impact_impulse_ns()[i] / scene.dt_s;
            let qb = exact.force_n()[i] - exact.impact_impulse_ns()[i] / scene.dt_s;
            dq = dq.max((qa - qb).abs());
            qmax = qmax.max(qb.abs());
        }
    }
    // the dropped terms are <= 2.4e-6 of each residue: displacements move
    // by 7e-7 of their peak, contact forces by 4e-5 (a landing located a
    // little earlier or later), far below the identification's own 1.9e-2
    assert!(
        du < 1e-5 * umax,
        "displacement moved {:e} of its peak",
        du / umax
    );
    assert!(dq < 1e-4 * qmax, "force moved {:e} of its peak", dq / qmax);
}

#[test]
fn modes_given_in_a_scene_keep_every_term_by_default() {
    // a residue with a genuine small third term (1e-7 of the first), below
    // the identified models' cut: a scene's own modes are taken as given
    let modes = vec![mode([2.0, 1.0, 2e-7])];
    let mut scene = tirecontact::analysis::bench::scenes::many_points(3, 1);
    scene.tyre = tirecontact::scene::Tyre::Modal { modes };
    let exact = Simulation::from_scene(&scene).unwrap();
    assert_eq!(exact.num_states(), 3);
    // an explicit cut applies to any model
    let cut_opts = SolverOptions {
        rank_tolerance: Some(IDENTIFIED_RANK_TOLERANCE),
        ..SolverOptions::default()
    };
    let cut = Simulation::from_scene_with(&scene, cut_opts).unwrap();
    assert_eq!(cut.num_states(), 2);
    // and the automatic choice per model kind
    let auto = SolverOptions::default();
    assert_eq!(
        auto.rank_tolerance_of(scene.modes_identified()),
        EXACT_RANK_TOLERANCE
    );
    let paper = Scene::load(std::path::Path::new("presets/paper.ron")).unwrap();
    assert_eq!(
        auto.rank_tolerance_of(paper.modes_identified()),
        IDENTIFIED_RANK_TOLERANCE
    );
    // and the problem built from each scene carries its kind to the solver
    let problem = |s: &Scene| tirecontact::PreparedModel::of(s).unwrap().problem().clone();
    assert_eq!(
        auto.rank_tolerance_for(&problem(&scene)),
        EXACT_RANK_TOLERANCE
    );
    assert_eq!(
        auto.rank_tolerance_for(&problem(&paper)),
        IDENTIFIED_RANK_TOLERANCE
    );
}
