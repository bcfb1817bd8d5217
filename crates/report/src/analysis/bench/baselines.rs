//! Baselines for the work-precision study: the paper's contact scheme (method
//! §4 steps 1-5, Gauss quadrature `c_m = dt/2`, paper eqs. 25-29) on top of
//! two convolution kernels a user would otherwise write:
//!
//! * [`Kernel::AlphaBeta`]: the paper's α/β accumulators (eqs. 4-6, 9),
//!   which lose `ξωt / ln 10` digits and overflow once `ξωt > 709.78`;
//! * [`Kernel::Direct`]: direct quadrature of method eq. 3 over the whole
//!   force history, O(N²).
//!
//! Both share the in-step influence `(dt/2) g(dt - s_m)` of the Gauss forces.

use crate::analysis::bench::BenchError;
use faer::linalg::solvers::Solve;
use tirecontact_core::base::modal::ModalModel;
use tirecontact_core::model::road::{RoadProfile, ramp};
use tirecontact_io::identify::ModeCache;
use tirecontact_io::scene::Scene;

/// Which convolution the baseline uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kernel {
    AlphaBeta,
    Direct,
}

/// Time histories of a baseline run, sampled every step.
#[derive(Debug, Clone, Default)]
pub struct BaselineRun {
    pub t_s: Vec<f64>,
    /// `u[k][i]` (m) at `t_s[k]`.
    pub u_m: Vec<Vec<f64>>,
    /// Step-mean force `q[k][i]` (N).
    pub q_n: Vec<Vec<f64>>,
    /// First time (s) at which a value was not finite, if any.
    pub overflow_t_s: Option<f64>,
}

/// A run of the stable solver recorded every step (the reference and the
/// compared runs of the bench).
impl tirecontact_core::solver::drive::Probe for BaselineRun {
    fn after_step(&mut self, sim: &tirecontact_core::Simulation) -> std::io::Result<()> {
        self.t_s.push(sim.time_s());
        self.u_m.push(sim.displacement_m().to_vec());
        self.q_n.push(sim.force_n().to_vec());
        Ok(())
    }
}

/// The road height and rate `(r_i, ṙ_i)` (m, m/s) point `i` meets at `t`
/// (method §4): the profile under the point (on a surface, on the point's
/// own track `y_m` across), less its undeformed height, ramped in over
/// `ramp_s`.
pub(crate) fn road_seen(scene: &Scene, road: &RoadProfile, t: f64, i: usize) -> (f64, f64) {
    let pt = scene.points[i];
    let (w, dw) = ramp(t, scene.ramp_s);
    let (z, dz) = road
        .sample_at(pt.x_m + scene.speed_mps * t, pt.y_m)
        .unwrap_or((0.0, 0.0));
    (
        w * (z - pt.h_m),
        dw * (z - pt.h_m) + w * dz * scene.speed_mps,
    )
}

