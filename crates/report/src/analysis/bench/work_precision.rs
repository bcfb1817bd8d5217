//! Work-precision study: run time against error for each method, over a
//! range of time steps, against a converged reference (a Located run at a
//! quarter of the finest step).
//!
//! Errors: displacement, RMS relative over a common sampling grid; force,
//! RMS relative of its means over windows (impacts are impulses, so only
//! window means compare).

use crate::analysis::bench::BenchError;
use crate::analysis::bench::baselines::{BaselineRun, Kernel, run_baseline};
mod curves;
mod patch;
mod report;
mod timing;
pub use curves::*;
use patch::has_tread_springs;
pub use patch::{PatchCut, patch_scene, patch_study};
pub use report::{TREAD_ERROR_LEVEL, figure, to_csv, to_markdown, tread_times};
use timing::cpu_since;
pub use timing::*;
use tirecontact_core::solver::simulation::SolverOptions;
use tirecontact_io::identify::ModeCache;
use tirecontact_io::scene::{ContactScheme, Scene};
use web_time::Instant;

/// The methods compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Stable convolution, events located inside the step (the default).
    Located,
    /// Stable convolution, the paper's step-end contact rule.
    Paper,
    /// The paper's α/β convolution with its contact rule.
    AlphaBeta,
    /// Direct O(N²) convolution with the paper's contact rule.
    Direct,
    /// Newmark (average acceleration) on the modal equations, penalty
    /// contact (`bench::peers::run_newmark`, feature `peers`).
    Newmark,
    /// Adaptive Dormand–Prince 5(4), penalty contact
    /// (`bench::peers::run_dopri`, feature `peers`).
    Dopri,
    /// Adaptive implicit BDF, penalty contact, its switches located as
    /// events (`bench::peers::run_bdf`, feature `peers`).
    Bdf,
    /// Adaptive implicit BDF on a scene's own undamped tread springs, the
    /// landings and releases located as events
    /// (`bench::peers::run_bdf_tread`, feature `peers`).
    BdfTread,
}

impl Method {
    pub const ALL: [Method; 8] = [
        Method::Located,
        Method::Paper,
        Method::AlphaBeta,
        Method::Direct,
        Method::Newmark,
        Method::Dopri,
        Method::Bdf,
        Method::BdfTread,
    ];
    /// The methods people use for dynamic contact, swept over penalties.
    pub const PEERS: [Method; 3] = [Method::Newmark, Method::Dopri, Method::Bdf];
    pub fn label(self) -> &'static str {
        match self {
            Method::Located => "stable + located events",
            Method::Paper => "stable + paper contact",
            Method::AlphaBeta => "paper alpha/beta",
            Method::Direct => "direct convolution O(N^2)",
            Method::Newmark => "Newmark + penalty",
            Method::Dopri => "Dormand-Prince 5(4) + penalty",
            Method::Bdf => "BDF, located switches + penalty",
            Method::BdfTread => "BDF, located switches + tread springs",
        }
    }
    pub fn key(self) -> &'static str {
        match self {
            Method::Located => "located",
            Method::Paper => "paper",
            Method::AlphaBeta => "alpha_beta",
            Method::Direct => "direct",
            Method::Newmark => "newmark_penalty",
            Method::Dopri => "dopri5_penalty",
            Method::Bdf => "bdf_penalty",
            Method::BdfTread => "bdf_tread",
        }
    }
}

/// What to run.
#[derive(Debug, Clone)]
pub struct Config {
    /// Time steps, coarse to fine (s); each divides the first.
    pub dts: Vec<f64>,
    /// Run length of the stable methods and α/β (s).
    pub duration_s: f64,
    /// Run length of the direct method (s): it is O(N²).
    pub direct_duration_s: f64,
    /// Largest number of steps of a direct run.
    pub direct_max_steps: usize,
    /// Whether the paper's α/β and direct convolution baselines run.
    pub baselines: bool,
    /// Force window (s).
    pub force_window_s: f64,
    /// Penalty stiffnesses of the peer baselines (N/m), swept.
    pub penalties_n_m: Vec<f64>,
    /// Relative tolerances of the adaptive explicit integrator, swept.
    pub rtols: Vec<f64>,
    /// Relative tolerances of the adaptive implicit integrator, swept.
    pub implicit_rtols: Vec<f64>,
}

