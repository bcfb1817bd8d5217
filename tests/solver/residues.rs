//! A mode written as a residue matrix means what it says: its rank terms
//! rebuild it on hard matrices, and a residue, its mode shapes and one state
//! per source give the same Green functions, forced response and contact run.

use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;
use tirecontact::SceneSimulation;
use tirecontact::base::modal::{ModalModel, unit_impulse};
use tirecontact::model::convolution::{ModalBasis, ModalState, StepTable};
use tirecontact::scene::{Mode, Tyre};
use tirecontact::{Scene, Simulation, SolverOptions};

/// `‖A − Σ_s a_s b_sᵀ‖_F / ‖A‖_F` of the basis's single mode against `a`,
/// from the stored vectors (an independent rebuild: plain sums).
fn rebuild_error(basis: &ModalBasis, a: &[Vec<f64>]) -> f64 {
    let (p, ns) = (basis.num_points, basis.stored_states());
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..p {
        for j in 0..p {
            let sum: f64 = (0..ns)
                .map(|s| basis.out[i * ns + s] * basis.inp[s * p + j])
                .sum();
            num += (a[i][j] - sum).powi(2);
            den += a[i][j].powi(2);
        }
    }
    if den > 0.0 {
        (num / den).sqrt()
    } else {
        num.sqrt()
    }
}

fn residue_mode(a: Vec<Vec<f64>>) -> Mode {
    Mode {
        freq_hz: 100.0,
        damping_ratio: 0.05,
        residue: a,
        shape: Vec::new(),
    }
}

/// Rank terms of `a` through the solver's basis: the rebuild error and the
/// number of terms.
fn split(a: &[Vec<f64>]) -> (f64, usize) {
    let basis =
        ModalBasis::new(&[residue_mode(a.to_vec())], a.len()).unwrap_or_else(|e| panic!("{e}"));
    (rebuild_error(&basis, a), basis.num_states())
}

/// A random orthogonal matrix (product of Householder reflections of
/// random vectors), rows as vectors.
fn orthogonal(n: usize, rng: &mut ChaCha8Rng) -> Vec<Vec<f64>> {
    let mut q: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    for _ in 0..n {
        let v: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        let vv: f64 = v.iter().map(|x| x * x).sum();
        if vv == 0.0 {
            continue;
        }
        // q ← q (I − 2 v vᵀ / vᵀv)
        for row in q.iter_mut() {
            let d: f64 = row.iter().zip(&v).map(|(a, b)| a * b).sum();
            for (x, vj) in row.iter_mut().zip(&v) {
                *x -= 2.0 * d / vv * vj;
            }
        }
    }
    q
}

/// `Q diag(λ) Qᵀ`.
fn with_eigenvalues(lambda: &[f64], rng: &mut ChaCha8Rng) -> Vec<Vec<f64>> {
    let n = lambda.len();
    let q = orthogonal(n, rng);
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| (0..n).map(|k| q[i][k] * lambda[k] * q[j][k]).sum())
                .collect()
        })
        .collect()
}

#[test]
fn all_equal_residues_of_every_size_rebuild_with_one_term() {
    for n in 1..=16 {
        for c in [0.1389, -2.5e-3, 7.0e4] {
            let a = vec![vec![c; n]; n];
            let (err, terms) = split(&a);
            assert!(err < 1e-13, "{n}x{n} all {c}: rebuilt to {err:e}");
            assert_eq!(terms, 1, "{n}x{n} all {c}: rank 1");
        }
    }
}

