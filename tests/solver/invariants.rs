//! Invariants of the numerical core (method §1-4) that the other reference
//! checks (contact.rs, stress.rs, the #[cfg(test)] modules) do not test:
//!
//! - the reported step-mean forces (impacts included) are the impulses the
//!   modal equations of motion need, on three coupled points (rigid contact,
//!   both schemes, and compliant contact): checked
//!   against each mode's momentum balance, computed here from `u`, `v` alone;
//! - two points on decoupled modes behave as two separate one-point runs;
//! - the paper scheme's complementarity bounds (method §4 step 4): at most
//!   `2P` solves, no pulling force, force only at points in contact, the
//!   reported worst penetration equal to the one measured from the outputs;
//! - `T_ramp = 0` accepted exactly where no point starts below the road,
//!   refused otherwise naming `ramp_s`, for sine, harmonic and measured roads.

use crate::support::temp_dir;
use tirecontact::SceneSimulation;
// Numerical loops index several arrays in parallel; ranges read clearer here.
use crate::dense::solve;
use crate::support::models::{SplitMix, modal_scene, shape_mode};

use std::f64::consts::TAU;

use tirecontact::Simulation;
use tirecontact::model::road::{Harmonic, Road};
use tirecontact::scene::SceneError;
use tirecontact::scene::{Contact, ContactScheme, Mode, Point, Scene};

fn sine(amplitude_m: f64, wavelength_m: f64) -> Road {
    Road::Sine {
        amplitude_m,
        wavelength_m,
    }
}

/// Per step end (index 0 = t = 0, at rest): `u`, `v`, and per step the
/// step-mean force; total located events.
struct History {
    u: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
    q: Vec<Vec<f64>>,
    events: u64,
}

fn history(sc: &Scene) -> History {
    let mut sim = Simulation::from_scene(sc).expect("valid scene");
    let p = sc.points.len();
    let mut h = History {
        u: vec![vec![0.0; p]],
        v: vec![vec![0.0; p]],
        q: Vec::new(),
        events: 0,
    };
    while !sim.finished() {
        sim.step().expect("step");
        h.u.push(sim.displacement_m().to_vec());
        h.v.push(sim.velocity_mps().to_vec());
        h.q.push(sim.force_n().to_vec());
    }
    h.events = sim.stats().events;
    h
}

/// Each mode `k` with shape `φ_k` has a modal coordinate `η_k`
/// (`u = Σ_k φ_k η_k`) obeying `η'' + 2ξω η' + ω² η = φ_k · q`. Integrated
/// over a window `[t_a, t_b]`:
///
/// ```text
/// φ_k · ∫ q dt = [η_k'] + 2ξω [η_k] + ω² ∫ η_k dt
/// ```
///
/// The left side is the solver's reported forces times `dt` (impacts
/// included, method §4 step 5); the right side comes from the reported `u`,
/// `v` only (`η = Φ⁻¹ u`, the integral by the trapezoid rule with its
/// end correction `-dt²/12 [η']`). Returns the largest window mismatch
/// relative to the largest window impulse, and the latter.
fn momentum_mismatch(sc: &Scene, modes: &[Mode], window_steps: usize) -> (f64, f64, u64) {
    let h = history(sc);
    let p = sc.points.len();
    assert_eq!(modes.len(), p, "one mode per point: Φ must be square");
    let dt = sc.dt_s;
    let phi: Vec<Vec<f64>> = (0..p)
        .map(|i| modes.iter().map(|m| m.shape[i]).collect())
        .collect();
    let eta = |u: &[f64]| solve(phi.clone(), u.to_vec()).expect("non-singular");
    let eta_u: Vec<Vec<f64>> = h.u.iter().map(|u| eta(u)).collect();
    let eta_v: Vec<Vec<f64>> = h.v.iter().map(|v| eta(v)).collect();
    let n = h.q.len();
    let (mut worst, mut largest) = (0.0f64, 0.0f64);
    for w in 0..n / window_steps {
        let (a, b) = (w * window_steps, (w + 1) * window_steps);
        for (k, m) in modes.iter().enumerate() {
            let omega = TAU * m.freq_hz;
            let lhs: f64 = (a..b)
                .map(|s| (0..p).map(|i| m.shape[i] * h.q[s][i]).sum::<f64>() * dt)
                .sum();
            let trap: f64 = (a..b)
                .map(|s| 0.5 * dt * (eta_u[s][k] + eta_u[s + 1][k]))
                .sum::<f64>()
                - dt * dt / 12.0 * (eta_v[b][k] - eta_v[a][k]);
            let rhs = eta_v[b][k] - eta_v[a][k]
                + 2.0 * m.damping_ratio * omega * (eta_u[b][k] - eta_u[a][k])
                + omega * omega * trap;
            worst = worst.max((lhs - rhs).abs());
            largest = largest.max(lhs.abs());
        }
    }
    (worst / largest, largest, h.events)
}

