//! method §7 (the paper's application as shipped in
//! `presets/paper.ron`): what the LSCE identification (method §5-6: "usually
//! with fewer modes than the source") changes in the contact results,
//! measured against the same run on the ring's own modal model (all orders
//! 0..=N, every branch; its Green functions are checked against closed
//! forms in `ring_green.rs`).
//!
//! Measured (dt 1e-5 s, 0.1 s, relative RMS after the ramp): against the
//! ring's 13 modes below 500 Hz, 5.8e-5 in displacement and 3.3e-4 in
//! force; against all 81 modes (to 24 kHz), 2.9e-2 and 2.3: with rigid
//! contact the impact forces depend on every mode kept (the velocity jump
//! per unit impulse `Σ A_k` grows with the number of orders), so the
//! preset's forces are those of its 0-500 Hz model, not of the ring.

use crate::support::rel_rms;
use tirecontact::SceneSimulation;
use tirecontact::base::modal::ModalModel;
use tirecontact::scene::Tyre;
use tirecontact::{DEFAULT_PRESET, DEFAULT_PRESET_NAME, Scene, Simulation};

fn history(sc: &Scene) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let mut sim = Simulation::from_scene(sc).expect("valid scene");
    let (mut u, mut q) = (Vec::new(), Vec::new());
    for _ in 0..sc.num_steps() {
        sim.step().expect("step");
        u.push(sim.displacement_m().to_vec());
        q.push(sim.force_n().to_vec());
    }
    (u, q)
}

#[test]
fn identified_preset_against_the_rings_own_modes() {
    let mut scene = Scene::from_ron_str(DEFAULT_PRESET, DEFAULT_PRESET_NAME).unwrap();
    scene.duration_s = 0.1;
    let Tyre::Ring { ring, .. } = scene.tyre.clone() else {
        panic!("method §7: the ring tyre");
    };
    let xs: Vec<f64> = scene.points.iter().map(|p| p.x_m).collect();
    let identified = tirecontact::ModeCache::new().modes(&scene).unwrap();
    let own = ring.modes(&xs);
    let p = xs.len();
    let c_id = ModalModel::from_modes(&identified, p).static_compliance();
    let c_own = ModalModel::from_modes(&own, p).static_compliance();
    println!(
        "modes: identified {}, ring's own {} (max {:.0} Hz); static compliance (0,0): identified {:.4e} m/N, ring {:.4e} m/N",
        identified.len(),
        own.len(),
        own.iter().map(|m| m.freq_hz).fold(0.0, f64::max),
        c_id[0],
        c_own[0]
    );
    let (u_id, q_id) = history(&scene);
    let from = (scene.ramp_s / scene.dt_s) as usize;
    for band in [500.0, 1000.0, 2000.0, 1e9] {
        let mut truth = scene.clone();
        let kept: Vec<_> = own.iter().filter(|m| m.freq_hz < band).cloned().collect();
        let n = kept.len();
        truth.tyre = Tyre::Modal { modes: kept };
        let (u_own, q_own) = history(&truth);
        let (eu, eq) = (
            rel_rms(&u_id[from..], &u_own[from..]),
            rel_rms(&q_id[from..], &q_own[from..]),
        );
        println!(
            "ring modes below {band} Hz ({n}): after the ramp, relative RMS difference of the identified run: displacement {eu:.3e}, force {eq:.3e}"
        );
        if band == 500.0 {
            // the identification band of the preset: LSCE reproduces the
            // ring's in-band modes (measured 5.8e-5 and 3.3e-4)
            assert_eq!(n, identified.len());
            assert!(
                eu < 5e-4 && eq < 3e-3,
                "in-band: displacement {eu:e}, force {eq:e}"
            );
        } else {
            // the modes above the band change the rigid-contact forces at
            // O(1) (g'(0+) = Σ A_k grows with every order): the preset's
            // results are those of its band-limited model (method §5-6)
            assert!(eq > 0.1, "modes above 500 Hz: force difference {eq:e}");
        }
    }
}