impl Config {
    /// The default study: dt from 4e-5 s to 1.25e-6 s, penalties from
    /// 1e6 to 1e12 N/m, Dormand-Prince's tolerance from 1e-3 to 1e-7 and
    /// BDF's from 1e-3 to 1e-8 (tighter, their errors are those of the
    /// tightest to three digits on every preset: the penalty's).
    pub fn standard() -> Self {
        Config {
            dts: (0..6).map(|k| 4e-5 / 2f64.powi(k)).collect(),
            duration_s: 0.2,
            direct_duration_s: 0.1,
            direct_max_steps: 10_000,
            baselines: true,
            force_window_s: 1e-3,
            penalties_n_m: (6..=12).map(|e| 10f64.powi(e)).collect(),
            rtols: vec![1e-3, 1e-5, 1e-7],
            implicit_rtols: (3..=8).map(|e| 10f64.powi(-e)).collect(),
        }
    }
    /// The study of a large scene (tens of points, hundreds of modes): the
    /// standard time steps over a shorter run (0.05 s), without the α/β
    /// and direct baselines (on 50 points and 200 modes an α/β run takes
    /// up to two minutes; the direct one is O(N²) in steps), and the
    /// peers' sweeps thinned to every other
    /// decade of penalty (1e8 to 1e12 N/m; below, the penalty error is
    /// above 1e-2) and of tolerance.
    pub fn large() -> Self {
        Config {
            duration_s: 0.05,
            baselines: false,
            penalties_n_m: vec![1e8, 1e10, 1e12],
            rtols: vec![1e-3, 1e-5],
            implicit_rtols: vec![1e-3, 1e-5, 1e-7],
            ..Config::standard()
        }
    }
    /// The study of a contact patch with tread springs ([`patch_scene`]):
    /// the located solver over time steps from 1e-4 s to 1.5625e-6 s
    /// (its reference at 3.9e-7 s, 1e-6 accurate on the chip seal's cut)
    /// and the BDF peer on the same tread springs over tolerances from
    /// 1e-3 to 1e-8, over `duration_s`; no penalty sweep (the springs are
    /// the scene's) and neither the α/β nor the direct baseline (the
    /// paper's rigid contact, another physics). Looser tolerances make
    /// BDF's switches chatter and its runs slower (on the chip seal's cut,
    /// 15 000 switches and 14 s at 1e-2 against 600 and 1.3 s at 1e-4).
    pub fn patch(duration_s: f64) -> Self {
        Config {
            dts: (0..7).map(|k| 1e-4 / 2f64.powi(k)).collect(),
            duration_s,
            baselines: false,
            penalties_n_m: Vec::new(),
            rtols: Vec::new(),
            implicit_rtols: (3..=8).map(|e| 10f64.powi(-e)).collect(),
            ..Config::standard()
        }
    }
    /// A small study for tests.
    pub fn quick() -> Self {
        Config {
            dts: vec![4e-5, 2e-5, 1e-5],
            duration_s: 0.08,
            direct_duration_s: 0.08,
            direct_max_steps: 2_000,
            baselines: true,
            force_window_s: 1e-3,
            penalties_n_m: vec![1e7, 1e9],
            rtols: vec![1e-4, 1e-7],
            implicit_rtols: vec![1e-4, 1e-7],
        }
    }
}

/// One run of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub scene: String,
    pub method: Method,
    pub dt_s: f64,
    pub steps: usize,
    pub wall_s: f64,
    /// The run's CPU time (s, the process's; `None` where it cannot be
    /// read): from the tyre's modes to the recorded run, set-up included.
    pub cpu_s: Option<f64>,
    /// RMS relative displacement error.
    pub disp_err: f64,
    /// RMS relative error of the window-mean forces.
    pub force_err: f64,
    /// Observed order of the displacement error against the previous dt.
    pub order: Option<f64>,
    /// The peer baselines' penalty stiffness (N/m).
    pub penalty_n_m: Option<f64>,
    /// The adaptive integrator's relative tolerance (its `dt_s` is the
    /// output interval).
    pub rtol: Option<f64>,
    pub note: String,
}

/// Sampled histories: displacements on the grid of the coarsest step, window-mean forces.
pub struct Sampled {
    pub u: Vec<f64>,
    pub q: Vec<f64>,
}