fn three_point_case(scheme: ContactScheme) -> (Scene, Vec<Mode>) {
    // the shipped three-point preset's modes and geometry: impacts throw
    // neighbours off the road
    let modes = vec![
        shape_mode(80.0, 0.05, &[0.25, 0.3, 0.25]),
        shape_mode(150.0, 0.04, &[0.3, 0.0, -0.3]),
        shape_mode(300.0, 0.03, &[0.2, -0.3, 0.2]),
    ];
    let points = [-0.05, 0.0, 0.05]
        .iter()
        .map(|&x_m| Point {
            x_m,
            y_m: 0.0,
            h_m: -0.0015,
        })
        .collect();
    let sc = modal_scene(
        modes.clone(),
        points,
        sine(0.0005, 0.12),
        12.0,
        0.03,
        1e-5,
        0.15,
        scheme,
    );
    (sc, modes)
}

#[test]
fn reported_forces_balance_each_modes_momentum() {
    for scheme in [ContactScheme::Located, ContactScheme::Paper] {
        let (sc, modes) = three_point_case(scheme);
        let (rel, largest, events) = momentum_mismatch(&sc, &modes, 100);
        println!(
            "{scheme:?}: largest 1 ms modal impulse {largest:.3e} N s, worst mismatch {rel:.2e} of it, {events} located events"
        );
        if scheme == ContactScheme::Located {
            assert!(events > 20, "the case must have impacts: {events} events");
        }
        // the trapezoid rule's error at the kinks of u (velocity jumps of
        // impacts) is (ω dt)² of a jump at most: 4e-4 at 300 Hz, 1e-5 s.
        // Measured: Located 1.4e-5, 3.2e-6, 7.5e-7 at dt = 1e-5, 5e-6,
        // 2.5e-6 (the dt² of that quadrature); Paper 2e-9 (no kinks)
        assert!(
            rel < 2e-4,
            "{scheme:?}: forces and motion disagree by {rel:.2e} of the largest window impulse"
        );
    }
    // compliant contact (tread springs): forces linear in each step, no impacts
    let (mut sc, modes) = three_point_case(ContactScheme::Located);
    sc.contact = Contact::Compliant {
        stiffness_n_m: vec![3e6],
    };
    let (rel, largest, _) = momentum_mismatch(&sc, &modes, 100);
    println!(
        "Compliant: largest 1 ms modal impulse {largest:.3e} N s, worst mismatch {rel:.2e} of it"
    );
    assert!(rel < 2e-4, "compliant: mismatch {rel:.2e}");
}

