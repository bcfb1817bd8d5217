//! The implicit peer: the contact equations by adaptive variable-order BDF
//! (`diffsol::Bdf`) with their contact switches located as events, for
//! penalty contact ([`run_bdf`]: a spring and its critical damper) and for
//! the scene's own undamped tread springs ([`run_bdf_tread`]).
//!
//! Between two switches each point's force is either its contact force
//! `g_i = k_i (r_i - u_i) + c_i (ṙ_i - u̇_i)` or zero, so the equations are
//! linear and smooth; the kink of `max(0, g_i)` is where `g_i` crosses
//! zero. Each crossing is a root of [`Switched::roots`], located by
//! diffsol's root finder on the BDF interpolant; the run moves back to it,
//! switches the point and restarts BDF there in the new mode. No step ever
//! spans a switch.
//!
//! The forces are unknowns of the system (a semi-explicit index-1 DAE, see
//! [`Switched`]): the modes then couple only through the `P` force rows
//! and columns of the Newton matrix, which [`BorderedLu`] factors in
//! `O(K P² + P³)` instead of the `O((2K + P)³)` of a dense LU.

use super::Oscillators;
use crate::analysis::bench::BenchError;
use crate::analysis::bench::baselines::{BaselineRun, road_seen};
use diffsol::{
    Bdf, FaerSparseLU, FaerSparseMat, FaerVec, OdeBuilder, OdeSolverMethod, OdeSolverStopReason,
};
use std::cell::{Cell, RefCell};
use tirecontact_core::model::road::RoadProfile;
use tirecontact_io::identify::ModeCache;
use tirecontact_io::scene::{Contact, Scene};

/// The contact equations in one mode (a fixed active set `A`), a
/// semi-explicit index-1 DAE `M y' = f(t, y)` in `y = [η, η', J, w]`:
///
/// `η_s'' = -ω_s² η_s - 2ξ_s ω_s η_s' + Σ_i b_s[i] w_i`, `J_i' = w_i`,
/// `0 = [i∈A] g_i - w_i`,
///
/// with `g_i = k_i (r_i - u_i) + c_i (ṙ_i - u̇_i)` the force point `i`
/// bears when active (`u = Σ_s a_s η_s`; `c_i = 0` for a tread spring),
/// `w_i` its force (N) and `J_i` its impulse (N·s). Within a mode `f` is
/// linear in `y`.
pub(super) struct Switched<'a> {
    osc: &'a Oscillators,
    scene: &'a Scene,
    road: &'a RoadProfile,
    /// Each point's spring (N/m).
    k_n_m: Vec<f64>,
    /// Each point's damper (N·s/m).
    c_ns_m: Vec<f64>,
    /// Whether each point bears its force `g_i` in the current mode.
    active: RefCell<Vec<bool>>,
    /// Offsets of the root functions ([`Switched::roots`]).
    shift: RefCell<Vec<f64>>,
    /// Evaluations of `f`.
    evaluations: Cell<u64>,
}

impl<'a> Switched<'a> {
    fn new(
        osc: &'a Oscillators,
        scene: &'a Scene,
        road: &'a RoadProfile,
        k_n_m: Vec<f64>,
        c_ns_m: Vec<f64>,
    ) -> Self {
        Switched {
            osc,
            scene,
            road,
            k_n_m,
            c_ns_m,
            active: RefCell::new(vec![false; osc.p]),
            shift: RefCell::new(vec![0.0; osc.p]),
            evaluations: Cell::new(0),
        }
    }

    fn ns(&self) -> usize {
        self.osc.ns()
    }

    /// The length of `y`: `2K + 2P`.
    fn len(&self) -> usize {
        2 * self.ns() + 2 * self.osc.p
    }

    /// Where the forces `w` start in `y`; before them the differential part.
    fn forces_at(&self) -> usize {
        2 * self.ns() + self.osc.p
    }

    /// `g_i = k_i (r_i - u_i) + c_i (ṙ_i - u̇_i)` (N) of point `i` at `(t, y)`.
    fn gap(&self, t: f64, y: &[f64], i: usize) -> f64 {
        let ns = self.ns();
        let a = &self.osc.out[i * ns..(i + 1) * ns];
        let (mut u, mut v) = (0.0, 0.0);
        for s in 0..ns {
            u += a[s] * y[s];
            v += a[s] * y[ns + s];
        }
        let (r, rd) = road_seen(self.scene, self.road, t, i);
        self.k_n_m[i] * (r - u) + self.c_ns_m[i] * (rd - v)
    }

