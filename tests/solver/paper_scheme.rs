//! method §1 and §4: sign conventions, road sampling and
//! ramp as the solver sees them, the output force as a step mean, and the
//! paper's plain scheme (method §4 steps 1-5) against an implementation of
//! those steps written here from docs/method.md alone (own closed-form modal
//! recursion per (mode, source), own dense solve), compared to round-off.

use crate::dense::solve_equilibrated;
use crate::oscillator::{gauss_weights, propagator};
use crate::support::models::{modal_scene, points, shape_mode, sine};
use std::f64::consts::TAU;
use tirecontact::SceneSimulation;
use tirecontact::Simulation;
use tirecontact::scene::{ContactScheme, Mode};

/// method §4, written out: `r_i(t) = w(t) (a sin(2π (x_i + V t)/λ) - h_i)`,
/// `w = 3s² - 2s³`, and `dr_i/dt`, `d²r_i/dt²`.
#[derive(Clone, Copy)]
struct SpecRoad {
    a: f64,
    lambda: f64,
    v: f64,
    ramp: f64,
}

impl SpecRoad {
    fn r(&self, x: f64, h: f64, t: f64) -> (f64, f64, f64) {
        let (w, wd, wdd) = if self.ramp == 0.0 || t >= self.ramp {
            (1.0, 0.0, 0.0)
        } else if t <= 0.0 {
            (0.0, 0.0, 0.0)
        } else {
            let s = t / self.ramp;
            (
                3.0 * s * s - 2.0 * s * s * s,
                (6.0 * s - 6.0 * s * s) / self.ramp,
                (6.0 - 12.0 * s) / (self.ramp * self.ramp),
            )
        };
        let k = TAU / self.lambda;
        let ph = k * (x + self.v * t);
        let z = self.a * ph.sin() - h;
        let zd = self.a * k * self.v * ph.cos();
        let zdd = -self.a * (k * self.v).powi(2) * ph.sin();
        (w * z, wd * z + w * zd, wdd * z + 2.0 * wd * zd + w * zdd)
    }
}

/// method §1 and §4 conventions on two decoupled, stiff, preloaded points that
/// never leave the road: displacement positive up and equal to the road of
/// method §4 (the tyre moves with `x_i + V t`, the road height enters as
/// `+z`, the preload as `-h`, ramped by `3s² - 2s³`), the force positive up,
/// and the reported force the step mean of the force that the modal equation
/// `u'' + 2ξωu' + ω²u = A q` needs to follow the road
/// (`A ∫q = [u' + 2ξωu] + ω² ∫ r`, `∫ r` by 8-point Gauss-Legendre).
#[test]
fn conventions_road_ramp_and_step_mean_force_on_the_road() {
    let (f, xi, amp): (f64, f64, [f64; 2]) = (400.0, 0.05, [1.0, 0.8]);
    let omega = TAU * f;
    let modes = vec![
        shape_mode(f, xi, &[amp[0].sqrt(), 0.0]),
        shape_mode(f, xi, &[0.0, amp[1].sqrt()]),
    ];
    let road = SpecRoad {
        a: 0.5e-3,
        lambda: 0.3,
        v: 10.0,
        ramp: 0.02,
    };
    let pts = [(0.0, -2.0e-3), (0.075, -1.5e-3)]; // a quarter wavelength apart
    let dt = 2e-5;
    let sc = modal_scene(
        modes,
        points(&pts),
        sine(road.a, road.lambda),
        road.v,
        road.ramp,
        dt,
        0.06,
        ContactScheme::Located,
    );
    let mut sim = Simulation::from_scene(&sc).expect("valid scene");
    // 8-point Gauss-Legendre on [0, 1]
    let gl: [(f64, f64); 8] = {
        let x = [
            0.183_434_642_495_649_8,
            0.525_532_409_916_329_0,
            0.796_666_477_413_626_7,
            0.960_289_856_497_536_3,
        ];
        let w = [
            0.362_683_783_378_362_0,
            0.313_706_645_877_887_3,
            0.222_381_034_453_374_5,
            0.101_228_536_290_376_3,
        ];
        let mut g = [(0.0, 0.0); 8];
        for k in 0..4 {
            g[2 * k] = (0.5 - 0.5 * x[k], 0.5 * w[k]);
            g[2 * k + 1] = (0.5 + 0.5 * x[k], 0.5 * w[k]);
        }
        g
    };
    let (mut worst_u, mut worst_v, mut worst_q) = (0.0f64, 0.0f64, 0.0f64);
    let mut qmax = 0.0f64;
    let n = sc.num_steps() as usize;
    for step in 0..n {
        let t0 = step as f64 * dt;
        sim.step().expect("step");
        let t1 = sim.time_s();
        for (i, &(x, h)) in pts.iter().enumerate() {
            let (r1, rd1, _) = road.r(x, h, t1);
            let (r0, rd0, _) = road.r(x, h, t0);
            let u = sim.displacement_m()[i];
            let v = sim.velocity_mps()[i];
            let q = sim.force_n()[i];
            assert!(sim.in_contact()[i], "point {i} left the road at {t1} s");
            worst_u = worst_u.max((u - r1).abs());
            worst_v = worst_v.max((v - rd1).abs());
            // signs: the preload lifts the point (u > 0), the road pushes up (q > 0)
            assert!(u > 0.0 && q > 0.0, "t {t1}: u {u} m, q {q} N");
            let int_r: f64 = gl
                .iter()
                .map(|&(s, w)| w * road.r(x, h, t0 + s * dt).0)
                .sum::<f64>()
                * dt;
            let impulse = ((rd1 + 2.0 * xi * omega * r1) - (rd0 + 2.0 * xi * omega * r0)
                + omega * omega * int_r)
                / amp[i];
            let q_ref = impulse / dt;
            worst_q = worst_q.max((q - q_ref).abs());
            qmax = qmax.max(q_ref.abs());
        }
    }
    println!(
        "on the road: max |u - r| {worst_u:.2e} m, max |v - r'| {worst_v:.2e} m/s, max |q - q_ref| {worst_q:.2e} N of {qmax:.1} N"
    );
    assert!(worst_u < 1e-15, "u vs the road r(t): {worst_u:e} m");
    assert!(worst_v < 1e-12, "v vs the road rate: {worst_v:e} m/s");
    assert!(
        worst_q < 1e-9 * qmax,
        "step-mean force: {worst_q:e} N of {qmax} N"
    );
}

