//! A run's history as flat arrays, row for row what `run -o` writes
//! ([`super::csv::RunWriter`]): the run sampler's samples
//! ([`super::sampler`]), the state at `t = 0`, then one row every `every`
//! steps and one for a last partial window; the force of a row is the mean
//! over its steps, so that impulses are kept, the other values the state at
//! its end. For callers that want numbers, not text (the Python package).

use crate::output::sampler::{LastWindow, Sampler, Stride};
use tirecontact_core::solver::simulation::Simulation;

/// Rows of a run, time-major: value `[row * p + i]` is point `i`'s.
#[derive(Debug, Clone, Default)]
pub struct RunArrays {
    pub num_points: usize,
    pub t_s: Vec<f64>,
    pub u_m: Vec<f64>,
    pub v_mps: Vec<f64>,
    pub q_n: Vec<f64>,
    pub gap_m: Vec<f64>,
    /// Contact state at the row's time.
    pub contact: Vec<bool>,
    sampler: Sampler,
}

impl RunArrays {
    /// Arrays for `steps` steps of `num_points` points, a row every `every`
    /// steps (at least 1), their room reserved here.
    pub fn new(num_points: usize, steps: u64, every: u64) -> Self {
        let every = every.max(1);
        let rows = (steps / every + 2) as usize;
        let values = rows * num_points;
        RunArrays {
            num_points,
            t_s: Vec::with_capacity(rows),
            u_m: Vec::with_capacity(values),
            v_mps: Vec::with_capacity(values),
            q_n: Vec::with_capacity(values),
            gap_m: Vec::with_capacity(values),
            contact: Vec::with_capacity(values),
            sampler: Sampler::new(num_points, Stride::Every(every), LastWindow::Partial),
        }
    }

    /// Rows recorded.
    pub fn rows(&self) -> usize {
        self.t_s.len()
    }

    /// Appends the row of the sampler's last window: its mean forces and
    /// `sim`'s state at its end.
    fn push(&mut self, sim: &Simulation) {
        let w = self.sampler.last_window();
        self.t_s.push(sim.time_s());
        self.u_m.extend_from_slice(sim.displacement_m());
        self.v_mps.extend_from_slice(sim.velocity_mps());
        self.q_n.extend_from_slice(w.q_n);
        self.gap_m
            .extend((0..self.num_points).map(|i| sim.gap_m(i)));
        self.contact.extend_from_slice(sim.in_contact());
    }
}

impl tirecontact_core::solver::drive::Probe for RunArrays {
    fn start(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.sampler.start(sim);
        self.push(sim);
        Ok(())
    }

    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        if self.sampler.after_step(sim).is_some() {
            self.push(sim);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::csv::RunWriter;
    use tirecontact_core::solver::drive::{Watch, run_to_end};
    use tirecontact_io::SceneSimulation;

    /// The arrays hold the CSV's numbers: every field of every row of
    /// `run -o`'s writer, read back, to its ten significant digits.
    #[test]
    fn the_arrays_are_the_csv_rows() {
        let mut scene = tirecontact_io::Scene::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        )))
        .unwrap();
        scene.duration_s = 0.012;
        let p = scene.num_points();
        for every in [1, 7] {
            let mut sim = Simulation::from_scene(&scene).unwrap();
            let mut arrays = RunArrays::new(p, scene.num_steps(), every);
            let mut w = RunWriter::new(Vec::new(), p, every).unwrap();
            run_to_end(&mut sim, &mut (&mut arrays, &mut w), Watch::none()).unwrap();
            let text = String::from_utf8(w.finish().unwrap()).unwrap();
            let rows: Vec<Vec<f64>> = text
                .lines()
                .skip(1)
                .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
                .collect();
            assert_eq!(rows.len(), arrays.rows(), "every {every}");
            let close = |a: f64, b: f64| (a - b).abs() <= 5e-10 * a.abs().max(b.abs()).max(1e-300);
            for (r, row) in rows.iter().enumerate() {
                assert!(close(row[0], arrays.t_s[r]));
                for i in 0..p {
                    let k = r * p + i;
                    for (col, v) in [
                        (1, arrays.u_m[k]),
                        (1 + p, arrays.v_mps[k]),
                        (1 + 2 * p, arrays.q_n[k]),
                        (1 + 3 * p, arrays.gap_m[k]),
                    ] {
                        assert!(
                            close(row[col + i], v),
                            "every {every} row {r} col {}: {} vs {v}",
                            col + i,
                            row[col + i]
                        );
                    }
                    assert_eq!(row[1 + 4 * p + i] == 1.0, arrays.contact[k]);
                }
            }
            // the run has impacts and releases: the comparison covers them
            assert!(arrays.contact.iter().any(|&c| c) && arrays.contact.iter().any(|&c| !c));
        }
    }
}