    /// `f(t, y)` in the current mode.
    fn rhs(&self, t: f64, y: &[f64], f: &mut [f64]) {
        self.evaluations.set(self.evaluations.get() + 1);
        let (p, ns, m) = (self.osc.p, self.ns(), self.forces_at());
        let w = &y[m..];
        for s in 0..ns {
            let (om, xi) = (self.osc.omega[s], self.osc.xi[s]);
            let b = &self.osc.inp[s * p..(s + 1) * p];
            let bw: f64 = b.iter().zip(w).map(|(b, w)| b * w).sum();
            f[s] = y[ns + s];
            f[ns + s] = bw - 2.0 * xi * om * y[ns + s] - om * om * y[s];
        }
        let active = self.active.borrow();
        for i in 0..p {
            f[2 * ns + i] = w[i];
            let g = if active[i] { self.gap(t, y, i) } else { 0.0 };
            f[m + i] = g - w[i];
        }
    }

    /// The analytic Jacobian times `v`, `(∂f/∂y) v`, in the current mode
    /// (constant within a mode): the Jacobian's columns of the non-zeros
    /// of `v` summed, so that the unit vectors diffsol assembles the
    /// Jacobian with cost `O(K + P)` each.
    fn jac_mul(&self, v: &[f64], out: &mut [f64]) {
        let (p, ns, m) = (self.osc.p, self.ns(), self.forces_at());
        out.fill(0.0);
        let active = self.active.borrow();
        for (k, &vk) in v.iter().enumerate() {
            if vk == 0.0 {
                continue;
            }
            if k < ns {
                // ∂/∂η_s: the mode's spring, the active points' stiffness
                let (s, om) = (k, self.osc.omega[k]);
                out[ns + s] -= om * om * vk;
                for i in (0..p).filter(|&i| active[i]) {
                    out[m + i] -= self.k_n_m[i] * self.osc.out[i * ns + s] * vk;
                }
            } else if k < 2 * ns {
                // ∂/∂η'_s: the mode's velocity, its damper, the points' dampers
                let (s, om, xi) = (k - ns, self.osc.omega[k - ns], self.osc.xi[k - ns]);
                out[s] += vk;
                out[ns + s] -= 2.0 * xi * om * vk;
                for i in (0..p).filter(|&i| active[i]) {
                    out[m + i] -= self.c_ns_m[i] * self.osc.out[i * ns + s] * vk;
                }
            } else if k >= m {
                // ∂/∂w_i: the force drives the modes and the impulse
                let i = k - m;
                for s in 0..ns {
                    out[ns + s] += self.osc.inp[s * p + i] * vk;
                }
                out[2 * ns + i] += vk;
                out[m + i] -= vk;
            }
            // J appears in no equation
        }
    }

    /// `M v + β y`, `M` the identity on `[η, η', J]` and zero on `w`.
    fn mass(&self, v: &[f64], beta: f64, y: &mut [f64]) {
        let m = self.forces_at();
        for (k, yk) in y.iter_mut().enumerate() {
            *yk = if k < m { v[k] } else { 0.0 } + beta * *yk;
        }
    }

    /// The root functions, one a point: `σ_i g_i + shift_i`, `σ_i = +1`
    /// for an active point, `-1` for an inactive one, so that each is
    /// positive while the point's mode agrees with its force and crosses
    /// zero at its switch. Right after a switch `g_i ≈ 0`: the shift holds
    /// the switched point's function at [`Switched::switch_margin`] there
    /// (the root finder sees sign changes only), and is dropped once
    /// `σ_i g_i` is positive on its own ([`Switched::settle`]).
    fn roots(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let (active, shift) = (self.active.borrow(), self.shift.borrow());
        for (i, r) in out.iter_mut().enumerate() {
            let sigma = if active[i] { 1.0 } else { -1.0 };
            *r = sigma * self.gap(t, y, i) + shift[i];
        }
    }

    /// Point `i`'s root function's value right after its switch (N): the
    /// force of a penetration of 1e-12 m.
    fn switch_margin(&self, i: usize) -> f64 {
        self.k_n_m[i] * 1e-12
    }

    /// Puts each point in the mode its force `g_i` says at `(t, y)`, its
    /// root function shifted up to the switch margin if below it (the
    /// start of a run).
    fn start(&self, t: f64, y: &[f64]) {
        let mut active = self.active.borrow_mut();
        let mut shift = self.shift.borrow_mut();
        for i in 0..self.osc.p {
            let g = self.gap(t, y, i);
            active[i] = g > 0.0;
            shift[i] = (self.switch_margin(i) - g.abs()).max(0.0);
        }
    }