#[test]
fn decoupled_points_run_as_separate_one_point_runs() {
    // two points, each on its own mode (A_k zero off the diagonal): nothing
    // couples them, so each must move as it would alone
    let road = sine(0.002, 0.5);
    let pts = [
        Point {
            x_m: 0.0,
            y_m: 0.0,
            h_m: -0.001,
        },
        Point {
            x_m: 0.13,
            y_m: 0.0,
            h_m: -0.0008,
        },
    ];
    let (m0, m1) = (
        (100.0, 0.05, 0.3f64), // freq, damping, shape value at its point
        (170.0, 0.03, 0.25f64),
    );
    for (scheme, tol) in [
        // the same arithmetic up to the order of sums: round-off
        (ContactScheme::Paper, 1e-9),
        // the other point's events split the step: a different (exact for
        // its force shape) discretisation of the same motion, O(dt^3) apart
        (ContactScheme::Located, 1e-5),
    ] {
        let both = modal_scene(
            vec![
                shape_mode(m0.0, m0.1, &[m0.2, 0.0]),
                shape_mode(m1.0, m1.1, &[0.0, m1.2]),
            ],
            pts.to_vec(),
            road.clone(),
            20.0,
            0.05,
            1e-5,
            0.3,
            scheme,
        );
        let hb = history(&both);
        for (i, m) in [m0, m1].iter().enumerate() {
            let alone = modal_scene(
                vec![shape_mode(m.0, m.1, &[m.2])],
                vec![Point {
                    x_m: 0.0,
                    y_m: 0.0,
                    h_m: pts[i].h_m,
                }], // the same road under the point: shifted by its position
                Road::Harmonics {
                    components: vec![Harmonic {
                        amplitude_m: 0.002,
                        wavelength_m: 0.5,
                        phase_rad: TAU * pts[i].x_m / 0.5,
                    }],
                },
                20.0,
                0.05,
                1e-5,
                0.3,
                scheme,
            );
            let ha = history(&alone);
            let umax = ha.u.iter().map(|u| u[0].abs()).fold(0.0, f64::max);
            let du = (0..ha.u.len())
                .map(|s| (ha.u[s][0] - hb.u[s][i]).abs())
                .fold(0.0, f64::max);
            // impulses over 1 ms windows (single-step forces at impacts are
            // step-placement dependent)
            let win = 100;
            let (mut dq, mut qmax) = (0.0f64, 0.0f64);
            for w in 0..ha.q.len() / win {
                let sa: f64 = (w * win..(w + 1) * win).map(|s| ha.q[s][0]).sum();
                let sb: f64 = (w * win..(w + 1) * win).map(|s| hb.q[s][i]).sum();
                dq = dq.max((sa - sb).abs());
                qmax = qmax.max(sa.abs());
            }
            println!(
                "{scheme:?} point {i}: max |u| {umax:.3e} m, max |Δu| {:.2e} relative, max window impulse difference {:.2e} relative ({} events alone)",
                du / umax,
                dq / qmax,
                ha.events
            );
            assert!(umax > 1e-4, "the point must move");
            assert!(
                du <= tol * umax && dq <= 10.0 * tol * qmax,
                "{scheme:?} point {i}: coupled run differs from the run alone by {:.2e} (u) and {:.2e} (impulse) relative",
                du / umax,
                dq / qmax
            );
        }
    }
}

#[test]
fn paper_scheme_keeps_its_complementarity_bounds() {
    let (mut sc, _) = three_point_case(ContactScheme::Paper);
    sc.duration_s = 0.3;
    let p = sc.points.len();
    let mut sim = Simulation::from_scene(&sc).unwrap();
    let mut worst_pen = 0.0f64;
    let mut contact_steps = 0u64;
    let mut releases_to_flight = 0u64;
    let mut prev_contact = vec![false; p];
    while !sim.finished() {
        let rep = sim.step().unwrap();
        assert!(
            rep.solves as usize <= 2 * p,
            "t = {} s: {} solves (at most 2P = {})",
            rep.t_s,
            rep.solves,
            2 * p
        );
        assert_eq!(rep.events, 0, "the paper scheme locates no events");
        let (q, c) = (sim.force_n(), sim.in_contact());
        let mut pen = 0.0f64;
        for i in 0..p {
            assert!(
                q[i] >= 0.0,
                "t = {} s: point {i} pulls: {} N",
                rep.t_s,
                q[i]
            );
            assert!(
                c[i] || q[i] == 0.0,
                "t = {} s: point {i} off the road with force {} N",
                rep.t_s,
                q[i]
            );
            pen = pen.max(sim.road_m()[i] - sim.displacement_m()[i]);
            contact_steps += c[i] as u64;
            releases_to_flight += (prev_contact[i] && !c[i]) as u64;
        }
        assert_eq!(rep.penetration_m, pen.max(0.0), "t = {} s", rep.t_s);
        worst_pen = worst_pen.max(pen);
        prev_contact.copy_from_slice(c);
    }
    let st = sim.stats();
    assert!(st.max_solves_per_step as usize <= 2 * p);
    assert_eq!(st.worst_penetration_m, worst_pen);
    assert!(
        contact_steps > 0 && releases_to_flight > 3,
        "a case with contact and releases"
    );
    println!(
        "paper scheme: max {} solves per step (2P = {}), worst penetration {:.2e} m, {releases_to_flight} releases",
        st.max_solves_per_step,
        2 * p,
        worst_pen
    );
}