/// Runs `scene` for `n_steps` with the paper's contact scheme on `kernel`.
/// Errors if the scene's road cannot be built or a mode is not underdamped
/// (the α/β form needs `ξ < 1`).
pub fn run_baseline(
    scene: &Scene,
    kernel: Kernel,
    n_steps: usize,
    cache: &ModeCache,
) -> Result<BaselineRun, BenchError> {
    tirecontact_core::base::linalg::sequential();
    let p = scene.num_points();
    let modes = cache.modes(scene)?;
    let model = ModalModel::from_modes(&modes, p);
    if kernel == Kernel::AlphaBeta
        && let Some((mode, m)) = model
            .modes
            .iter()
            .enumerate()
            .find(|(_, m)| m.damping_ratio >= 1.0)
    {
        return Err(BenchError::AlphaBetaDamping {
            mode,
            damping_ratio: m.damping_ratio,
        });
    }
    let road = tirecontact_io::scene::load_road(&scene.road, scene.base_dir.as_deref())?;
    let dt = scene.dt_s;
    let gauss = [
        dt * (0.5 - 0.5 / 3f64.sqrt()),
        dt * (0.5 + 0.5 / 3f64.sqrt()),
    ];
    // influence of this step's Gauss forces at the step end: (dt/2) g(dt - s_m)
    let mut inf = vec![[0.0; 4]; p * p];
    for i in 0..p {
        for j in 0..p {
            let (g1, gd1) = model.green(i, j, dt - gauss[0]);
            let (g2, gd2) = model.green(i, j, dt - gauss[1]);
            inf[i * p + j] = [0.5 * dt * g1, 0.5 * dt * g2, 0.5 * dt * gd1, 0.5 * dt * gd2];
        }
    }
    // Direct: the Green functions at every lag t_{n+1} - (t_m + s_g), m <= n.
    let lag_table: Vec<[f64; 4]> = if kernel == Kernel::Direct {
        let mut t = vec![[0.0; 4]; (n_steps + 1) * p * p];
        for k in 0..=n_steps {
            for i in 0..p {
                for j in 0..p {
                    let base = (k as f64 + 1.0) * dt;
                    let (g1, gd1) = model.green(i, j, base - gauss[0]);
                    let (g2, gd2) = model.green(i, j, base - gauss[1]);
                    t[(k * p + i) * p + j] =
                        [0.5 * dt * g1, 0.5 * dt * g2, 0.5 * dt * gd1, 0.5 * dt * gd2];
                }
            }
        }
        t
    } else {
        Vec::new()
    };
    // α/β accumulators per (mode, source): Σ (dt/2) e^{a t_g} (cos, sin)(ω_d t_g) q_g
    let nm = model.modes.len();
    let mut ab = vec![[0.0f64; 2]; nm * p];
    let mut history: Vec<[f64; 2]> = Vec::new(); // (q1, q2) per step and point
    let road_at = |t: f64, i: usize| road_seen(scene, &road, t, i);
    let mut out = BaselineRun::default();
    let (mut uh, mut vh) = (vec![0.0; p], vec![0.0; p]);
    for n in 0..n_steps {
        let t1 = (n + 1) as f64 * dt;
        // 1. free prediction at t1 from the committed forces
        uh.fill(0.0);
        vh.fill(0.0);
        match kernel {
            Kernel::Direct => {
                for m in 0..n {
                    let lag = n - m;
                    for i in 0..p {
                        for j in 0..p {
                            let g = lag_table[(lag * p + i) * p + j];
                            let q = history[m * p + j];
                            uh[i] += g[0] * q[0] + g[1] * q[1];
                            vh[i] += g[2] * q[0] + g[3] * q[1];
                        }
                    }
                }
            }
            Kernel::AlphaBeta => {
                for (k, m) in model.modes.iter().enumerate() {
                    let a = m.decay_rate();
                    let wd =
                        m.omega_rad_s * ((1.0 - m.damping_ratio) * (1.0 + m.damping_ratio)).sqrt();
                    let e = (-a * t1).exp();
                    let (s, c) = (wd * t1).sin_cos();
                    for j in 0..p {
                        let [al, be] = ab[k * p + j];
                        let x = e * (s * al - c * be) / wd;
                        let v = e * (-a * (s * al - c * be) + wd * (c * al + s * be)) / wd;
                        for i in 0..p {
                            let aij = m.residue[i * p + j];
                            uh[i] += aij * x;
                            vh[i] += aij * v;
                        }
                    }
                }
            }
        }
        // 2-4. the paper's active set
        let rr: Vec<(f64, f64)> = (0..p).map(|i| road_at(t1, i)).collect();
        let (q1, q2) = paper_active_set(p, &uh, &vh, &rr, &inf);
        // 5. commit
        for j in 0..p {
            history.push([q1[j], q2[j]]);
        }
        if kernel == Kernel::AlphaBeta {
            for (k, m) in model.modes.iter().enumerate() {
                let a = m.decay_rate();
                let wd = m.omega_rad_s * ((1.0 - m.damping_ratio) * (1.0 + m.damping_ratio)).sqrt();
                for (g, tg) in gauss.iter().enumerate() {
                    let tau = n as f64 * dt + tg;
                    let e = (a * tau).exp();
                    let (s, c) = (wd * tau).sin_cos();
                    for j in 0..p {
                        let q = if g == 0 { q1[j] } else { q2[j] };
                        ab[k * p + j][0] += 0.5 * dt * e * c * q;
                        ab[k * p + j][1] += 0.5 * dt * e * s * q;
                    }
                }
            }
        }
        let u: Vec<f64> = (0..p)
            .map(|i| {
                uh[i]
                    + (0..p)
                        .map(|j| inf[i * p + j][0] * q1[j] + inf[i * p + j][1] * q2[j])
                        .sum::<f64>()
            })
            .collect();
        if out.overflow_t_s.is_none() && u.iter().any(|x| !x.is_finite()) {
            out.overflow_t_s = Some(t1);
        }
        out.t_s.push(t1);
        out.q_n
            .push((0..p).map(|j| 0.5 * (q1[j] + q2[j])).collect());
        out.u_m.push(u);
    }
    Ok(out)
}

