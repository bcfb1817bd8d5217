//! Compliant contact: a tread spring of stiffness `k_i` (N/m) in series
//! with the tyre at each point, beside the paper's rigid kinematic contact
//! (method §4), which stays the default.
//!
//! The force is the spring's compression, `q_i = k_i max(0, r_i - u_i)`.
//! Over a step, or over the part of it between two events, the force is
//! linear, given by its values `q1`, `q2` at the Gauss points with the exact
//! weights (method §3-4), so that the end values are
//! `u_e = u_h + Gx1 q1 + Gx2 q2`, `v_e = v_h + Gv1 q1 + Gv2 q2`. A point in
//! the active set `S` satisfies the spring law in value and rate at the end:
//!
//! ```text
//! u_e,i + q_e,i / k_i = r_i(t + τ),      q_e = -GB q1 + GA q2          (end value)
//! v_e,i + q'_i  / k_i = dr_i/dt(t + τ),  q'  = √3 (q2 - q1) / τ         (slope)
//! ```
//!
//! i.e. the rigid Gauss-point system of method §4 plus a diagonal compliance
//! term, which vanishes as `k → ∞`: the scheme tends to the rigid one
//! algebraically, whatever `k dt² / m` (no stability limit from the spring).
//!
//! The spring law holds only while the spring is compressed, so the step
//! is split at its events as the rigid contact's is (method §4, "Events
//! inside the step"; the loop of `events.rs`): a free point lands where the
//! cubic (Hermite) interpolant of its gap `u - r` first crosses zero, and
//! joins the active set there with no impulse (the spring has no mass: its
//! force starts from zero and the velocity is continuous); an active point
//! is released where its trial linear force crosses zero, the force up to
//! there being the trial's, restricted (a spring the step does not resolve
//! is released only at once, see [`Simulation::spring_unresolved`]). Every
//! piece of a step then carries a force that is non-negative on average,
//! and so does the step: its mean force never pulls. Applying the spring
//! law over the whole step instead (deciding contact at the step end only)
//! puts a tensile force on the part of a landing step before the touch:
//! negative step means at landings (down to -0.9 % of the peak force at
//! `dt = 1e-5` on a point bouncing off a 5e7 N/m tread), and an erratic
//! convergence. Steps without an event are one full-step solve with the
//! set carried over ([`Simulation::compliant_steady_step`]).
//!
//! The error is second order in `dt` and comes from inside the contacts:
//! the linear force through the end conditions follows the contact's own
//! oscillation (frequency `sqrt(ω² + k ΣA)`) to `O(dt²)`; the located events
//! are not what limits it (`tests/solver/contact.rs` measures the orders
//! against an RK4 solution of the modal equations).
//!
//! The spring is undamped and massless: a landing point whose impact is
//! resolved in time (`sqrt(k ΣA) dt` small) bounces elastically off it,
//! whereas the rigid contact is perfectly inelastic. The compliant solution
//! therefore tends to the rigid one as `k` grows for points that stay in
//! contact (`u = r - q / k`, an `O(1/k)` difference), not through impacts.

use super::active_set::ActiveSetRule;
use super::{GA, GB, SQRT3, Simulation, Table, crosses};
use crate::solver::error::SolverError;

/// The compliant step-end rule (method §4.6): a point enters where the
/// free prediction leaves its spring compressed; a point may leave only if
/// its linear force also ends negative (a landing late in the interval has
/// a negative mean but a positive end; an unresolved stiff impulse can end
/// negative with a positive mean); the compliant Gauss-point solve.
pub(super) struct CompliantRule;

impl ActiveSetRule for CompliantRule {
    const FIRST_OF_EQUALLY_DEEP: bool = false;

    fn start_set(sim: &mut Simulation) {
        sim.ensure_projected_all();
        let (st, s) = (&mut sim.state, &sim.scratch);
        st.active.clear();
        for i in 0..sim.tables.p {
            if s.re[i] - s.uh[i] > 0.0 {
                st.active.push(i);
            }
        }
    }

