//! Residual flexibility in the work-precision output: the modes above a
//! cut-off `f_c` dropped (plain truncation), or dropped and replaced by
//! their static compliance (`SolverOptions::residual_above_hz`), against the
//! full model at the same time step: error against run time.

use crate::analysis::bench::BenchError;
use crate::analysis::bench::work_precision::{Sampled, rms_rel, sample};
use tirecontact_core::model::convolution::ModalBasis;
use tirecontact_core::solver::simulation::SolverOptions;
use tirecontact_io::identify::{ModeCache, PreparedModel};
use tirecontact_io::scene::{Scene, Tyre};

/// One variant of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct ResidualRow {
    pub scene: String,
    /// "full", "truncated", "truncated + residual" (the scene's contact
    /// scheme) or "truncated + residual, paper contact rule".
    pub variant: &'static str,
    /// Cut-off (Hz).
    pub cutoff_hz: f64,
    /// Modes in the convolution, of all.
    pub modes_kept: usize,
    pub modes_total: usize,
    /// Convolution states (rank terms).
    pub states: usize,
    pub dt_s: f64,
    pub wall_s: f64,
    /// RMS relative displacement error against the full model (-).
    pub disp_err: f64,
    /// RMS relative error of the window-mean forces against the full model (-).
    pub force_err: f64,
    /// Located events (impacts and releases) in the run.
    pub events: u64,
    /// Why the run failed, if it did (e.g. fewer kept modes than points
    /// in contact: the rigid contact system is singular).
    pub note: String,
}

/// The default cut-off of a scene: the median mode frequency (the upper
/// half of the modes is dropped); `None` with fewer than two modes.
pub fn default_cutoff_hz(model: &PreparedModel) -> Option<f64> {
    let mut f: Vec<f64> = model.modes().iter().map(|m| m.freq_hz).collect();
    if f.len() < 2 {
        return None;
    }
    f.sort_by(f64::total_cmp);
    Some(f[(f.len() - 1) / 2])
}

/// Runs the three variants of `scene` (its own dt, `duration_s`) and
/// compares each with the full model; force errors over `window_s` means.
pub fn residual_study(
    model: &PreparedModel,
    cutoff_hz: f64,
    duration_s: f64,
    window_s: f64,
) -> Result<Vec<ResidualRow>, BenchError> {
    let scene = model.scene();
    let modes = model.modes();
    let p = scene.num_points();
    let dt = scene.dt_s;
    let mut truncated = scene.clone();
    let kept: Vec<_> = modes
        .iter()
        .filter(|m| m.freq_hz <= cutoff_hz)
        .cloned()
        .collect();
    // every variant at the source scene's rank cut (the truncated scene's
    // modes are the source's, identified or given)
    let base = SolverOptions {
        rank_tolerance: Some(SolverOptions::default().rank_tolerance_for(model.problem())),
        ..SolverOptions::default()
    };
    let states = |m: &[tirecontact_core::base::modal::Mode]| {
        ModalBasis::with_rank_tolerance(m, p, base.rank_tolerance_for(model.problem()))
            .map(|b| b.num_states())
    };
    let (states_all, states_kept) = (states(modes)?, states(&kept)?);
    truncated.tyre = Tyre::Modal {
        modes: kept.clone(),
    };
    let mut paper = scene.clone();
    paper.contact_scheme = tirecontact_io::scene::ContactScheme::Paper;
    let variants = [
        ("full", scene, base, modes.len(), states_all),
        ("truncated", &truncated, base, kept.len(), states_kept),
        (
            "truncated + residual",
            scene,
            SolverOptions {
                residual_above_hz: Some(cutoff_hz),
                ..base
            },
            kept.len(),
            states_kept,
        ),
        (
            "truncated + residual, paper contact rule",
            &paper,
            SolverOptions {
                residual_above_hz: Some(cutoff_hz),
                ..base
            },
            kept.len(),
            states_kept,
        ),
    ];
    // the variants share the source's modes: none is identified again
    let cache = ModeCache::new();
    cache.remember(model);
    let mut rows = Vec::new();
    let mut reference = None;
    for (variant, sc, options, modes_kept, states) in variants {
        let mut row = ResidualRow {
            scene: scene.name.clone(),
            variant,
            cutoff_hz,
            modes_kept,
            modes_total: modes.len(),
            states,
            dt_s: dt,
            wall_s: f64::NAN,
            disp_err: f64::NAN,
            force_err: f64::NAN,
            events: 0,
            note: String::new(),
        };
        let (t_s, u_m, q_n, wall, events) = match run(sc, duration_s, options, &cache) {
            Ok(r) => r,
            Err(e) if reference.is_some() => {
                row.note = e.to_string();
                rows.push(row);
                continue;
            }
            Err(e) => return Err(e),
        };
        let smp = sample(&t_s, &u_m, &q_n, dt, window_s, dt, duration_s);
        let (disp_err, force_err) = match &reference {
            None => (0.0, 0.0),
            Some(r) => {
                let r: &Sampled = r;
                (rms_rel(&smp.u, &r.u), rms_rel(&smp.q, &r.q))
            }
        };
        if reference.is_none() {
            reference = Some(smp);
        }
        rows.push(ResidualRow {
            wall_s: wall,
            disp_err,
            force_err,
            events,
            ..row
        });
    }
    Ok(rows)
}

/// Time history of a run: times, displacements, step-mean forces, its wall
/// time (s, the steps only) and its located events.
type History = (Vec<f64>, Vec<Vec<f64>>, Vec<Vec<f64>>, f64, u64);

fn run(
    scene: &Scene,
    duration_s: f64,
    options: SolverOptions,
    cache: &ModeCache,
) -> Result<History, BenchError> {
    let (run, wall, events) = crate::analysis::bench::work_precision::run_stable(
        scene,
        scene.contact_scheme,
        scene.dt_s,
        duration_s,
        options,
        cache,
    )?;
    Ok((run.t_s, run.u_m, run.q_n, wall, events))
}

/// Markdown table of the rows.
pub fn to_markdown(rows: &[ResidualRow]) -> String {
    let mut s = String::from(
        "| scene | variant | f_c (Hz) | modes kept | states | dt (s) | run time (s) | displacement error | force error (window means) | located events | note |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {} | {:.0} | {} of {} | {} | {:e} | {:.4} | {:.2e} | {:.2e} | {} | {} |\n",
            r.scene,
            r.variant,
            r.cutoff_hz,
            r.modes_kept,
            r.modes_total,
            r.states,
            r.dt_s,
            r.wall_s,
            r.disp_err,
            r.force_err,
            r.events,
            r.note
        ));
    }
    s
}