pub fn sample(
    t_s: &[f64],
    u: &[Vec<f64>],
    q: &[Vec<f64>],
    grid_s: f64,
    window_s: f64,
    dt: f64,
    t_end: f64,
) -> Sampled {
    let every = (grid_s / dt).round() as usize;
    let nwin = (t_end / window_s).floor() as usize;
    let p = u.first().map_or(0, Vec::len);
    let mut qs = vec![0.0; nwin * p];
    let per = (window_s / dt).round();
    let mut us = Vec::new();
    for (k, (t, (uk, qk))) in t_s.iter().zip(u.iter().zip(q)).enumerate() {
        if (k + 1) % every == 0 {
            us.extend_from_slice(uk);
        }
        let w = ((t - 0.5 * dt) / window_s).floor() as usize;
        if w < nwin {
            for i in 0..p {
                qs[w * p + i] += qk[i] / per;
            }
        }
    }
    Sampled { u: us, q: qs }
}

pub fn rms_rel(a: &[f64], reference: &[f64]) -> f64 {
    let n = a.len().min(reference.len());
    let num: f64 = (0..n).map(|k| (a[k] - reference[k]).powi(2)).sum();
    let den: f64 = (0..n).map(|k| reference[k].powi(2)).sum();
    if a[..n].iter().any(|x| !x.is_finite()) {
        return f64::INFINITY;
    }
    (num / den.max(f64::MIN_POSITIVE)).sqrt()
}

/// The study of one scene. `progress` is told each run as it starts. The
/// peers ([`Method::PEERS`], [`Method::BdfTread`]) run with the feature
/// `peers` only.
///
/// A scene with tread springs (`contact: Compliant`) is studied on its own
/// contact law: the located solver over the time steps and the BDF peer on
/// the same undamped springs over the implicit tolerances
/// ([`Method::BdfTread`]); the penalty peers and the rigid-contact
/// baselines (another physics) do not run.
pub fn study(
    scene: &Scene,
    cfg: &Config,
    mut progress: impl FnMut(&str),
) -> Result<Vec<Row>, BenchError> {
    // the tyre is identified once for every time step of the study
    let cache = ModeCache::new();
    let reference = Reference::run(scene, cfg, &cache, &mut progress)?;
    let runs = Runs {
        scene,
        cfg,
        cache: &cache,
        reference,
    };
    let mut rows = Vec::new();
    if has_tread_springs(scene) {
        rows.extend(runs.convolution_rows(Method::Located, &mut progress)?);
        #[cfg(feature = "peers")]
        rows.extend(runs.bdf_tread_rows(&mut progress)?);
        return Ok(rows);
    }
    for method in [
        Method::Located,
        Method::Paper,
        Method::AlphaBeta,
        Method::Direct,
    ] {
        if cfg.baselines || matches!(method, Method::Located | Method::Paper) {
            rows.extend(runs.convolution_rows(method, &mut progress)?);
        }
    }
    // the peers: Newmark over the time steps, Dormand-Prince (output
    // every finest step) and BDF (output on the comparison grid) over the
    // tolerances, each for every penalty
    #[cfg(feature = "peers")]
    for &k in &cfg.penalties_n_m {
        rows.extend(runs.newmark_rows(k, &mut progress)?);
        rows.extend(runs.dopri_rows(k, &mut progress)?);
        rows.extend(runs.bdf_rows(k, &mut progress)?);
    }
    Ok(rows)
}

/// The converged reference of a study, sampled, and the sampling that
/// compares a run with it.
struct Reference {
    /// Displacements are compared on the grid of the coarsest step (s).
    grid_s: f64,
    /// Forces are compared as means over windows of this length (s).
    window_s: f64,
    sampled: Sampled,
}

impl Reference {
    /// The reference: a Located run at a quarter of the finest step.
    fn run(
        scene: &Scene,
        cfg: &Config,
        cache: &ModeCache,
        progress: &mut dyn FnMut(&str),
    ) -> Result<Self, BenchError> {
        let grid_s = cfg.dts[0];
        let dt_ref = cfg.dts.iter().cloned().fold(f64::INFINITY, f64::min) / 4.0;
        progress(&format!(
            "{}: reference, located at dt = {dt_ref:e} s",
            scene.name
        ));
        let (reference, _, _) = run_stable(
            scene,
            ContactScheme::Located,
            dt_ref,
            cfg.duration_s,
            SolverOptions::default(),
            cache,
        )?;
        let sampled = sample(
            &reference.t_s,
            &reference.u_m,
            &reference.q_n,
            grid_s,
            cfg.force_window_s,
            dt_ref,
            cfg.duration_s,
        );
        Ok(Reference {
            grid_s,
            window_s: cfg.force_window_s,
            sampled,
        })
    }