fn field_errors(sc: &Scene) -> Vec<String> {
    match sc.validate() {
        Ok(()) => Vec::new(),
        Err(e) => e.iter().map(|e| e.field.clone()).collect(),
    }
}

#[test]
fn zero_ramp_only_without_initial_penetration() {
    let (a, lambda) = (0.002, 0.5);
    let one = |x_m: f64, h_m: f64, road: Road| {
        modal_scene(
            vec![shape_mode(100.0, 0.05, &[0.3])],
            vec![Point { x_m, y_m: 0.0, h_m }],
            road,
            20.0,
            0.0,
            1e-5,
            0.05,
            ContactScheme::Located,
        )
    };
    // z(λ/4) = a: touching the crest (z - h = 0) is allowed, any lower is not
    let crest = lambda / 4.0;
    assert!(field_errors(&one(crest, a, sine(a, lambda))).is_empty());
    assert_eq!(
        field_errors(&one(crest, a - 1e-7, sine(a, lambda))),
        ["ramp_s"]
    );
    // z(3λ/4) = -a: a point at h = -a touches the trough; preload (h < z) is refused
    let trough = 3.0 * lambda / 4.0;
    assert!(field_errors(&one(trough, -a, sine(a, lambda))).is_empty());
    assert_eq!(
        field_errors(&one(trough, -a - 1e-7, sine(a, lambda))),
        ["ramp_s"]
    );
    // with a phase: the harmonic's height at the point, not at x = 0
    let shifted = Road::Harmonics {
        components: vec![Harmonic {
            amplitude_m: a,
            wavelength_m: lambda,
            phase_rad: TAU / 4.0, // z(0) = a
        }],
    };
    assert_eq!(
        field_errors(&one(0.0, a - 1e-7, shifted.clone())),
        ["ramp_s"]
    );
    assert!(field_errors(&one(0.0, a, shifted)).is_empty());

    // an allowed zero ramp runs from rest with a gap >= 0 and forces >= 0
    // (at the trough the road rises into the point at once)
    let sc = one(trough, -a, sine(a, lambda));
    let mut sim = Simulation::from_scene(&sc).unwrap();
    assert!(sim.gap_m(0) >= 0.0);
    let mut landed = false;
    while !sim.finished() {
        sim.step().unwrap();
        landed |= sim.in_contact()[0];
        assert!(sim.force_n()[0] >= -1e-9 * sim.stats().max_force_n[0].max(1.0));
    }
    assert!(landed, "the road rises into the point: it must land");

    // a measured road is checked when the simulation reads it
    let tmp = temp_dir();
    let dir = tmp.path();
    std::fs::write(dir.join("bump.csv"), "x_m,z_m\n-1,0\n0,0.001\n1,0\n").unwrap();
    let measured = Road::Measured {
        file: "bump.csv".into(),
        looped: false,
    };
    let mut sc = one(0.0, 0.0005, measured);
    sc.speed_mps = 1.0;
    sc.base_dir = Some(dir.to_path_buf());
    match Simulation::from_scene(&sc) {
        Err(SceneError::Invalid { errors, .. }) => {
            assert_eq!(errors.len(), 1, "{errors:?}");
            assert_eq!(errors[0].field, "ramp_s");
            assert!(errors[0].expected.contains("point 0"), "{errors:?}");
        }
        Err(e) => panic!("expected a ramp_s error, got {e}"),
        Ok(_) => panic!("a zero ramp with the point 0.5 mm below a measured road was accepted"),
    }
    sc.points[0].h_m = 0.001;
    assert!(
        Simulation::from_scene(&sc).is_ok(),
        "touching the measured road is allowed"
    );
}