    #[inline]
    fn may_release(q1: f64, q2: f64) -> bool {
        -GB * q1 + GA * q2 < 0.0
    }

    fn solve(sim: &mut Simulation, t_end: f64, sel: Table) -> Result<(), SolverError> {
        // (through `solve_contact`, as the paper's rule: no end state of
        // an earlier, larger set's solve is left to `commit`)
        sim.solve_contact(t_end, sel)
    }
}

impl Simulation {
    /// The step from `t0` when it has no event, as most are: the springs
    /// in compression at the start stay so over the whole step, which is
    /// one full-step solve (its factorisation reused while the set holds).
    /// `Some(solves)` once committed; `None`, with only scratch values
    /// changed, when a free spring starts compressed, a trial force would
    /// pull, or a free point lands inside the step: the step is then
    /// [`Simulation::located_step`]'s, whose first trial is this one again
    /// (the same prediction and solve, so the same values, bit for bit, as
    /// when that loop takes a step without events).
    pub(super) fn compliant_steady_step(&mut self, t0: f64) -> Result<Option<u32>, SolverError> {
        let (p, dt) = (self.tables.p, self.tables.dt_s);
        self.scratch.merged.trial_ready = false;
        self.state.active.clear();
        for i in 0..p {
            if self.state.contact[i] {
                self.state.active.push(i);
            } else if self.state.u[i] - self.state.r[i] < -self.pen_tol_m {
                return Ok(None);
            }
        }
        self.predict(t0, dt, Table::Full)?;
        self.solve_compliant(t0 + dt, Table::Full)?;
        self.scratch.merged.trial_ready = true;
        for &j in &self.state.active {
            let (q1, q2) = (self.scratch.q1[j], self.scratch.q2[j]);
            let (qs, qe) = (GA * q1 - GB * q2, -GB * q1 + GA * q2);
            if qs + qe < 0.0 || qe < 0.0 && !self.spring_unresolved(j, dt) {
                return Ok(None);
            }
        }
        let (st, s) = (&self.state, &self.scratch);
        let (u, v, r, rd) = (&st.u[..p], &st.v[..p], &st.r[..p], &st.rd[..p]);
        let (ue, ve, re, rde) = (&s.ue[..p], &s.ve[..p], &s.re[..p], &s.rde[..p]);
        for i in 0..p {
            if st.contact[i] {
                continue;
            }
            let (g0, d0) = (u[i] - r[i], (v[i] - rd[i]) * dt);
            let (g1, d1) = (ue[i] - re[i], (ve[i] - rde[i]) * dt);
            if crosses(g0, d0, g1, d1, self.pen_tol_m, st.released[i]) {
                return Ok(None);
            }
        }
        self.commit(dt, Table::Full);
        Ok(Some(!self.state.active.is_empty() as u32))
    }

    /// Whether the tread spring of point `j` is stiffer than a (sub-)step
    /// of `tau_s` resolves: `tau_s sqrt(k_j J_jj) > 1`, with `J_jj` the
    /// velocity the point takes per unit impulse (`g'_jj(0+)`, method §2), so
    /// that the contact's own half period `π / sqrt(k_j J_jj)` is shorter
    /// than about three such steps. The trial force is then an impulse's
    /// two values, not the spring's force: its end may be negative under a
    /// positive mean, where the spring has not let go (releasing there
    /// throws the point off the road with the impulse's positive part).
    /// Such a spring is released only if its mean force pulls, at the start
    /// of the (sub-)step, and the step tends to the rigid one as `k` grows.
    #[inline]
    pub(super) fn spring_unresolved(&self, j: usize, tau_s: f64) -> bool {
        tau_s * tau_s * self.tables.tread_k_n_m[j] * self.tables.jump[j * self.tables.p + j] > 1.0
    }

