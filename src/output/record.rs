//! Recording a run for figures: displacement, window-mean force and contact
//! per point, at most `max_samples` samples (forces averaged over each
//! window so impulses are kept).

use crate::output::figures::{Figure, Panel, Series};
use crate::simulation::Simulation;

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
    every: u64,
    count: u64,
    q_sum: Vec<f64>,
}

impl Recording {
    /// A recording of `total_steps` steps keeping about `max_samples` samples.
    pub fn new(p: usize, total_steps: u64, max_samples: u64) -> Self {
        Recording {
            u_m: vec![Vec::new(); p],
            q_n: vec![Vec::new(); p],
            r_m: vec![Vec::new(); p],
            every: total_steps.div_ceil(max_samples.max(1)).max(1),
            q_sum: vec![0.0; p],
            ..Default::default()
        }
    }

    /// Call after every step.
    pub fn after_step(&mut self, sim: &Simulation) {
        for (s, q) in self.q_sum.iter_mut().zip(sim.force_n()) {
            *s += q;
        }
        self.count += 1;
        if self.count == self.every || sim.finished() {
            self.t_s.push(sim.time_s());
            for i in 0..self.q_sum.len() {
                self.u_m[i].push(sim.displacement_m()[i]);
                self.r_m[i].push(sim.road_m()[i]);
                self.q_n[i].push(self.q_sum[i] / self.count as f64);
            }
            self.q_sum.fill(0.0);
            self.count = 0;
        }
    }

    /// Window length of a sample (steps).
    pub fn every(&self) -> u64 {
        self.every
    }

    /// The standard run figure: displacements (mm) and forces (N) per point.
    pub fn figure(&self, title: &str, subtitle: &str, dt_s: f64) -> Figure {
        let series = |data: &[Vec<f64>], scale: f64, name: &dyn Fn(usize) -> String| {
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
                .collect::<Vec<_>>()
        };
        let win_ms = self.every as f64 * dt_s * 1e3;
        Figure {
            title: title.to_string(),
            subtitle: subtitle.to_string(),
            panels: vec![
                Panel {
                    title: "Displacement of the contact points (positive up)".into(),
                    x_label: "time t (s)".into(),
                    y_label: "displacement u (mm)".into(),
                    series: series(&self.u_m, 1e3, &|i| format!("u{i}")),
                    ..Panel::default()
                },
                Panel {
                    title: format!("Contact force, mean over {win_ms:.3} ms windows"),
                    x_label: "time t (s)".into(),
                    y_label: "contact force q (N)".into(),
                    series: series(&self.q_n, 1.0, &|i| format!("q{i}")),
                    ..Panel::default()
                },
            ],
        }
    }
}
