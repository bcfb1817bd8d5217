//! Peer baselines: what users would otherwise write for dynamic contact,
//! on the same modal model and road as the stable solver.
//!
//! * [`run_newmark`]: the modal equations (one oscillator per rank term of
//!   each mode, [`ModalBasis`]) integrated by Newmark's average
//!   acceleration rule (β = 1/4, γ = 1/2), with penalty contact at each
//!   point, `q_i = max(0, k (r_i - u_i) + c_i (ṙ_i - u̇_i))`, solved
//!   implicitly at each step (an active-set iteration on the P points);
//! * [`run_dopri`]: the same penalty equations by an adaptive explicit
//!   Dormand–Prince 5(4) integrator (`ode_solvers::Dopri5`, the method of
//!   scipy's `solve_ivp(method="RK45")`), its tolerance swept; each point's
//!   impulse is integrated with the state, so that step means of the force
//!   keep the short penalty pulses of the impacts;
//! * [`run_bdf`]: the same penalty equations by an adaptive, variable-order
//!   implicit BDF integrator (`diffsol::Bdf`, the method of scipy's
//!   `solve_ivp(method="BDF")`) with an analytic Jacobian, its switches
//!   located: between two switches the active set is fixed and the
//!   equations are linear; each switch (a force
//!   `k (r_i - u_i) + c_i (ṙ_i - u̇_i)` crossing zero) is a root the
//!   integrator locates, and the integration restarts there in the new
//!   active set, so the kink of `max(0, ·)` is never stepped across
//!   (module `implicit`);
//! * [`run_bdf_tread`]: that BDF integrator on a scene's own undamped
//!   tread springs, `q_i = k_i max(0, r_i - u_i)`, the law the located
//!   solver integrates on a contact patch: its switches are the zeros of
//!   the gaps `r_i - u_i`, located and restarted at in the same way.
//!
//! A penalty is a user's choice with two faces: a soft spring lets the
//! points into the road (the penalty error), a stiff one makes the
//! equations stiff (the time step or the explicit integrator's step
//! limit). The bench sweeps `k` over decades and keeps the best. The
//! damper `c_i = 2 √(k m_i)` (critical for the point's own effective mass
//! `m_i = 1 / Σ_s a_s[i] b_s[i]`, the inverse of its velocity jump per unit
//! impulse) makes the contact's restitution tend to 0 as `k` grows, the
//! rigid model's: a spring alone would bounce back elastically and
//! converge to another physics.

use crate::analysis::bench::BenchError;
use crate::analysis::bench::baselines::{BaselineRun, road_seen};
use ode_solvers::{DVector, Dopri5, OutputType, System};
use tirecontact_core::model::convolution::ModalBasis;
use tirecontact_core::model::road::RoadProfile;
use tirecontact_core::solver::simulation::SolverOptions;
use tirecontact_io::identify::ModeCache;
use tirecontact_io::scene::Scene;

mod implicit;
pub use implicit::{ImplicitRun, ImplicitStats, Switch, run_bdf, run_bdf_tread};

/// The modal oscillators of a scene: `η_s'' + 2ξω η_s' + ω² η_s = b_sᵀ q`,
/// `u = Σ_s a_s η_s`, one per rank term the located runs keep (the
/// default rank cut, `SolverOptions::rank_tolerance_for`: identified
/// residues' terms below 1e-5 of the largest dropped), so that the peers
/// integrate the model the reference integrates.
struct Oscillators {
    p: usize,
    omega: Vec<f64>,
    xi: Vec<f64>,
    /// `a_s[i]` at `[i * ns + s]`.
    out: Vec<f64>,
    /// `b_s[j]` at `[s * p + j]`.
    inp: Vec<f64>,
}

