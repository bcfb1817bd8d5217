//! The work-precision study's outputs: its CSV, the markdown tables
//! (speed-ups at equal error, against the peers at set error levels) and
//! the diagram.

use super::{
    CpuAtError, Method, PEER_ERROR_LEVELS, PLATEAU_FACTOR, Row, cpu_at_error, fastest_at_error,
    plateau, time_at_error,
};
use crate::output::figures::{Figure, Panel, Series, Style};

/// CSV of the rows.
pub fn to_csv(rows: &[Row]) -> Result<String, csv::Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "scene",
        "method",
        "dt_s",
        "steps",
        "wall_s",
        "disp_rms_rel_err",
        "force_window_rms_rel_err",
        "disp_order",
        "penalty_n_m",
        "rtol",
        "note",
        "cpu_s",
    ])?;
    for r in rows {
        w.write_record([
            r.scene.clone(),
            r.method.key().to_string(),
            format!("{:e}", r.dt_s),
            r.steps.to_string(),
            format!("{:.6e}", r.wall_s),
            format!("{:.6e}", r.disp_err),
            format!("{:.6e}", r.force_err),
            r.order.map_or(String::new(), |o| format!("{o:.3}")),
            r.penalty_n_m.map_or(String::new(), |k| format!("{k:e}")),
            r.rtol.map_or(String::new(), |t| format!("{t:e}")),
            r.note.clone(),
            r.cpu_s.map_or(String::new(), |t| format!("{t:.6e}")),
        ])?;
    }
    let bytes = w.into_inner().map_err(|e| e.into_error())?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// Markdown table of the rows, plus speed-ups at equal error.