/// A point held above the road (`h > a`) never touches it: no force, no motion.
#[test]
fn point_above_the_road_stays_free() {
    let sc = modal_scene(
        vec![shape_mode(100.0, 0.05, &[1.0])],
        points(&[(0.0, 2.0e-3)]),
        sine(1.0e-3, 0.2),
        10.0,
        0.0,
        1e-4,
        0.05,
        ContactScheme::Located,
    );
    let mut sim = Simulation::from_scene(&sc).expect("T_ramp = 0 allowed: no point below the road");
    for _ in 0..sc.num_steps() {
        sim.step().expect("step");
        assert_eq!(sim.displacement_m()[0], 0.0);
        assert_eq!(sim.force_n()[0], 0.0);
        assert!(!sim.in_contact()[0]);
        assert!(sim.gap_m(0) > 0.0);
    }
}

/// One mode of the replica: `(ω, ξ, A)` with `A` row-major P×P.
struct RMode {
    omega: f64,
    xi: f64,
    a: Vec<f64>,
}

/// The paper's plain scheme, method §4 steps 1-5, from the method's text:
/// per (mode, source) state `(x, v)` advanced exactly (closed-form `Φ` and
/// Gauss-point weights of the linear force), candidates from the free
/// prediction, the coupled `2|S|` system, monotone release of the most
/// negative step-mean force (never re-added in the step), a free point
/// pushed below the road by a neighbour added, at most `2P` solves, output
/// the step mean `(q1 + q2)/2`.
struct PaperReplica {
    p: usize,
    modes: Vec<RMode>,
    phi: Vec<[f64; 4]>,
    wg: Vec<[[f64; 2]; 2]>,
    /// state[k][j] = (x, v) of mode k driven by the force at j
    state: Vec<Vec<[f64; 2]>>,
    pts: Vec<(f64, f64)>,
    road: SpecRoad,
    dt: f64,
    pen_tol: f64,
    t: f64,
}