#[test]
fn repeated_and_zero_eigenvalues_rebuild_with_the_rank() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let cases: Vec<Vec<f64>> = vec![
        vec![2.0, 2.0, 2.0, 0.0, 0.0],
        vec![1.0, 1.0, 0.0],
        vec![3.0, 3.0, -1.0, -1.0, 0.0, 0.0, 0.0],
        vec![0.5; 9],
        vec![1e-3, 1e-3, 1e-3, 1e-3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        vec![4.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    ];
    for lambda in cases {
        let a = with_eigenvalues(&lambda, &mut rng);
        // exactly symmetric, as a user writes a symmetric residue
        let a: Vec<Vec<f64>> = (0..a.len())
            .map(|i| (0..a.len()).map(|j| a[i.min(j)][i.max(j)]).collect())
            .collect();
        let (err, terms) = split(&a);
        let rank = lambda.iter().filter(|l| **l != 0.0).count();
        assert!(err < 1e-12, "eigenvalues {lambda:?}: rebuilt to {err:e}");
        assert_eq!(terms, rank, "eigenvalues {lambda:?}");
    }
}

#[test]
fn ring_cos_sin_pairs_rebuild_with_two_terms() {
    // A_ij = a cos(n (θ_i − θ_j)): the ring's degenerate pair of order n
    for p in 2..=15 {
        for n in 1..=4 {
            let theta: Vec<f64> = (0..p).map(|i| 0.08 * i as f64 - 0.3).collect();
            let a: Vec<Vec<f64>> = (0..p)
                .map(|i| {
                    (0..p)
                        .map(|j| 0.02 * (n as f64 * (theta[i] - theta[j])).cos())
                        .collect()
                })
                .collect();
            let (err, terms) = split(&a);
            assert!(err < 1e-12, "P = {p}, n = {n}: rebuilt to {err:e}");
            assert!(terms <= 2, "P = {p}, n = {n}: {terms} terms");
        }
    }
}

#[test]
fn random_definite_indefinite_and_nonsymmetric_residues_rebuild() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for n in 1..=13 {
        let b: Vec<Vec<f64>> = (0..n)
            .map(|_| (0..n).map(|_| rng.random_range(-1.0..1.0)).collect())
            .collect();
        let psd: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| (0..n).map(|k| b[i][k] * b[j][k]).sum())
                    .collect()
            })
            .collect();
        let indefinite: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| b[i][j] + b[j][i]).collect())
            .collect();
        let nonsym: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| psd[i][j] + 1e-9 * b[i][j]).collect())
            .collect();
        for (what, a) in [
            ("PSD", psd),
            ("indefinite", indefinite),
            ("non-symmetric", nonsym),
        ] {
            let (err, _) = split(&a);
            assert!(err < 1e-12, "{what} {n}x{n}: rebuilt to {err:e}");
        }
    }
}

