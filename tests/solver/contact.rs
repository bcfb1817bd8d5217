//! Independent reference checks of the contact solver and the fast convolution
//! (method §1-4).
//!
//! Every expected value here comes from the physics, written in this file:
//! closed-form oscillator responses, an event-driven one-point contact
//! solution with analytic free flight and root-found impacts and releases,
//! static compliance solves, an RK4 solution of the modal equations with
//! tread springs, and self-convergence. Nothing is recorded from
//! the solver. Run with `--nocapture` to see the tables.

// Numerical loops index several arrays in parallel; ranges read clearer here.
use crate::dense::solve;
use crate::support::models::{SplitMix, modal_scene, sine};
use crate::support::rel_rms;

use std::f64::consts::TAU;
use std::time::Instant;

use tirecontact::SceneSimulation;
use tirecontact::Simulation;
use tirecontact::model::road::Road;
use tirecontact::scene::{ContactScheme, Mode, Point, Scene, Tyre};

// ---------------------------------------------------------------------------
// Own closed forms of the unit oscillator h'' + 2ξω h' + ω² h = δ(t)
// ---------------------------------------------------------------------------

/// `S(x) = sinh(√x)/√x` (x > 0) or `sin(√-x)/√-x` (x < 0), and
/// `C(x) = cosh(√x)` or `cos(√-x)`, by their common power series near 0.
fn s_c(x: f64) -> (f64, f64) {
    if x.abs() < 1.0 {
        // S = Σ x^n/(2n+1)!, C = Σ x^n/(2n)!
        let (mut s, mut c) = (0.0, 0.0);
        let mut term = 1.0; // x^n / (2n)!
        for n in 0..30 {
            let nf = n as f64;
            c += term;
            let ts = term / (2.0 * nf + 1.0);
            s += ts;
            term *= x / ((2.0 * nf + 1.0) * (2.0 * nf + 2.0));
        }
        (s, c)
    } else if x > 0.0 {
        let r = x.sqrt();
        (r.sinh() / r, r.cosh())
    } else {
        let r = (-x).sqrt();
        (r.sin() / r, r.cos())
    }
}

/// `(h, h')` of the unit oscillator at `t >= 0`, one formula for every ξ:
/// `h = e^{-ξωt} t S((ξ²-1)ω²t²)`, `h' = e^{-ξωt} (C - ξωt S)`.
fn my_h(omega: f64, xi: f64, t: f64) -> (f64, f64) {
    let a = xi * omega;
    if xi > 1.5 {
        // two real poles, written directly (no cancellation here)
        let kappa = omega * (xi * xi - 1.0).sqrt();
        let (lp, lm) = (-a + kappa, -a - kappa);
        let (ep, em) = ((lp * t).exp(), (lm * t).exp());
        return (
            (ep - em) / (2.0 * kappa),
            (lp * ep - lm * em) / (2.0 * kappa),
        );
    }
    let x = (xi - 1.0) * (xi + 1.0) * omega * omega * t * t;
    let (s, c) = s_c(x);
    let e = (-a * t).exp();
    (e * t * s, e * (c - a * t * s))
}

/// Unit step response `∫_0^t h = (1 - e^{-ξωt}(C + ξωt S))/ω²`.
fn my_step(omega: f64, xi: f64, t: f64) -> f64 {
    let (h, hd) = my_h(omega, xi, t);
    // h' + 2ξω h = e^{-at}(C + a t S)
    (1.0 - (hd + 2.0 * xi * omega * h)) / (omega * omega)
}

/// Receptance `1/(ω² - Ω² + 2iξωΩ)` as (re, im).
fn my_receptance(omega: f64, xi: f64, big: f64) -> (f64, f64) {
    let (re, im) = (omega * omega - big * big, 2.0 * xi * omega * big);
    let d = re * re + im * im;
    (re / d, -im / d)
}

/// Response from rest to `cos(Ωt)`: steady state plus the free solution that
/// cancels its initial displacement and velocity.
fn my_harmonic(omega: f64, xi: f64, big: f64, t: f64) -> f64 {
    let (hr, hi) = my_receptance(omega, xi, big);
    let (s, c) = (big * t).sin_cos();
    let steady = hr * c - hi * s; // Re(H e^{iΩt})
    let y0 = -hr; // cancels u(0) = Re H
    let yd0 = big * hi; // cancels u'(0) = Re(iΩH) = -Ω Im H
    let (h, hd) = my_h(omega, xi, t);
    steady + y0 * (hd + 2.0 * xi * omega * h) + yd0 * h
}

fn order(e_coarse: f64, e_fine: f64, ratio: f64) -> f64 {
    (e_coarse / e_fine).ln() / ratio.ln()
}

// ---------------------------------------------------------------------------
// Scenes and runs
// ---------------------------------------------------------------------------

/// Time history of a run: per step end `u` (point-major rows), step-mean
/// force, contact flags, located events.
struct Run {
    dt: f64,
    u: Vec<Vec<f64>>,
    q: Vec<Vec<f64>>,
    contact: Vec<Vec<bool>>,
    events: Vec<u32>,
    worst_penetration_m: f64,
}

fn run(sc: &Scene) -> Run {
    let mut sim = Simulation::from_scene(sc).expect("valid scene");
    let n = sc.num_steps() as usize;
    let p = sc.points.len();
    let mut out = Run {
        dt: sc.dt_s,
        u: Vec::with_capacity(n),
        q: Vec::with_capacity(n),
        contact: Vec::with_capacity(n),
        events: Vec::with_capacity(n),
        worst_penetration_m: 0.0,
    };
    for _ in 0..n {
        let rep = sim.step().unwrap_or_else(|e| panic!("solver error: {e}"));
        assert_eq!(sim.displacement_m().len(), p);
        out.u.push(sim.displacement_m().to_vec());
        out.q.push(sim.force_n().to_vec());
        out.contact.push(sim.in_contact().to_vec());
        out.events.push(rep.events);
    }
    out.worst_penetration_m = sim.stats().worst_penetration_m;
    out
}

// ---------------------------------------------------------------------------
// 1. One point, one mode on a sine road: event-driven reference
// ---------------------------------------------------------------------------

/// The road seen by one point, `r(t) = w(t) (a sin(k(x0 + V t)) - h)`, and
/// its first two derivatives (method §4).
#[derive(Clone, Copy)]
struct SineRoad {
    a: f64,
    k: f64,
    v: f64,
    x0: f64,
    h: f64,
    ramp: f64,
}

impl SineRoad {
    fn eval(&self, t: f64) -> (f64, f64, f64) {
        let (w, wd, wdd) = if t >= self.ramp {
            (1.0, 0.0, 0.0)
        } else if t <= 0.0 {
            (0.0, 0.0, 0.0)
        } else {
            let s = t / self.ramp;
            (
                s * s * (3.0 - 2.0 * s),
                6.0 * s * (1.0 - s) / self.ramp,
                6.0 * (1.0 - 2.0 * s) / (self.ramp * self.ramp),
            )
        };
        let ph = self.k * (self.x0 + self.v * t);
        let kv = self.k * self.v;
        let z = self.a * ph.sin() - self.h;
        let zd = self.a * kv * ph.cos();
        let zdd = -self.a * kv * kv * ph.sin();
        (w * z, wd * z + w * zd, wdd * z + 2.0 * wd * zd + w * zdd)
    }
}

#[derive(Clone, Copy, Debug)]
enum Seg {
    /// On the road from `t0`.
    Contact { t0: f64 },
    /// Free flight from `(t0, u0, v0)`.
    Free { t0: f64, u0: f64, v0: f64 },
}

/// Event-driven exact solution for one point on one mode `u'' + 2ξωu' + ω²u = A q`.
struct OnePointReference {
    omega: f64,
    xi: f64,
    res: f64,
    road: SineRoad,
    /// Segments with their start times (sorted).
    segs: Vec<Seg>,
    starts: Vec<f64>,
    /// Impacts: (time, impulse N·s).
    impacts: Vec<(f64, f64)>,
    releases: usize,
}

impl OnePointReference {
    /// Contact force if the point follows the road at `t`.
    fn q_contact(&self, t: f64) -> f64 {
        let (r, rd, rdd) = self.road.eval(t);
        (rdd + 2.0 * self.xi * self.omega * rd + self.omega * self.omega * r) / self.res
    }

    fn free(&self, t0: f64, u0: f64, v0: f64, t: f64) -> (f64, f64) {
        let (h, hd) = my_h(self.omega, self.xi, t - t0);
        (
            u0 * (hd + 2.0 * self.xi * self.omega * h) + v0 * h,
            -self.omega * self.omega * u0 * h + v0 * hd,
        )
    }

    /// First `t` in `(t0, t_end]` where `f` turns negative (f(t0+) >= 0),
    /// bisected to adjacent floats; `breaks` are forced scan points.
    fn first_negative(
        f: impl Fn(f64) -> f64,
        t0: f64,
        t_end: f64,
        scan: f64,
        breaks: &[f64],
    ) -> Option<f64> {
        let mut lo = t0;
        loop {
            if lo >= t_end {
                return None;
            }
            let mut hi = (lo + scan).min(t_end);
            for &b in breaks {
                if b > lo && b < hi {
                    hi = b;
                }
            }
            if f(hi) < 0.0 {
                let (mut a, mut b) = (lo, hi);
                loop {
                    let m = 0.5 * (a + b);
                    if m <= a || m >= b {
                        return Some(b);
                    }
                    if f(m) < 0.0 {
                        b = m;
                    } else {
                        a = m;
                    }
                }
            }
            lo = hi;
        }
    }