    /// The step-end rule over `[t, t + tau]` (the fallback of a cascade of
    /// events, as the paper's rule is for rigid contact), in the loop of
    /// `active_set.rs` with [`CompliantRule`]: candidates are the points
    /// the free prediction leaves compressed (`r_e - u_h > 0`); a point
    /// whose step-mean force `(q1 + q2)/2` and end force `q_e` are both
    /// negative is released (the most negative mean first) and not
    /// re-added in that step; a free point compressed by its neighbours'
    /// forces is added; at most `2P` solves. A point still pulling on
    /// average then (a landing late in the interval) is let go, its force
    /// zeroed: the mean force never pulls, the compression is corrected by
    /// the next step. Returns the number of solves.
    pub(super) fn compliant_substep(
        &mut self,
        t: f64,
        tau: f64,
        sel: Table,
    ) -> Result<u32, SolverError> {
        self.step_end_rule::<CompliantRule>(t, tau, sel)
    }

    /// Solves the compliant Gauss-point system of `active` (after `predict`
    /// over `sel`) and the end values of every point into `ue`, `ve`. Over
    /// the full step the factorisation is reused while the active set is
    /// unchanged (the full-step operator of a compliant run is always the
    /// compliant one); over a sub-step it is the rigid sub-step solve with
    /// the tread compliance on the diagonal ([`Simulation::fill_sub_block`]).
    pub(super) fn solve_compliant(&mut self, t_end: f64, sel: Table) -> Result<(), SolverError> {
        let large =
            self.tables.large_sets() && self.state.active.len() >= self.tables.large_set_from();
        if sel == Table::Sub {
            if self.iterative_sub_step() && self.solve_sub_iterative() {
                return Ok(());
            }
            return self.solve_active(t_end, Table::Sub);
        }
        if large && self.tables.options.reuse_factorisation {
            return self.solve_full_large(t_end);
        }
        let n = self.state.active.len();
        let p = self.tables.p;
        let s = &mut self.scratch;
        s.ue.copy_from_slice(&s.uh);
        s.ve.copy_from_slice(&s.vh);
        if n == 0 {
            return Ok(());
        }
        let reuse = self.tables.options.reuse_factorisation
            && self.factors.factored
            && self.factors.current.set == self.state.active;
        if !reuse {
            self.state.stats.factorisations += 1;
            let act = &self.state.active;
            let g = &self.tables.full_inf;
            let kk = &self.tables.tread_k_n_m;
            let rate = SQRT3 / self.tables.dt_s;
            let blocks = [&g.gx1, &g.gx2, &g.gv1, &g.gv2];
            // compliance of the end value (row block 0) and slope (row block 1)
            let diag = [[-GB, GA], [-rate, rate]];
            let entry = |r: usize, c: usize| {
                let (rb, cb) = ((r >= n) as usize, (c >= n) as usize);
                let (i, j) = (act[r % n], act[c % n]);
                let mut a = blocks[2 * rb + cb][i * p + j];
                if i == j {
                    a += diag[rb][cb] / kk[i];
                }
                a
            };
            let res = self.factors.current.solver.factor(2 * n, entry);
            self.factors.factored = res.is_ok();
            self.factors.current.set.clone_from(&self.state.active);
            if let Err(e) = res {
                return Err(SolverError::SingularContactSystem {
                    t_s: t_end,
                    points: self.state.active.clone(),
                    pivot: e.pivot,
                });
            }
        }
        let (active, s) = (&self.state.active, &mut self.scratch);
        for (k, &i) in active.iter().enumerate() {
            s.rhs[k] = s.re[i] - s.uh[i];
            s.rhs[n + k] = s.rde[i] - s.vh[i];
        }
        self.factors.current.solver.solve(&mut s.rhs[..2 * n]);
        s.q1.fill(0.0);
        s.q2.fill(0.0);
        for (k, &j) in active.iter().enumerate() {
            s.q1[j] = s.rhs[k];
            s.q2[j] = s.rhs[n + k];
        }
        self.end_values_by_columns();
        Ok(())
    }