    /// The displacement and window-force errors of a run recorded every `dt`.
    fn errors(&self, run: &BaselineRun, dt: f64, duration: f64) -> (f64, f64) {
        let smp = sample(
            &run.t_s,
            &run.u_m,
            &run.q_n,
            self.grid_s,
            self.window_s,
            dt,
            duration,
        );
        (
            rms_rel(&smp.u, &self.sampled.u),
            rms_rel(&smp.q, &self.sampled.q),
        )
    }
}

/// What the runs of a study share: the scene, the configuration, the
/// tyre's modes and the reference they are compared with.
struct Runs<'a> {
    scene: &'a Scene,
    cfg: &'a Config,
    cache: &'a ModeCache,
    reference: Reference,
}

impl Runs<'_> {
    /// The rows of a convolution method (`Located`, `Paper`, `AlphaBeta` or
    /// `Direct`) over the time steps: direct runs only up to
    /// `direct_max_steps` steps, and a baseline that cannot run ends the
    /// method's sweep.
    fn convolution_rows(
        &self,
        method: Method,
        progress: &mut dyn FnMut(&str),
    ) -> Result<Vec<Row>, BenchError> {
        let cfg = self.cfg;
        let mut rows = Vec::new();
        let mut prev: Option<(f64, f64)> = None;
        for &dt in &cfg.dts {
            let duration = if method == Method::Direct {
                cfg.direct_duration_s
            } else {
                cfg.duration_s
            };
            let steps = (duration / dt).round() as usize;
            if method == Method::Direct && steps > cfg.direct_max_steps {
                continue;
            }
            progress(&format!(
                "{}: {} at dt = {dt:e} s",
                self.scene.name,
                method.label()
            ));
            let cpu = process_cpu_s();
            let Some((run, wall)) = self.convolution_run(method, dt, duration, steps, progress)?
            else {
                break;
            };
            let cpu_s = cpu_since(cpu);
            let (disp_err, force_err) = self.reference.errors(&run, dt, duration);
            let order = observed_order(prev, dt, disp_err);
            prev = Some((dt, disp_err));
            let note = match run.overflow_t_s {
                Some(t) => format!("overflow (non-finite) from t = {t:.4} s"),
                None if method == Method::Direct => format!("{duration} s run (O(N^2))"),
                None => String::new(),
            };
            rows.push(Row {
                scene: self.scene.name.clone(),
                method,
                dt_s: dt,
                steps,
                wall_s: wall,
                cpu_s,
                disp_err,
                force_err,
                order,
                penalty_n_m: None,
                rtol: None,
                note,
            });
        }
        Ok(rows)
    }

    /// One run of a convolution method at `dt`, recorded every step, and
    /// its wall time (s); `None` when the α/β or direct baseline cannot run
    /// (told to `progress`).
    fn convolution_run(
        &self,
        method: Method,
        dt: f64,
        duration: f64,
        steps: usize,
        progress: &mut dyn FnMut(&str),
    ) -> Result<Option<(BaselineRun, f64)>, BenchError> {
        match method {
            Method::Located | Method::Paper => {
                let scheme = if method == Method::Located {
                    ContactScheme::Located
                } else {
                    ContactScheme::Paper
                };
                let (run, wall, _) = run_stable(
                    self.scene,
                    scheme,
                    dt,
                    duration,
                    SolverOptions::default(),
                    self.cache,
                )?;
                Ok(Some((run, wall)))
            }
            Method::Newmark | Method::Dopri | Method::Bdf | Method::BdfTread => {
                unreachable!(
                    "the peers have their own rows (newmark_rows, dopri_rows, bdf_rows, bdf_tread_rows)"
                )
            }
            Method::AlphaBeta | Method::Direct => {
                let kernel = if method == Method::AlphaBeta {
                    Kernel::AlphaBeta
                } else {
                    Kernel::Direct
                };
                let mut s = self.scene.clone();
                s.dt_s = dt;
                let start = Instant::now();
                let run = match run_baseline(&s, kernel, steps, self.cache) {
                    Ok(r) => r,
                    Err(e) => {
                        progress(&format!("  skipped: {e}"));
                        return Ok(None);
                    }
                };
                Ok(Some((run, start.elapsed().as_secs_f64())))
            }
        }
    }

    /// The rows of Newmark with penalty contact of stiffness `k` (N/m) over
    /// the time steps.
    #[cfg(feature = "peers")]
    fn newmark_rows(&self, k: f64, progress: &mut dyn FnMut(&str)) -> Result<Vec<Row>, BenchError> {
        let cfg = self.cfg;
        let mut rows = Vec::new();
        let mut prev: Option<(f64, f64)> = None;
        for &dt in &cfg.dts {
            progress(&format!(
                "{}: Newmark + penalty k = {k:e} N/m at dt = {dt:e} s",
                self.scene.name
            ));
            let mut s = self.scene.clone();
            s.dt_s = dt;
            let steps = (cfg.duration_s / dt).round() as usize;
            let (start, cpu) = (Instant::now(), process_cpu_s());
            let run = crate::analysis::bench::peers::run_newmark(&s, k, steps, self.cache)?;
            let wall = start.elapsed().as_secs_f64();
            let cpu_s = cpu_since(cpu);
            let (disp_err, force_err) = self.reference.errors(&run, dt, cfg.duration_s);
            let order = observed_order(prev, dt, disp_err);
            prev = Some((dt, disp_err));
            rows.push(Row {
                scene: self.scene.name.clone(),
                method: Method::Newmark,
                dt_s: dt,
                steps,
                wall_s: wall,
                cpu_s,
                disp_err,
                force_err,
                order,
                penalty_n_m: Some(k),
                rtol: None,
                note: run.overflow_t_s.map_or(String::new(), |t| {
                    format!("overflow (non-finite) from t = {t:.4} s")
                }),
            });
        }
        Ok(rows)
    }

    /// The rows of Dormand-Prince with penalty contact of stiffness `k`
    /// (N/m) over the tolerances, its output every finest step; a run that
    /// cannot start is skipped (told to `progress`).
    #[cfg(feature = "peers")]
    fn dopri_rows(&self, k: f64, progress: &mut dyn FnMut(&str)) -> Result<Vec<Row>, BenchError> {
        let cfg = self.cfg;
        let dt_out = cfg.dts.iter().cloned().fold(f64::INFINITY, f64::min);
        let mut rows = Vec::new();
        for &rtol in &cfg.rtols {
            progress(&format!(
                "{}: Dormand-Prince + penalty k = {k:e} N/m at rtol = {rtol:e}",
                self.scene.name
            ));
            let (start, cpu) = (Instant::now(), process_cpu_s());
            let (run, st) = match crate::analysis::bench::peers::run_dopri(
                self.scene,
                k,
                rtol,
                dt_out,
                cfg.duration_s,
                self.cache,
            ) {
                Ok(r) => r,
                Err(e) => {
                    progress(&format!("  skipped: {e}"));
                    continue;
                }
            };
            let wall = start.elapsed().as_secs_f64();
            let cpu_s = cpu_since(cpu);
            let (disp_err, force_err) = self.reference.errors(&run, dt_out, cfg.duration_s);
            rows.push(Row {
                scene: self.scene.name.clone(),
                method: Method::Dopri,
                dt_s: dt_out,
                steps: st.accepted as usize,
                wall_s: wall,
                cpu_s,
                disp_err,
                force_err,
                order: None,
                penalty_n_m: Some(k),
                rtol: Some(rtol),
                note: format!(
                    "{} accepted, {} rejected steps, {} evaluations",
                    st.accepted, st.rejected, st.evaluations
                ),
            });
        }
        Ok(rows)
    }

    /// The rows of BDF with penalty contact of stiffness `k` (N/m) and
    /// located switches over the tolerances, its output on the grid the
    /// errors are sampled on (the coarsest step: displacements there, and
    /// the impulse differences whose sums are the window means of the
    /// force); a run that gives up is a row of infinite error, its note
    /// the reason.
    #[cfg(feature = "peers")]
    fn bdf_rows(&self, k: f64, progress: &mut dyn FnMut(&str)) -> Result<Vec<Row>, BenchError> {
        let cfg = self.cfg;
        let dt_out = self.reference.grid_s;
        let mut rows = Vec::new();
        for &rtol in &cfg.implicit_rtols {
            progress(&format!(
                "{}: BDF + penalty k = {k:e} N/m at rtol = {rtol:e}",
                self.scene.name
            ));
            let (start, cpu) = (Instant::now(), process_cpu_s());
            let (run, st) = match crate::analysis::bench::peers::run_bdf(
                self.scene,
                k,
                rtol,
                dt_out,
                cfg.duration_s,
                self.cache,
            ) {
                Ok(r) => (r.run, r.stats),
                Err(e) => {
                    // kept as a row: a stiff penalty at a loose tolerance
                    // can make the integrator give up
                    progress(&format!("  gave up: {e}"));
                    rows.push(Row {
                        scene: self.scene.name.clone(),
                        method: Method::Bdf,
                        dt_s: dt_out,
                        steps: 0,
                        wall_s: start.elapsed().as_secs_f64(),
                        cpu_s: cpu_since(cpu),
                        disp_err: f64::INFINITY,
                        force_err: f64::INFINITY,
                        order: None,
                        penalty_n_m: Some(k),
                        rtol: Some(rtol),
                        note: format!("gave up: {e}"),
                    });
                    continue;
                }
            };
            let wall = start.elapsed().as_secs_f64();
            let cpu_s = cpu_since(cpu);
            let (disp_err, force_err) = self.reference.errors(&run, dt_out, cfg.duration_s);
            rows.push(Row {
                scene: self.scene.name.clone(),
                method: Method::Bdf,
                dt_s: dt_out,
                steps: st.accepted as usize,
                wall_s: wall,
                cpu_s,
                disp_err,
                force_err,
                order: None,
                penalty_n_m: Some(k),
                rtol: Some(rtol),
                note: format!(
                    "{} accepted, {} rejected steps, {} evaluations, {} factorisations, {} located switches",
                    st.accepted, st.rejected, st.evaluations, st.factorisations, st.switches
                ),
            });
        }
        Ok(rows)
    }
}