    /// Switches point `i` at `(t, y)`, its root function shifted up to the
    /// switch margin there; whether it is now active.
    fn switch(&self, i: usize, t: f64, y: &[f64]) -> bool {
        let g = self.gap(t, y, i);
        let mut active = self.active.borrow_mut();
        active[i] = !active[i];
        let sigma = if active[i] { 1.0 } else { -1.0 };
        self.shift.borrow_mut()[i] = (self.switch_margin(i) - sigma * g).max(0.0);
        active[i]
    }

    /// Drops the shift of each point whose root function is positive
    /// without it at `(t, y)`.
    fn settle(&self, t: f64, y: &[f64]) {
        let active = self.active.borrow();
        for (i, sh) in self.shift.borrow_mut().iter_mut().enumerate() {
            let sigma = if active[i] { 1.0 } else { -1.0 };
            if *sh != 0.0 && sigma * self.gap(t, y, i) > 0.0 {
                *sh = 0.0;
            }
        }
    }

    /// Sets the forces `w` of `y` to the current mode's at `t`.
    fn consistent_forces(&self, t: f64, y: &mut [f64]) {
        let m = self.forces_at();
        for i in 0..self.osc.p {
            let on = self.active.borrow()[i];
            y[m + i] = if on { self.gap(t, y, i) } else { 0.0 };
        }
    }
}

/// A contact switch located by [`run_bdf`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Switch {
    pub t_s: f64,
    pub point: usize,
    /// Whether the point bears its force from `t_s` on.
    pub on: bool,
}

/// A run of [`run_bdf`]: its outputs, what it took and its switches.
#[derive(Debug, Clone)]
pub struct ImplicitRun {
    pub run: BaselineRun,
    pub stats: ImplicitStats,
    pub switches: Vec<Switch>,
}

/// What an implicit run took.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImplicitStats {
    /// Evaluations of the right-hand side.
    pub evaluations: u64,
    pub accepted: u64,
    /// Steps rejected by the error test.
    pub rejected: u64,
    /// Factorisations of the Newton matrix.
    pub factorisations: u64,
    /// Contact switches located (each a restart; simultaneous ones count
    /// once a point).
    pub switches: u64,
}

/// Largest number of located switches of one run: a run whose contact
/// chatters (switches back and forth without advancing) stops with an
/// error.
const MAX_SWITCHES: u64 = 10_000_000;

/// Adaptive variable-order BDF (`diffsol::Bdf`, orders 1 to 5, the method
/// of scipy's `solve_ivp(method="BDF")`) on the penalty equations of
/// stiffness `k_n_m` (N/m) and its critical dampers, written in each mode
/// (a fixed set `A` of points bearing their force) as the index-1 DAE
///
/// `η_s'' = -ω_s² η_s - 2ξ_s ω_s η_s' + Σ_i b_s[i] w_i`, `J_i' = w_i`,
/// `0 = [i∈A] g_i - w_i`, `g_i = k (r_i - u_i) + c_i (ṙ_i - u̇_i)`,
///
/// its switches (the zeros of each `g_i`) located as events; at relative
/// tolerance `rtol` and absolute `rtol` × 1e-3 (as `run_dopri`), the
/// forces `w` (algebraic) out of the error test, as IDA's suppressed
/// algebraic variables; recorded every `dt_out_s` to `duration_s`: the
/// displacements and the step means of the force (impulse differences).
///
/// Tuned as the equations allow: the Jacobian is analytic and, within a
/// mode, exact and constant, so it is re-evaluated only at the switches
/// and the Newton matrix refactored only when the step size or order
/// changes it (diffsol's 30 % rule) or a step fails; the Newton matrix,
/// 2×2 blocks per mode bordered by the `P` force rows and columns, is
/// factored by block elimination and a dense `P × P` Schur complement.
/// Each switch is a root of the functions `σ_i g_i` (`σ_i = +1` active,
/// `-1` inactive), found by diffsol on the BDF interpolant: the state is
/// moved back to it, every point whose function is not positive there
/// changes mode, the forces and `y'` are set to the new mode's, the
/// Jacobian is re-evaluated and BDF restarts at order 1 with a step
/// re-estimated for the new mode (diffsol's initial step size rule).
pub fn run_bdf(
    scene: &Scene,
    k_n_m: f64,
    rtol: f64,
    dt_out_s: f64,
    duration_s: f64,
    cache: &ModeCache,
) -> Result<ImplicitRun, BenchError> {
    let osc = Oscillators::new(scene, cache)?;
    let c_ns_m = osc.dampers(k_n_m);
    run_switched(
        scene,
        &osc,
        vec![k_n_m; osc.p],
        c_ns_m,
        rtol,
        dt_out_s,
        duration_s,
    )
}

