//! How the cost of a step grows with the number of points `P` and of
//! rank-1 modes `K` ([`scaling_scene`]: the middle third of the points
//! pressed on a gentle sine road, the others lifted clear): wall time per
//! step, the contact's share (against the same scene lifted off the road),
//! and the fitted exponents of `time per step ∝ P^a`, `∝ K^b`. The
//! synthetic tyre's mode shapes are smooth, so pressing the centre lifts
//! its neighbours: about one point is on the road whatever `P` (the
//! measured `on_road` says so), the regime of a small active set.

use crate::bench::scenes::many_points;
use crate::drive::{Watch, run_to_end};
use crate::identify::PreparedModel;
use crate::output::figures::{Figure, Panel, Series, Style};
use crate::road::Road;
use crate::simulation::{Simulation, SolverOptions};
use std::time::Instant;

/// Preload of the footprint's centre point (m).
pub const PRELOAD_M: f64 = 0.002;

/// [`many_points`] with a footprint: point `i` at `x_i` on a line of
/// length `L` sits at `h_i = PRELOAD_M ((6 (x_i - x_mid) / L)² - 1)`, so
/// the middle third is pressed (up to `PRELOAD_M` at the centre) and the
/// rest lifted; the road is a 0.1 mm, 0.2 m sine at 10 m/s.
pub fn scaling_scene(points: usize, modes: usize) -> crate::Scene {
    let mut s = many_points(points, modes);
    let xs: Vec<f64> = s.points.iter().map(|p| p.x_m).collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let (mid, len) = (0.5 * (lo + hi), (hi - lo).max(1e-9));
    for p in &mut s.points {
        let y = 6.0 * (p.x_m - mid) / len;
        p.h_m = PRELOAD_M * (y * y - 1.0);
    }
    s.road = Road::Sine {
        amplitude_m: 1e-4,
        wavelength_m: 0.2,
    };
    s.speed_mps = 10.0;
    s.name = format!("{points} points x {modes} rank-1 modes, footprint");
    s
}

/// One measured size.
#[derive(Debug, Clone, PartialEq)]
pub struct ScalingRow {
    pub points: usize,
    pub modes: usize,
    pub steps: u64,
    /// Wall time per step with contact (s).
    pub step_s: f64,
    /// Wall time per step of the same scene off the road (s).
    pub free_step_s: f64,
    /// Mean fraction of the points on the road at a step end.
    pub on_road: f64,
    /// Located events per step.
    pub events_per_step: f64,
    /// Factorisations of the contact system per step.
    pub factorisations_per_step: f64,
}

impl ScalingRow {
    /// The share of a step spent on contact: `1 - free / with contact`.
    pub fn contact_share(&self) -> f64 {
        (1.0 - self.free_step_s / self.step_s).max(0.0)
    }
}

/// Runs [`scaling_scene`]`(points, modes)` for `duration_s` (ramp 0.01 s)
/// with contact and lifted off the road; the fastest of `repeats` runs of
/// each.
pub fn measure(
    points: usize,
    modes: usize,
    duration_s: f64,
    repeats: usize,
) -> Result<ScalingRow, String> {
    let mut scene = scaling_scene(points, modes);
    scene.duration_s = duration_s;
    let time = |scene: &crate::Scene| -> Result<(f64, Simulation), String> {
        let model = PreparedModel::of(scene).map_err(|e| e.to_string())?;
        let mut best: Option<(f64, Simulation)> = None;
        for _ in 0..repeats.max(1) {
            let mut sim =
                Simulation::new(&model, SolverOptions::default()).map_err(|e| e.to_string())?;
            let t = Instant::now();
            run_to_end(&mut sim, &mut (), Watch::none()).map_err(|e| e.to_string())?;
            let w = t.elapsed().as_secs_f64();
            if best.as_ref().is_none_or(|(b, _)| w < *b) {
                best = Some((w, sim));
            }
        }
        best.ok_or_else(|| "no run".to_string())
    };
    let (wall, sim) = time(&scene)?;
    let mut free = scene.clone();
    for p in &mut free.points {
        p.h_m = 0.05; // 5 cm above a 0.1 mm road: never touches
    }
    let (free_wall, _) = time(&free)?;
    let st = sim.stats();
    let steps = st.steps.max(1);
    Ok(ScalingRow {
        points,
        modes,
        steps,
        step_s: wall / steps as f64,
        free_step_s: free_wall / steps as f64,
        on_road: st.contact_steps.iter().sum::<u64>() as f64 / (steps as f64 * points as f64),
        events_per_step: st.events as f64 / steps as f64,
        factorisations_per_step: st.factorisations as f64 / steps as f64,
    })
}