impl Oscillators {
    fn new(scene: &Scene, cache: &ModeCache) -> Result<Self, BenchError> {
        tirecontact_core::base::linalg::sequential();
        let p = scene.num_points();
        let modes = cache.modes(scene)?;
        let basis = ModalBasis::with_rank_tolerance(
            &modes,
            p,
            SolverOptions::default().rank_tolerance_of(scene.modes_identified()),
        )?;
        let ns = basis.num_states();
        let stored = basis.stored_states();
        let mut out = vec![0.0; p * ns];
        for i in 0..p {
            out[i * ns..(i + 1) * ns].copy_from_slice(&basis.out[i * stored..i * stored + ns]);
        }
        let (omega, xi) = (0..ns).map(|s| basis.modes[basis.mode_of_state[s]]).unzip();
        Ok(Oscillators {
            p,
            omega,
            xi,
            out,
            inp: basis.inp[..ns * p].to_vec(),
        })
    }

    fn ns(&self) -> usize {
        self.omega.len()
    }

    /// The critical penalty damper of each point for stiffness `k` (N·s/m).
    fn dampers(&self, k: f64) -> Vec<f64> {
        let ns = self.ns();
        (0..self.p)
            .map(|i| {
                let jump: f64 = (0..ns)
                    .map(|s| self.out[i * ns + s] * self.inp[s * self.p + i])
                    .sum();
                2.0 * (k / jump.max(f64::MIN_POSITIVE)).sqrt()
            })
            .collect()
    }

    /// `u = Σ_s a_s η_s`.
    fn displacement(&self, eta: &[f64], u: &mut [f64]) {
        let ns = self.ns();
        for (i, ui) in u.iter_mut().enumerate() {
            *ui = self.out[i * ns..(i + 1) * ns]
                .iter()
                .zip(eta)
                .map(|(a, e)| a * e)
                .sum();
        }
    }
}

/// The penalty forces of an implicit step: `q_i = max(0, rhs_i - kd_i
/// (S q)_i)` (`S` P×P row-major, `kd_i` the point's stiffness and damper
/// per unit of `S q`), the active-set iteration of a piecewise-linear
/// system, at most `4P` solves; `active` holds the final set.
fn penalty_solve(kd: &[f64], s: &[f64], rhs: &[f64], q: &mut [f64], active: &mut Vec<usize>) {
    let p = rhs.len();
    active.clear();
    active.extend((0..p).filter(|&i| rhs[i] > 0.0));
    for _ in 0..4 * p {
        q.fill(0.0);
        let n = active.len();
        if n > 0 {
            // (I + diag(kd) S)_AA q_A = rhs_A
            let a = faer::Mat::from_fn(n, n, |x, y| {
                let (i, j) = (active[x], active[y]);
                kd[i] * s[i * p + j] + if x == y { 1.0 } else { 0.0 }
            });
            let b = faer::Mat::from_fn(n, 1, |x, _| rhs[active[x]]);
            use faer::linalg::solvers::Solve;
            let sol = a.partial_piv_lu().solve(&b);
            for (x, &j) in active.iter().enumerate() {
                q[j] = sol[(x, 0)];
            }
        }
        // a pulling contact leaves; a pushed point joins
        if let Some(x) = (0..n)
            .filter(|&x| q[active[x]] < 0.0)
            .min_by(|&a, &b| q[active[a]].total_cmp(&q[active[b]]))
        {
            active.remove(x);
            continue;
        }
        let pushed = (0..p)
            .filter(|i| !active.contains(i))
            .map(|i| {
                let sq: f64 = active.iter().map(|&j| s[i * p + j] * q[j]).sum();
                (i, rhs[i] - kd[i] * sq)
            })
            .filter(|&(_, f)| f > 0.0)
            .max_by(|a, b| a.1.total_cmp(&b.1));
        match pushed {
            Some((i, _)) => active.push(i),
            None => return,
        }
    }
}