fn matrix(max_n: usize) -> impl Strategy<Value = Vec<Vec<f64>>> {
    (1..=max_n, any::<u64>(), 0u8..4, -8i32..8).prop_map(|(n, seed, kind, exp)| {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let scale = 10f64.powi(exp);
        let lambda: Vec<f64> = (0..n)
            .map(|k| match kind {
                // all equal eigenvalues, some zero
                0 => {
                    if k % 2 == 0 {
                        scale
                    } else {
                        0.0
                    }
                }
                // rank 1 with every entry equal
                1 => {
                    if k == 0 {
                        scale * n as f64
                    } else {
                        0.0
                    }
                }
                // random signs and sizes
                _ => scale * rng.random_range(-1.0..1.0),
            })
            .collect();
        if kind == 1 {
            return vec![vec![scale; n]; n];
        }
        let a = with_eigenvalues(&lambda, &mut rng);
        (0..n)
            .map(|i| (0..n).map(|j| a[i.min(j)][i.max(j)]).collect())
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn generated_residues_rebuild_to_round_off(a in matrix(16)) {
        let (err, terms) = split(&a);
        prop_assert!(err < 1e-12, "rebuilt to {:e}: {:?}", err, a);
        prop_assert!(terms <= a.len());
    }
}

/// Five points, six modes: the ring's breathing mode seen by every point
/// alike (all entries equal), two degenerate cos/sin pairs, a single mode.
/// Each mode as `(freq_hz, damping_ratio, shapes)`.
fn five_point_modes() -> Vec<(f64, f64, Vec<Vec<f64>>)> {
    let theta: Vec<f64> = (0..5).map(|i| (-0.05 + 0.025 * i as f64) / 0.31).collect();
    let pair = |n: f64, a: f64| -> Vec<Vec<f64>> {
        vec![
            theta.iter().map(|t| a * (n * t).cos()).collect(),
            theta.iter().map(|t| a * (n * t).sin()).collect(),
        ]
    };
    vec![
        (82.0, 0.05, vec![vec![0.3727; 5]]),
        (105.0, 0.05, pair(2.0, 0.35)),
        (131.0, 0.04, pair(3.0, 0.3)),
        (240.0, 0.03, vec![vec![0.2, -0.1, 0.25, -0.3, 0.15]]),
    ]
}

#[derive(Clone, Copy, Debug)]
enum Form {
    Residue,
    Shapes,
    PerSource,
}

fn modes_as(form: Form) -> Vec<Mode> {
    let mut out = Vec::new();
    for (f, xi, shapes) in five_point_modes() {
        match form {
            Form::Shapes => out.extend(shapes.iter().map(|s| Mode {
                freq_hz: f,
                damping_ratio: xi,
                residue: Vec::new(),
                shape: s.clone(),
            })),
            Form::Residue | Form::PerSource => out.push(Mode {
                freq_hz: f,
                damping_ratio: xi,
                residue: (0..5)
                    .map(|i| {
                        (0..5)
                            .map(|j| shapes.iter().map(|s| s[i] * s[j]).sum())
                            .collect()
                    })
                    .collect(),
                shape: Vec::new(),
            }),
        }
    }
    out
}

fn basis_of(form: Form) -> ModalBasis {
    let modes = modes_as(form);
    match form {
        Form::PerSource => ModalBasis::per_source(&modes, 5),
        _ => ModalBasis::new(&modes, 5).unwrap(),
    }
}

#[test]
fn residue_shapes_and_per_source_give_the_same_green_functions() {
    // the closed form Σ_k A_k[i][j] h_k(t) against the basis's states
    let truth = ModalModel::from_modes(&modes_as(Form::Residue), 5);
    for form in [Form::Residue, Form::Shapes, Form::PerSource] {
        let basis = basis_of(form);
        let ns = basis.stored_states();
        let mut worst = 0.0f64;
        for k in 0..200 {
            let t = 2.5e-5 * k as f64;
            for i in 0..5 {
                for j in 0..5 {
                    let g: f64 = (0..ns)
                        .map(|s| {
                            let (w, xi) = basis.modes[basis.mode_of_state[s]];
                            basis.out[i * ns + s] * basis.inp[s * 5 + j] * unit_impulse(w, xi, t).0
                        })
                        .sum();
                    let exact = truth.green(i, j, t).0;
                    worst = worst.max((g - exact).abs());
                }
            }
        }
        let peak = (0..5)
            .map(|i| truth.green(i, i, 1.0 / (4.0 * 82.0)).0.abs())
            .fold(0.0, f64::max);
        assert!(
            worst < 1e-13 * peak,
            "{form:?}: g differs by {worst:e} (peak {peak:e})"
        );
    }
}

/// Displacements of the five points under a known force history (N),
/// stepped by the convolution with constant forces per step.
fn forced(form: Form) -> Vec<f64> {
    let basis = basis_of(form);
    let table = StepTable::new(&basis, 2e-5);
    let (mut s, mut tmp) = (ModalState::zeros(&basis), ModalState::zeros(&basis));
    let (mut u, mut v) = (vec![0.0; 5], vec![0.0; 5]);
    let mut out = Vec::new();
    for k in 0..5000 {
        let t = 2e-5 * k as f64;
        let q: Vec<f64> = (0..5)
            .map(|i| 100.0 * (TAU * (60.0 + 37.0 * i as f64) * t).sin() + 20.0 * i as f64)
            .collect();
        s.predict_into(&table, &mut tmp);
        std::mem::swap(&mut s, &mut tmp);
        s.add_constant_forces(&basis, &table, &q);
        s.project(&basis, &mut u, &mut v);
        out.extend_from_slice(&u);
    }
    out
}

fn rel_rms(a: &[f64], b: &[f64]) -> f64 {
    let num: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    let den: f64 = b.iter().map(|y| y * y).sum();
    (num / den).sqrt()
}

#[test]
fn residue_shapes_and_per_source_give_the_same_forced_response() {
    let reference = forced(Form::Shapes);
    assert!(reference.iter().any(|u| u.abs() > 1e-6), "no motion");
    for form in [Form::Residue, Form::PerSource] {
        let e = rel_rms(&forced(form), &reference);
        assert!(e < 1e-13, "{form:?}: {e:e} relative RMS displacement");
    }
}

/// The five points rolling with a mild preload over a sine road, contact
/// on, the displacements of every step.
fn contact_run(form: Form, h_m: f64, amplitude_m: f64) -> (Vec<f64>, f64) {
    let mut scene = Scene::parse(tirecontact::DEFAULT_PRESET, "paper").unwrap();
    scene.tyre = Tyre::Modal {
        modes: modes_as(form),
    };
    for p in &mut scene.points {
        p.h_m = h_m;
    }
    scene.road = tirecontact::model::road::Road::Sine {
        amplitude_m,
        wavelength_m: 0.3,
    };
    scene.speed_mps = 10.0;
    scene.ramp_s = 0.01;
    scene.duration_s = 0.06;
    let options = SolverOptions {
        rank_reduction: !matches!(form, Form::PerSource),
        ..SolverOptions::default()
    };
    let mut sim = Simulation::from_scene_with(&scene, options).unwrap();
    let (mut u, mut contact_steps, mut steps) = (Vec::new(), 0usize, 0usize);
    while !sim.finished() {
        sim.step().unwrap();
        u.extend_from_slice(sim.displacement_m());
        contact_steps += sim.in_contact().iter().filter(|c| **c).count();
        steps += 5;
    }
    (u, contact_steps as f64 / steps as f64)
}

#[test]
fn residue_shapes_and_per_source_give_the_same_contact_run() {
    // points that stay on the road, and points that leave it and land again
    for (h_m, amplitude_m) in [(-0.002, 0.0002), (-0.0004, 0.0008)] {
        let (reference, fraction) = contact_run(Form::Shapes, h_m, amplitude_m);
        assert!(
            fraction > 0.2,
            "h {h_m}: the points barely touch ({fraction})"
        );
        for form in [Form::Residue, Form::PerSource] {
            let (u, f) = contact_run(form, h_m, amplitude_m);
            let e = rel_rms(&u, &reference);
            assert!(
                e < 1e-9,
                "{form:?}, h {h_m} m: {e:e} relative RMS displacement (contact {f} vs {fraction})"
            );
        }
    }
}

#[test]
fn a_residue_that_cannot_be_factored_is_a_typed_error_naming_the_mode() {
    let mut bad = vec![vec![0.1; 3]; 3];
    bad[1][2] = f64::NAN;
    let modes = vec![
        Mode {
            freq_hz: 50.0,
            damping_ratio: 0.05,
            residue: Vec::new(),
            shape: vec![0.1, 0.2, 0.3],
        },
        Mode {
            freq_hz: 120.0,
            ..residue_mode(bad)
        },
    ];
    let err = ModalBasis::new(&modes, 3).unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("mode 1 (120 Hz)") && text.contains("non-finite"),
        "{text}"
    );
}

/// Two points at one `x` across the tread (`y = ±0.04 m`) of a modal tyre,
/// preloaded on a sine road, rigid contact, with the residues of the second
/// mode `second` (2 × 2).
fn across_the_tread(first_shape: [f64; 2], second: [[f64; 2]; 2]) -> Scene {
    let text = format!(
        "Scene(
    name: \"across the tread\",
    tyre: Modal(modes: [
        Mode(freq_hz: 80.0, damping_ratio: 0.05, shape: {first_shape:?}),
        Mode(freq_hz: 150.0, damping_ratio: 0.05, residue: {second:?}),
    ]),
    points: [Point(x_m: 0.0, y_m: 0.04, h_m: -0.001), Point(x_m: 0.0, y_m: -0.04, h_m: -0.001)],
    road: Sine(amplitude_m: 0.0005, wavelength_m: 0.2),
    speed_mps: 10.0,
    ramp_s: 0.01,
    dt_s: 1e-5,
    duration_s: 0.06,
)"
    );
    Scene::parse(&text, "across.ron").unwrap_or_else(|e| panic!("{e}"))
}