/// The landing time of method §4's impact location, by brute force: the cubic
/// Hermite interpolant of the gap sampled on a fine grid; the first sample
/// below `-tol` (after one above `+tol` when `require_rise`, unless the
/// start is), and the zero crossing before it by bisection between the last
/// non-negative sample and the next one. `None` when no sample goes below.
fn brute_crossing(g0: f64, d0: f64, g1: f64, d1: f64, tol: f64, rise: bool) -> Option<f64> {
    let g0 = g0.max(0.0);
    let p = |y: f64| {
        let (h00, h10) = ((1.0 + 2.0 * y) * (1.0 - y).powi(2), y * (1.0 - y).powi(2));
        let (h01, h11) = (y * y * (3.0 - 2.0 * y), y * y * (y - 1.0));
        g0 * h00 + d0 * h10 + g1 * h01 + d1 * h11
    };
    // uniform, plus logarithmic near the start (a rise and fall within
    // 1e-5 of the interval is a real landing)
    let n = 20_000;
    let mut grid: Vec<f64> = (1..=n).map(|k| k as f64 / n as f64).collect();
    grid.extend((0..=180).map(|k| 10f64.powf(-13.0 + k as f64 / 20.0)));
    grid.sort_by(f64::total_cmp);
    let mut risen = !rise || g0 > tol;
    let mut last_nonneg = 0.0;
    for y in grid {
        let v = p(y);
        if risen && v < -tol {
            let (mut lo, mut hi) = (last_nonneg, y);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if p(mid) >= 0.0 { lo = mid } else { hi = mid }
            }
            return Some(0.5 * (lo + hi));
        }
        risen |= v > tol;
        if v >= 0.0 {
            last_nonneg = y;
        }
    }
    None
}

#[test]
fn hermite_landing_time_matches_brute_force() {
    let mut rng = SplitMix(4);
    let (mut found, mut none) = (0, 0);
    for case in 0..8_000 {
        let mut r = |a: f64, b: f64| a + (b - a) * rng.unit();
        // starts on, above, or (round-off) just below the road
        let g0 = match case % 4 {
            0 => 0.0,
            1 => -1e-13,
            _ => r(0.0, 1.0),
        };
        let (d0, g1, d1) = (r(-4.0, 4.0), r(-1.0, 1.0), r(-4.0, 4.0));
        let tol = if case % 3 == 0 { 1e-3 } else { 1e-12 };
        let rise = case % 5 == 0;
        let got = tirecontact::solver::simulation::first_crossing(g0, d0, g1, d1, tol, rise);
        let want = brute_crossing(g0, d0, g1, d1, tol, rise);
        match (got, want) {
            (Some(y), Some(w)) => {
                found += 1;
                assert!(
                    (y - w).abs() < 1e-10,
                    "case {case}: g0 {g0} d0 {d0} g1 {g1} d1 {d1} tol {tol} rise {rise}: landing at {y}, brute force {w}"
                );
            }
            (None, None) => none += 1,
            // a dip below -tol narrower than the grid (1/20000) can be
            // missed by the brute force only by a hair: check the depth
            (Some(y), None) => {
                let h = |y: f64| {
                    let g0 = g0.max(0.0);
                    g0 * (1.0 + 2.0 * y) * (1.0 - y).powi(2)
                        + d0 * y * (1.0 - y).powi(2)
                        + g1 * y * y * (3.0 - 2.0 * y)
                        + d1 * y * y * (y - 1.0)
                };
                let depth = (0..=2000)
                    .map(|k| h(y + (1.0 - y) * k as f64 / 2000.0))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    depth > -tol - 1e-6,
                    "case {case}: landing at {y} found, brute force none, depth {depth}"
                );
            }
            (None, Some(w)) => panic!(
                "case {case}: g0 {g0} d0 {d0} g1 {g1} d1 {d1} tol {tol} rise {rise}: no landing found, brute force lands at {w}"
            ),
        }
    }
    println!("landing times: {found} found, {none} without landing");
    assert!(found > 2000 && none > 800, "{found} / {none}");
}