impl PaperReplica {
    fn uv(&self, state: &[Vec<[f64; 2]>]) -> (Vec<f64>, Vec<f64>) {
        let p = self.p;
        let (mut u, mut v) = (vec![0.0; p], vec![0.0; p]);
        for (k, m) in self.modes.iter().enumerate() {
            for i in 0..p {
                for j in 0..p {
                    u[i] += m.a[i * p + j] * state[k][j][0];
                    v[i] += m.a[i * p + j] * state[k][j][1];
                }
            }
        }
        (u, v)
    }

    /// End displacement/velocity influence of `q_m` at `j` on point `i`.
    fn g(&self, i: usize, j: usize, m: usize, comp: usize) -> f64 {
        let p = self.p;
        self.modes
            .iter()
            .enumerate()
            .map(|(k, md)| md.a[i * p + j] * self.wg[k][m][comp])
            .sum()
    }

    /// One step; returns (u, q_mean, contact).
    fn step(&mut self) -> (Vec<f64>, Vec<f64>, Vec<bool>) {
        let p = self.p;
        let t1 = self.t + self.dt;
        // 1. free prediction
        for (k, st) in self.state.iter_mut().enumerate() {
            let f = self.phi[k];
            for s in st.iter_mut() {
                *s = [f[0] * s[0] + f[1] * s[1], f[2] * s[0] + f[3] * s[1]];
            }
        }
        let (uh, vh) = self.uv(&self.state);
        let (mut r, mut rd) = (vec![0.0; p], vec![0.0; p]);
        for i in 0..p {
            let (a, b, _) = self.road.r(self.pts[i].0, self.pts[i].1, t1);
            (r[i], rd[i]) = (a, b);
        }
        // 2. candidates
        let mut released = vec![false; p];
        let mut active: Vec<usize> = (0..p).filter(|&i| uh[i] - r[i] < 0.0).collect();
        let (mut q1, mut q2) = (vec![0.0; p], vec![0.0; p]);
        let mut solves = 0;
        let end = |active: &[usize], q1: &[f64], q2: &[f64]| -> Vec<f64> {
            (0..p)
                .map(|i| {
                    uh[i]
                        + active
                            .iter()
                            .map(|&j| self.g(i, j, 0, 0) * q1[j] + self.g(i, j, 1, 0) * q2[j])
                            .sum::<f64>()
                })
                .collect()
        };
        loop {
            // 3. the coupled 2|S| system
            let n = active.len();
            q1.fill(0.0);
            q2.fill(0.0);
            if n > 0 {
                let mut a = vec![vec![0.0; 2 * n]; 2 * n];
                let mut b = vec![0.0; 2 * n];
                for (ri, &i) in active.iter().enumerate() {
                    for (cj, &j) in active.iter().enumerate() {
                        a[ri][cj] = self.g(i, j, 0, 0);
                        a[ri][n + cj] = self.g(i, j, 1, 0);
                        a[n + ri][cj] = self.g(i, j, 0, 1);
                        a[n + ri][n + cj] = self.g(i, j, 1, 1);
                    }
                    b[ri] = r[i] - uh[i];
                    b[n + ri] = rd[i] - vh[i];
                }
                let x = solve_equilibrated(a, b).expect("non-singular contact system");
                for (c, &j) in active.iter().enumerate() {
                    q1[j] = x[c];
                    q2[j] = x[n + c];
                }
                solves += 1;
            }
            if solves >= 2 * p {
                break;
            }
            // 4. complementarity: release the most negative step-mean force
            let worst = active
                .iter()
                .enumerate()
                .map(|(c, &j)| (c, q1[j] + q2[j]))
                .filter(|&(_, s)| s < 0.0)
                .min_by(|x, y| x.1.total_cmp(&y.1));
            if let Some((c, _)) = worst {
                released[active.remove(c)] = true;
                continue;
            }
            // a neighbour's force pushed a free point below the road
            let ue = end(&active, &q1, &q2);
            let deepest = (0..p)
                .filter(|&i| !released[i] && !active.contains(&i))
                .map(|i| (i, ue[i] - r[i]))
                .filter(|&(_, g)| g < -self.pen_tol)
                .min_by(|x, y| x.1.total_cmp(&y.1));
            match deepest {
                Some((i, _)) => active.push(i),
                None => break,
            }
        }
        // at the solve bound a still pulling point is let go
        active.retain(|&j| {
            let keep = q1[j] + q2[j] >= 0.0;
            if !keep {
                (q1[j], q2[j]) = (0.0, 0.0);
            }
            keep
        });
        // 5. update the states with the solved forces
        for (k, st) in self.state.iter_mut().enumerate() {
            let w = self.wg[k];
            for &j in &active {
                st[j][0] += w[0][0] * q1[j] + w[1][0] * q2[j];
                st[j][1] += w[0][1] * q1[j] + w[1][1] * q2[j];
            }
        }
        self.t = t1;
        let (u, _) = self.uv(&self.state);
        let q = (0..p).map(|j| 0.5 * (q1[j] + q2[j])).collect();
        let contact = (0..p).map(|j| active.contains(&j)).collect();
        (u, q, contact)
    }
}

