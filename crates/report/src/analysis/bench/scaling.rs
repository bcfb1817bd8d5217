//! How the cost of a step grows with the number of points `P` and of
//! rank-1 modes `K` ([`scaling_scene`]: the middle third of the points
//! pressed on a gentle sine road, the others lifted clear): wall time per
//! step, the contact's share (against the same scene lifted off the road),
//! and the fitted exponents of `time per step ∝ P^a`, `∝ K^b`, in two
//! regimes ([`Regime`]). With the paper's rigid contact the synthetic
//! tyre's smooth shapes lift the neighbours of a pressed point: about one
//! point is on the road whatever `P`, a small active set. With a soft tread
//! spring at each point the whole pressed third is on the road, and the
//! dense contact solve of `2|S|` unknowns grows with `P`.

pub mod presets;
pub mod report;

use crate::analysis::bench::BenchError;
use crate::analysis::bench::scenes::many_points;
use crate::output::figures::{Figure, Panel, Series, Style};
use tirecontact_core::model::road::Road;
use tirecontact_core::solver::drive::{Watch, run_to_end};
use tirecontact_core::solver::simulation::{Simulation, SolverOptions};
use tirecontact_io::identify::PreparedModel;
use web_time::Instant;

/// Preload of the footprint's centre point (m).
pub const PRELOAD_M: f64 = 0.002;

/// Total tread stiffness of a [`Regime::Tread`] scene (N/m), shared by its
/// points: a tenth of the synthetic tyre's stiffness in its first mode
/// (40 Hz, unit modal mass: about 6.3e4 N/m), so that the tread, not the
/// tyre, takes the preload and the whole footprint stays on the road.
pub const TREAD_TOTAL_N_M: f64 = 6e3;

/// The contact of a scaling scene, which sets how many points are on the
/// road.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Regime {
    /// The paper's rigid contact: the smooth shapes lift the neighbours of
    /// a pressed point, about one point is on the road whatever `P`.
    Rigid,
    /// A tread spring at each point (compliant contact), soft against the
    /// tyre: the pressed third of the points is on the road.
    Tread,
    /// Tread springs on a contact patch: [`patch_scene`] with `P / 20`
    /// points along and 20 across the tread (`y_m`), the pressed third on
    /// the road.
    Patch,
}

impl Regime {
    pub const ALL: [Regime; 3] = [Regime::Rigid, Regime::Tread, Regime::Patch];

    pub fn label(self) -> &'static str {
        match self {
            Regime::Rigid => "rigid contact",
            Regime::Tread => "tread springs",
            Regime::Patch => "tread springs, patch 20 across",
        }
    }

    /// The name in `--scaling-one` and the CSV.
    pub fn key(self) -> &'static str {
        match self {
            Regime::Rigid => "rigid",
            Regime::Tread => "tread",
            Regime::Patch => "patch",
        }
    }

    pub fn from_key(key: &str) -> Option<Regime> {
        Regime::ALL.into_iter().find(|r| r.key() == key)
    }
}

/// [`many_points`] with a footprint: point `i` at `x_i` on a line of
/// length `L` sits at `h_i = PRELOAD_M ((6 (x_i - x_mid) / L)² - 1)`, so
/// the middle third is pressed (up to `PRELOAD_M` at the centre) and the
/// rest lifted; the road is a 0.1 mm, 0.2 m sine at 10 m/s. With
/// [`Regime::Tread`] each point has a tread of `TREAD_TOTAL_N_M / P`.
pub fn scaling_scene(points: usize, modes: usize, regime: Regime) -> tirecontact_io::Scene {
    if regime == Regime::Patch {
        let across = PATCH_GRID.1;
        return patch_scene((points / across).max(1), across, modes, Regime::Tread);
    }
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
    if regime != Regime::Rigid {
        s.contact = tirecontact_io::scene::Contact::Compliant {
            stiffness_n_m: vec![TREAD_TOTAL_N_M / points as f64],
        };
    }
    s.name = format!(
        "{points} points x {modes} rank-1 modes, footprint, {}",
        regime.label()
    );
    s
}