/// Displacement every `grid` steps and the mean force over windows of
/// `window` steps (impulse / window), of `sc` at its own `dt_s`.
fn sampled(sc: &Scene, every: usize, window: usize) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let mut sim = Simulation::from_scene(sc).expect("valid scene");
    let p = sc.points.len();
    let (mut u, mut q) = (Vec::new(), Vec::new());
    let mut acc = vec![0.0; p];
    for k in 1..=sc.num_steps() as usize {
        sim.step().expect("step");
        for (a, f) in acc.iter_mut().zip(sim.force_n()) {
            *a += f;
        }
        if k % every == 0 {
            u.push(sim.displacement_m().to_vec());
        }
        if k % window == 0 {
            q.push(acc.iter().map(|a| a / window as f64).collect());
            acc.fill(0.0);
        }
    }
    (u, q)
}

/// method §4's measured figures on "five points of a ring tyre with frequent
/// impacts": the paper's rule 3e-3 in displacement and 20 % in the force
/// averaged over 10 ms; located events ~5e-7 in displacement at dt = 1e-5
/// and force within 1e-4, converging at order ~2. Checked here on the
/// shipped preset (84 located events in 0.1 s, impacts up to 0.31 N·s)
/// against the located scheme at dt/16. Measured: located 2.0e-10
/// (displacement) and 1.2e-9 (1 ms force) at dt = 1e-5, 3.7e-11 and 1.9e-10
/// at 5e-6 (order 2.5); paper's rule 1.9e-4 and 1.1e-3 (10 ms force).
#[test]
fn preset_errors_against_a_fine_reference_match_spec_figures() {
    use tirecontact::scene::ContactScheme;
    let mut base = Scene::from_ron_str(DEFAULT_PRESET, DEFAULT_PRESET_NAME).unwrap();
    base.duration_s = 0.1;
    // the identified modes once, as a modal scene (same model for every run)
    base.tyre = Tyre::Modal {
        modes: tirecontact::ModeCache::new().modes(&base).unwrap().to_vec(),
    };
    let dt0 = 1e-5;
    let grid_s = 1e-4;
    let run = |dt: f64, scheme: ContactScheme, window_s: f64| {
        let mut s = base.clone();
        s.dt_s = dt;
        s.contact_scheme = scheme;
        let every = (grid_s / dt).round() as usize;
        let window = (window_s / dt).round() as usize;
        sampled(&s, every, window)
    };
    let from_u = (base.ramp_s / grid_s) as usize;
    let reference_1ms = run(dt0 / 16.0, ContactScheme::Located, 1e-3);
    let reference_10ms = run(dt0 / 16.0, ContactScheme::Located, 1e-2);
    let mut errs = Vec::new();
    for m in [1.0, 2.0, 4.0] {
        let (u, q) = run(dt0 / m, ContactScheme::Located, 1e-3);
        let eu = rel_rms(&u[from_u..], &reference_1ms.0[from_u..]);
        let from_q = (base.ramp_s / 1e-3) as usize;
        let eq = rel_rms(&q[from_q..], &reference_1ms.1[from_q..]);
        println!(
            "Located dt {:.2e}: displacement {eu:.2e}, force (1 ms) {eq:.2e}",
            dt0 / m
        );
        errs.push((eu, eq));
    }
    let (u, q) = run(dt0, ContactScheme::Paper, 1e-2);
    let pu = rel_rms(&u[from_u..], &reference_10ms.0[from_u..]);
    let from_q = (base.ramp_s / 1e-2) as usize;
    let pq = rel_rms(&q[from_q..], &reference_10ms.1[from_q..]);
    println!("Paper dt 1e-5: displacement {pu:.2e}, force (10 ms) {pq:.2e}");
    let order = (errs[0].0 / errs[1].0).log2();
    println!("Located displacement order between 1e-5 and 5e-6: {order:.2}");
    // the method's figures as upper bounds for the located scheme at dt = 1e-5
    assert!(errs[0].0 < 5e-7, "located displacement {:e}", errs[0].0);
    assert!(errs[0].1 < 1e-4, "located force {:e}", errs[0].1);
    assert!(order > 1.5, "located order {order}");
    // the paper's rule: first order, far behind (measured 1.9e-4 / 1.1e-3,
    // below the method's 3e-3 / 20 % for its harsher five-point case)
    assert!(
        pu > 100.0 * errs[0].0 && pu < 3e-3,
        "paper displacement {pu:e}"
    );
    assert!(pq < 0.2, "paper force {pq:e}");
}