/// Newmark (average acceleration) on the modal oscillators with penalty
/// contact of stiffness `k_n_m` (N/m) and its critical dampers, `n_steps`
/// steps of `scene.dt_s`.
/// Each recorded force is the step's trapezoidal mean.
pub fn run_newmark(
    scene: &Scene,
    k_n_m: f64,
    n_steps: usize,
    cache: &ModeCache,
) -> Result<BaselineRun, BenchError> {
    let osc = Oscillators::new(scene, cache)?;
    let road = tirecontact_io::scene::load_road(&scene.road, scene.base_dir.as_deref())?;
    let (p, ns, dt) = (osc.p, osc.ns(), scene.dt_s);
    let h = 0.25 * dt * dt;
    // D_s = 1 + dt ξω + dt²ω²/4: the implicit step's diagonal
    let d: Vec<f64> = (0..ns)
        .map(|s| 1.0 + dt * osc.xi[s] * osc.omega[s] + h * osc.omega[s] * osc.omega[s])
        .collect();
    // S = dt²/4 Σ_s a_s b_sᵀ / D_s: the step-end displacement per force
    let mut sm = vec![0.0; p * p];
    for i in 0..p {
        for j in 0..p {
            sm[i * p + j] = (0..ns)
                .map(|s| h * osc.out[i * ns + s] * osc.inp[s * p + j] / d[s])
                .sum();
        }
    }
    let (mut eta, mut vel, mut acc) = (vec![0.0; ns], vec![0.0; ns], vec![0.0; ns]);
    let (mut eta_p, mut f_p) = (vec![0.0; ns], vec![0.0; ns]);
    let c = osc.dampers(k_n_m);
    // per unit of `S q`: displacement k, velocity (2/dt) c
    let kd: Vec<f64> = c.iter().map(|ci| k_n_m + 2.0 * ci / dt).collect();
    let (mut u_free, mut v_free, mut u) = (vec![0.0; p], vec![0.0; p], vec![0.0; p]);
    let mut rhs = vec![0.0; p];
    let (mut q, mut q_old) = (vec![0.0; p], vec![0.0; p]);
    let mut active = Vec::with_capacity(p);
    let mut out = BaselineRun {
        t_s: Vec::with_capacity(n_steps),
        u_m: Vec::with_capacity(n_steps),
        q_n: Vec::with_capacity(n_steps),
        overflow_t_s: None,
    };
    for n in 0..n_steps {
        let t1 = (n + 1) as f64 * dt;
        for s in 0..ns {
            let v_p = vel[s] + 0.5 * dt * acc[s];
            eta_p[s] = eta[s] + dt * vel[s] + h * acc[s];
            f_p[s] = 2.0 * osc.xi[s] * osc.omega[s] * v_p + osc.omega[s] * osc.omega[s] * eta_p[s];
            // the displacement without contact forces: a = -f*/D
            vel[s] = v_p;
        }
        let free: Vec<f64> = (0..ns).map(|s| eta_p[s] - h * f_p[s] / d[s]).collect();
        osc.displacement(&free, &mut u_free);
        let free_v: Vec<f64> = (0..ns).map(|s| vel[s] - 0.5 * dt * f_p[s] / d[s]).collect();
        osc.displacement(&free_v, &mut v_free);
        for (i, b) in rhs.iter_mut().enumerate() {
            let (r, rd) = road_seen(scene, &road, t1, i);
            *b = k_n_m * (r - u_free[i]) + c[i] * (rd - v_free[i]);
        }
        penalty_solve(&kd, &sm, &rhs, &mut q, &mut active);
        for s in 0..ns {
            let bq: f64 = (0..p).map(|j| osc.inp[s * p + j] * q[j]).sum();
            acc[s] = (bq - f_p[s]) / d[s];
            eta[s] = eta_p[s] + h * acc[s];
            vel[s] += 0.5 * dt * acc[s];
        }
        osc.displacement(&eta, &mut u);
        if out.overflow_t_s.is_none() && u.iter().any(|x| !x.is_finite()) {
            out.overflow_t_s = Some(t1);
        }
        out.t_s.push(t1);
        out.u_m.push(u.clone());
        out.q_n
            .push(q.iter().zip(&q_old).map(|(a, b)| 0.5 * (a + b)).collect());
        q_old.copy_from_slice(&q);
    }
    Ok(out)
}

/// The penalty equations as a first-order system: `[η, η', J]`, `J_i` the
/// impulse of point `i`'s force so far (N·s).
struct PenaltySystem<'a> {
    osc: &'a Oscillators,
    scene: &'a Scene,
    road: &'a RoadProfile,
    k_n_m: f64,
    c: Vec<f64>,
}