/// Points along and across the tread of the patch study's grid (5 mm
/// apart: 0.25 m by 0.1 m).
pub const PATCH_GRID: (usize, usize) = (50, 20);

/// A contact patch: `along × across` points 5 mm apart on a tyre with a
/// width, `modes` rank-1 modes of an orthotropic plate (mode `k` has
/// order `k / 8` along and `k % 8` across, shape
/// `(sin(m π (a + 1) / (A + 1)) + [m = 0]) cos(n π (c + ½) / C)` at point
/// `(a, c)`, 40 Hz and up, masses growing with order as in
/// [`many_points`]); the preload of [`scaling_scene`] along the patch
/// (the middle third pressed, the same across), the same road and tread.
/// Point `a × across + c` is at `x = 5 mm (a - (A - 1)/2)`, and
/// `y = 5 mm (c - (C - 1)/2)` across.
pub fn patch_scene(
    along: usize,
    across: usize,
    modes: usize,
    regime: Regime,
) -> tirecontact_io::Scene {
    use std::f64::consts::PI;
    use tirecontact_io::scene::{Mode, Point, Tyre};
    const ORDERS_ACROSS: usize = 8;
    let (na, nc, n_modes) = (along as f64, across as f64, modes);
    let modes: Vec<Mode> = (0..n_modes)
        .map(|k| {
            let (m, n) = ((k / ORDERS_ACROSS) as f64, (k % ORDERS_ACROSS) as f64);
            let amp = 0.5 / ((m + 1.0) * (n + 1.0)).sqrt();
            let shape = (0..along * across)
                .map(|i| {
                    let (a, c) = ((i / across) as f64, (i % across) as f64);
                    let along =
                        (m * PI * (a + 1.0) / (na + 1.0)).sin() + if m == 0.0 { 1.0 } else { 0.0 };
                    amp * along * (n * PI * (c + 0.5) / nc).cos()
                })
                .collect();
            Mode {
                freq_hz: 40.0 * (1.0 + 0.5 * m).powf(1.4) * (1.0 + 0.3 * n),
                damping_ratio: 0.05,
                residue: vec![],
                shape,
            }
        })
        .collect();
    let mut s = scaling_scene(along * across, 0, regime);
    s.tyre = Tyre::Modal { modes };
    let len = 0.005 * (na - 1.0).max(1e-6);
    s.points = (0..along * across)
        .map(|i| {
            let x_m = 0.005 * ((i / across) as f64 - 0.5 * (na - 1.0));
            let rel = 6.0 * x_m / len;
            Point {
                x_m,
                y_m: 0.005 * ((i % across) as f64 - 0.5 * (nc - 1.0)),
                h_m: PRELOAD_M * (rel * rel - 1.0),
            }
        })
        .collect();
    s.name = format!(
        "{along} x {across} points x {n_modes} plate modes, contact patch, {}",
        regime.label()
    );
    s
}

/// `scene` with every point 5 cm above the road (a 0.1 mm sine): the same
/// tyre and steps without contact.
pub fn lifted(scene: &tirecontact_io::Scene) -> tirecontact_io::Scene {
    let mut free = scene.clone();
    for p in &mut free.points {
        p.h_m = 0.05;
    }
    free
}

/// One measured size.
#[derive(Debug, Clone, PartialEq)]
pub struct ScalingRow {
    pub points: usize,
    pub regime: Regime,
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
    /// Instructions per rolling step (callgrind), where counted.
    pub instructions_per_step: Option<f64>,
    /// The same off the road.
    pub free_instructions_per_step: Option<f64>,
}

impl ScalingRow {
    /// The share of a step spent on contact: `1 - free / with contact`.
    pub fn contact_share(&self) -> f64 {
        (1.0 - self.free_step_s / self.step_s).max(0.0)
    }

    /// The same share by instructions, where counted: exact, where wall
    /// times of identical runs vary by tens of percent.
    pub fn contact_share_instructions(&self) -> Option<f64> {
        Some((1.0 - self.free_instructions_per_step? / self.instructions_per_step?).max(0.0))
    }
}