/// The crate's `Paper` scheme against the replica of method §4 steps 1-5, on
/// two points coupled by three modes (two mode shapes and a full residue
/// matrix) rolling over a sine road with take-offs and landings.
#[test]
fn paper_scheme_matches_a_replica_of_spec_steps_one_to_five() {
    paper_replica_case(
        vec![
            shape_mode(120.0, 0.05, &[1.0, 0.6]),
            shape_mode(260.0, 0.08, &[0.7, -0.9]),
            Mode {
                freq_hz: 75.0,
                damping_ratio: 0.03,
                residue: vec![vec![0.3, 0.1], vec![0.1, 0.25]],
                shape: vec![],
            },
        ],
        -1.0e-3,
    );
}

/// As above with a critically damped and an overdamped mode (method §2: every
/// `ξ >= 0`) beside an undamped one.
#[test]
fn paper_scheme_matches_the_replica_with_critical_and_overdamped_modes() {
    paper_replica_case(
        vec![
            shape_mode(90.0, 0.0, &[1.0, 0.5]),
            shape_mode(200.0, 1.0, &[0.8, -0.7]),
            Mode {
                freq_hz: 140.0,
                damping_ratio: 2.5,
                residue: vec![vec![0.4, -0.1], vec![-0.1, 0.35]],
                shape: vec![],
            },
        ],
        -0.8e-3,
    );
}

fn paper_replica_case(modes: Vec<Mode>, h_m: f64) {
    let road = SpecRoad {
        a: 1.5e-3,
        lambda: 0.2,
        v: 15.0,
        ramp: 0.01,
    };
    let pts = vec![(0.0, h_m), (0.04, h_m)];
    let dt = 5e-5;
    let sc = modal_scene(
        modes.clone(),
        points(&pts),
        sine(road.a, road.lambda),
        road.v,
        road.ramp,
        dt,
        0.08,
        ContactScheme::Paper,
    );
    let p = pts.len();
    let rmodes: Vec<RMode> = modes
        .iter()
        .map(|m| RMode {
            omega: TAU * m.freq_hz,
            xi: m.damping_ratio,
            a: m.residue_matrix().into_iter().flatten().collect(),
        })
        .collect();
    let mut rep = PaperReplica {
        p,
        phi: rmodes
            .iter()
            .map(|m| propagator(m.omega, m.xi, dt))
            .collect(),
        wg: rmodes
            .iter()
            .map(|m| gauss_weights(m.omega, m.xi, dt))
            .collect(),
        state: vec![vec![[0.0; 2]; p]; rmodes.len()],
        modes: rmodes,
        pts: pts.clone(),
        road,
        dt,
        // as the solver's penetration tolerance (1e-12 of the scene's length scale)
        pen_tol: 1e-12 * road.a.max(h_m.abs()),
        t: 0.0,
    };
    let mut sim = Simulation::from_scene(&sc).expect("valid scene");
    let (mut du, mut dq, mut umax, mut qmax) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut landings, mut take_offs, mut mismatched_flags) = (0, 0, 0);
    let mut last = vec![false; p];
    for _ in 0..sc.num_steps() {
        sim.step().expect("step");
        let (u, q, c) = rep.step();
        for i in 0..p {
            du = du.max((sim.displacement_m()[i] - u[i]).abs());
            dq = dq.max((sim.force_n()[i] - q[i]).abs());
            umax = umax.max(u[i].abs());
            qmax = qmax.max(q[i].abs());
            mismatched_flags += (sim.in_contact()[i] != c[i]) as usize;
            landings += (c[i] && !last[i]) as usize;
            take_offs += (!c[i] && last[i]) as usize;
        }
        last = c;
    }
    println!(
        "paper scheme vs method §4 replica over {} steps: max |Δu| {:.2e} of {umax:.3e} m, max |Δq| {:.2e} of {qmax:.1} N; {landings} landings, {take_offs} take-offs, {mismatched_flags} contact flags differ",
        sc.num_steps(),
        du,
        dq
    );
    assert!(
        landings >= 4 && take_offs >= 4,
        "the case must leave and land"
    );
    assert_eq!(mismatched_flags, 0);
    assert!(du < 1e-12 * umax, "displacement {du:e} m of {umax:e} m");
    assert!(dq < 1e-10 * qmax, "force {dq:e} N of {qmax:e} N");
}