    /// Every point's end values into `ue`, `ve`: the free ones (`uh`, `vh`,
    /// projected for every point) plus the response to the active points'
    /// full-step forces, down their contiguous influence columns
    /// (`full_inf_cols`, in row blocks: `columns.rs`); each point sums its
    /// terms in the order of the active set.
    pub(super) fn end_values_by_columns(&mut self) {
        self.forces_response_by_columns();
        let s = &mut self.scratch;
        for i in 0..self.tables.p {
            s.ue[i] = s.uh[i] + s.du[i];
            s.ve[i] = s.vh[i] + s.dv[i];
        }
    }

    /// The response at every point to the active points' full-step forces
    /// into `du`, `dv` (m, m/s), down their contiguous influence columns
    /// (`full_inf_cols`, in row blocks: `columns.rs`); each point sums its
    /// terms in the order of the active set.
    pub(super) fn forces_response_by_columns(&mut self) {
        let p = self.tables.p;
        let (active, s) = (&self.state.active, &mut self.scratch);
        let (du, dv) = (&mut s.du[..p], &mut s.dv[..p]);
        du.fill(0.0);
        dv.fill(0.0);
        self.tables
            .add_set_full_step_response(active, &s.q1, &s.q2, du, dv);
    }
}

#[cfg(test)]
mod tests {
    use crate::Simulation;
    use std::f64::consts::TAU;

    const F_HZ: f64 = 100.0;
    const A_PER_KG: f64 = 0.1;