/// How a size is timed: the fastest of `repeats` runs, on `threads`
/// threads ([`SolverOptions::threads`]; results do not depend on them).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Timing {
    pub repeats: usize,
    pub threads: usize,
}

/// The fastest of `timing.repeats` whole runs of `scene` (wall time, s,
/// from the first step; the set-up not included) and its simulation at
/// the end.
pub fn fastest_run(
    scene: &tirecontact_io::Scene,
    timing: Timing,
) -> Result<(f64, Simulation), BenchError> {
    let model = PreparedModel::of(scene)?;
    let mut best: Option<(f64, Simulation)> = None;
    let options = SolverOptions {
        threads: timing.threads.max(1),
        ..SolverOptions::default()
    };
    for _ in 0..timing.repeats.max(1) {
        let mut sim = model.simulation(options)?;
        let t = Instant::now();
        run_to_end(&mut sim, &mut (), Watch::none())?;
        let w = t.elapsed().as_secs_f64();
        if best.as_ref().is_none_or(|(b, _)| w < *b) {
            best = Some((w, sim));
        }
    }
    best.ok_or(BenchError::NoRun)
}

/// Runs [`scaling_scene`]`(points, modes, regime)` for `duration_s` (ramp 0.01 s)
/// with contact and lifted off the road; the fastest of `repeats` runs of
/// each.
pub fn measure(
    points: usize,
    modes: usize,
    regime: Regime,
    duration_s: f64,
    timing: Timing,
) -> Result<ScalingRow, BenchError> {
    let mut scene = scaling_scene(points, modes, regime);
    scene.duration_s = duration_s;
    measure_scene(&scene, modes, regime, timing)
}

/// [`measure`] of a given scene of `modes` modes: the fastest of
/// `timing.repeats` runs with contact and lifted off the road.
pub fn measure_scene(
    scene: &tirecontact_io::Scene,
    modes: usize,
    regime: Regime,
    timing: Timing,
) -> Result<ScalingRow, BenchError> {
    let points = scene.num_points();
    let (wall, sim) = fastest_run(scene, timing)?;
    let (free_wall, _) = fastest_run(&lifted(scene), timing)?;
    let st = sim.stats();
    let steps = st.steps.max(1);
    Ok(ScalingRow {
        points,
        regime,
        modes,
        steps,
        step_s: wall / steps as f64,
        free_step_s: free_wall / steps as f64,
        on_road: st.contact_steps.iter().sum::<u64>() as f64 / (steps as f64 * points as f64),
        events_per_step: st.events as f64 / steps as f64,
        factorisations_per_step: st.factorisations as f64 / steps as f64,
        instructions_per_step: None,
        free_instructions_per_step: None,
    })
}