/// [`run_bdf`] on the scene's own contact law: its undamped tread springs
/// (`contact: Compliant`, `q_i = k_i max(0, r_i - u_i)`, `c_i = 0`), the
/// law the located solver integrates. Each switch, a landing or a release
/// of a spring, is a zero of the gap `r_i - u_i` (of `k_i (r_i - u_i)`),
/// located on the BDF interpolant inside the step; the run moves back to
/// it and restarts there, so no step spans the kink of `max(0, ·)` and the
/// force is never smoothed. Refuses a scene with rigid contact.
pub fn run_bdf_tread(
    scene: &Scene,
    rtol: f64,
    dt_out_s: f64,
    duration_s: f64,
    cache: &ModeCache,
) -> Result<ImplicitRun, BenchError> {
    let p = scene.num_points();
    let k_n_m = match &scene.contact {
        Contact::Compliant { stiffness_n_m } if stiffness_n_m.len() == 1 => {
            vec![stiffness_n_m[0]; p]
        }
        Contact::Compliant { stiffness_n_m } if stiffness_n_m.len() == p => stiffness_n_m.clone(),
        _ => return Err(BenchError::NoTreadSprings),
    };
    let osc = Oscillators::new(scene, cache)?;
    run_switched(scene, &osc, k_n_m, vec![0.0; p], rtol, dt_out_s, duration_s)
}

/// BDF with located switches on the contact equations of springs `k_n_m`
/// (N/m) and dampers `c_ns_m` (N·s/m), one each a point: [`run_bdf`]'s
/// integration.
fn run_switched(
    scene: &Scene,
    osc: &Oscillators,
    k_n_m: Vec<f64>,
    c_ns_m: Vec<f64>,
    rtol: f64,
    dt_out_s: f64,
    duration_s: f64,
) -> Result<ImplicitRun, BenchError> {
    let road = tirecontact_io::scene::load_road(&scene.road, scene.base_dir.as_deref())?;
    let (p, ns) = (osc.p, osc.ns());
    let sys = Switched::new(osc, scene, &road, k_n_m, c_ns_m);
    let (n, m) = (sys.len(), sys.forces_at());
    // every point active while diffsol finds the Jacobian's sparsity
    sys.active.borrow_mut().fill(true);
    let mut problem = OdeBuilder::<FaerSparseMat<f64>>::new()
        .rtol(rtol)
        .atol((0..n).map(|k| if k < m { rtol * 1e-3 } else { f64::MAX }))
        .rhs_implicit(
            |y: &[f64], _: &[f64], t: f64, f: &mut [f64]| sys.rhs(t, y, f),
            |_: &[f64], _: &[f64], _: f64, v: &[f64], out: &mut [f64]| sys.jac_mul(v, out),
        )
        .mass(|v: &[f64], _: &[f64], _: f64, beta: f64, y: &mut [f64]| sys.mass(v, beta, y))
        .init(|_: &[f64], _: f64, y: &mut [f64]| y.fill(0.0), n)
        .root(
            |y: &[f64], _: &[f64], t: f64, out: &mut [f64]| sys.roots(t, y, out),
            p,
        )
        .build()?;
    problem.ode_options.max_number_timesteps = usize::MAX;
    problem.ode_options.update_jacobian_after_steps = usize::MAX;
    problem.ode_options.update_rhs_jacobian_after_steps = usize::MAX;
    sys.start(0.0, &vec![0.0; n]);
    let state = problem.bdf_state::<FaerSparseLU<f64>>()?;
    let mut solver: Bdf<'_, _, BorderedLu> =
        Bdf::new(&problem, state, BorderedLu::for_switched(ns, p))?;
    solver.set_stop_time(duration_s)?;

    let n_out = (duration_s / dt_out_s).round() as usize;
    let mut out = BaselineRun {
        t_s: Vec::with_capacity(n_out),
        u_m: Vec::with_capacity(n_out),
        q_n: Vec::with_capacity(n_out),
        overflow_t_s: None,
    };
    let mut recorder = Recorder {
        osc,
        dt_out_s,
        n_out,
        next: 1,
        y: solver.state().y.clone(),
        impulse: vec![0.0; p],
        eta: vec![0.0; ns],
    };
    let (mut y, mut f, mut roots) = (vec![0.0; n], vec![0.0; n], vec![0.0; p]);
    let mut switches = Vec::new();
    loop {
        let reason = solver.step()?;
        let t_end = match reason {
            OdeSolverStopReason::RootFound(t, _) => t,
            _ => solver.state().t,
        };
        recorder.record(&solver, t_end, &mut out)?;
        match reason {
            OdeSolverStopReason::TstopReached => break,
            OdeSolverStopReason::InternalTimestep => {
                let st = solver.state();
                for k in 0..n {
                    y[k] = st.y[k];
                }
                sys.settle(st.t, &y);
            }
            OdeSolverStopReason::RootFound(t, idx) => {
                if switches.len() as u64 >= MAX_SWITCHES {
                    return Err(BenchError::Chattering { t_s: t });
                }
                solver.state_mut_back(t)?;
                for k in 0..n {
                    y[k] = solver.state().y[k];
                }
                sys.roots(t, &y, &mut roots);
                for i in 0..p {
                    if roots[i] <= 0.0 || i == idx {
                        let on = sys.switch(i, t, &y);
                        switches.push(Switch {
                            t_s: t,
                            point: i,
                            on,
                        });
                    }
                }
                sys.consistent_forces(t, &mut y);
                sys.rhs(t, &y, &mut f);
                {
                    let st = solver.state_mut();
                    for k in 0..n {
                        st.y[k] = y[k];
                        // the forces' rates jump at a switch: the restart's
                        // first-order predictor takes them as zero
                        st.dy[k] = if k < m { f[k] } else { 0.0 };
                    }
                }
                // the new mode's Jacobian, from which the Newton matrix is
                // rebuilt at the restart, and a first step for it
                drop(solver.jacobian());
                let problem = solver.problem();
                solver
                    .state_mut()
                    .set_step_size(1.0, &problem.atol, problem.rtol, &problem.eqn, 1);
            }
        }
    }
    let st = solver.get_statistics();
    Ok(ImplicitRun {
        run: out,
        stats: ImplicitStats {
            evaluations: sys.evaluations.get(),
            accepted: st.number_of_steps as u64,
            rejected: st.number_of_error_test_failures as u64,
            factorisations: st.number_of_linear_solver_setups as u64,
            switches: switches.len() as u64,
        },
        switches,
    })
}