    /// One point on one mode (100 Hz, residue 0.1 /kg), preload `h`, sine road.
    fn scene(
        contact: &str,
        xi: f64,
        h_m: f64,
        amp_m: f64,
        dt_s: f64,
        duration_s: f64,
    ) -> crate::Problem {
        let text = format!(
            "Scene(name: \"c\", tyre: Modal(modes: [Mode(freq_hz: {F_HZ}, damping_ratio: {xi}, residue: [[{A_PER_KG}]])]),
              points: [Point(x_m: 0.0, h_m: {h_m})], road: Sine(amplitude_m: {amp_m}, wavelength_m: 0.5),
              speed_mps: 20.0, ramp_s: 0.02, dt_s: {dt_s}, duration_s: {duration_s}, contact: {contact})"
        );
        crate::solver::test_problem::problem(&text)
    }

    fn compliant(k: f64) -> String {
        format!("Compliant(stiffness_n_m: [{k:e}])")
    }

    /// Runs to the end; returns (t, u, r) per step after `from_s`, and the last force.
    fn run(scene: &crate::Problem, from_s: f64) -> (Vec<(f64, f64, f64)>, f64) {
        let mut sim = Simulation::new(scene, crate::SolverOptions::default()).unwrap();
        let mut out = Vec::new();
        while !sim.finished() {
            sim.step().unwrap();
            if sim.time_s() >= from_s {
                out.push((sim.time_s(), sim.displacement_m()[0], sim.road_m()[0]));
            }
        }
        (out, sim.force_n()[0])
    }

    /// Static preload on a flat road: the tyre's static compliance
    /// `c = A / ω²` in series with the tread spring: `q = |h| / (c + 1/k)`,
    /// `u = c q`.
    #[test]
    fn static_preload_matches_springs_in_series() {
        let h = -1e-3;
        let c = A_PER_KG / (TAU * F_HZ).powi(2);
        for k in [1e6, 4e6, 1e9] {
            let s = scene(&compliant(k), 0.3, h, 0.0, 1e-5, 0.25);
            let (out, q) = run(&s, 0.0);
            let u = out.last().unwrap().1;
            let q_exact = h.abs() / (c + 1.0 / k);
            let (eq, eu) = ((q / q_exact - 1.0).abs(), (u / (c * q_exact) - 1.0).abs());
            eprintln!(
                "k = {k:e}: q = {q:.6} N (exact {q_exact:.6}), rel. errors q {eq:.1e}, u {eu:.1e}"
            );
            assert!(eq < 1e-9 && eu < 1e-9, "k = {k}: q {q} vs {q_exact}, u {u}");
        }
    }

    /// A sine road at small amplitude with the point kept in contact: the
    /// tyre mode `u'' + 2ξωu' + ω²u = A q` with `q = k (r - u)` is the
    /// oscillator `u'' + 2ξωu' + (ω² + A k) u = A k r`, whose steady
    /// response to `r = |h| + a sin(Ω t)` is
    /// `u = A k |h| / (ω² + A k) + a Im(H e^{iΩt})`,
    /// `H = A k / (ω² + A k - Ω² + 2iξωΩ)`. Second order in `dt`.
    #[test]
    fn sine_road_matches_forced_response_of_combined_oscillator() {
        let (h, a, xi, k): (f64, f64, f64, f64) = (-1e-3, 1e-4, 0.3, 4e6);
        let (w, big_w) = (TAU * F_HZ, TAU * 20.0 / 0.5);
        let ak = A_PER_KG * k;
        let (re_d, im_d) = (w * w + ak - big_w * big_w, 2.0 * xi * w * big_w);
        let d2 = re_d * re_d + im_d * im_d;
        let (hr, hi) = (ak * re_d / d2, -ak * im_d / d2);
        let exact = |t: f64| {
            let (s, c) = (big_w * t).sin_cos();
            ak * h.abs() / (w * w + ak) + a * (hr * s + hi * c)
        };
        let mut errs = Vec::new();
        for dt in [2e-4, 1e-4, 5e-5] {
            let (out, _) = run(&scene(&compliant(k), xi, h, a, dt, 0.3), 0.25);
            let e = out
                .iter()
                .map(|&(t, u, _)| (u - exact(t)).abs())
                .fold(0.0, f64::max);
            eprintln!("dt = {dt:e}: max |u - u_exact| / a = {:.2e}", e / a);
            errs.push(e / a);
        }
        assert!(errs[2] < 1e-4, "{errs:?}");
        for pair in errs.windows(2) {
            let order = (pair[0] / pair[1]).log2();
            assert!(order > 1.7, "order {order:.2}: {errs:?}");
        }
    }

    /// As `k` grows the compliant solution tends to the rigid one
    /// (`u = r` while in contact): RMS difference `O(1/k)`.
    #[test]
    fn stiff_tread_tends_to_rigid_contact() {
        let (h, a, xi, dt) = (-1e-3, 2e-4, 0.05, 1e-5);
        let (rigid, _) = run(&scene("Rigid", xi, h, a, dt, 0.15), 0.05);
        let rms = |k: f64| {
            let (out, _) = run(&scene(&compliant(k), xi, h, a, dt, 0.15), 0.05);
            let s: f64 = out
                .iter()
                .zip(&rigid)
                .map(|(c, r)| (c.1 - r.1).powi(2))
                .sum();
            (s / out.len() as f64).sqrt()
        };
        let ks = [1e6, 1e9, 1e11];
        let d: Vec<f64> = ks.iter().map(|&k| rms(k)).collect();
        for (k, e) in ks.iter().zip(&d) {
            eprintln!(
                "k = {k:e}: RMS(u_compliant - u_rigid) = {e:.3e} m, x k = {:.3e} N",
                e * k
            );
        }
        assert!(d[0] > d[1] && d[1] > d[2], "{d:?}");
        // 1/k: the product stays within 10 % from 1e9 to 1e11 (static + dynamic spring force)
        let (p1, p2) = (d[1] * ks[1], d[2] * ks[2]);
        assert!((p1 / p2 - 1.0).abs() < 0.1, "{p1} vs {p2}");
    }
}

#[cfg(test)]
mod step_end_rule {
    use super::super::Table;
    use crate::Simulation;

