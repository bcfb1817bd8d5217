//! criterion benchmarks (`cargo bench`): one step per (mode x source), the
//! bare loops of the same size (free prediction + projection; and the state
//! update driven by given forces at every point), the stages of a step one
//! at a time (predict, solve, locate, commit), the contact solve, the
//! ring tyre's sampled responses and their LSCE identification,
//! the shipped presets end to end. Ratios, not absolute times, are what the
//! README reports.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use tirecontact::SceneSimulation;
use tirecontact::analysis::bench::scenes::many_points;
use tirecontact::model::convolution::{ModalBasis, ModalState, StepTable};
use tirecontact::model::lsce::{Responses, identify};
use tirecontact::scene::Tyre;
use tirecontact::solver::simulation::contact::DenseSolver;
use tirecontact::{Scene, Simulation};

fn steps(c: &mut Criterion) {
    let mut scenes: Vec<(String, Scene, usize)> = [(5, 20), (50, 200)]
        .into_iter()
        .map(|(p, m)| {
            let mut scene = many_points(p, m);
            scene.duration_s = 10.0;
            (format!("{p}x{m}"), scene, 3000)
        })
        .collect();
    // the paper preset: 5 points, 13 identified modes of rank-2 residues
    // (26 states at the default rank cut); warmed up past its 0.05 s ramp
    if let Ok(mut scene) = Scene::load(std::path::Path::new("presets/paper.ron")) {
        scene.duration_s = 10.0;
        scenes.push(("paper".into(), scene, 6000));
    }
    for (name, scene, warm_up) in scenes {
        let p = scene.num_points();
        // the full step, warmed up past the ramp (contact, events)
        let model = tirecontact::PreparedModel::of(&scene).unwrap();
        let mut sim = model
            .simulation(tirecontact::SolverOptions::default())
            .unwrap();
        for _ in 0..warm_up {
            sim.step().unwrap();
        }
        c.bench_function(&format!("step/full/{name}"), |b| {
            b.iter(|| black_box(sim.step().unwrap()))
        });
        // the bound: predict + project of the same states, nothing else
        let basis = ModalBasis::with_rank_tolerance(
            model.modes(),
            p,
            tirecontact::SolverOptions::default().rank_tolerance_for(model.problem()),
        )
        .unwrap();
        let table = StepTable::new(&basis, scene.dt_s);
        let (mut s0, mut s1) = (ModalState::zeros(&basis), ModalState::zeros(&basis));
        s0.x.iter_mut()
            .enumerate()
            .for_each(|(k, x)| *x = 1e-6 * (k as f64).sin());
        let (mut u, mut v) = (vec![0.0; p], vec![0.0; p]);
        // Always from the same start state: iterating the free decay would
        // reach subnormal numbers within criterion's millions of iterations
        // (e^-6400 after 500 s simulated) and time their slow arithmetic.
        c.bench_function(&format!("step/bare_loop/{name}"), |b| {
            b.iter(|| {
                black_box(&mut s0).predict_into(&table, &mut s1);
                s1.project(&basis, &mut u, &mut v);
                black_box(u[0])
            })
        });
        // the convolution the contact step wraps: the same states driven by
        // given forces at every point (linear through the Gauss points, as
        // the full step's), `x <- Φ x + W1 B q1 + W2 B q2`, then projected;
        // no road, no contact solve, no event checks
        let every: Vec<usize> = (0..p).collect();
        let q1: Vec<f64> = (0..p).map(|j| 100.0 + j as f64).collect();
        let q2: Vec<f64> = (0..p).map(|j| 120.0 - j as f64).collect();
        c.bench_function(&format!("step/bare_update/{name}"), |b| {
            b.iter(|| {
                black_box(&mut s0).predict_into(&table, &mut s1);
                s1.add_gauss_forces(&basis, &table, &every, black_box(&q1), &q2);
                s1.project(&basis, &mut u, &mut v);
                black_box(u[0])
            })
        });
    }
}