/// The fitted log-log slope of `xy` to two decimals, or "—" for fewer
/// than two points.
fn slope_label(xy: &[(f64, f64)]) -> String {
    if xy.len() < 2 {
        "—".into()
    } else {
        format!("{:.2}", loglog_slope(xy))
    }
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

/// Least-squares line `y = a + b x` through `xy`: `(a, b)`.
pub fn line_fit(xy: &[(f64, f64)]) -> (f64, f64) {
    let n = xy.len() as f64;
    let mx = xy.iter().map(|p| p.0).sum::<f64>() / n;
    let my = xy.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = xy.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xy.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    let b = sxy / sxx.max(f64::MIN_POSITIVE);
    (my - b * mx, b)
}

/// What a panel of [`figure`] draws per step.
#[derive(Clone, Copy, PartialEq)]
enum Measure {
    WallTime,
    Instructions,
}

/// The figure: time per step against `P` (at fixed `K`) and against `K`
/// (at fixed `P`), log-log, for each regime and off the road, each with
/// its fitted exponent in the legend; below, the same for callgrind's
/// instructions per step where every row has them. `by_p`, `by_k` hold
/// both regimes; the free runs drawn are the rigid regime's (the same tyre
/// lifted clear).
pub fn figure(by_p: &[ScalingRow], by_k: &[ScalingRow]) -> Figure {
    let panel = |rows: &[ScalingRow], by_points: bool, measure: Measure| {
        let x = |r: &ScalingRow| (if by_points { r.points } else { r.modes }) as f64;
        let y = |r: &ScalingRow| match measure {
            Measure::WallTime => r.step_s * 1e6,
            Measure::Instructions => r.instructions_per_step.unwrap_or(f64::NAN),
        };
        let of = |regime: Regime| rows.iter().filter(move |r| r.regime == regime);
        let mut series: Vec<Series> = Regime::ALL
            .iter()
            .enumerate()
            .filter_map(|(i, &regime)| {
                let xy: Vec<(f64, f64)> = of(regime).map(|r| (x(r), y(r))).collect();
                (!xy.is_empty()).then(|| Series {
                    name: format!("{} (slope {})", regime.label(), slope_label(&xy)),
                    points: xy,
                    style: Style::LineMarkers(4),
                    color: Some(i),
                })
            })
            .collect();
        // the patch's own tyre off the road (its plate modes)
        let patch_free: Vec<(f64, f64)> = of(Regime::Patch)
            .map(|r| {
                let y = match measure {
                    Measure::WallTime => r.free_step_s * 1e6,
                    Measure::Instructions => r.free_instructions_per_step.unwrap_or(f64::NAN),
                };
                (x(r), y)
            })
            .collect();
        if !patch_free.is_empty() {
            series.push(Series {
                name: format!("patch off the road (slope {})", slope_label(&patch_free)),
                points: patch_free,
                style: Style::LineMarkers(4),
                color: Some(Regime::ALL.len() + 1),
            });
        }
        {
            let free: Vec<(f64, f64)> = of(Regime::Rigid)
                .map(|r| {
                    (
                        x(r),
                        match measure {
                            Measure::WallTime => r.free_step_s * 1e6,
                            Measure::Instructions => {
                                r.free_instructions_per_step.unwrap_or(f64::NAN)
                            }
                        },
                    )
                })
                .collect();
            series.push(Series {
                name: format!("off the road (slope {})", slope_label(&free)),
                points: free,
                style: Style::LineMarkers(4),
                color: Some(Regime::ALL.len()),
            });
        }
        let fixed = rows
            .first()
            .map_or(0, |r| if by_points { r.modes } else { r.points });
        let what = match measure {
            Measure::WallTime => "Wall time",
            Measure::Instructions => "Instructions (callgrind)",
        };
        Panel {
            title: if by_points {
                format!("{what} against the number of points P ({fixed} rank-1 modes)")
            } else {
                format!("{what} against the number of rank-1 modes K ({fixed} points)")
            },
            x_label: if by_points {
                "points P".into()
            } else {
                "modes K".into()
            },
            y_label: match measure {
                Measure::WallTime => "wall time per step (µs)".into(),
                Measure::Instructions => "instructions per step".into(),
            },
            series,
            log_x: true,
            log_y: true,
            y_names: Vec::new(),
        }
    };
    let mut panels = vec![
        panel(by_p, true, Measure::WallTime),
        panel(by_k, false, Measure::WallTime),
    ];
    let counted = |rows: &[ScalingRow]| {
        !rows.is_empty() && rows.iter().all(|r| r.instructions_per_step.is_some())
    };
    if counted(by_p) && counted(by_k) {
        panels.push(panel(by_p, true, Measure::Instructions));
        panels.push(panel(by_k, false, Measure::Instructions));
    }
    Figure {
        title: "Cost of a step against the problem's size".into(),
        subtitle: format!(
            "rank-1 modes, middle third pressed (up to {} mm), 0.1 mm sine road, 10 m/s, dt = 1e-5 s; on the road: about 1 point (rigid), a third (tread, patch)",
            PRELOAD_M * 1e3
        ),
        panels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ONE: Timing = Timing {
        repeats: 1,
        threads: 1,
    };

    #[test]
    fn the_slope_of_a_power_law_is_its_exponent() {
        let xy: Vec<(f64, f64)> = [5.0, 20.0, 80.0, 400.0]
            .iter()
            .map(|&x: &f64| (x, 3.0 * x.powf(1.7)))
            .collect();
        assert!((loglog_slope(&xy) - 1.7).abs() < 1e-12);
    }

    #[test]
    fn a_line_is_fitted_through_its_points() {
        let xy: Vec<(f64, f64)> = [10.0, 25.0, 100.0, 400.0]
            .iter()
            .map(|&x: &f64| (x, 8300.0 + 110.0 * x))
            .collect();
        let (a, b) = line_fit(&xy);
        assert!(
            (a - 8300.0).abs() < 1e-8 && (b - 110.0).abs() < 1e-12,
            "{a} {b}"
        );
    }

    #[test]
    fn tread_springs_hold_the_pressed_third_on_the_road_and_rigid_contact_about_one_point() {
        for (p, k) in [(30, 10), (60, 50), (90, 200)] {
            let tread = measure(p, k, Regime::Tread, 0.03, ONE).unwrap();
            let on = tread.on_road * p as f64;
            assert!(
                on > 0.28 * p as f64 && on < 0.38 * p as f64,
                "{on} of {p} on the road: {tread:?}"
            );
            let rigid = measure(p, k, Regime::Rigid, 0.03, ONE).unwrap();
            let on = rigid.on_road * p as f64;
            assert!(on > 0.5 && on < 3.0, "{on} of {p} on the road: {rigid:?}");
        }
    }

    /// The patch is a grid of points across the tread (distinct `y_m`
    /// sharing each `x_m`), its tyre's responses differ across the width,
    /// and its tread holds the pressed third on the road.
    #[test]
    fn the_patch_is_a_grid_across_the_tread_with_its_third_on_the_road() {
        let s = scaling_scene(200, 40, Regime::Patch);
        assert_eq!(s.num_points(), 200);
        assert!(s.validate().is_ok(), "{:?}", s.validate());
        let ys: std::collections::BTreeSet<i64> = s
            .points
            .iter()
            .map(|p| (p.y_m * 1e6).round() as i64)
            .collect();
        let xs: std::collections::BTreeSet<i64> = s
            .points
            .iter()
            .map(|p| (p.x_m * 1e6).round() as i64)
            .collect();
        assert_eq!((xs.len(), ys.len()), (10, 20), "{xs:?} {ys:?}");
        // points 0 and 1 share x: a mode across the width tells them apart
        let tirecontact_io::scene::Tyre::Modal { modes } = &s.tyre else {
            panic!("a modal tyre")
        };
        assert!(modes.iter().any(|m| (m.shape[0] - m.shape[1]).abs() > 1e-3));
        let r = measure(200, 40, Regime::Patch, 0.03, ONE).unwrap();
        let on = r.on_road * 200.0;
        assert!(
            on > 0.25 * 200.0 && on < 0.42 * 200.0,
            "{on} of 200 on the road: {r:?}"
        );
    }

    #[test]
    fn a_measured_size_counts_its_steps_and_the_footprint_on_the_road() {
        // wall times are the benchmark's to compare (a loaded machine can
        // make any two of them swap); here what a row counts must hold
        for (p, k) in [(5, 20), (60, 20), (5, 200)] {
            let r = measure(p, k, Regime::Rigid, 0.02, ONE).unwrap();
            // 0.02 s at dt = 1e-5 s
            assert_eq!(r.steps, 2000, "{r:?}");
            assert!(r.step_s > 0.0 && r.free_step_s > 0.0, "{r:?}");
            assert!(r.step_s.is_finite() && r.free_step_s.is_finite(), "{r:?}");
            // the footprint's centre is on the road, the lifted ends are not
            assert!(r.on_road > 0.0 && r.on_road < 0.5, "{r:?}");
            assert!(r.events_per_step >= 0.0 && r.factorisations_per_step >= 0.0);
        }
    }
}