    fn new(omega: f64, xi: f64, res: f64, road: SineRoad, t_end: f64) -> Self {
        let mut me = OnePointReference {
            omega,
            xi,
            res,
            road,
            segs: Vec::new(),
            starts: Vec::new(),
            impacts: Vec::new(),
            releases: 0,
        };
        let scan = 2e-6;
        let breaks = [road.ramp];
        // At rest on the road at t = 0 (zero gap).
        let mut seg = Seg::Contact { t0: 0.0 };
        // Contact at t = 0 only if the force starts non-negative.
        if me.q_contact(1e-12) < 0.0 {
            seg = Seg::Free {
                t0: 0.0,
                u0: 0.0,
                v0: 0.0,
            };
        }
        loop {
            assert!(me.segs.len() < 100_000, "reference: too many events");
            me.segs.push(seg);
            match seg {
                Seg::Contact { t0 } => {
                    me.starts.push(t0);
                    let Some(tr) =
                        Self::first_negative(|t| me.q_contact(t), t0, t_end, scan, &breaks)
                    else {
                        break;
                    };
                    me.releases += 1;
                    let (r, rd, _) = road.eval(tr);
                    seg = Seg::Free {
                        t0: tr,
                        u0: r,
                        v0: rd,
                    };
                }
                Seg::Free { t0, u0, v0 } => {
                    me.starts.push(t0);
                    let gap = |t: f64| me.free(t0, u0, v0, t).0 - road.eval(t).0;
                    let Some(ti) = Self::first_negative(gap, t0, t_end, scan, &[]) else {
                        break;
                    };
                    let (_, v_minus) = me.free(t0, u0, v0, ti);
                    let (r, rd, _) = road.eval(ti);
                    me.impacts.push((ti, (rd - v_minus) / res));
                    seg = if me.q_contact(ti * (1.0 + 1e-15) + 1e-18) >= 0.0 {
                        Seg::Contact { t0: ti }
                    } else {
                        me.releases += 1;
                        Seg::Free {
                            t0: ti,
                            u0: r,
                            v0: rd,
                        }
                    };
                }
            }
        }
        me
    }

    fn seg_at(&self, t: f64) -> usize {
        self.starts.partition_point(|&s| s <= t).saturating_sub(1)
    }

    fn displacement(&self, t: f64) -> f64 {
        match self.segs[self.seg_at(t)] {
            Seg::Contact { .. } => self.road.eval(t).0,
            Seg::Free { t0, u0, v0 } => self.free(t0, u0, v0, t).0,
        }
    }