pub fn to_markdown(rows: &[Row]) -> String {
    let mut s = String::from(
        "| scene | method | dt (s) | steps | run time (s) | displacement error | force error (window means) | order | note |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows
        .iter()
        .filter(|r| !Method::PEERS.contains(&r.method) && r.method != Method::BdfTread)
    {
        s.push_str(&format!(
            "| {} | {} | {:e} | {} | {:.4} | {:.2e} | {:.2e} | {} | {} |\n",
            r.scene,
            r.method.label(),
            r.dt_s,
            r.steps,
            r.wall_s,
            r.disp_err,
            r.force_err,
            r.order.map_or("".into(), |o| format!("{o:.2}")),
            r.note
        ));
    }
    let mut scenes: Vec<&str> = rows.iter().map(|r| r.scene.as_str()).collect();
    scenes.dedup();
    s.push_str("\nSpeed-up of the default method (stable + located events) at equal displacement error: the error of each other method's finest run, and the time the located method needs for it (interpolated log-log; `>=` when its coarsest run is already more accurate).\n\n| scene | error | method | its run time (s) | located run time (s) | speed-up |\n|---|---|---|---|---|---|\n");
    for sc in scenes {
        let sr: Vec<Row> = rows.iter().filter(|r| r.scene == sc).cloned().collect();
        let located: Vec<&Row> = sr.iter().filter(|r| r.method == Method::Located).collect();
        for m in [Method::Paper, Method::AlphaBeta, Method::Direct] {
            let Some(finest) = sr.iter().rfind(|r| r.method == m && r.disp_err.is_finite()) else {
                continue;
            };
            let target = finest.disp_err;
            let (tl, bound) = match time_at_error(&sr, Method::Located, target) {
                Some(t) => (t, ""),
                None => match located
                    .iter()
                    .filter(|r| r.disp_err <= target)
                    .map(|r| r.wall_s)
                    .reduce(f64::min)
                {
                    Some(t) => (t, ">= "),
                    None => continue,
                },
            };
            s.push_str(&format!(
                "| {sc} | {target:.2e} | {} | {:.4} | {tl:.5} | {bound}{:.0}x |\n",
                m.label(),
                finest.wall_s,
                finest.wall_s / tl.max(1e-9)
            ));
        }
    }
    // the peers' table when they ran (the feature `peers`)
    if rows.iter().any(|r| Method::PEERS.contains(&r.method)) {
        s.push_str(&peer_markdown(rows));
    }
    if rows.iter().any(|r| r.method == Method::BdfTread) {
        s.push_str(&tread_markdown(rows));
    }
    s
}

/// The error level of the tread-spring comparison's speed ratio.
pub const TREAD_ERROR_LEVEL: f64 = 1e-4;

/// The CPU times of the located solver and of the BDF peer on `scene` at
/// displacement error `target`, each on its work-precision curve
/// ([`cpu_at_error`]: `(s, whether an upper bound)`, `None` when no run
/// reaches the error).
pub fn tread_times(
    rows: &[Row],
    scene: &str,
    target: f64,
) -> (Option<CpuAtError>, Option<CpuAtError>) {
    (
        cpu_at_error(rows, scene, Method::Located, target),
        cpu_at_error(rows, scene, Method::BdfTread, target),
    )
}

/// The tread-spring scenes' table: both methods' runs (CPU time, set-up
/// included), the CPU-time ratio at [`TREAD_ERROR_LEVEL`] and where each
/// error stops falling.
fn tread_markdown(rows: &[Row]) -> String {
    let mut scenes: Vec<&str> = rows
        .iter()
        .filter(|r| r.method == Method::BdfTread)
        .map(|r| r.scene.as_str())
        .collect();
    scenes.dedup();
    let mut s = String::from(
        "\nTread springs on a contact patch: the located solver and adaptive implicit BDF on the same undamped tread springs (`q = k max(0, r - u)`, the scene's k), BDF's landings and releases located as roots of the gap on its interpolant and each a restart there; the reference is the located solver at a quarter of its finest step. CPU time of each run from the tyre's modes (set-up included); a run at a time step for the located solver, at a relative tolerance for BDF (its output every coarsest step).\n\n| scene | method | dt (s) or rtol | steps | CPU time (s) | displacement error | force error (window means) | note |\n|---|---|---|---|---|---|---|---|\n",
    );
    for sc in &scenes {
        for r in rows
            .iter()
            .filter(|r| r.scene == *sc && matches!(r.method, Method::Located | Method::BdfTread))
        {
            let setting = match r.rtol {
                Some(t) => format!("rtol {t:.0e}"),
                None => format!("{:e}", r.dt_s),
            };
            s.push_str(&format!(
                "| {sc} | {} | {setting} | {} | {} | {:.2e} | {:.2e} | {} |\n",
                r.method.label(),
                r.steps,
                r.cpu_s.map_or("-".into(), |t| format!("{t:.4}")),
                r.disp_err,
                r.force_err,
                r.note
            ));
        }
    }
    s.push_str(&format!(
        "\nAt displacement error {TREAD_ERROR_LEVEL:.0e}: each method's CPU time on its work-precision curve (the lower envelope of its runs, interpolated log-log; `<=` when its fastest run is already more accurate: no run of its sweep gets there faster), and where each error stops falling (the first run that no finer one improves on by {PLATEAU_FACTOR}x):\n\n| scene | located at {TREAD_ERROR_LEVEL:.0e} (s) | BDF at {TREAD_ERROR_LEVEL:.0e} (s) | BDF / located | located stops at | BDF stops at |\n|---|---|---|---|---|---|\n",
    ));
    for sc in &scenes {
        let (l, b) = tread_times(rows, sc, TREAD_ERROR_LEVEL);
        let t = |x: Option<CpuAtError>| match x {
            Some((t, bound)) => format!("{}{t:.4}", if bound { "<= " } else { "" }),
            None => "not reached".into(),
        };
        let ratio = match (l, b) {
            (Some((l, lb)), Some((b, bb))) => format!(
                "{}{:.1}x",
                match (lb, bb) {
                    (false, false) => "",
                    (true, false) => ">= ",
                    (false, true) => "<= ",
                    (true, true) => "~ ",
                },
                b / l
            ),
            _ => "-".into(),
        };
        let stop = |m: Method| match plateau(rows, sc, m) {
            Some(r) => format!(
                "{:.1e} from {}",
                r.disp_err,
                match r.rtol {
                    Some(t) => format!("rtol {t:.0e}"),
                    None => format!("dt {:e} s", r.dt_s),
                }
            ),
            None => "still falling at the finest run".into(),
        };
        s.push_str(&format!(
            "| {sc} | {} | {} | {ratio} | {} | {} |\n",
            t(l),
            t(b),
            stop(Method::Located),
            stop(Method::BdfTread)
        ));
    }
    s
}

/// The peers' table: per scene, error level and peer, the fastest run of
/// the peer's sweep (penalty, time step or tolerance) reaching the error,
/// the fastest located run reaching it, and the speed-up.
fn peer_markdown(rows: &[Row]) -> String {
    let mut scenes: Vec<&str> = rows
        .iter()
        .filter(|r| Method::PEERS.contains(&r.method))
        .map(|r| r.scene.as_str())
        .collect();
    scenes.dedup();
    let mut s = String::from(
        "\nSpeed-up of the default method at equal displacement error against the methods people use for dynamic contact: Newmark (average acceleration) on the modal equations, adaptive Dormand-Prince 5(4), and adaptive implicit BDF with its contact switches located as events, all with penalty contact (a spring k with its critical damper at each point), each the fastest run of its sweep over k, the time step or the tolerance that reaches the error; the located method's fastest run reaching it.\n\n| scene | error | peer | its fastest run (s) | its k (N/m), dt or rtol | located run (s) | speed-up |\n|---|---|---|---|---|---|---|\n",
    );
    for sc in scenes {
        let sr: Vec<Row> = rows.iter().filter(|r| r.scene == sc).cloned().collect();
        for target in PEER_ERROR_LEVELS {
            let located = fastest_at_error(&sr, Method::Located, target);
            for m in Method::PEERS {
                let peer = fastest_at_error(&sr, m, target);
                let how = |r: &Row| match (r.penalty_n_m, r.rtol) {
                    (Some(k), Some(t)) => format!("k = {k:.0e}, rtol = {t:.0e}"),
                    (Some(k), None) => format!("k = {k:.0e}, dt = {:e} s", r.dt_s),
                    _ => String::new(),
                };
                let (pt, pk) = match peer {
                    Some(r) => (format!("{:.4}", r.wall_s), how(r)),
                    None => ("not reached".into(), "-".into()),
                };
                let lt = located.map_or("not reached".into(), |r| format!("{:.5}", r.wall_s));
                let speed = match (peer, located) {
                    (Some(p), Some(l)) => format!("{:.0}x", p.wall_s / l.wall_s.max(1e-9)),
                    (None, Some(_)) => "peer never reaches it".into(),
                    _ => "-".into(),
                };
                s.push_str(&format!(
                    "| {sc} | {target:.0e} | {} | {pt} | {pk} | {lt} | {speed} |\n",
                    m.label()
                ));
            }
        }
    }
    s
}

/// The lower envelope of `(time, error)` points: by time, each point more
/// accurate than every faster one (what a user sweeping the method's
/// choices gets for a given time).
fn best_of_sweep(mut points: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut best = f64::INFINITY;
    points.retain(|&(_, e)| {
        let keep = e < best;
        best = best.min(e);
        keep
    });
    points
}

/// The diagram: error against run time, log-log, one line per method.
pub fn figure(rows: &[Row], scene: &str) -> Figure {
    // a tread-spring scene's runs are compared by CPU time (set-up included)
    let tread = rows
        .iter()
        .any(|r| r.scene == scene && r.method == Method::BdfTread);
    let time = |r: &Row| match (tread, r.cpu_s) {
        (true, Some(t)) => t,
        _ => r.wall_s,
    };
    let mk = |force: bool| Panel {
        title: if force {
            "Contact force (means over 1 ms windows)"
        } else {
            "Displacement"
        }
        .into(),
        x_label: if tread {
            "CPU time (s)"
        } else {
            "run time (s)"
        }
        .into(),
        y_label: if force {
            "force RMS relative error (-)"
        } else {
            "displacement RMS relative error (-)"
        }
        .into(),
        series: Method::ALL
            .iter()
            .enumerate()
            .map(|(k, &m)| {
                let mut points: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.method == m && r.scene == scene)
                    .map(|r| {
                        (
                            time(r).max(1e-6),
                            if force { r.force_err } else { r.disp_err },
                        )
                    })
                    .filter(|p| p.1.is_finite() && p.1 > 0.0)
                    .collect();
                if Method::PEERS.contains(&m) {
                    points = best_of_sweep(points);
                }
                Series {
                    name: if Method::PEERS.contains(&m) {
                        format!("{} (best of its sweep)", m.label())
                    } else {
                        m.label().into()
                    },
                    points,
                    style: Style::LineMarkers(4),
                    color: Some(k),
                }
            })
            .collect(),
        log_x: true,
        log_y: true,
        y_names: Vec::new(),
    };
    Figure {
        title: format!("Work-precision: {scene}"),
        subtitle: if tread {
            "the same tread springs by both methods; the located solver's dt and BDF's tolerance from coarse to fine; CPU time from the tyre's modes; reference: located events at a quarter of the finest dt"
        } else {
            "each line runs dt from coarse (left) to fine (right); the penalty methods: the most accurate run of their sweep (k, dt or tolerance) for its time; reference: located events at a quarter of the finest dt"
        }
        .into(),
        panels: vec![mk(false), mk(true)],
    }
}