/// Points at one `x` and different `y` see the same road and are told
/// apart by their residues: while both are on the road they sit at one
/// height, and push with the forces their residues give them. Residues that
/// do not tell them apart are a modal tyre's to give: accepted, and run as
/// far as the solver can (identical rows leave the split of the force
/// between the two points open; it may also find the system singular).
#[test]
fn points_across_the_tread_are_told_apart_by_their_residues() {
    // shapes [0.3, 0.25] and [0.2, -0.15]: rows that differ
    let scene = across_the_tread([0.3, 0.25], [[0.04, -0.03], [-0.03, 0.0225]]);
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let (mut both, mut du_max, mut q_max, mut dq_max) = (0, 0.0f64, 0.0f64, 0.0f64);
    while !sim.finished() {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
        let (u, q) = (sim.displacement_m(), sim.force_n());
        if sim.in_contact().iter().all(|c| *c) {
            both += 1;
            du_max = du_max.max((u[0] - u[1]).abs());
        }
        q_max = q_max.max(q[0].abs()).max(q[1].abs());
        dq_max = dq_max.max((q[0] - q[1]).abs());
    }
    assert!(both > 1000, "{both} steps with both points on the road");
    assert!(du_max < 1e-12, "heights differ by {du_max:e} m on one road");
    assert!(
        dq_max > 0.1 * q_max,
        "forces {dq_max:e} N apart of {q_max:e} N: the residues were not told apart"
    );
    // identical rows: valid; the two points move as one
    let same = across_the_tread([0.3, 0.3], [[0.04, 0.04], [0.04, 0.04]]);
    same.validate().unwrap();
    let mut sim = Simulation::from_scene(&same).unwrap();
    while !sim.finished() {
        match sim.step() {
            Ok(_) => {
                let u = sim.displacement_m();
                assert!((u[0] - u[1]).abs() < 1e-12, "{u:?} at t = {}", sim.time_s());
            }
            Err(tirecontact::SolverError::SingularContactSystem { .. }) => break,
            Err(e) => panic!("{e}"),
        }
    }
}