/// The outputs of a run every `dt_out_s`, from the BDF interpolant.
struct Recorder<'a> {
    osc: &'a Oscillators,
    dt_out_s: f64,
    n_out: usize,
    /// The next output's index (its time `next · dt_out_s`).
    next: usize,
    y: FaerVec<f64>,
    /// The impulses at the last output (N·s).
    impulse: Vec<f64>,
    eta: Vec<f64>,
}

impl Recorder<'_> {
    /// The outputs at or before `t_end`, the end of the last step (or a
    /// root inside it).
    fn record<'a, S, E>(
        &mut self,
        solver: &S,
        t_end: f64,
        out: &mut BaselineRun,
    ) -> Result<(), BenchError>
    where
        E: diffsol::OdeEquations<V = FaerVec<f64>, T = f64> + 'a,
        S: OdeSolverMethod<'a, E>,
    {
        let (p, ns) = (self.osc.p, self.osc.ns());
        while self.next <= self.n_out {
            let t = self.next as f64 * self.dt_out_s;
            if t > t_end * (1.0 + 1e-12) {
                break;
            }
            solver.interpolate_inplace(t.min(t_end), &mut self.y)?;
            for s in 0..ns {
                self.eta[s] = self.y[s];
            }
            let mut u = vec![0.0; p];
            self.osc.displacement(&self.eta, &mut u);
            if out.overflow_t_s.is_none() && u.iter().any(|x| !x.is_finite()) {
                out.overflow_t_s = Some(t);
            }
            let q = (0..p)
                .map(|i| {
                    let j = self.y[2 * ns + i];
                    let q = (j - self.impulse[i]) / self.dt_out_s;
                    self.impulse[i] = j;
                    q
                })
                .collect();
            out.t_s.push(t);
            out.u_m.push(u);
            out.q_n.push(q);
            self.next += 1;
        }
        Ok(())
    }
}

mod bordered_lu;
use bordered_lu::BorderedLu;
#[cfg(test)]
mod tests;