    /// Locating events changes only the steps that have them: a step
    /// without events is the full-step solve of the springs compressed at
    /// its start, which is what the step-end rule (the scheme without event
    /// location) computes from the same state, bit for bit. Checked in lock
    /// step on three coupled points that land and take off.
    #[test]
    fn steps_without_events_are_the_step_end_rule_bit_for_bit() {
        for k in [3e6, 5e7] {
            let text = include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../presets/three_points.ron"
            ))
            .replace(
                "contact_scheme: Located",
                &format!("contact: Compliant(stiffness_n_m: [{k:e}])"),
            );
            let scene = crate::solver::test_problem::problem(&text);
            let mut a = Simulation::new(&scene, crate::SolverOptions::default()).unwrap();
            // the step-end rule, from `a`'s state at every step start
            let mut b = Simulation::new(&scene, crate::SolverOptions::default()).unwrap();
            let bits = |x: &[f64]| x.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let (mut same, mut with_events) = (0, 0);
            for step in 0..20_000 {
                let (sa, sb) = (&a.state, &mut b.state);
                sb.modal.clone_from(&sa.modal);
                for (x, y) in [(&mut sb.u, &sa.u), (&mut sb.v, &sa.v), (&mut sb.r, &sa.r)] {
                    x.clone_from(y);
                }
                sb.rd.clone_from(&sa.rd);
                (sb.t_s, sb.steps) = (sa.t_s, sa.steps);
                sb.released.fill(false);
                b.scratch.impulse.fill(0.0);
                // (every step, so that both advance their road alike)
                b.compliant_substep(b.state.t_s, b.tables.dt_s, Table::Full)
                    .unwrap();
                if a.step().unwrap().events > 0 {
                    with_events += 1;
                    continue;
                }
                // (a finished step keeps its impulses as the step's mean
                // forces, impulse / dt, and clears them)
                let inv_dt = 1.0 / b.tables.dt_s;
                let b_mean: Vec<f64> = b.scratch.impulse.iter().map(|j| j * inv_dt).collect();
                for (x, y, what) in [
                    (&a.state.u, &b.state.u, "displacements"),
                    (&a.state.v, &b.state.v, "velocities"),
                    (&a.state.q_mean, &b_mean, "mean forces"),
                ] {
                    assert_eq!(bits(x), bits(y), "k = {k:e}: {what} at step {step}");
                }
                same += 1;
            }
            eprintln!("k = {k:e}: {same} steps without events, {with_events} with");
            assert!(same > 15_000 && with_events > 20, "{same}, {with_events}");
        }
    }

    /// A cascade of events cut short by the event limit ends its step with
    /// the step-end rule, whose zeroing of a pulling mean keeps the forces
    /// from pulling there too: with the limit at zero every event step
    /// takes it.
    #[test]
    fn step_end_rule_after_the_event_limit_never_pulls() {
        let text = include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        ))
        .replace(
            "contact_scheme: Located",
            "contact: Compliant(stiffness_n_m: [5e7])",
        );
        let scene = crate::solver::test_problem::problem(&text);
        let mut sim = Simulation::new(&scene, crate::SolverOptions::default()).unwrap();
        sim.tables.max_events = 0;
        let (mut lowest, mut largest) = (0.0f64, 0.0f64);
        for _ in 0..20_000 {
            sim.step().unwrap();
            for &q in sim.force_n() {
                (lowest, largest) = (lowest.min(q), largest.max(q));
            }
        }
        let st = sim.stats();
        eprintln!(
            "{} event steps cut short; step-mean forces from {lowest:.3e} to {largest:.3e} N; worst penetration {:.2e} m",
            st.events, st.worst_penetration_m
        );
        assert!(st.events > 50, "{} events", st.events);
        assert!(
            lowest >= -1e-9 * largest,
            "{lowest} N (largest {largest} N)"
        );
    }
}