impl PenaltySystem<'_> {
    fn forces(&self, t: f64, eta: &[f64], eta_dot: &[f64], q: &mut [f64]) {
        let p = self.osc.p;
        let (mut u, mut v) = (vec![0.0; p], vec![0.0; p]);
        self.osc.displacement(eta, &mut u);
        self.osc.displacement(eta_dot, &mut v);
        for (i, qi) in q.iter_mut().enumerate() {
            let (r, rd) = road_seen(self.scene, self.road, t, i);
            *qi = (self.k_n_m * (r - u[i]) + self.c[i] * (rd - v[i])).max(0.0);
        }
    }
}

impl System<f64, DVector<f64>> for PenaltySystem<'_> {
    fn system(&self, t: f64, y: &DVector<f64>, dy: &mut DVector<f64>) {
        let (p, ns) = (self.osc.p, self.osc.ns());
        let y = y.as_slice();
        let mut q = vec![0.0; p];
        self.forces(t, &y[..ns], &y[ns..2 * ns], &mut q);
        let dy = dy.as_mut_slice();
        for s in 0..ns {
            let (w, xi) = (self.osc.omega[s], self.osc.xi[s]);
            let bq: f64 = (0..p).map(|j| self.osc.inp[s * p + j] * q[j]).sum();
            dy[s] = y[ns + s];
            dy[ns + s] = bq - 2.0 * xi * w * y[ns + s] - w * w * y[s];
        }
        dy[2 * ns..2 * ns + p].copy_from_slice(&q);
    }
}

/// What an adaptive run took.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveStats {
    pub evaluations: u64,
    pub accepted: u64,
    pub rejected: u64,
}

/// Dormand–Prince 5(4) on the penalty equations (stiffness `k_n_m`, N/m,
/// and its critical dampers)
/// at relative and absolute tolerances `rtol` (absolute: `rtol` × 1 mm
/// for displacements), recorded every `dt_out_s` to `duration_s`: the
/// displacements and the step means of the force (impulse differences).
pub fn run_dopri(
    scene: &Scene,
    k_n_m: f64,
    rtol: f64,
    dt_out_s: f64,
    duration_s: f64,
    cache: &ModeCache,
) -> Result<(BaselineRun, AdaptiveStats), BenchError> {
    let osc = Oscillators::new(scene, cache)?;
    let road = tirecontact_io::scene::load_road(&scene.road, scene.base_dir.as_deref())?;
    let (p, ns) = (osc.p, osc.ns());
    let sys = PenaltySystem {
        osc: &osc,
        scene,
        road: &road,
        k_n_m,
        c: osc.dampers(k_n_m),
    };
    let y0 = DVector::zeros(2 * ns + p);
    let mut solver = Dopri5::from_param(
        sys,
        0.0,
        duration_s,
        dt_out_s,
        y0,
        rtol,
        rtol * 1e-3,
        0.9,
        0.04,
        0.2,
        10.0,
        duration_s,
        0.0,
        u32::MAX,
        u32::MAX,
        OutputType::Dense,
    );
    let stats = solver.integrate()?;
    let (ts, ys) = (solver.x_out(), solver.y_out());
    let mut out = BaselineRun::default();
    let mut u = vec![0.0; p];
    for k in 1..ts.len() {
        let (y, y0) = (ys[k].as_slice(), ys[k - 1].as_slice());
        osc.displacement(&y[..ns], &mut u);
        if out.overflow_t_s.is_none() && u.iter().any(|x| !x.is_finite()) {
            out.overflow_t_s = Some(ts[k]);
        }
        let dt = ts[k] - ts[k - 1];
        out.t_s.push(ts[k]);
        out.u_m.push(u.clone());
        out.q_n.push(
            (0..p)
                .map(|i| (y[2 * ns + i] - y0[2 * ns + i]) / dt)
                .collect(),
        );
    }
    Ok((
        out,
        AdaptiveStats {
            evaluations: u64::from(stats.num_eval),
            accepted: u64::from(stats.accepted_steps),
            rejected: u64::from(stats.rejected_steps),
        },
    ))
}