/// Five points on five coupled modes spanning every damping regime: `xi`
/// for three of them, critical (ξ = 1) and overdamped (ξ = 3) for the others.
fn five_point_modes(xi: f64) -> Vec<Mode> {
    let p = 5;
    (0..5)
        .map(|k| {
            let shape: Vec<f64> = (0..p)
                .map(|i| {
                    0.3 * ((k as f64 + 0.5) * std::f64::consts::PI * (i as f64 + 0.5) / p as f64)
                        .cos()
                })
                .collect();
            let damping = match k {
                2 => 1.0,
                4 => 3.0,
                _ => xi,
            };
            shape_mode(60.0 * (1.0 + k as f64).powf(1.3), damping, &shape)
        })
        .collect()
}

fn five_point_scene(xi: f64, h_m: &[f64], amp_m: f64, dt_s: f64, duration_s: f64) -> Scene {
    modal_scene(
        five_point_modes(xi),
        h_m.iter()
            .enumerate()
            .map(|(i, &h_m)| Point {
                x_m: 0.03 * i as f64,
                y_m: 0.0,
                h_m,
            })
            .collect(),
        sine(amp_m, 0.1),
        25.0,
        0.02,
        dt_s,
        duration_s,
        ContactScheme::Located,
    )
}

/// `u` of all points every `grid_s`.
fn sampled(sc: &Scene, grid_s: f64) -> Vec<Vec<f64>> {
    let every = (grid_s / sc.dt_s).round() as u64;
    assert!((every as f64 * sc.dt_s - grid_s).abs() < 1e-9 * grid_s);
    let mut sim = Simulation::from_scene(sc).unwrap();
    let mut out = Vec::new();
    while !sim.finished() {
        sim.step().unwrap();
        if sim.steps().is_multiple_of(every) {
            out.push(sim.displacement_m().to_vec());
        }
    }
    out
}

#[test]
fn every_damping_regime_on_five_points_converges_at_second_order() {
    // impacts throw neighbours off (hundreds of located events) while modes
    // at ξ = 0 or 0.05, 1 and 3 carry the motion
    let h = [-0.001, -0.0013, -0.001, -0.0013, -0.001];
    for xi in [0.0, 0.05] {
        let reference = sampled(&five_point_scene(xi, &h, 0.002, 1.25e-6, 0.2), 2e-4);
        let errors: Vec<f64> = [2e-5, 1e-5, 5e-6]
            .iter()
            .map(|&dt| {
                let r = sampled(&five_point_scene(xi, &h, 0.002, dt, 0.2), 2e-4);
                let (mut num, mut den) = (0.0, 0.0);
                for (a, b) in r.iter().zip(&reference) {
                    for (x, y) in a.iter().zip(b) {
                        num += (x - y).powi(2);
                        den += y * y;
                    }
                }
                (num / den).sqrt()
            })
            .collect();
        println!(
            "xi {xi}: relative RMS error against dt = 1.25e-6 at dt = 2e-5, 1e-5, 5e-6: {errors:?}"
        );
        assert!(errors[1] < 3e-5, "xi {xi}: {errors:?}");
        for w in errors.windows(2) {
            // order > 1.5 per halving (measured 2.4 to 3.1)
            assert!(w[0] / w[1] > 2.8, "xi {xi}: not second order: {errors:?}");
        }
    }
}

#[test]
fn static_preload_with_critical_and_overdamped_modes() {
    // flat road, preloads designed for compressive forces at every point:
    // the settled forces are C⁻¹ (-h), C = Σ_k A_k / ω_k², whatever the damping
    let modes = five_point_modes(0.2);
    let p = 5;
    let mut c = vec![vec![0.0; p]; p];
    for m in &modes {
        let w2 = (TAU * m.freq_hz).powi(2);
        for i in 0..p {
            for j in 0..p {
                c[i][j] += m.shape[i] * m.shape[j] / w2;
            }
        }
    }
    let design = [900.0, 1200.0, 1000.0, 1300.0, 800.0];
    let h: Vec<f64> = (0..p)
        .map(|i| -(0..p).map(|j| c[i][j] * design[j]).sum::<f64>())
        .collect();
    let expected = solve(c, h.iter().map(|x| -x).collect()).expect("non-singular");
    for scheme in [ContactScheme::Located, ContactScheme::Paper] {
        let mut sc = five_point_scene(0.2, &h, 0.0, 2e-5, 0.4);
        sc.contact_scheme = scheme;
        let mut sim = Simulation::from_scene(&sc).unwrap();
        while !sim.finished() {
            sim.step().unwrap();
        }
        let q = sim.force_n();
        let rel = (0..p)
            .map(|i| (q[i] - expected[i]).abs() / expected[i])
            .fold(0.0, f64::max);
        println!("{scheme:?}: forces {q:.6?} N, expected {expected:.6?} N, max rel err {rel:.1e}");
        assert!(sim.in_contact().iter().all(|&c| c), "{scheme:?}");
        assert!(rel < 1e-7, "{scheme:?}: {q:?} vs {expected:?}");
        for i in 0..p {
            assert!(
                (sim.displacement_m()[i] + h[i]).abs() < 1e-12,
                "{scheme:?} point {i}"
            );
        }
    }
}