/// Energy balance of an inelastic impact (method §4: restitution 0). One
/// undamped mode (`u'' + ω²u = A q`) preloaded by a ramp fast enough to
/// throw the point off the road; it flies with the constant energy
/// `E = (v² + ω²u²)/(2A)` and lands on the now flat road `r = -h`: the
/// landing impulse must take exactly the normal velocity,
/// `A J = sqrt(2AE - ω²h²)` (the kinetic energy `A J²/2` is lost), after
/// which the point rests on the road at `u = -h` with the static force
/// `ω²(-h)/A`.
#[test]
fn inelastic_landing_takes_the_whole_normal_velocity() {
    let (f, a_res, h, ramp): (f64, f64, f64, f64) = (50.0, 1.0, -1.0e-3, 2e-3);
    let omega = TAU * f;
    let dt = 1e-5;
    let sc = modal_scene(
        vec![Mode {
            freq_hz: f,
            damping_ratio: 0.0,
            residue: vec![vec![a_res]],
            shape: vec![],
        }],
        points(&[(0.0, h)]),
        sine(0.0, 1.0),
        0.0,
        ramp,
        dt,
        0.05,
        ContactScheme::Located,
    );
    let mut sim = Simulation::from_scene(&sc).expect("valid scene");
    let mut flight_energy: Vec<f64> = Vec::new();
    let (mut landed_at, mut left_at) = (None, None);
    let mut impulse = 0.0;
    let mut was = false;
    for _ in 0..sc.num_steps() {
        sim.step().expect("step");
        let (u, v) = (sim.displacement_m()[0], sim.velocity_mps()[0]);
        let on = sim.in_contact()[0];
        impulse += sim.impact_impulse_ns()[0];
        if was && !on && left_at.is_none() {
            left_at = Some(sim.time_s());
        }
        if !on && sim.time_s() > ramp {
            flight_energy.push((v * v + omega * omega * u * u) / (2.0 * a_res));
        }
        if on && !was && left_at.is_some() {
            landed_at = Some(sim.time_s());
        }
        if let Some(t_land) = landed_at {
            assert!(on, "left the flat road again at {} s", sim.time_s());
            assert!((u + h).abs() < 1e-15 && v.abs() < 1e-12, "u {u}, v {v}");
            let q_static = omega * omega * (-h) / a_res;
            if sim.time_s() > t_land + 1.5 * dt {
                assert!(
                    (sim.force_n()[0] - q_static).abs() < 1e-9 * q_static,
                    "resting force {} vs {q_static} N",
                    sim.force_n()[0]
                );
            }
        }
        was = on;
    }
    let (left, landed) = (left_at.expect("thrown off"), landed_at.expect("landed"));
    let e = flight_energy[0];
    let drift = flight_energy
        .iter()
        .map(|x| (x - e).abs() / e)
        .fold(0.0, f64::max);
    let j_expected = (2.0 * a_res * e - omega * omega * h * h).sqrt() / a_res;
    println!(
        "left the road at {left:.5} s, landed at {landed:.5} s; flight energy {e:.6e} J (drift {drift:.1e}); landing impulse {impulse:.9e} N·s, expected sqrt(2AE - ω²h²)/A = {j_expected:.9e} N·s (rel {:.1e}); kinetic energy lost {:.4e} J",
        (impulse - j_expected).abs() / j_expected,
        a_res * impulse * impulse / 2.0
    );
    assert!(drift < 1e-12, "undamped flight energy drifts by {drift:e}");
    assert!(impulse > 0.0, "the road pushes up at a landing");
    assert!(
        (impulse - j_expected).abs() < 1e-11 * j_expected,
        "landing impulse {impulse} vs {j_expected} N·s"
    );
}