impl Runs<'_> {
    /// The rows of BDF on the scene's own tread springs (no damper), its
    /// landings and releases located, over the implicit tolerances, its
    /// output on the grid the errors are sampled on; a run that gives up is
    /// a row of infinite error, its note the reason.
    #[cfg(feature = "peers")]
    fn bdf_tread_rows(&self, progress: &mut dyn FnMut(&str)) -> Result<Vec<Row>, BenchError> {
        let cfg = self.cfg;
        let dt_out = self.reference.grid_s;
        let mut rows = Vec::new();
        for &rtol in &cfg.implicit_rtols {
            progress(&format!(
                "{}: BDF + tread springs at rtol = {rtol:e}",
                self.scene.name
            ));
            let (start, cpu) = (Instant::now(), process_cpu_s());
            let result = crate::analysis::bench::peers::run_bdf_tread(
                self.scene,
                rtol,
                dt_out,
                cfg.duration_s,
                self.cache,
            );
            let (wall, cpu_s) = (start.elapsed().as_secs_f64(), cpu_since(cpu));
            let mut row = Row {
                scene: self.scene.name.clone(),
                method: Method::BdfTread,
                dt_s: dt_out,
                steps: 0,
                wall_s: wall,
                cpu_s,
                disp_err: f64::INFINITY,
                force_err: f64::INFINITY,
                order: None,
                penalty_n_m: None,
                rtol: Some(rtol),
                note: String::new(),
            };
            match result {
                Ok(r) => {
                    let st = r.stats;
                    (row.disp_err, row.force_err) =
                        self.reference.errors(&r.run, dt_out, cfg.duration_s);
                    row.steps = st.accepted as usize;
                    row.note = format!(
                        "{} accepted, {} rejected steps, {} evaluations, {} factorisations, {} located switches",
                        st.accepted, st.rejected, st.evaluations, st.factorisations, st.switches
                    );
                }
                Err(e) => {
                    progress(&format!("  gave up: {e}"));
                    row.note = format!("gave up: {e}");
                }
            }
            rows.push(row);
        }
        Ok(rows)
    }
}

/// The observed order of the error `err` at `dt` against the previous
/// run's `(dt, error)`.
fn observed_order(prev: Option<(f64, f64)>, dt: f64, err: f64) -> Option<f64> {
    prev.and_then(|(pdt, pe)| {
        (err.is_finite() && pe.is_finite() && err > 0.0).then(|| (pe / err).ln() / (pdt / dt).ln())
    })
}
