//! Reading the work-precision curves: the fastest run under an error,
//! where a method's error stops falling, and the time at an error
//! interpolated between runs.

use super::{Method, Row};

/// The fastest run of `method` (any penalty, time step or tolerance) whose
/// displacement error is at most `target`: the best a user sweeping the
/// method's choices gets at that error.
pub fn fastest_at_error(rows: &[Row], method: Method, target: f64) -> Option<&Row> {
    rows.iter()
        .filter(|r| r.method == method && r.disp_err.is_finite() && r.disp_err <= target)
        .min_by(|a, b| a.wall_s.total_cmp(&b.wall_s))
}

/// A refinement (a finer step or a tighter tolerance) that lowers the
/// error by less than this factor, and every later one too, means the
/// error stopped falling ([`plateau`]).
pub const PLATEAU_FACTOR: f64 = 2.0;

/// Where the error of `method` on `scene` stops falling: over its runs in
/// sweep order (time steps coarse to fine, tolerances loose to tight), the
/// first run that no later run improves on by [`PLATEAU_FACTOR`]; `None`
/// when the error still falls at the last run (or it has fewer than two
/// finite runs).
pub fn plateau<'a>(rows: &'a [Row], scene: &str, method: Method) -> Option<&'a Row> {
    let runs: Vec<&Row> = rows
        .iter()
        .filter(|r| r.scene == scene && r.method == method && r.disp_err.is_finite())
        .collect();
    (0..runs.len().saturating_sub(1)).find_map(|k| {
        let best_later = runs[k + 1..]
            .iter()
            .map(|r| r.disp_err)
            .fold(f64::INFINITY, f64::min);
        (best_later * PLATEAU_FACTOR > runs[k].disp_err).then_some(runs[k])
    })
}

/// A CPU time (s) at an error, and whether it is an upper bound
/// ([`cpu_at_error`]).
pub type CpuAtError = (f64, bool);

/// The CPU time (s) `method` needs on `scene` for displacement error
/// `target`, on its work-precision curve: the lower envelope of its runs
/// (by CPU time, each run more accurate than every faster one: what a
/// user sweeping its step or tolerance gets), interpolated log-log between
/// the two envelope runs that bracket the error. When the envelope's
/// fastest run is already more accurate, its time, flagged `true` (an
/// upper bound: no run of the sweep reaches the error faster). `None`
/// when no run reaches it or a run has no CPU time.
pub fn cpu_at_error(rows: &[Row], scene: &str, method: Method, target: f64) -> Option<(f64, bool)> {
    let mut pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.scene == scene && r.method == method)
        .filter(|r| r.disp_err.is_finite() && r.disp_err > 0.0)
        .map(|r| Some((r.cpu_s?.max(1e-9), r.disp_err)))
        .collect::<Option<_>>()?;
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut best = f64::INFINITY;
    pts.retain(|&(_, e)| {
        let keep = e < best;
        best = best.min(e);
        keep
    });
    let first = *pts.first()?;
    if first.1 <= target {
        return Some((first.0, true));
    }
    let swapped: Vec<(f64, f64)> = pts.iter().map(|&(t, e)| (e, t)).collect();
    interpolate_time(&swapped, target).map(|t| (t, false))
}

/// Log-log interpolation of `(error, time)` points at error `target`
/// between the first consecutive pair that brackets it.
fn interpolate_time(pts: &[(f64, f64)], target: f64) -> Option<f64> {
    pts.windows(2).find_map(|w| {
        let ((e0, t0), (e1, t1)) = (w[0], w[1]);
        let (lo, hi) = (e0.min(e1), e0.max(e1));
        (lo <= target && target <= hi && e0 != e1).then(|| {
            let f = (target.ln() - e0.ln()) / (e1.ln() - e0.ln());
            (t0.ln() + f * (t1.ln() - t0.ln())).exp()
        })
    })
}

/// Error levels of the speed-ups against the peers.
pub const PEER_ERROR_LEVELS: [f64; 3] = [1e-2, 1e-4, 1e-6];

/// Interpolated run time (s) of `method` at displacement error `target`
/// (log-log between the bracketing runs), if its runs bracket it.
pub fn time_at_error(rows: &[Row], method: Method, target: f64) -> Option<f64> {
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.method == method && r.disp_err.is_finite() && r.disp_err > 0.0)
        .map(|r| (r.disp_err, r.wall_s.max(1e-9)))
        .collect();
    interpolate_time(&pts, target)
}