#[test]
fn crossing_exists_exactly_where_it_is_located() {
    let mut rng = SplitMix(11);
    let mut found = 0;
    for case in 0..20_000 {
        let mut r = |a: f64, b: f64| a + (b - a) * rng.unit();
        let g0 = match case % 3 {
            0 => 0.0,
            _ => r(-1e-12, 1.0),
        };
        let (d0, g1, d1) = (r(-4.0, 4.0), r(-1.0, 1.0), r(-4.0, 4.0));
        let tol = if case % 2 == 0 { 1e-3 } else { 1e-12 };
        let rise = case % 5 == 0;
        use tirecontact::solver::simulation::{crosses, first_crossing};
        let located = first_crossing(g0, d0, g1, d1, tol, rise);
        assert_eq!(
            crosses(g0, d0, g1, d1, tol, rise),
            located.is_some(),
            "case {case}: g0 {g0} d0 {d0} g1 {g1} d1 {d1} tol {tol} rise {rise}"
        );
        found += located.is_some() as usize;
    }
    assert!(found > 2_000, "only {found} crossings among the cases");
}

/// Grazing and flat crossings (a triple root, a double root beside a
/// simple one, a tiny slope through the root) are located as the brute
/// force locates them, to what the cubic's values can resolve there.
#[test]
fn flat_crossings_are_located_as_by_bisection() {
    let mut rng = SplitMix(29);
    for case in 0..3_000 {
        let mut r = |a: f64, b: f64| a + (b - a) * rng.unit();
        let root = r(0.02, 0.98);
        let scale = 10f64.powf(r(-9.0, 0.0));
        let eps = match case % 3 {
            0 => 0.0,
            1 => scale * 10f64.powf(r(-12.0, -2.0)),
            _ => scale * r(0.0, 1.0),
        };
        // p(y) = -scale (y - root)^3 - eps (y - root), decreasing through the root
        let p = |y: f64| -scale * (y - root).powi(3) - eps * (y - root);
        let dp = |y: f64| -3.0 * scale * (y - root).powi(2) - eps;
        let (g0, d0, g1, d1) = (p(0.0), dp(0.0), p(1.0), dp(1.0));
        let tol = 1e-3 * p(1.0).abs().min(p(0.0));
        let got = tirecontact::solver::simulation::first_crossing(g0, d0, g1, d1, tol, false);
        let want = brute_crossing(g0, d0, g1, d1, tol, false);
        let (Some(y), Some(w)) = (got, want) else {
            panic!("case {case}: root {root}: located {got:?}, brute force {want:?}");
        };
        // the cubic's rounding (about 1e-16 of its terms) hides the sign of
        // p within |p| <= 4e-16 (g0 + |d0| + |g1| + |d1|) of its root
        let noise = 4e-16 * (g0.abs() + d0.abs() + g1.abs() + d1.abs());
        let resolved = ((noise + eps * 1e-3) / scale)
            .cbrt()
            .min(noise / eps.max(1e-300));
        assert!(
            (y - w).abs() <= 2.0 * resolved + 1e-12,
            "case {case}: root {root} scale {scale:e} eps {eps:e}: located {y}, brute force {w}, resolvable {resolved:e}"
        );
    }
}