/// Least-squares slope of `ln y` against `ln x`.
pub fn loglog_slope(xy: &[(f64, f64)]) -> f64 {
    let n = xy.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = xy.iter().map(|&(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx.max(f64::MIN_POSITIVE)
}

/// The figure: time per step against `P` (at fixed `K`) and against `K`
/// (at fixed `P`), log-log, with and without contact, each with its fitted
/// exponent in the legend.
pub fn figure(by_p: &[ScalingRow], by_k: &[ScalingRow]) -> Figure {
    let panel = |rows: &[ScalingRow], by_points: bool| {
        let x = |r: &ScalingRow| (if by_points { r.points } else { r.modes }) as f64;
        let with: Vec<(f64, f64)> = rows.iter().map(|r| (x(r), r.step_s * 1e6)).collect();
        let free: Vec<(f64, f64)> = rows.iter().map(|r| (x(r), r.free_step_s * 1e6)).collect();
        let fixed = rows
            .first()
            .map_or(0, |r| if by_points { r.modes } else { r.points });
        Panel {
            title: if by_points {
                format!("Against the number of points P ({fixed} rank-1 modes)")
            } else {
                format!("Against the number of rank-1 modes K ({fixed} points)")
            },
            x_label: if by_points {
                "points P".into()
            } else {
                "modes K".into()
            },
            y_label: "wall time per step (µs)".into(),
            series: vec![
                Series {
                    name: format!("with contact (slope {:.2})", loglog_slope(&with)),
                    points: with,
                    style: Style::LineMarkers(4),
                    color: Some(0),
                },
                Series {
                    name: format!("off the road (slope {:.2})", loglog_slope(&free)),
                    points: free,
                    style: Style::LineMarkers(4),
                    color: Some(1),
                },
            ],
            log_x: true,
            log_y: true,
            y_names: Vec::new(),
        }
    };
    Figure {
        title: "Cost of a step against the problem's size".into(),
        subtitle: format!(
            "rank-1 modes; the middle third of the points pressed by up to {} mm on a 0.1 mm sine road at 10 m/s (about one point on the road); dt = 1e-5 s; fastest of repeated runs",
            PRELOAD_M * 1e3
        ),
        panels: vec![panel(by_p, true), panel(by_k, false)],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_slope_of_a_power_law_is_its_exponent() {
        let xy: Vec<(f64, f64)> = [5.0, 20.0, 80.0, 400.0]
            .iter()
            .map(|&x: &f64| (x, 3.0 * x.powf(1.7)))
            .collect();
        assert!((loglog_slope(&xy) - 1.7).abs() < 1e-12);
    }

    #[test]
    fn a_step_costs_more_with_more_points_and_modes() {
        let small = measure(5, 20, 0.02, 1).unwrap();
        let more_points = measure(60, 20, 0.02, 1).unwrap();
        let more_modes = measure(5, 200, 0.02, 1).unwrap();
        assert!(
            more_points.free_step_s > small.free_step_s,
            "{small:?} {more_points:?}"
        );
        assert!(
            more_modes.free_step_s > small.free_step_s,
            "{small:?} {more_modes:?}"
        );
        // the footprint's centre is on the road
        assert!(
            small.on_road > 0.0 && more_points.on_road > 0.0,
            "{small:?} {more_points:?}"
        );
    }
}