    /// Impulse (N·s) the road gives in `[a, b)`: impacts plus `∫ q` over
    /// contact, by 5-point Gauss-Legendre on pieces of at most 20 µs.
    fn impulse(&self, a: f64, b: f64) -> f64 {
        const GL5: [(f64, f64); 5] = [
            (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
            (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (0.0, 0.568_888_888_888_888_9),
            (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (0.906_179_845_938_664, 0.236_926_885_056_189_1),
        ];
        let mut total: f64 = self
            .impacts
            .iter()
            .filter(|&&(t, _)| t >= a && t < b)
            .map(|&(_, i)| i)
            .sum();
        // cut points: segment starts and the ramp end inside [a, b]
        let mut cuts = vec![a, b];
        cuts.extend(self.starts.iter().copied().filter(|&s| s > a && s < b));
        if self.road.ramp > a && self.road.ramp < b {
            cuts.push(self.road.ramp);
        }
        cuts.sort_by(f64::total_cmp);
        for w in cuts.windows(2) {
            let (c0, c1) = (w[0], w[1]);
            if c1 <= c0 {
                continue;
            }
            if !matches!(self.segs[self.seg_at(0.5 * (c0 + c1))], Seg::Contact { .. }) {
                continue;
            }
            let n = ((c1 - c0) / 2e-5).ceil().max(1.0) as usize;
            let hs = (c1 - c0) / n as f64;
            for k in 0..n {
                let mid = c0 + (k as f64 + 0.5) * hs;
                for &(x, wgt) in &GL5 {
                    total += 0.5 * hs * wgt * self.q_contact(mid + 0.5 * hs * x);
                }
            }
        }
        total
    }
}

/// Relative RMS displacement error and relative RMS error of the impulses
/// over `window` (s) of a one-point run against the reference.
fn one_point_errors(
    run: &Run,
    refsol: &OnePointReference,
    window: f64,
    ref_u: &mut Vec<f64>,
) -> (f64, f64) {
    let dt = run.dt;
    let n = run.u.len();
    ref_u.clear();
    ref_u.extend((1..=n).map(|k| refsol.displacement(k as f64 * dt)));
    let (mut num, mut den) = (0.0, 0.0);
    for k in 0..n {
        let e = run.u[k][0] - ref_u[k];
        num += e * e;
        den += ref_u[k] * ref_u[k];
    }
    let eu = (num / den).sqrt();
    let per = (window / dt).round() as usize;
    assert!((per as f64 * dt - window).abs() < 1e-9 * window);
    let (mut num, mut den) = (0.0, 0.0);
    for w in 0..n / per {
        let solver: f64 = (w * per..(w + 1) * per).map(|k| run.q[k][0] * dt).sum();
        let reference = refsol.impulse(w as f64 * window, (w + 1) as f64 * window);
        num += (solver - reference).powi(2);
        den += reference * reference;
    }
    (eu, (num / den).sqrt())
}

#[test]
fn one_point_sine_road_against_event_driven_reference() {
    let (f, xi, res) = (100.0, 0.05, 0.1);
    let (a, lambda, speed, h, ramp, duration) = (0.002, 0.5, 20.0, -0.001, 0.05, 0.3);
    let omega = TAU * f;
    let road = SineRoad {
        a,
        k: TAU / lambda,
        v: speed,
        x0: 0.0,
        h,
        ramp,
    };
    let t0 = Instant::now();
    let refsol = OnePointReference::new(omega, xi, res, road, duration + 1e-3);
    println!(
        "\n[1] one point, one mode (100 Hz, ξ 0.05, A 0.1/kg), 2 mm 0.5 m sine at 20 m/s, 1 mm preload, {duration} s:\n    reference: {} impacts, {} releases, built in {:.2} s",
        refsol.impacts.len(),
        refsol.releases,
        t0.elapsed().as_secs_f64()
    );
    assert!(
        refsol.impacts.len() >= 5 && refsol.releases >= 5,
        "the scenario must lose and regain contact repeatedly"
    );
    let dts = [4e-5, 2e-5, 1e-5, 5e-6];
    let window = 1e-3;
    let mut table: Vec<(ContactScheme, Vec<(f64, f64)>)> = Vec::new();
    let mut ref_u = Vec::new();
    for scheme in [ContactScheme::Located, ContactScheme::Paper] {
        let mut errs = Vec::new();
        for &dt in &dts {
            let sc = modal_scene(
                vec![Mode {
                    freq_hz: f,
                    damping_ratio: xi,
                    residue: vec![vec![res]],
                    shape: vec![],
                }],
                vec![Point {
                    x_m: 0.0,
                    y_m: 0.0,
                    h_m: h,
                }],
                sine(a, lambda),
                speed,
                ramp,
                dt,
                duration,
                scheme,
            );
            let r = run(&sc);
            errs.push(one_point_errors(&r, &refsol, window, &mut ref_u));
        }
        table.push((scheme, errs));
    }
    println!("    scheme   dt       disp err   order   impulse(1 ms) err   order");
    for (scheme, errs) in &table {
        for (k, &(eu, eq)) in errs.iter().enumerate() {
            let (ou, oq) = if k == 0 {
                (String::from("   -  "), String::from("   -  "))
            } else {
                (
                    format!("{:6.2}", order(errs[k - 1].0, eu, 2.0)),
                    format!("{:6.2}", order(errs[k - 1].1, eq, 2.0)),
                )
            };
            println!(
                "    {:8} {:.0e}  {eu:9.3e}  {ou}   {eq:9.3e}          {oq}",
                format!("{scheme:?}"),
                dts[k]
            );
        }
    }
    println!("    total time {:.2} s", t0.elapsed().as_secs_f64());
    let loc = &table[0].1;
    let pap = &table[1].1;
    // One point on one mode: in contact the state (u, v) = (r, r') is imposed
    // exactly, so the only errors come from event location; they may reach
    // round-off, where an order means nothing. Below FLOOR a pair passes.
    const FLOOR: f64 = 1e-12;
    for k in 1..loc.len() {
        for (what, c, fine) in [
            ("displacement", loc[k - 1].0, loc[k].0),
            ("impulse", loc[k - 1].1, loc[k].1),
        ] {
            let o = order(c, fine, 2.0);
            assert!(
                o >= 1.8 || fine <= FLOOR,
                "Located {what} order {o:.2} between dt {} and {} (errors {c:.3e}, {fine:.3e})",
                dts[k - 1],
                dts[k],
            );
        }
    }
    let last = loc.len() - 1;
    assert!(
        10.0 * loc[last].0 <= pap[last].0,
        "Located displacement error {:.3e} not 10x below Paper's {:.3e} at dt {}",
        loc[last].0,
        pap[last].0,
        dts[last]
    );
    assert!(
        10.0 * loc[last].1 <= pap[last].1,
        "Located impulse error {:.3e} not 10x below Paper's {:.3e} at dt {}",
        loc[last].1,
        pap[last].1,
        dts[last]
    );
}

// ---------------------------------------------------------------------------
// 2. Three points, coupled modes: an impact throws a neighbour off the road
// ---------------------------------------------------------------------------

fn three_point_modes() -> Vec<Mode> {
    let m = |f: f64, shape: [f64; 3]| Mode {
        freq_hz: f,
        damping_ratio: 0.05,
        residue: vec![],
        shape: shape.to_vec(),
    };
    vec![
        m(60.0, [0.3, 0.3, 0.3]),
        m(110.0, [0.3, 0.0, -0.3]),
        m(170.0, [0.15, -0.3, 0.15]),
    ]
}

fn three_point_scene(dt: f64, duration: f64, scheme: ContactScheme) -> Scene {
    modal_scene(
        three_point_modes(),
        vec![
            Point {
                x_m: -0.05,
                y_m: 0.0,
                h_m: -0.001,
            },
            Point {
                x_m: 0.0,
                y_m: 0.0,
                h_m: -0.001,
            },
            Point {
                x_m: 0.05,
                y_m: 0.0,
                h_m: -0.001,
            },
        ],
        sine(0.002, 0.5),
        20.0,
        0.05,
        dt,
        duration,
        scheme,
    )
}

/// Steps where a point in contact leaves the road while another lands.
fn throw_offs(r: &Run) -> Vec<(usize, usize, usize)> {
    let mut out = Vec::new();
    for k in 1..r.contact.len() {
        let (before, after) = (&r.contact[k - 1], &r.contact[k]);
        for i in 0..before.len() {
            if before[i] && !after[i] {
                for j in 0..before.len() {
                    if !before[j] && after[j] {
                        out.push((k, j, i));
                    }
                }
            }
        }
    }
    out
}

/// Relative RMS difference of displacement between a run and a finer one
/// (`m` times finer), on the coarse grid.
fn rms_diff(coarse: &Run, fine: &Run) -> f64 {
    let m = (coarse.dt / fine.dt).round() as usize;
    let (mut num, mut den) = (0.0, 0.0);
    for (k, uc) in coarse.u.iter().enumerate() {
        let uf = &fine.u[(k + 1) * m - 1];
        for (a, b) in uc.iter().zip(uf) {
            num += (a - b) * (a - b);
            den += b * b;
        }
    }
    (num / den).sqrt()
}

/// RK4 sub-steps per 5 µs of the multi-point reference (h = 0.625 µs).
const REF_SUB: usize = 8;

/// Relative RMS displacement error of a run against reference displacements
/// sampled every `grid` seconds.
fn rms_err_vs_ref(r: &Run, reference: &[Vec<f64>], grid: f64) -> f64 {
    let m = (r.dt / grid).round() as usize;
    assert!((m as f64 * grid - r.dt).abs() < 1e-9 * r.dt);
    let (mut num, mut den) = (0.0, 0.0);
    for (k, u) in r.u.iter().enumerate() {
        let ur = &reference[(k + 1) * m - 1];
        for (a, b) in u.iter().zip(ur) {
            num += (a - b) * (a - b);
            den += b * b;
        }
    }
    (num / den).sqrt()
}

#[test]
fn three_points_impact_throws_neighbour_off() {
    let duration = 0.3;
    let t0 = Instant::now();
    let sc0 = three_point_scene(1e-5, duration, ContactScheme::Located);
    let roads: Vec<SineRoad> = sc0
        .points
        .iter()
        .map(|pt| SineRoad {
            a: 0.002,
            k: TAU / 0.5,
            v: 20.0,
            x0: pt.x_m,
            h: pt.h_m,
            ramp: 0.05,
        })
        .collect();
    let refsys = MultiReference::new(&three_point_modes(), roads);
    let grid = 5e-6;
    let n = (duration / grid).round() as usize;
    let (reference, rst) = refsys.solve(grid, n, REF_SUB, 1e-8);
    let t_ref = t0.elapsed().as_secs_f64();
    // the reference against itself with half the RK4 step
    let (check, _) = refsys.solve(grid, n, REF_SUB / 2, 1e-8);
    // Uncertainty of the reference: its difference from the run with twice
    // the RK4 step. It does not fall as h⁴ below ~1e-11 (round-off of ~5e5
    // projected RK4 steps and event bisections), so it is taken raw.
    let ref_err = rel_rms(&reference, &check);
    println!(
        "\n[2] three points (x = -5, 0, 5 cm), modes 60/110/170 Hz with coupled shapes, 2 mm 0.5 m sine at 20 m/s, 1 mm preload, {duration} s\n    event-driven reference: {} impacts, {} releases, {} throw-offs, {} Zeno tails cut; RK4 h {:.2e}, differs from h x 2 by {ref_err:.1e} (built in {t_ref:.2} s)",
        rst.impacts,
        rst.releases,
        rst.throw_offs,
        rst.zeno_cuts,
        grid / REF_SUB as f64
    );
    assert!(ref_err < 1e-11, "reference not converged: {ref_err:e}");
    assert!(
        rst.throw_offs > 0,
        "the reference scenario has no throw-off"
    );
    let dts = [8e-5, 4e-5, 2e-5, 1e-5, 5e-6];
    let nd = dts.len();
    println!(
        "    scheme   dt      err vs ref   order   |u(dt)-u(dt/2)|  order   throw-off steps  located events  worst penetration"
    );
    let mut results = Vec::new();
    for scheme in [ContactScheme::Located, ContactScheme::Paper] {
        let runs: Vec<Run> = dts
            .iter()
            .map(|&dt| run(&three_point_scene(dt, duration, scheme)))
            .collect();
        let errs: Vec<f64> = runs
            .iter()
            .map(|r| rms_err_vs_ref(r, &reference, grid))
            .collect();
        let rich: Vec<f64> = (1..nd).map(|k| rms_diff(&runs[k - 1], &runs[k])).collect();
        for (k, r) in runs.iter().enumerate() {
            let throws = throw_offs(r);
            assert!(
                !throws.is_empty(),
                "{scheme:?} dt {}: no step where a point in contact leaves while another lands",
                dts[k]
            );
            let eo = if k == 0 {
                "   -  ".to_string()
            } else {
                format!("{:6.2}", order(errs[k - 1], errs[k], 2.0))
            };
            let rd = rich
                .get(k)
                .map_or("     -   ".to_string(), |d| format!("{d:9.3e}"));
            let ro = if k == 0 || k + 1 >= nd {
                "   -  ".to_string()
            } else {
                format!("{:6.2}", order(rich[k - 1], rich[k], 2.0))
            };
            println!(
                "    {:8} {:.0e}  {:9.3e}   {eo}   {rd}        {ro}   {:6} (first t {:.5} s)  {:6}  {:.2e} m",
                format!("{scheme:?}"),
                dts[k],
                errs[k],
                throws.len(),
                (throws[0].0 + 1) as f64 * dts[k],
                r.events.iter().sum::<u32>(),
                r.worst_penetration_m
            );
        }
        results.push((scheme, errs, rich));
    }
    println!("    total time {:.2} s", t0.elapsed().as_secs_f64());
    let (_, le, lr) = &results[0];
    let (_, pe, _) = &results[1];
    let lo: Vec<f64> = (1..nd).map(|k| order(le[k - 1], le[k], 2.0)).collect();
    let lro: Vec<f64> = (1..nd - 1).map(|k| order(lr[k - 1], lr[k], 2.0)).collect();
    let po: Vec<f64> = (1..nd).map(|k| order(pe[k - 1], pe[k], 2.0)).collect();
    let mut failures = Vec::new();
    if !po.iter().all(|&o| o < 1.5) {
        failures.push(format!(
            "Paper orders {po:?} (errors {pe:?}): expected first order (< 1.5)"
        ));
    }
    // an error within 3x the reference's own uncertainty cannot show an order;
    // nor can a Richardson difference at that level
    let floor = 3.0 * ref_err;
    // dt = 8e-5 (ω dt up to 0.09, several events per step) is printed but
    // pre-asymptotic; the asserted range is dt <= 4e-5.
    let first = 2;
    let lo_ok = (first..nd).all(|k| lo[k - 1] >= 1.8 || le[k] <= floor);
    let lro_ok = (first..nd - 1).all(|k| lro[k - 1] >= 1.8 || lr[k] <= floor);
    println!(
        "    Located orders vs reference {lo:.2?}, Richardson {lro:.2?} (asserted for dt <= {:e}; errors below {floor:.1e} are at the reference's floor)\n    Paper orders vs reference {po:.2?}",
        dts[first - 1]
    );
    if !(lo_ok && lro_ok) {
        failures.push(format!(
            "Located orders {lo:?} vs the reference (errors {le:?}, floor {floor:e}), Richardson {lro:?} (differences {lr:?}): expected >= 1.8"
        ));
    }
    if 10.0 * le[nd - 1] > pe[nd - 1] {
        failures.push(format!(
            "Located error {:.3e} not 10x below Paper's {:.3e} at dt {}",
            le[nd - 1],
            pe[nd - 1],
            dts[nd - 1]
        ));
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Event-driven reference for several points on rank-one modes
/// (`A_k = φ_k φ_kᵀ`): modal coordinates `x_k'' + 2ξω x_k' + ω² x_k = φ_kᵀ q`,
/// `u = Σ φ_k x_k`. Between events the contact set `S` is fixed and
/// `u_S = r_S` is kept by the forces solved from the acceleration constraint
/// (`J_SS q_S = r_S'' + [Φ(2ξω x' + ω² x)]_S`, `J = Σ φ_k φ_kᵀ`); the ODE is
/// integrated by classical RK4 on a fine grid with the constraint projected
/// after each step. Impacts and releases are located by bisection on the RK4
/// map to adjacent floats; impacts solve the impulse LCP over the landing
/// point and all points on the road, and the contact set then comes from the
/// force LCP, both by enumeration of all subsets (exact for these sizes, and
/// a different algorithm from the solver's monotone rule). A Zeno sequence of
/// throw-offs is cut when a separation speed falls below `w_min`.
struct MultiReference {
    p: usize,
    /// `phi[k][i]`.
    phi: Vec<Vec<f64>>,
    omega: Vec<f64>,
    xi: Vec<f64>,
    roads: Vec<SineRoad>,
    jm: Vec<Vec<f64>>,
}

#[derive(Default, Debug, Clone, Copy)]
struct MultiStats {
    impacts: usize,
    releases: usize,
    throw_offs: usize,
    zeno_cuts: usize,
}

impl MultiReference {
    fn new(modes: &[Mode], roads: Vec<SineRoad>) -> Self {
        let p = roads.len();
        let phi: Vec<Vec<f64>> = modes.iter().map(|m| m.shape.clone()).collect();
        let jm = (0..p)
            .map(|i| {
                (0..p)
                    .map(|j| phi.iter().map(|f| f[i] * f[j]).sum())
                    .collect()
            })
            .collect();
        MultiReference {
            p,
            omega: modes.iter().map(|m| TAU * m.freq_hz).collect(),
            xi: modes.iter().map(|m| m.damping_ratio).collect(),
            phi,
            roads,
            jm,
        }
    }

    fn uv(&self, x: &[f64], xd: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let u = (0..self.p)
            .map(|i| self.phi.iter().zip(x).map(|(f, x)| f[i] * x).sum())
            .collect();
        let v = (0..self.p)
            .map(|i| self.phi.iter().zip(xd).map(|(f, x)| f[i] * x).sum())
            .collect();
        (u, v)
    }

    fn sub(&self, set: &[usize]) -> Vec<Vec<f64>> {
        set.iter()
            .map(|&i| set.iter().map(|&j| self.jm[i][j]).collect())
            .collect()
    }

    /// Free acceleration of the points (no contact force) minus the road's.
    fn free_rel_acc(&self, t: f64, x: &[f64], xd: &[f64]) -> Vec<f64> {
        (0..self.p)
            .map(|i| {
                let a: f64 = (0..self.phi.len())
                    .map(|k| {
                        -self.phi[k][i]
                            * (2.0 * self.xi[k] * self.omega[k] * xd[k]
                                + self.omega[k] * self.omega[k] * x[k])
                    })
                    .sum();
                a - self.roads[i].eval(t).2
            })
            .collect()
    }

    /// Contact forces of the points in `set` (others zero).
    fn forces(&self, t: f64, x: &[f64], xd: &[f64], set: &[usize]) -> Vec<f64> {
        let mut q = vec![0.0; self.p];
        if set.is_empty() {
            return q;
        }
        let b = self.free_rel_acc(t, x, xd);
        let sol = solve(self.sub(set), set.iter().map(|&i| -b[i]).collect()).expect("non-singular");
        for (k, &i) in set.iter().enumerate() {
            q[i] = sol[k];
        }
        q
    }

    fn deriv(&self, t: f64, x: &[f64], xd: &[f64], set: &[usize]) -> (Vec<f64>, Vec<f64>) {
        let q = self.forces(t, x, xd, set);
        let xdd = (0..self.phi.len())
            .map(|k| {
                let f: f64 = (0..self.p).map(|i| self.phi[k][i] * q[i]).sum();
                f - 2.0 * self.xi[k] * self.omega[k] * xd[k] - self.omega[k] * self.omega[k] * x[k]
            })
            .collect();
        (xd.to_vec(), xdd)
    }

    fn rk4(&self, t: f64, x: &[f64], xd: &[f64], set: &[usize], h: f64) -> (Vec<f64>, Vec<f64>) {
        let axpy = |a: &[f64], s: f64, b: &[f64]| -> Vec<f64> {
            a.iter().zip(b).map(|(a, b)| a + s * b).collect()
        };
        let (k1x, k1v) = self.deriv(t, x, xd, set);
        let (k2x, k2v) = self.deriv(
            t + h / 2.0,
            &axpy(x, h / 2.0, &k1x),
            &axpy(xd, h / 2.0, &k1v),
            set,
        );
        let (k3x, k3v) = self.deriv(
            t + h / 2.0,
            &axpy(x, h / 2.0, &k2x),
            &axpy(xd, h / 2.0, &k2v),
            set,
        );
        let (k4x, k4v) = self.deriv(t + h, &axpy(x, h, &k3x), &axpy(xd, h, &k3v), set);
        let comb = |y: &[f64], a: &[f64], b: &[f64], c: &[f64], d: &[f64]| -> Vec<f64> {
            (0..y.len())
                .map(|k| y[k] + h / 6.0 * (a[k] + 2.0 * b[k] + 2.0 * c[k] + d[k]))
                .collect()
        };
        (
            comb(x, &k1x, &k2x, &k3x, &k4x),
            comb(xd, &k1v, &k2v, &k3v, &k4v),
        )
    }

    /// Minimal-norm correction so that `u_S = r_S`, `v_S = r'_S` exactly.
    fn project(&self, t: f64, x: &mut [f64], xd: &mut [f64], set: &[usize]) {
        if set.is_empty() {
            return;
        }
        let (u, v) = self.uv(x, xd);
        let js = self.sub(set);
        let du = solve(
            js.clone(),
            set.iter()
                .map(|&i| self.roads[i].eval(t).0 - u[i])
                .collect(),
        )
        .expect("non-singular");
        let dv = solve(
            js,
            set.iter()
                .map(|&i| self.roads[i].eval(t).1 - v[i])
                .collect(),
        )
        .expect("non-singular");
        for k in 0..self.phi.len() {
            for (m, &i) in set.iter().enumerate() {
                x[k] += self.phi[k][i] * du[m];
                xd[k] += self.phi[k][i] * dv[m];
            }
        }
    }

    /// Subsets of `cand`, largest first.
    fn subsets(cand: &[usize]) -> Vec<Vec<usize>> {
        let n = cand.len();
        let mut masks: Vec<u32> = (0..1u32 << n).collect();
        masks.sort_by_key(|m| std::cmp::Reverse(m.count_ones()));
        masks
            .into_iter()
            .map(|m| {
                (0..n)
                    .filter(|b| m >> b & 1 == 1)
                    .map(|b| cand[b])
                    .collect()
            })
            .collect()
    }

    /// LCP `y = J z + b >= 0, z >= 0, y z = 0` over `cand` (b indexed by
    /// point), by enumeration, larger sets first. `tol` (relative to max |b|)
    /// accepts slightly negative `z` and `y`: with `tol > 0` degenerate points
    /// (both ~0, e.g. a landing exactly where the force would start to grow)
    /// stay in contact; a release uses `tol = 0`.
    fn lcp(&self, cand: &[usize], b: &[f64], tol: f64) -> (Vec<usize>, Vec<f64>) {
        let scale_b = cand
            .iter()
            .map(|&i| b[i].abs())
            .fold(0.0, f64::max)
            .max(1e-300);
        let jmax = cand.iter().map(|&i| self.jm[i][i]).fold(0.0, f64::max);
        for set in Self::subsets(cand) {
            let z_s = if set.is_empty() {
                vec![]
            } else {
                solve(self.sub(&set), set.iter().map(|&i| -b[i]).collect()).expect("non-singular")
            };
            let mut z = vec![0.0; self.p];
            for (k, &i) in set.iter().enumerate() {
                z[i] = z_s[k];
            }
            let ok_z = set.iter().all(|&i| z[i] >= -tol * scale_b / jmax);
            let ok_y = cand.iter().filter(|i| !set.contains(i)).all(|&i| {
                let y: f64 = b[i] + (0..self.p).map(|j| self.jm[i][j] * z[j]).sum::<f64>();
                y >= -(tol + 1e-13) * scale_b
            });
            if ok_z && ok_y {
                return (set, z);
            }
        }
        panic!("reference: no LCP solution for {cand:?}");
    }

    /// First θ in (0, h] where `f` turns negative (f(h) < 0), to adjacent floats.
    fn bisect(f: impl Fn(f64) -> f64, h: f64) -> f64 {
        let (mut a, mut b) = (0.0, h);
        loop {
            let m = 0.5 * (a + b);
            if m <= a || m >= b {
                return b;
            }
            if f(m) < 0.0 {
                b = m;
            } else {
                a = m;
            }
        }
    }

    /// Displacements at `m * grid` for `m = 1..=n`, RK4 sub-steps of `grid / sub`.
    fn solve(&self, grid: f64, n: usize, sub: usize, w_min: f64) -> (Vec<Vec<f64>>, MultiStats) {
        let nm = self.phi.len();
        let (mut x, mut xd) = (vec![0.0; nm], vec![0.0; nm]);
        let mut t = 0.0;
        let mut st = MultiStats::default();
        // at rest on the road at t = 0: the force LCP decides who stays
        let all: Vec<usize> = (0..self.p).collect();
        let (mut set, _) = self.lcp(&all, &self.free_rel_acc(1e-15, &x, &xd), 1e-9);
        let mut out = Vec::with_capacity(n);
        let hs = grid / sub as f64;
        let mut stalled = 0usize;
        for m in 1..=n {
            let target = m as f64 * grid;
            while target - t > 1e-9 * hs {
                assert!(st.impacts < 1_000_000, "reference: too many events");
                let h = hs.min(target - t);
                let (mut x1, mut xd1) = self.rk4(t, &x, &xd, &set, h);
                // events in (t, t + h]
                let gap_at = |i: usize, th: f64| {
                    let (xa, _) = self.rk4(t, &x, &xd, &set, th);
                    let (u, _) = self.uv(&xa, &xd);
                    u[i] - self.roads[i].eval(t + th).0
                };
                let q_at = |i: usize, th: f64| {
                    let (xa, xda) = self.rk4(t, &x, &xd, &set, th);
                    self.forces(t + th, &xa, &xda, &set)[i]
                };
                let mut first: Option<(f64, usize, bool)> = None; // (θ, point, is_impact)
                let q1 = self.forces(t + h, &x1, &xd1, &set);
                let (u1, _) = self.uv(&x1, &xd1);
                let (u0, _) = self.uv(&x, &xd);
                for i in 0..self.p {
                    let th = if set.contains(&i) {
                        (q1[i] < 0.0).then(|| (Self::bisect(|th| q_at(i, th), h), false))
                    } else {
                        // a point may start the step at a round-off
                        // penetration (1e-17 m, left by an event): it lands
                        // when its gap falls below that level again
                        let g0 = (u0[i] - self.roads[i].eval(t).0).min(0.0);
                        (u1[i] - self.roads[i].eval(t + h).0 < g0)
                            .then(|| (Self::bisect(|th| gap_at(i, th) - g0, h), true))
                    };
                    if let Some((th, imp)) = th
                        && first.is_none_or(|f| th < f.0)
                    {
                        first = Some((th, i, imp));
                    }
                }
                let Some((th, i, is_impact)) = first else {
                    self.project(t + h, &mut x1, &mut xd1, &set);
                    (x, xd, t) = (x1, xd1, t + h);
                    continue;
                };
                stalled = if th < 1e-12 * hs { stalled + 1 } else { 0 };
                assert!(
                    stalled < 10_000,
                    "reference stalled at t = {t:e}: set {set:?}, event at point {i} (impact {is_impact})"
                );
                (x, xd) = self.rk4(t, &x, &xd, &set, th);
                t += th;
                self.project(t, &mut x, &mut xd, &set);
                if !is_impact {
                    st.releases += 1;
                    let b = self.free_rel_acc(t, &x, &xd);
                    set = self.lcp(&set, &b, 0.0).0;
                    continue;
                }
                st.impacts += 1;
                let mut cand = set.clone();
                cand.push(i);
                let (_, v) = self.uv(&x, &xd);
                let w: Vec<f64> = (0..self.p)
                    .map(|j| v[j] - self.roads[j].eval(t).1)
                    .collect();
                let (_, imp) = self.lcp(&cand, &w, 0.0);
                for k in 0..nm {
                    xd[k] += (0..self.p).map(|j| self.phi[k][j] * imp[j]).sum::<f64>();
                }
                let (_, v) = self.uv(&x, &xd);
                let mut stay = Vec::new();
                for &j in &cand {
                    let wj = v[j] - self.roads[j].eval(t).1;
                    if wj <= w_min {
                        if wj > 1e-14 {
                            st.zeno_cuts += 1;
                        }
                        stay.push(j);
                    } else if set.contains(&j) {
                        st.throw_offs += 1;
                    }
                }
                let b = self.free_rel_acc(t, &x, &xd);
                set = self.lcp(&stay, &b, 1e-9).0;
                // points kept on the road move with it (cut Zeno tails included)
                self.project(t, &mut x, &mut xd, &set);
            }
            out.push(self.uv(&x, &xd).0);
        }
        (out, st)
    }
}

// ---------------------------------------------------------------------------
// 3. Static preload: steady force from the static compliance
// ---------------------------------------------------------------------------

/// Outcome of a static-preload run: mean step force over the last `WINDOW`
/// steps, last displacement, steps of that window not all in contact, and the
/// located events in it.
struct StaticOutcome {
    q: Vec<f64>,
    u: Vec<f64>,
    lost: usize,
    events: u32,
    first_all_in_contact_s: Option<f64>,
}

const WINDOW: usize = 500;

fn static_run(modes: Vec<Mode>, points: Vec<Point>, scheme: ContactScheme) -> StaticOutcome {
    let dt = 2e-5;
    let sc = modal_scene(modes, points, sine(0.0, 0.5), 20.0, 0.05, dt, 0.6, scheme);
    let r = run(&sc);
    let n = r.q.len();
    let p = sc.points.len();
    let tail = n - WINDOW..n;
    StaticOutcome {
        q: (0..p)
            .map(|i| r.q[tail.clone()].iter().map(|row| row[i]).sum::<f64>() / WINDOW as f64)
            .collect(),
        u: r.u[n - 1].clone(),
        lost: r.contact[tail.clone()]
            .iter()
            .filter(|c| !c.iter().all(|&x| x))
            .count(),
        events: r.events[tail].iter().sum(),
        first_all_in_contact_s: r
            .contact
            .iter()
            .position(|c| c.iter().all(|&x| x))
            .map(|k| (k + 1) as f64 * dt),
    }
}

#[test]
fn static_preload_matches_static_compliance() {
    println!("\n[3] static preload (no road amplitude, 50 ms ramp, hold to 0.6 s, dt 2e-5)");
    let mut failures = Vec::new();
    // one point, two modes: q = penetration / Σ A_k / ω_k²
    let modes1 = vec![
        Mode {
            freq_hz: 100.0,
            damping_ratio: 0.05,
            residue: vec![vec![0.1]],
            shape: vec![],
        },
        Mode {
            freq_hz: 260.0,
            damping_ratio: 0.08,
            residue: vec![vec![0.05]],
            shape: vec![],
        },
    ];
    let pen = 0.0012;
    let c: f64 = modes1
        .iter()
        .map(|m| m.residue[0][0] / (TAU * m.freq_hz).powi(2))
        .sum();
    let expected = pen / c;
    for scheme in [ContactScheme::Located, ContactScheme::Paper] {
        let o = static_run(
            modes1.clone(),
            vec![Point {
                x_m: 0.0,
                y_m: 0.0,
                h_m: -pen,
            }],
            scheme,
        );
        let rel = (o.q[0] - expected).abs() / expected;
        println!(
            "    1 point  {scheme:?}: force {:.9e} N, expected pen/C = {expected:.9e} N, rel err {rel:.2e}; u - pen {:.1e} m; steps off the road in the last {WINDOW}: {}",
            o.q[0],
            o.u[0] - pen,
            o.lost
        );
        if !(rel < 1e-7 && (o.u[0] - pen).abs() < 1e-12 && o.lost == 0) {
            failures.push(format!(
                "1 point {scheme:?}: force {} vs {expected}, u {} vs {pen}, {} steps off",
                o.q[0], o.u[0], o.lost
            ));
        }
    }
    // three points: three coupled modes plus a rank-3 residue matrix mode
    let mut modes3 = three_point_modes();
    modes3.push(Mode {
        freq_hz: 240.0,
        damping_ratio: 0.1,
        residue: vec![
            vec![0.04, 0.01, -0.005],
            vec![0.01, 0.03, 0.01],
            vec![-0.005, 0.01, 0.04],
        ],
        shape: vec![],
    });
    let x_m = [0.0, 0.05, 0.1];
    let mut cmat = vec![vec![0.0; 3]; 3];
    for m in &modes3 {
        let a = m.residue_matrix();
        let w2 = (TAU * m.freq_hz).powi(2);
        for i in 0..3 {
            for j in 0..3 {
                cmat[i][j] += a[i][j] / w2;
            }
        }
    }
    // preloads chosen to give compressive forces everywhere (about 3-4 kN)
    let design = [3000.0, 4000.0, 3500.0];
    let hs: Vec<f64> = (0..3)
        .map(|i| -(0..3).map(|j| cmat[i][j] * design[j]).sum::<f64>())
        .collect();
    let points: Vec<Point> = (0..3)
        .map(|i| Point {
            x_m: x_m[i],
            y_m: 0.0,
            h_m: hs[i],
        })
        .collect();
    let expected = solve(cmat.clone(), hs.iter().map(|h| -h).collect()).expect("non-singular");
    for i in 0..3 {
        let r: f64 = (0..3).map(|j| cmat[i][j] * expected[j]).sum::<f64>() + hs[i];
        assert!(r.abs() < 1e-15, "own solve residual {r}");
        assert!((expected[i] - design[i]).abs() < 1e-8 * design[i]);
    }
    for scheme in [ContactScheme::Located, ContactScheme::Paper] {
        let o = static_run(modes3.clone(), points.clone(), scheme);
        let rel = (0..3)
            .map(|i| (o.q[i] - expected[i]).abs() / expected[i])
            .fold(0.0, f64::max);
        let du = (0..3).map(|i| (o.u[i] + hs[i]).abs()).fold(0.0, f64::max);
        println!(
            "    3 points {scheme:?}: forces {:.4?} N, expected C⁻¹ pen {expected:.4?} N, max rel err {rel:.2e}; max |u - pen| {du:.1e} m\n             steps not all in contact in the last {WINDOW}: {}, located events there: {}, first step end with all in contact: {:?} s",
            o.q, o.lost, o.events, o.first_all_in_contact_s
        );
        if !(rel < 1e-7 && du < 1e-12 && o.lost == 0) {
            failures.push(format!(
                "3 points {scheme:?}: forces {:?} vs {expected:?}, max |u - pen| {du:e}, {} of the last {WINDOW} steps not all in contact",
                o.q, o.lost
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

// ---------------------------------------------------------------------------
// 4. Stability of the bounded recursion; overflow of the paper's α/β form
// ---------------------------------------------------------------------------

#[test]
fn bounded_recursion_stable_alpha_beta_overflows() {
    use tirecontact::model::convolution::paper_alpha_beta::AlphaBeta;
    use tirecontact::model::convolution::{ModalBasis, ModalState, StepTable};
    let (f, xi, dt) = (4000.0, 0.1, 1e-5);
    let steps: usize = 10_000_000;
    let omega = TAU * f;
    let modes = [Mode {
        freq_hz: f,
        damping_ratio: xi,
        residue: vec![vec![1.0]],
        shape: vec![],
    }];
    let basis = ModalBasis::new(&modes, 1).unwrap();
    let table = StepTable::new(&basis, dt);
    let mut s0 = ModalState::zeros(&basis);
    let mut s1 = ModalState::zeros(&basis);
    let (mut u, mut v) = ([0.0], [0.0]);
    // bounded force: a 1 kHz harmonic plus seeded noise, |q| <= 1.5
    let big = TAU * 1000.0;
    let mut rng = SplitMix(7);
    let force =
        |k: usize, rng: &mut SplitMix| (big * (k as f64 + 0.5) * dt).sin() + 0.5 * rng.signed();
    let wd = omega * (1.0 - xi * xi).sqrt();
    let bound = 1.5 / (xi * omega * wd); // ∫|h| <= 1/(ξω ω_d)
    let start = Instant::now();
    let mut umax = 0.0f64;
    let mut ab = AlphaBeta::new(omega, xi, dt);
    let overflow_t = ab.overflow_time_s();
    let mut ab_bad_at = None;
    let mut ab_err_early = 0.0f64;
    let mut rng_ab = SplitMix(7);
    for k in 0..steps {
        let q = [force(k, &mut rng)];
        s0.predict_into(&table, &mut s1);
        s1.add_constant_forces(&basis, &table, &q);
        std::mem::swap(&mut s0, &mut s1);
        if k % 64 == 0 || k + 1 == steps {
            s0.project(&basis, &mut u, &mut v);
            umax = umax.max(u[0].abs());
            assert!(
                u[0].is_finite() && v[0].is_finite(),
                "non-finite at step {k}"
            );
        }
        if ab_bad_at.is_none() {
            let qa = force(k, &mut rng_ab);
            let ua = ab.step(qa);
            if !ua.is_finite() {
                ab_bad_at = Some((k + 1) as f64 * dt);
            } else if (k + 1) as f64 * dt <= 0.05 {
                s0.project(&basis, &mut u, &mut v);
                ab_err_early = ab_err_early.max((ua - u[0]).abs());
            }
        }
    }
    let elapsed = start.elapsed().as_secs_f64();
    s0.project(&basis, &mut u, &mut v);
    println!(
        "\n[4] {steps:e} steps of a {f} Hz, ξ {xi} mode at dt {dt:e} ({:.0} s simulated) in {elapsed:.2} s: max |u| {umax:.3e} (bound ∫|h| max|q| = {bound:.3e}), final u {:.3e}",
        steps as f64 * dt,
        u[0]
    );
    println!(
        "    α/β baseline: agrees to {ab_err_early:.1e} m until 0.05 s, first non-finite at t = {:?} s (overflow_time_s = {overflow_t:.4} s)",
        ab_bad_at
    );
    assert!(
        umax <= bound && umax > 0.1 * bound,
        "max |u| {umax} vs bound {bound}"
    );
    assert!(
        ab_err_early <= 1e-9 * umax,
        "α/β disagrees early: {ab_err_early}"
    );
    let bad = ab_bad_at.expect("α/β baseline should overflow");
    assert!(
        bad >= 0.95 * overflow_t && bad <= overflow_t + 0.02,
        "α/β went non-finite at {bad} s, overflow time {overflow_t} s"
    );
    assert!(steps as f64 * dt > 100.0 * overflow_t);
}

// ---------------------------------------------------------------------------
// 5. Fast convolution against direct quadrature; observed orders
// ---------------------------------------------------------------------------

/// Gauss points of the step, as fractions: `(1 ∓ 1/√3)/2`.
fn gauss_fractions() -> (f64, f64) {
    let r = 1.0 / 3f64.sqrt();
    ((1.0 - r) / 2.0, (1.0 + r) / 2.0)
}

#[test]
fn fast_convolution_matches_direct_quadrature() {
    use tirecontact::model::convolution::direct::direct_convolution;
    use tirecontact::model::convolution::{ModalBasis, ModalState, StepTable};
    // two points: a rank-2 residue mode, a mode shape, an overdamped and an undamped mode
    let modes = vec![
        Mode {
            freq_hz: 200.0,
            damping_ratio: 0.05,
            residue: vec![vec![0.1, 0.03], vec![0.03, 0.08]],
            shape: vec![],
        },
        Mode {
            freq_hz: 450.0,
            damping_ratio: 0.02,
            residue: vec![],
            shape: vec![0.2, -0.1],
        },
        Mode {
            freq_hz: 90.0,
            damping_ratio: 3.0,
            residue: vec![vec![0.05, 0.02], vec![0.02, 0.05]],
            shape: vec![],
        },
        Mode {
            freq_hz: 300.0,
            damping_ratio: 0.0,
            residue: vec![],
            shape: vec![0.1, 0.15],
        },
    ];
    let res: Vec<Vec<Vec<f64>>> = modes.iter().map(Mode::residue_matrix).collect();
    let green = |i: usize, j: usize, t: f64| -> f64 {
        modes
            .iter()
            .zip(&res)
            .map(|(m, a)| a[i][j] * my_h(TAU * m.freq_hz, m.damping_ratio, t).0)
            .sum()
    };
    let basis = ModalBasis::new(&modes, 2).unwrap();
    let (dt, n) = (5e-5, 300usize);
    let table = StepTable::new(&basis, dt);
    let (g1, g2) = gauss_fractions();
    let mut rng = SplitMix(2011);
    // per step, per point: constant value, and Gauss-point values of a linear force
    let qc: Vec<[f64; 2]> = (0..n).map(|_| [rng.signed(), rng.signed()]).collect();
    let ql: Vec<[[f64; 2]; 2]> = (0..n)
        .map(|_| [[rng.signed(), rng.signed()], [rng.signed(), rng.signed()]])
        .collect();
    let start = Instant::now();
    let mut worst = [0.0f64; 2];
    for (shape, w) in worst.iter_mut().enumerate() {
        // fast
        let mut s0 = ModalState::zeros(&basis);
        let mut s1 = ModalState::zeros(&basis);
        let (mut u, mut v) = ([0.0; 2], [0.0; 2]);
        let mut fast = Vec::with_capacity(n);
        for m in 0..n {
            s0.predict_into(&table, &mut s1);
            if shape == 0 {
                s1.add_constant_forces(&basis, &table, &qc[m]);
            } else {
                let q1 = [ql[m][0][0], ql[m][0][1]];
                let q2 = [ql[m][1][0], ql[m][1][1]];
                s1.add_gauss_forces(&basis, &table, &[0, 1], &q1, &q2);
            }
            std::mem::swap(&mut s0, &mut s1);
            s0.project(&basis, &mut u, &mut v);
            fast.push(u);
        }
        // direct: u_i = Σ_j ∫ g_ij q_j
        let (qc, ql) = (&qc, &ql);
        let force = move |j: usize| {
            move |m: usize, s: f64| -> f64 {
                if shape == 0 {
                    qc[m][j]
                } else {
                    let (a, b) = (ql[m][0][j], ql[m][1][j]);
                    a + (b - a) * (s / dt - g1) / (g2 - g1)
                }
            }
        };
        let mut scale = 0.0f64;
        let mut err = 0.0f64;
        for i in 0..2 {
            let d0 = direct_convolution(|t| green(i, 0, t), force(0), dt, n, 2);
            let d1 = direct_convolution(|t| green(i, 1, t), force(1), dt, n, 2);
            for m in 0..n {
                let d = d0[m] + d1[m];
                scale = scale.max(d.abs());
                err = err.max((fast[m][i] - d).abs());
            }
        }
        *w = err / scale;
    }
    println!(
        "\n[5] fast vs direct quadrature, 2 points, 4 modes (ξ 0.05 rank 2, 0.02, 3, 0), {n} steps of {dt:e} s, seeded random forces:\n    piecewise-constant max rel diff {:.2e}, linear (Gauss points) {:.2e}  ({:.2} s)",
        worst[0],
        worst[1],
        start.elapsed().as_secs_f64()
    );
    assert!(worst[0] < 1e-12, "piecewise-constant: {:e}", worst[0]);
    assert!(worst[1] < 1e-12, "linear: {:e}", worst[1]);
}

/// Response from rest to `cos(Ωt + φ)`.
fn my_harmonic_phase(omega: f64, xi: f64, big: f64, phi: f64, t: f64) -> f64 {
    let (hr, hi) = my_receptance(omega, xi, big);
    // H e^{iφ}
    let (c0, s0) = (phi.cos(), phi.sin());
    let (pr, pi) = (hr * c0 - hi * s0, hr * s0 + hi * c0);
    let (s, c) = (big * t).sin_cos();
    let steady = pr * c - pi * s;
    let (u0, ud0) = (pr, -big * pi);
    let (h, hd) = my_h(omega, xi, t);
    steady - u0 * (hd + 2.0 * xi * omega * h) - ud0 * h
}

#[test]
fn smooth_force_orders_of_the_force_shapes() {
    use tirecontact::model::convolution::{ModalBasis, ModalState, StepTable};
    let (f, xi) = (200.0, 0.05);
    let omega = TAU * f;
    let modes = [Mode {
        freq_hz: f,
        damping_ratio: xi,
        residue: vec![vec![1.0]],
        shape: vec![],
    }];
    let basis = ModalBasis::new(&modes, 1).unwrap();
    // q = 0.2 + sin(2π 150 t) + 0.5 cos(2π 370 t + 0.3), exact response in closed form
    let (b1, b2) = (TAU * 150.0, TAU * 370.0);
    let q = |t: f64| 0.2 + (b1 * t).sin() + 0.5 * (b2 * t + 0.3).cos();
    let exact = |t: f64| {
        0.2 * my_step(omega, xi, t)
            + my_harmonic_phase(omega, xi, b1, -std::f64::consts::FRAC_PI_2, t)
            + 0.5 * my_harmonic_phase(omega, xi, b2, 0.3, t)
    };
    let t_end: f64 = 0.02;
    let dts: [f64; 4] = [2e-4, 1e-4, 5e-5, 2.5e-5];
    let (g1, g2) = gauss_fractions();
    let mut errs = [[0.0f64; 4]; 3];
    for (kd, &dt) in dts.iter().enumerate() {
        let n = (t_end / dt).round() as usize;
        let table = StepTable::new(&basis, dt);
        for (shape, row) in errs.iter_mut().enumerate() {
            let mut s0 = ModalState::zeros(&basis);
            let mut s1 = ModalState::zeros(&basis);
            let (mut u, mut v) = ([0.0], [0.0]);
            let (mut e, mut scale) = (0.0f64, 0.0f64);
            for m in 0..n {
                let t = m as f64 * dt;
                s0.predict_into(&table, &mut s1);
                match shape {
                    // piecewise constant, sampled at the step start
                    0 => s1.add_constant_forces(&basis, &table, &[q(t)]),
                    // linear through the step ends
                    1 => {
                        let (qa, qb) = (q(t), q(t + dt));
                        let q1 = [qa + (qb - qa) * g1];
                        let q2 = [qa + (qb - qa) * g2];
                        s1.add_gauss_forces(&basis, &table, &[0], &q1, &q2);
                    }
                    // linear through the Gauss points
                    _ => s1.add_gauss_forces(
                        &basis,
                        &table,
                        &[0],
                        &[q(t + g1 * dt)],
                        &[q(t + g2 * dt)],
                    ),
                }
                std::mem::swap(&mut s0, &mut s1);
                s0.project(&basis, &mut u, &mut v);
                let x = exact(t + dt);
                e = e.max((u[0] - x).abs());
                scale = scale.max(x.abs());
            }
            row[kd] = e / scale;
        }
    }
    println!(
        "\n[5b] smooth force, 200 Hz ξ 0.05 mode, 20 ms: max rel error against the closed form"
    );
    println!("    shape                    dt=2e-4     1e-4        5e-5        2.5e-5      orders");
    let names = [
        "piecewise constant (start)",
        "linear through ends",
        "linear through Gauss pts",
    ];
    let expected = [(0.8, 1.3), (1.8, 2.3), (3.7, 4.5)];
    for (s, row) in errs.iter().enumerate() {
        let orders: Vec<f64> = (1..4).map(|k| order(row[k - 1], row[k], 2.0)).collect();
        println!(
            "    {:26} {:.3e}  {:.3e}  {:.3e}  {:.3e}  {:.2?}",
            names[s], row[0], row[1], row[2], row[3], orders
        );
        for &o in &orders {
            assert!(
                o >= expected[s].0 && o <= expected[s].1,
                "{}: order {o:.2} outside {:?} (errors {row:?})",
                names[s],
                expected[s]
            );
        }
    }
}

// ---------------------------------------------------------------------------
// 6. Impulse, step and harmonic responses of every damping regime
// ---------------------------------------------------------------------------

const REGIMES: [f64; 6] = [0.0, 0.05, 1.0, 1.0 - 1e-9, 1.0 + 1e-9, 3.0];

#[test]
fn impulse_and_step_responses_every_regime() {
    use tirecontact::base::modal::{ModalMode, unit_impulse};
    use tirecontact::model::convolution::{ModalBasis, ModalState, StepTable, mode_step};
    let omega = TAU * 150.0;
    let mut worst = [0.0f64; 6];
    for &xi in &REGIMES {
        let mode = ModalMode {
            omega_rad_s: omega,
            damping_ratio: xi,
            residue: vec![1.0],
        };
        // closed forms at ωt from 1e-4 to 40
        for k in 0..=200 {
            let wt = 1e-4 * (4e5f64).powf(k as f64 / 200.0);
            let t = wt / omega;
            let (h, hd) = my_h(omega, xi, t);
            // dimensionless amplitude envelope |ωh| + |h'| (never zero), times
            // 1 + ωt for the round-off of the phase
            let env = (h.abs() * omega + hd.abs()) * (1.0 + wt);
            let (h2, hd2) = unit_impulse(omega, xi, t);
            let eh = (h2 - h).abs() * omega / env;
            let ed = (hd2 - hd).abs() / env;
            let es =
                (mode.step_response(t) - my_step(omega, xi, t)).abs() * omega * omega / (1.0 + wt);
            // the step tables are built by doubling: their errors are
            // round-off of the peak |ωh| + |h'| = O(1), not of the local value
            let ms = mode_step(omega, xi, t);
            let peak = 1.0 + wt;
            let emh = ((ms.h[0] - h).abs() * omega + (ms.h[1] - hd).abs()) / peak;
            let emw = (ms.w_const[0] - my_step(omega, xi, t)).abs() * omega * omega / peak
                + (ms.w_const[1] - h).abs() * omega / peak;
            for (w, e) in worst.iter_mut().zip([eh, ed, es, emh, emw, 0.0]) {
                *w = w.max(e);
            }
            assert!(
                eh < 1e-13 && ed < 1e-13 && es < 1e-13 && emh < 1e-12 && emw < 1e-12,
                "ξ {xi} ωt {wt:.3e}: h {h2:e} vs {h:e}, h' {hd2:e} vs {hd:e}, step {:e} vs {:e}, mode_step h {:?} w_const {:?}",
                mode.step_response(t),
                my_step(omega, xi, t),
                ms.h,
                ms.w_const
            );
        }
        // the recursion itself: impulse and step responses stepped over 2000 steps
        let modes = [Mode {
            freq_hz: omega / TAU,
            damping_ratio: xi,
            residue: vec![vec![1.0]],
            shape: vec![],
        }];
        let basis = ModalBasis::new(&modes, 1).unwrap();
        let dt = 0.02 / omega;
        let table = StepTable::new(&basis, dt);
        let mut imp = ModalState::zeros(&basis);
        imp.add_impulses(&basis, &[0], &[1.0]);
        let mut stp = ModalState::zeros(&basis);
        let mut tmp = ModalState::zeros(&basis);
        let (mut u, mut v) = ([0.0], [0.0]);
        for m in 1..=2000 {
            let t = m as f64 * dt;
            let wt = omega * t;
            imp.predict_into(&table, &mut tmp);
            std::mem::swap(&mut imp, &mut tmp);
            stp.predict_into(&table, &mut tmp);
            tmp.add_constant_forces(&basis, &table, &[1.0]);
            std::mem::swap(&mut stp, &mut tmp);
            let (h, hd) = my_h(omega, xi, t);
            // stepped errors are round-off of the peak (|ωh| + |h'| <= √2)
            let env = 1.0 + wt;
            imp.project(&basis, &mut u, &mut v);
            let e_imp = ((u[0] - h).abs() * omega + (v[0] - hd).abs()) / env;
            stp.project(&basis, &mut u, &mut v);
            let e_stp = (u[0] - my_step(omega, xi, t)).abs() * omega * omega / (1.0 + wt)
                + (v[0] - h).abs() * omega / env;
            worst[5] = worst[5].max(e_imp).max(e_stp);
            assert!(
                e_imp < 1e-12 && e_stp < 1e-12,
                "recursion ξ {xi} step {m}: impulse ({}, {}) vs ({h:e}, {hd:e}); step u {} vs {}",
                u[0],
                v[0],
                u[0],
                my_step(omega, xi, t)
            );
        }
    }
    println!(
        "\n[6] impulse/step responses, ξ in {REGIMES:?}: worst scaled errors h {:.1e}, h' {:.1e}, step {:.1e}, mode_step h {:.1e}, weights {:.1e}, stepped recursion {:.1e}",
        worst[0], worst[1], worst[2], worst[3], worst[4], worst[5]
    );
}

#[test]
fn harmonic_responses_every_regime() {
    use tirecontact::base::modal::ModalModel;
    use tirecontact::model::convolution::{ModalBasis, ModalState, StepTable};
    let f = 150.0;
    let omega = TAU * f;
    let mut worst = (0.0f64, 0.0f64);
    for &xi in &REGIMES {
        let modes = [Mode {
            freq_hz: f,
            damping_ratio: xi,
            residue: vec![vec![0.7]],
            shape: vec![],
        }];
        let model = ModalModel::from_modes(&modes, 1);
        for ratio in [0.0, 0.3, 0.97, 1.0, 1.6, 7.0] {
            if xi == 0.0 && ratio == 1.0 {
                continue;
            }
            let (hr, hi) = my_receptance(omega, xi, ratio * omega);
            let g = model.frequency_response(0, 0, ratio * f);
            let e = ((g.re - 0.7 * hr).powi(2) + (g.im - 0.7 * hi).powi(2)).sqrt()
                / (0.7 * hr.hypot(hi));
            worst.0 = worst.0.max(e);
            assert!(
                e < 1e-13,
                "G(ω) ξ {xi} Ω/ω {ratio}: {g:?} vs 0.7 × ({hr}, {hi})"
            );
        }
        // time domain: cos(Ωt) from rest through the recursion (Gauss-point force shape)
        let basis = ModalBasis::new(&modes, 1).unwrap();
        let dt = 0.01 / omega;
        let table = StepTable::new(&basis, dt);
        let (g1, g2) = gauss_fractions();
        for ratio in [0.4, 1.3, 3.0] {
            let big = ratio * omega;
            let mut s0 = ModalState::zeros(&basis);
            let mut s1 = ModalState::zeros(&basis);
            let (mut u, mut v) = ([0.0], [0.0]);
            let (mut e, mut scale) = (0.0f64, 0.0f64);
            for m in 0..6000 {
                let t = m as f64 * dt;
                s0.predict_into(&table, &mut s1);
                s1.add_gauss_forces(
                    &basis,
                    &table,
                    &[0],
                    &[(big * (t + g1 * dt)).cos()],
                    &[(big * (t + g2 * dt)).cos()],
                );
                std::mem::swap(&mut s0, &mut s1);
                s0.project(&basis, &mut u, &mut v);
                let x = 0.7 * my_harmonic(omega, xi, big, t + dt);
                e = e.max((u[0] - x).abs());
                scale = scale.max(x.abs());
            }
            worst.1 = worst.1.max(e / scale);
            assert!(
                e < 1e-7 * scale,
                "harmonic ξ {xi} Ω/ω {ratio}: max err {e:e} of {scale:e}"
            );
        }
    }
    println!(
        "\n[6b] harmonic: G(ω) vs 1/(ω²-Ω²+2iξωΩ) worst rel {:.1e}; time-domain response to cos(Ωt) from rest (ωdt 0.01, ωt to 60) worst rel {:.1e}",
        worst.0, worst.1
    );
}

// ---------------------------------------------------------------------------
// 1b. One point, two modes: contact no longer fixes the whole state
// ---------------------------------------------------------------------------

/// With one mode, contact imposes the whole state `(u, v) = (r, r')`, so the
/// located scheme's errors are erased at every landing (test 1 reaches
/// round-off). A second mode leaves an internal coordinate free while in
/// contact: this is the one-point case where the order can be observed.
#[test]
fn one_point_two_modes_against_event_driven_reference() {
    let duration: f64 = 0.3;
    let modes = vec![
        Mode {
            freq_hz: 100.0,
            damping_ratio: 0.05,
            residue: vec![],
            shape: vec![0.1f64.sqrt()],
        },
        Mode {
            freq_hz: 230.0,
            damping_ratio: 0.05,
            residue: vec![],
            shape: vec![0.03f64.sqrt()],
        },
    ];
    let h = -0.001;
    let road = SineRoad {
        a: 0.002,
        k: TAU / 0.5,
        v: 20.0,
        x0: 0.0,
        h,
        ramp: 0.05,
    };
    let t0 = Instant::now();
    let refsys = MultiReference::new(&modes, vec![road]);
    let grid = 5e-6;
    let n = (duration / grid).round() as usize;
    let (reference, st) = refsys.solve(grid, n, REF_SUB, 1e-8);
    let (check, _) = refsys.solve(grid, n, REF_SUB / 2, 1e-8);
    let ref_err = rel_rms(&reference, &check);
    println!(
        "\n[1b] one point, two modes (100 Hz A 0.1, 230 Hz A 0.03, ξ 0.05), same road: reference {} impacts, {} releases, differs from RK4 h x 2 by {ref_err:.1e} ({:.2} s)",
        st.impacts,
        st.releases,
        t0.elapsed().as_secs_f64()
    );
    assert!(ref_err < 1e-11, "reference not converged: {ref_err:e}");
    assert!(
        st.impacts >= 5 && st.releases >= 5,
        "must lose and regain contact"
    );
    // coarser than test 1: the located errors reach the reference's floor
    // (~1e-11) already near dt = 1e-5
    let dts = [1.6e-4, 8e-5, 4e-5, 2e-5, 1e-5];
    let mut errs = Vec::new();
    for scheme in [ContactScheme::Located, ContactScheme::Paper] {
        let e: Vec<f64> = dts
            .iter()
            .map(|&dt| {
                let sc = modal_scene(
                    modes.clone(),
                    vec![Point {
                        x_m: 0.0,
                        y_m: 0.0,
                        h_m: h,
                    }],
                    sine(0.002, 0.5),
                    20.0,
                    0.05,
                    dt,
                    duration,
                    scheme,
                );
                rms_err_vs_ref(&run(&sc), &reference, grid)
            })
            .collect();
        let orders: Vec<f64> = (1..e.len()).map(|k| order(e[k - 1], e[k], 2.0)).collect();
        println!(
            "    {:8} disp err {e:?}  orders {orders:.2?}",
            format!("{scheme:?}")
        );
        errs.push(e);
    }
    let (loc, pap) = (&errs[0], &errs[1]);
    // an error within 3x the reference's own uncertainty cannot show an order
    let floor = 3.0 * ref_err;
    println!("    (errors below {floor:.1e} are at the reference's floor)");
    for k in 1..loc.len() {
        let o = order(loc[k - 1], loc[k], 2.0);
        assert!(
            o >= 1.8 || loc[k] <= floor,
            "Located order {o:.2} between dt {} and {} (errors {loc:?}, floor {floor:e})",
            dts[k - 1],
            dts[k]
        );
    }
    let last = loc.len() - 1;
    assert!(
        10.0 * loc[last] <= pap[last],
        "Located {:.3e} not 10x below Paper {:.3e}",
        loc[last],
        pap[last]
    );
}

// ---------------------------------------------------------------------------
// 5. Compliant contact (tread springs) against an RK4 solution of the ODEs
// ---------------------------------------------------------------------------

/// The modal equations with tread springs, integrated by RK4 in modal
/// coordinates (no convolution, no Green function):
/// `η_k'' + 2ξ_k ω_k η_k' + ω_k² η_k = Σ_j φ_k[j] q_j`, `u_i = Σ_k φ_k[i] η_k`,
/// `q_j = k_j max(0, r_j(t) - u_j)`. The force's slope jumps where a spring
/// starts or stops being compressed: an RK4 step across that would lose its
/// order, so every step is cut where a compression `r - u` changes sign
/// (bisected to the last bit), and each piece has a smooth right-hand side.
struct CompliantReference {
    /// `phi[k][i]`.
    phi: Vec<Vec<f64>>,
    omega: Vec<f64>,
    xi: Vec<f64>,
    roads: Vec<SineRoad>,
    k_n_m: Vec<f64>,
}

impl CompliantReference {
    /// The ODEs of a scene with modes given by shapes, a sine road and
    /// compliant contact.
    fn of(sc: &Scene) -> Self {
        let Tyre::Modal { modes } = &sc.tyre else {
            panic!("a modal tyre")
        };
        let Road::Sine {
            amplitude_m,
            wavelength_m,
        } = sc.road
        else {
            panic!("a sine road")
        };
        let p = sc.points.len();
        let k_n_m = sc.contact.stiffness_per_point(p);
        assert_eq!(k_n_m.len(), p, "compliant contact");
        CompliantReference {
            phi: modes.iter().map(|m| m.shape.clone()).collect(),
            omega: modes.iter().map(|m| TAU * m.freq_hz).collect(),
            xi: modes.iter().map(|m| m.damping_ratio).collect(),
            roads: sc
                .points
                .iter()
                .map(|pt| SineRoad {
                    a: amplitude_m,
                    k: TAU / wavelength_m,
                    v: sc.speed_mps,
                    x0: pt.x_m,
                    h: pt.h_m,
                    ramp: sc.ramp_s,
                })
                .collect(),
            k_n_m,
        }
    }

    fn displacements(&self, y: &[f64]) -> Vec<f64> {
        (0..self.roads.len())
            .map(|i| self.phi.iter().zip(y).map(|(f, x)| f[i] * x).sum())
            .collect()
    }

    /// Compressions `r_i - u_i` of the springs at `t`.
    fn compressions(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let u = self.displacements(y);
        self.roads
            .iter()
            .zip(&u)
            .map(|(road, u)| road.eval(t).0 - u)
            .collect()
    }

    /// `dy/dt` of `y = (η, η')`.
    fn rate(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let m = self.omega.len();
        let q: Vec<f64> = self
            .compressions(t, y)
            .iter()
            .zip(&self.k_n_m)
            .map(|(c, k)| k * c.max(0.0))
            .collect();
        let mut d = vec![0.0; 2 * m];
        for k in 0..m {
            let force: f64 = self.phi[k].iter().zip(&q).map(|(f, q)| f * q).sum();
            d[k] = y[m + k];
            d[m + k] = force
                - 2.0 * self.xi[k] * self.omega[k] * y[m + k]
                - self.omega[k] * self.omega[k] * y[k];
        }
        d
    }

    fn rk4(&self, t: f64, y: &[f64], h: f64) -> Vec<f64> {
        let at = |y0: &[f64], d: &[f64], s: f64| -> Vec<f64> {
            y0.iter().zip(d).map(|(a, b)| a + s * b).collect()
        };
        let k1 = self.rate(t, y);
        let k2 = self.rate(t + 0.5 * h, &at(y, &k1, 0.5 * h));
        let k3 = self.rate(t + 0.5 * h, &at(y, &k2, 0.5 * h));
        let k4 = self.rate(t + h, &at(y, &k3, h));
        (0..y.len())
            .map(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
            .collect()
    }

    /// `y` advanced from `t` by `h`, cut where a compression changes sign;
    /// returns the number of cuts.
    fn advance(&self, t: f64, y: &mut Vec<f64>, h: f64) -> usize {
        let (mut t, mut left, mut cuts) = (t, h, 0);
        loop {
            let end = self.rk4(t, y, left);
            let c0 = self.compressions(t, y);
            let flips = |c1: &[f64]| c0.iter().zip(c1).any(|(a, b)| (*a > 0.0) != (*b > 0.0));
            if !flips(&self.compressions(t + left, &end)) {
                *y = end;
                return cuts;
            }
            // the first sign change: a step of `hi` has one, of `lo` none
            let (mut lo, mut hi) = (0.0, left);
            loop {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if flips(&self.compressions(t + mid, &self.rk4(t, y, mid))) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            *y = self.rk4(t, y, hi);
            t += hi;
            left -= hi;
            cuts += 1;
            if left <= 1e-15 * h {
                return cuts;
            }
        }
    }

    /// Displacements at `grid`, `2 grid`, … (`n` samples), `sub` RK4 steps
    /// per sample; and the number of sign changes of the compressions.
    fn solve(&self, grid: f64, n: usize, sub: usize) -> (Vec<Vec<f64>>, usize) {
        let m = self.omega.len();
        let mut y = vec![0.0; 2 * m];
        let (mut out, mut cuts) = (Vec::with_capacity(n), 0);
        let h = grid / sub as f64;
        for s in 0..n {
            for j in 0..sub {
                cuts += self.advance((s * sub + j) as f64 * h, &mut y, h);
            }
            out.push(self.displacements(&y));
        }
        (out, cuts)
    }
}

/// Compliant contact converges at second order to the solution of its
/// ODEs, with the spring law applied only while a spring is compressed
/// (landings and releases located inside the step; method §4, "Events inside
/// the step"): never a pulling step-mean force. On a bouncing point whose
/// stiff tread (5e7 N/m) throws it off the road at every crest, and on the
/// three coupled points of `presets/three_points.ron` on the same tread.
#[test]
fn compliant_contact_converges_to_rk4_reference() {
    let one_point = Scene::parse(
        "Scene(name: \"one\", tyre: Modal(modes: [Mode(freq_hz: 100.0, damping_ratio: 0.05, shape: [0.3162])]),
          points: [Point(x_m: 0.0, h_m: -0.0005)], road: Sine(amplitude_m: 0.001, wavelength_m: 0.15),
          speed_mps: 25.0, ramp_s: 0.02, dt_s: 1e-5, duration_s: 0.1,
          contact: Compliant(stiffness_n_m: [5e7]))",
        "one point",
    )
    .unwrap();
    let mut three = Scene::parse(
        &std::fs::read_to_string("presets/three_points.ron")
            .unwrap()
            .replace(
                "contact_scheme: Located",
                "contact: Compliant(stiffness_n_m: [5e7])",
            ),
        "three points",
    )
    .unwrap();
    three.duration_s = 0.05;
    let dts = [8e-5, 4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6, 1.25e-6];
    let grid = 1.25e-6;
    // (case, error bound at dt = 1e-5: measured 1.4e-4 and 2.0e-4 relative)
    for (name, base, bound) in [
        ("one point", &one_point, 2e-4),
        ("three points", &three, 3e-4),
    ] {
        let t0 = Instant::now();
        let refsys = CompliantReference::of(base);
        let n = (base.duration_s / grid).round() as usize;
        let (reference, cuts) = refsys.solve(grid, n, 8);
        let (check, _) = refsys.solve(grid, n, 4);
        let ref_err = rel_rms(&reference, &check);
        println!(
            "\n[5] compliant contact, {name}: RK4 reference with {cuts} landings and releases, differs from RK4 h x 2 by {ref_err:.1e} ({:.2} s)",
            t0.elapsed().as_secs_f64()
        );
        assert!(ref_err < 1e-9, "reference not converged: {ref_err:e}");
        assert!(cuts >= 10, "{name}: must land and take off repeatedly");
        println!("    dt        disp err    order   lowest/largest step-mean force   events");
        let mut errs: Vec<f64> = Vec::new();
        for &dt in &dts {
            let mut sc = base.clone();
            sc.dt_s = dt;
            let r = run(&sc);
            let e = rms_err_vs_ref(&r, &reference, grid);
            let largest = r.q.iter().flatten().fold(0.0f64, |m, q| m.max(q.abs()));
            let lowest = r.q.iter().flatten().fold(0.0f64, |m, &q| m.min(q));
            let o = errs.last().map_or("   -  ".to_string(), |&c| {
                format!("{:6.2}", order(c, e, 2.0))
            });
            println!(
                "    {dt:.3e}  {e:9.3e}  {o}   {:10.3e}                       {}",
                lowest / largest,
                r.events.iter().sum::<u32>()
            );
            assert!(
                lowest >= -1e-9 * largest,
                "{name}, dt {dt}: step-mean force {lowest:.3e} N pulls (largest {largest:.3e} N)"
            );
            errs.push(e);
        }
        for k in 1..dts.len() {
            let o = order(errs[k - 1], errs[k], 2.0);
            assert!(
                o >= 1.8,
                "{name}: order {o:.2} between dt {} and {} ({errs:?})",
                dts[k - 1],
                dts[k]
            );
        }
        let e5 = errs[3];
        assert!(
            e5 <= bound,
            "{name}: displacement error {e5:.3e} at dt 1e-5 above {bound:e}"
        );
    }
}