/// The paper's active-set rule for one step: candidates from the free
/// prediction, the coupled Gauss system, release of the most negative mean
/// force (never re-added), points pushed below by a neighbour added, at most
/// `2P` solves. Returns the Gauss-point forces.
fn paper_active_set(
    p: usize,
    uh: &[f64],
    vh: &[f64],
    road: &[(f64, f64)],
    inf: &[[f64; 4]],
) -> (Vec<f64>, Vec<f64>) {
    let mut active: Vec<usize> = (0..p).filter(|&i| uh[i] < road[i].0).collect();
    let mut released = vec![false; p];
    let (mut q1, mut q2) = (vec![0.0; p], vec![0.0; p]);
    let mut solves = 0;
    loop {
        q1.fill(0.0);
        q2.fill(0.0);
        let n = active.len();
        if n == 0 {
            break;
        }
        solves += 1;
        let a = faer::Mat::from_fn(2 * n, 2 * n, |r, c| {
            let (i, j) = (active[r % n], active[c % n]);
            let k = match (r < n, c < n) {
                (true, true) => 0,
                (true, false) => 1,
                (false, true) => 2,
                (false, false) => 3,
            };
            inf[i * p + j][k]
        });
        let b = faer::Mat::from_fn(2 * n, 1, |r, _| {
            let i = active[r % n];
            if r < n {
                road[i].0 - uh[i]
            } else {
                road[i].1 - vh[i]
            }
        });
        // equilibrate rows so that g ~ dt and g' ~ 1 rows weigh alike
        let scale: Vec<f64> = (0..2 * n)
            .map(|r| {
                1.0 / (0..2 * n)
                    .map(|c| a[(r, c)].abs())
                    .fold(f64::MIN_POSITIVE, f64::max)
            })
            .collect();
        let a = faer::Mat::from_fn(2 * n, 2 * n, |r, c| a[(r, c)] * scale[r]);
        let b = faer::Mat::from_fn(2 * n, 1, |r, _| b[(r, 0)] * scale[r]);
        let x = a.partial_piv_lu().solve(&b);
        // a singular system gives non-finite values: stop as on a failed solve
        if (0..2 * n).any(|r| !x[(r, 0)].is_finite()) {
            break;
        }
        let x: Vec<f64> = (0..2 * n).map(|r| x[(r, 0)]).collect();
        for (k, &j) in active.iter().enumerate() {
            q1[j] = x[k];
            q2[j] = x[n + k];
        }
        if solves >= 2 * p {
            break;
        }
        if let Some((k, _)) = active
            .iter()
            .enumerate()
            .map(|(k, &j)| (k, q1[j] + q2[j]))
            .filter(|&(_, m)| m < 0.0)
            .min_by(|a, b| a.1.total_cmp(&b.1))
        {
            released[active.remove(k)] = true;
            continue;
        }
        let deepest = (0..p)
            .filter(|&i| !released[i] && !active.contains(&i))
            .map(|i| {
                let u = uh[i]
                    + active
                        .iter()
                        .map(|&j| inf[i * p + j][0] * q1[j] + inf[i * p + j][1] * q2[j])
                        .sum::<f64>();
                (i, u - road[i].0)
            })
            .filter(|&(_, g)| g < 0.0)
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match deepest {
            Some((i, _)) => active.push(i),
            None => break,
        }
    }
    (q1, q2)
}
