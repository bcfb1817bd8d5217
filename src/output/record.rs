//! Recording a run for figures: displacement, window-mean force and contact
//! per point, at most `max_samples` samples (forces averaged over each
//! window so impulses are kept, and their impact part beside them so that
//! the figure can clip impact spikes).

use crate::output::figures::{Figure, Panel, Series, Style};
use crate::output::impacts::{ImpactTracker, clip_level};
use crate::simulation::Simulation;

/// Name of the series of clipped impact samples in a recording's figure.
pub const CLIPPED_IMPACTS: &str = "impacts (impulse / dt), clipped";

/// Samples kept by the command line's run figures (`run --plot`,
/// `identify --figures`).
pub const PLOT_SAMPLES: u64 = 4000;

/// Decimated time histories of a run.
#[derive(Debug, Clone, Default)]
pub struct Recording {
    pub t_s: Vec<f64>,
    /// `u[i][k]` (m).
    pub u_m: Vec<Vec<f64>>,
    /// Window-mean force `q[i][k]` (N).
    pub q_n: Vec<Vec<f64>>,
    /// Road height `r[i][k]` (m).
    pub r_m: Vec<Vec<f64>>,
    /// The impact part of `q_n`, window mean `qi[i][k]` (N): located
    /// impulses / dt, or the paper scheme's landing steps.
    pub q_impact_n: Vec<Vec<f64>>,
    every: u64,
    count: u64,
    q_sum: Vec<f64>,
    qi_sum: Vec<f64>,
    impacts: ImpactTracker,
}

impl Recording {
    /// A recording of `total_steps` steps keeping about `max_samples` samples.
    pub fn new(p: usize, total_steps: u64, max_samples: u64) -> Self {
        Recording {
            u_m: vec![Vec::new(); p],
            q_n: vec![Vec::new(); p],
            r_m: vec![Vec::new(); p],
            q_impact_n: vec![Vec::new(); p],
            every: total_steps.div_ceil(max_samples.max(1)).max(1),
            q_sum: vec![0.0; p],
            qi_sum: vec![0.0; p],
            ..Default::default()
        }
    }

    /// Call after every step.
    pub fn after_step(&mut self, sim: &Simulation) {
        for (s, q) in self.q_sum.iter_mut().zip(sim.force_n()) {
            *s += q;
        }
        self.impacts.add_step(sim, &mut self.qi_sum);
        self.count += 1;
        if self.count == self.every || sim.finished() {
            self.t_s.push(sim.time_s());
            let n = self.count as f64;
            for i in 0..self.q_sum.len() {
                self.u_m[i].push(sim.displacement_m()[i]);
                self.r_m[i].push(sim.road_m()[i]);
                self.q_n[i].push(self.q_sum[i] / n);
                self.q_impact_n[i].push(self.qi_sum[i] / n);
            }
            self.q_sum.fill(0.0);
            self.qi_sum.fill(0.0);
            self.count = 0;
        }
    }

    /// Window length of a sample (steps).
    pub fn every(&self) -> u64 {
        self.every
    }

    /// The force level above which the figure clips impact spikes (N): a
    /// margin above the force without impacts; `None` without samples.
    pub fn clip_level_n(&self) -> Option<f64> {
        let smooth = self
            .q_n
            .iter()
            .zip(&self.q_impact_n)
            .flat_map(|(q, qi)| q.iter().zip(qi).map(|(a, b)| a - b));
        let (lo, hi) = smooth.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        (lo <= hi).then(|| clip_level((lo, hi)))
    }

    /// Displacement (mm) of every point, named `name(i)`.
    pub fn displacement_series(&self, name: &dyn Fn(usize) -> String) -> Vec<Series> {
        self.series(&self.u_m, 1e3, name)
    }

    /// Window-mean force (N) of every point, named `name(i)`. With
    /// `clip_impacts` the spikes are cut at [`Self::clip_level_n`] (so the
    /// force without impacts sets the axis), drawn in thin lines, and the
    /// cut samples follow as one series of dots, [`CLIPPED_IMPACTS`]; the
    /// flag returned says whether any sample was cut.
    pub fn force_series(
        &self,
        clip_impacts: bool,
        name: &dyn Fn(usize) -> String,
    ) -> (Vec<Series>, bool) {
        let mut forces = self.series(&self.q_n, 1.0, name);
        let Some(top) = self.clip_level_n().filter(|_| clip_impacts) else {
            return (forces, false);
        };
        let mut marks = Vec::new();
        for s in &mut forces {
            for p in &mut s.points {
                if p.1 > top {
                    p.1 = top;
                    marks.push(*p);
                }
            }
            // one-pixel lines: wide ones overshoot the panel at the cuts
            s.style = Style::ThinLine;
        }
        let clipped = !marks.is_empty();
        if clipped {
            forces.push(Series {
                name: CLIPPED_IMPACTS.into(),
                points: marks,
                style: Style::Markers(3),
                color: Some(6),
            });
        }
        (forces, clipped)
    }