/// The four stages of a step (method §4.3-4.4), each alone, over a full
/// step from a step start with points on the road (past the ramp): the free
/// prediction (`stage/predict`), the contact solve of the active set the
/// last step left with its factorisation reused (`stage/solve`), the release
/// and landing location in the solved trial (`stage/locate`) and the update
/// of the states by the solved forces (`stage/commit`). Predict, solve and
/// locate rewrite only scratch values, so every iteration does the same
/// work from the same state. Commit has no such repeatable form: iterated
/// alone it adds the same forces again and again into the two alternating
/// state buffers (values growing linearly, never subnormal); it runs on a
/// simulation of its own.
fn stages(c: &mut Criterion) {
    let mut scenes: Vec<(String, Scene)> = [(5, 20), (50, 200)]
        .into_iter()
        .map(|(p, m)| (format!("{p}x{m}"), many_points(p, m)))
        .collect();
    if let Ok(scene) = Scene::load(std::path::Path::new("presets/paper.ron")) {
        scenes.push(("paper".into(), scene));
    }
    let mut g = c.benchmark_group("stage");
    for (name, mut scene) in scenes {
        scene.duration_s = 10.0;
        let model = tirecontact::PreparedModel::of(&scene).unwrap();
        let options = tirecontact::SolverOptions::default();
        // past the ramp, to a step start with points on the road
        let at_contact = || {
            let mut sim = model.simulation(options).unwrap();
            let ramp_steps = (scene.ramp_s / scene.dt_s).ceil() as usize;
            for _ in 0..ramp_steps + 1000 {
                sim.step().unwrap();
            }
            while sim.stages().active().is_empty() && !sim.finished() {
                sim.step().unwrap();
            }
            sim
        };
        let mut sim = at_contact();
        let mut st = sim.stages();
        g.bench_function(format!("predict/{name}"), |b| {
            b.iter(|| st.predict().unwrap())
        });
        st.predict().unwrap();
        g.bench_function(format!("solve/{name}"), |b| b.iter(|| st.solve().unwrap()));
        st.solve().unwrap();
        g.bench_function(format!("locate/{name}"), |b| {
            b.iter(|| black_box(st.locate()))
        });
        let mut other = at_contact();
        let mut st = other.stages();
        st.predict().unwrap();
        st.solve().unwrap();
        g.bench_function(format!("commit/{name}"), |b| b.iter(|| st.commit()));
    }
    g.finish();
}

fn contact_solve(c: &mut Criterion) {
    use faer::linalg::solvers::Solve;
    // the 2|S| Gauss-point system of |S| active points, badly scaled rows as
    // at dt = 1e-5; the hand-written scaled LU against faer's partial-pivot
    // LU of the same matrix (both factor and solve every iteration)
    for n in [10usize, 40, 100] {
        let a: Vec<f64> = (0..n * n)
            .map(|k| {
                let (r, col) = (k / n, k % n);
                let scale = if r < n / 2 { 1e-5 } else { 1.0 };
                scale
                    * (if r == col {
                        4.0
                    } else {
                        1.0 / (1.0 + (r as f64 - col as f64).abs())
                    })
            })
            .collect();
        let mut solver = DenseSolver::new(n);
        let mut rhs = vec![1.0; n];
        c.bench_function(&format!("contact/factor_and_solve/{n}x{n}"), |b| {
            b.iter(|| {
                solver.factor(n, |r, col| a[r * n + col]).unwrap();
                rhs.fill(1.0);
                solver.solve(&mut rhs);
                black_box(rhs[0])
            })
        });
        let ones = faer::Mat::<f64>::from_fn(n, 1, |_, _| 1.0);
        c.bench_function(&format!("contact/faer_lu_factor_and_solve/{n}x{n}"), |b| {
            b.iter(|| {
                let m = faer::Mat::from_fn(n, n, |r, col| a[r * n + col]);
                let x = m.partial_piv_lu().solve(&ones);
                black_box(x[(0, 0)])
            })
        });
    }
}

fn presets(c: &mut Criterion) {
    // 2-3 ms per iteration: 30 samples steady the mean on a noisy machine
    let mut g = c.benchmark_group("preset");
    g.sample_size(30);
    for name in ["single_mode", "three_points", "paper"] {
        let path = format!("presets/{name}.ron");
        let Ok(mut scene) = Scene::load(std::path::Path::new(&path)) else {
            continue;
        };
        scene.duration_s = 0.1;
        g.bench_function(format!("{name}/0.1s"), |b| {
            b.iter(|| {
                let mut sim = Simulation::from_scene(&scene).unwrap();
                while !sim.finished() {
                    sim.step().unwrap();
                }
                black_box(sim.time_s())
            })
        });
    }
    g.finish();
}

/// The paper preset's tyre (method §5-6): sampling the ring's impulse
/// responses at the five points, and their LSCE identification (done once
/// per scene at load, cached per ring, options and positions).
fn ring_and_lsce(c: &mut Criterion) {
    let Ok(scene) = Scene::load(std::path::Path::new("presets/paper.ron")) else {
        return;
    };
    let Tyre::Ring {
        ring,
        identification: opts,
    } = &scene.tyre
    else {
        return;
    };
    let x_m: Vec<f64> = scene.points.iter().map(|pt| pt.x_m).collect();
    let mut g = c.benchmark_group("tyre");
    g.sample_size(10);
    g.bench_function("ring/sampled_responses/paper", |b| {
        b.iter(|| black_box(ring.sampled_responses(&x_m, opts.dt_s(), opts.num_samples())))
    });
    let (pairs, data) = ring.sampled_responses(&x_m, opts.dt_s(), opts.num_samples());
    let responses = Responses {
        dt_s: opts.dt_s(),
        num_points: x_m.len(),
        pairs,
        data,
    };
    g.bench_function("lsce/identify/paper", |b| {
        b.iter(|| black_box(identify(&responses, opts).map(|id| id.modes.len())))
    });
    g.finish();
}

criterion_group!(
    benches,
    steps,
    stages,
    contact_solve,
    presets,
    ring_and_lsce
);
criterion_main!(benches);