    fn series(&self, data: &[Vec<f64>], scale: f64, name: &dyn Fn(usize) -> String) -> Vec<Series> {
        data.iter()
            .enumerate()
            .map(|(i, d)| {
                Series::line(
                    name(i),
                    self.t_s
                        .iter()
                        .zip(d)
                        .map(|(&t, &x)| (t, x * scale))
                        .collect(),
                )
            })
            .collect()
    }

    /// Length of a sample's window (ms) for steps of `dt_s`.
    pub fn window_ms(&self, dt_s: f64) -> f64 {
        self.every as f64 * dt_s * 1e3
    }

    /// The standard run figure: displacements (mm) and forces (N) per point.
    /// With `clip_impacts` the force axis fits the force without impacts
    /// and impact spikes are cut a margin above it, each cut sample marked
    /// by a dot (impulse / dt of a rigid landing is tens of kN against a
    /// rolling force of about 1 kN).
    pub fn figure(&self, title: &str, subtitle: &str, dt_s: f64, clip_impacts: bool) -> Figure {
        let win_ms = self.window_ms(dt_s);
        // (clipped impacts are said by their legend entry, CLIPPED_IMPACTS:
        // said in the title too, it shrank to fit below the tick labels' size)
        let force_title = format!("Contact force, mean over {win_ms:.3} ms windows");
        let (forces, _clipped) = self.force_series(clip_impacts, &|i| format!("q{i}"));
        Figure {
            title: title.to_string(),
            subtitle: subtitle.to_string(),
            panels: vec![
                Panel {
                    title: "Displacement of the contact points (positive up)".into(),
                    x_label: "time t (s)".into(),
                    y_label: "displacement u (mm)".into(),
                    series: self.displacement_series(&|i| format!("u{i}")),
                    ..Panel::default()
                },
                Panel {
                    title: force_title,
                    x_label: "time t (s)".into(),
                    y_label: "contact force q (N)".into(),
                    series: forces,
                    ..Panel::default()
                },
            ],
        }
    }
}

impl crate::drive::Probe for Recording {
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        Recording::after_step(self, sim);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scene;
    use crate::scene::ContactScheme;

    /// Records the three-point preset (impacts at every landing) with `scheme`.
    fn record(scheme: ContactScheme) -> (Recording, f64) {
        let mut scene = Scene::load(std::path::Path::new("presets/three_points.ron")).unwrap();
        scene.duration_s = 0.06;
        scene.contact_scheme = scheme;
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut rec = Recording::new(scene.num_points(), scene.num_steps(), 3000);
        while !sim.finished() {
            sim.step().unwrap();
            rec.after_step(&sim);
        }
        (rec, scene.dt_s)
    }

    fn highest(series: &[Series], name_prefix: &str) -> f64 {
        series
            .iter()
            .filter(|s| s.name.starts_with(name_prefix))
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    #[test]
    fn the_force_panel_clips_impact_spikes_a_margin_above_the_rolling_force() {
        for scheme in [ContactScheme::Located, ContactScheme::Paper] {
            let (rec, dt) = record(scheme);
            let raw = rec.q_n.iter().flatten().fold(0.0f64, |m, &q| m.max(q));
            let top = rec.clip_level_n().unwrap();
            // the spikes are impulses / dt: far above the rolling force
            assert!(raw > 5.0 * top, "{scheme:?}: spikes {raw} N, clip {top} N");
            let clipped = rec.figure("t", "s", dt, true);
            let forces = &clipped.panels[1].series;
            assert!((highest(forces, "q") - top).abs() <= 1e-9 * top);
            let marks = forces.iter().find(|s| s.name == CLIPPED_IMPACTS).unwrap();
            assert!(!marks.points.is_empty());
            assert!(marks.points.iter().all(|p| p.1 == top));
            // said once, by the legend entry, not again in the caption
            assert!(!clipped.panels[1].title.contains("clipped"));
            // unclipped: the spikes are drawn whole
            let full = rec.figure("t", "s", dt, false);
            assert_eq!(highest(&full.panels[1].series, "q"), raw);
            assert!(
                full.panels[1]
                    .series
                    .iter()
                    .all(|s| s.name != CLIPPED_IMPACTS)
            );
        }
    }
}
