//! Contact metrics that mean the same at any time step.
//!
//! Under rigid contact a landing is an impulse (N·s). A step-mean force
//! writes it as impulse / dt, so the largest step-mean force and its RMS
//! grow without bound as dt → 0: they chart the time step, not the tyre.
//! A run is summarised here by quantities with a limit as dt → 0
//! (`tests/analysis/metrics_converge.rs` shows each one converging on the
//! paper's preset):
//!
//! * the contact force **without impacts** (the step-mean force less the
//!   impacts' impulse / dt, [`crate::output::impacts::ImpactTracker`]): its
//!   largest value and its RMS (N);
//! * the **impacts as impulses**: per point, the number of steps in which the
//!   point took an impact impulse, per second, and the mean and largest such
//!   impulse (N·s);
//! * the force **averaged over a stated window**, impacts included
//!   ([`FORCE_WINDOW_S`]): its largest value (N), a force level that counts
//!   the impacts' momentum without dividing it by dt;
//! * the fraction of the steps ending in contact;
//! * over all the points at once: the summed force without impacts (its
//!   largest value and RMS) and the number of points ending a step in
//!   contact (its mean and largest value), the contact patch's load and
//!   area ([`crate::output::patch`]).
//!
//! All are taken over the steady part of the run (steps starting at or after
//! `start_s`, by default the ramp time `ramp_s`).

use crate::output::impacts::ImpactTracker;
use tirecontact_core::solver::problem::RunShape;
use tirecontact_core::solver::simulation::Simulation;

/// The window of the averaged force (s): 1 ms, a tenth of the paper
/// preset's road period, long against any time step a run uses.
pub const FORCE_WINDOW_S: f64 = 1e-3;

/// The summary of a run's steady part, per point.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactSummary {
    /// Largest contact force without impacts (N).
    pub force_max_n: Vec<f64>,
    /// RMS of the contact force without impacts, static part included (N).
    pub force_rms_n: Vec<f64>,
    /// Steps with an impact impulse per second of steady run (1/s).
    pub impacts_per_s: Vec<f64>,
    /// Mean impulse of those steps (N·s); 0 without impacts.
    pub impulse_mean_ns: Vec<f64>,
    /// Largest impulse of a step (N·s); 0 without impacts.
    pub impulse_max_ns: Vec<f64>,
    /// Largest force averaged over [`FORCE_WINDOW_S`], impacts included (N).
    pub window_force_max_n: Vec<f64>,
    /// Fraction of the steady steps ending in contact (-).
    pub contact_fraction: Vec<f64>,
    /// Largest summed contact force of all the points without impacts (N).
    pub total_force_max_n: f64,
    /// RMS of that summed force, static part included (N).
    pub total_force_rms_n: f64,
    /// Mean number of points ending a steady step in contact.
    pub in_contact_mean: f64,
    /// Largest number of points ending a steady step in contact.
    pub in_contact_max: usize,
    /// Steady steps summarised.
    pub steps: u64,
}

/// A [`tirecontact_core::solver::drive::Probe`] accumulating a [`ContactSummary`] step by
/// step; every buffer is allocated in [`ContactMetrics::new`] (and
/// [`ContactMetrics::keeping_total_force`]).
#[derive(Debug, Clone)]
pub struct ContactMetrics {
    start_s: f64,
    dt_s: f64,
    tracker: Option<ImpactTracker>,
    /// Impact part of the current step's forces (N).
    part_n: Vec<f64>,
    force_max_n: Vec<f64>,
    force_sq_sum: Vec<f64>,
    impact_steps: Vec<u64>,
    impulse_sum_ns: Vec<f64>,
    impulse_max_ns: Vec<f64>,
    contact_steps: Vec<u64>,
    /// The summed force without impacts: largest and sum of squares (N, N²).
    total_smooth_max_n: f64,
    total_smooth_sq_sum: f64,
    /// Points in contact, summed over the steady steps, and the most at once.
    in_contact_sum: u64,
    in_contact_max: usize,
    /// The last `window_steps` step-mean forces per point, a ring buffer
    /// (step-major: a step writes one contiguous row of `P` forces), their
    /// sums and the largest full-window mean.
    window: Vec<f64>,
    window_steps: usize,
    window_sum: Vec<f64>,
    window_pos: usize,
    window_filled: usize,
    /// The largest full-window sum (N): the largest mean times the
    /// window, divided only for the summary (`s ↦ s / w` keeps the order of
    /// sums under rounding, so that the largest mean is the same number).
    window_max_sum_n: Vec<f64>,
    /// The summed force of every steady step (N): the band levels' signal,
    /// kept only when asked for ([`ContactMetrics::keeping_total_force`]).
    total_n: Vec<f64>,
    keep_total: bool,
    /// Steady steps expected from the scene (capped at 1e7).
    steady_steps: usize,
    steps: u64,
}

impl ContactMetrics {
    /// Metrics of `scene`'s steady part from `start_s` (default `ramp_s`);
    /// their memory does not grow with the run's length.
    pub fn new(scene: &impl RunShape, start_s: Option<f64>) -> Self {
        let p = scene.num_points();
        let window_steps = ((FORCE_WINDOW_S / scene.dt_s()).round() as usize).max(1);
        let start_s = start_s.unwrap_or(scene.ramp_s()).max(0.0);
        // (a guess: a scene too long to hold says so when its spectrum is taken)
        let steady_steps =
            ((scene.duration_s() - start_s) / scene.dt_s()).clamp(0.0, 1e7) as usize + 1;
        ContactMetrics {
            start_s,
            dt_s: scene.dt_s(),
            tracker: None,
            part_n: vec![0.0; p],
            force_max_n: vec![0.0; p],
            force_sq_sum: vec![0.0; p],
            impact_steps: vec![0; p],
            impulse_sum_ns: vec![0.0; p],
            impulse_max_ns: vec![0.0; p],
            contact_steps: vec![0; p],
            total_smooth_max_n: 0.0,
            total_smooth_sq_sum: 0.0,
            in_contact_sum: 0,
            in_contact_max: 0,
            window: vec![0.0; p * window_steps],
            window_steps,
            window_sum: vec![0.0; p],
            window_pos: 0,
            window_filled: 0,
            window_max_sum_n: vec![0.0; p],
            total_n: Vec::new(),
            keep_total: false,
            steady_steps,
            steps: 0,
        }
    }

    /// Also keeps the summed force of every steady step (8 bytes a step),
    /// for the band levels: [`ContactMetrics::total_force_n`].
    pub fn keeping_total_force(mut self) -> Self {
        self.total_n = Vec::with_capacity(self.steady_steps);
        self.keep_total = true;
        self
    }

    /// Call after every step of the run (from its first).
    pub fn after_step(&mut self, sim: &Simulation) {
        // the impact tracker needs the step before the first one summarised
        let tracker = self.tracker.get_or_insert_with(ImpactTracker::default);
        tracker.step_parts(sim, &mut self.part_n);
        // a step belongs to the steady part when it starts at or after start_s
        if sim.time_s() - sim.dt_s() < self.start_s - 1e-9 * sim.dt_s() {
            return;
        }
        self.steps += 1;
        let (q, c) = (sim.force_n(), sim.in_contact());
        let w = self.window_steps;
        let p = self.part_n.len();
        let row = &mut self.window[self.window_pos * p..(self.window_pos + 1) * p];
        if self.keep_total {
            self.total_n.push(q.iter().sum());
        }
        let (mut total_smooth, mut touching) = (0.0, 0usize);
        // (every per-point slice cut to `p` first: one length check each,
        // none per point)
        let (q, c, part_n) = (&q[..p], &c[..p], &self.part_n[..p]);
        let (force_max, force_sq) = (&mut self.force_max_n[..p], &mut self.force_sq_sum[..p]);
        let (window_sum, contact_steps) = (&mut self.window_sum[..p], &mut self.contact_steps[..p]);
        for i in 0..p {
            let impact_n = part_n[i];
            let smooth = q[i] - impact_n;
            total_smooth += smooth;
            touching += usize::from(c[i]);
            force_max[i] = force_max[i].max(smooth);
            force_sq[i] += smooth * smooth;
            if impact_n > 0.0 {
                let impulse = impact_n * self.dt_s;
                self.impact_steps[i] += 1;
                self.impulse_sum_ns[i] += impulse;
                self.impulse_max_ns[i] = self.impulse_max_ns[i].max(impulse);
            }
            contact_steps[i] += u64::from(c[i]);
            window_sum[i] += q[i] - row[i];
            row[i] = q[i];
        }
        self.total_smooth_max_n = self.total_smooth_max_n.max(total_smooth);
        self.total_smooth_sq_sum += total_smooth * total_smooth;
        self.in_contact_sum += touching as u64;
        self.in_contact_max = self.in_contact_max.max(touching);
        // (the next slot without an integer division)
        self.window_pos += 1;
        if self.window_pos == w {
            self.window_pos = 0;
        }
        self.window_filled = (self.window_filled + 1).min(w);
        if self.window_filled == w {
            for (m, &s) in self.window_max_sum_n.iter_mut().zip(&self.window_sum) {
                *m = m.max(s);
            }
        }
    }

    /// The summed contact force of each steady step so far (N); empty
    /// unless made [`ContactMetrics::keeping_total_force`].
    pub fn total_force_n(&self) -> &[f64] {
        &self.total_n
    }

    /// The summary of the steps seen so far. A steady part shorter than the
    /// window gives the mean of what it has.
    pub fn summary(&self) -> ContactSummary {
        let n = self.steps.max(1) as f64;
        let seconds = (self.steps as f64 * self.dt_s).max(f64::MIN_POSITIVE);
        let per_step = |x: &[u64]| x.iter().map(|&c| c as f64 / n).collect();
        let window_force_max_n = if self.window_filled == self.window_steps {
            let w = self.window_steps as f64;
            self.window_max_sum_n.iter().map(|s| s / w).collect()
        } else {
            let k = self.window_filled.max(1) as f64;
            self.window_sum.iter().map(|s| s / k).collect()
        };
        ContactSummary {
            force_max_n: self.force_max_n.clone(),
            force_rms_n: self.force_sq_sum.iter().map(|s| (s / n).sqrt()).collect(),
            impacts_per_s: self
                .impact_steps
                .iter()
                .map(|&c| c as f64 / seconds)
                .collect(),
            impulse_mean_ns: self
                .impulse_sum_ns
                .iter()
                .zip(&self.impact_steps)
                .map(|(s, &c)| if c > 0 { s / c as f64 } else { 0.0 })
                .collect(),
            impulse_max_ns: self.impulse_max_ns.clone(),
            window_force_max_n,
            contact_fraction: per_step(&self.contact_steps),
            total_force_max_n: self.total_smooth_max_n,
            total_force_rms_n: (self.total_smooth_sq_sum / n).sqrt(),
            in_contact_mean: self.in_contact_sum as f64 / n,
            in_contact_max: self.in_contact_max,
            steps: self.steps,
        }
    }
}

impl tirecontact_core::solver::drive::Probe for ContactMetrics {
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        ContactMetrics::after_step(self, sim);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::ContactMetrics;
    use tirecontact_core::solver::drive::{Watch, run_to_end};
    use tirecontact_core::solver::simulation::SolverOptions;
    use tirecontact_io::identify::PreparedModel;

    #[test]
    fn the_summed_force_is_kept_only_when_asked_for() {
        let mut scene = crate::analysis::bench::scenes::many_points(3, 5);
        scene.duration_s = 0.02;
        let model = PreparedModel::of(&scene).unwrap();
        let mut plain = ContactMetrics::new(&scene, None);
        let mut kept = ContactMetrics::new(&scene, None).keeping_total_force();
        let mut sim = model.simulation(SolverOptions::default()).unwrap();
        run_to_end(&mut sim, &mut (&mut plain, &mut kept), Watch::none()).unwrap();
        let steps = kept.summary().steps;
        assert!(steps > 0);
        assert_eq!(kept.total_force_n().len() as u64, steps);
        assert!(plain.total_force_n().is_empty());
        // the summed force is the points' forces summed (the last step)
        let last: f64 = sim.force_n().iter().sum();
        assert_eq!(*kept.total_force_n().last().unwrap(), last);
        assert_eq!(plain.summary(), kept.summary());
    }

    /// The largest 1 ms mean force is the largest mean over every full
    /// window of the step forces, summed afresh window by window (not by
    /// the running sum), to round-off.
    #[test]
    fn the_window_maximum_is_the_brute_force_one() {
        struct History(Vec<Vec<f64>>);
        impl tirecontact_core::solver::drive::Probe for History {
            fn after_step(&mut self, sim: &tirecontact_core::Simulation) -> std::io::Result<()> {
                self.0.push(sim.force_n().to_vec());
                Ok(())
            }
        }
        let mut scene = crate::analysis::bench::scenes::many_points(3, 5);
        scene.duration_s = 0.03;
        let model = PreparedModel::of(&scene).unwrap();
        let mut metrics = ContactMetrics::new(&scene, Some(0.0));
        let mut history = History(Vec::new());
        let mut sim = model.simulation(SolverOptions::default()).unwrap();
        run_to_end(&mut sim, &mut (&mut metrics, &mut history), Watch::none()).unwrap();
        let w = metrics.window_steps;
        let steps = history.0.len();
        assert!(steps > 2 * w, "{steps} steps, window {w}");
        let summary = metrics.summary();
        for i in 0..sim.num_points() {
            let want = (0..=steps - w)
                .map(|k| (k..k + w).map(|n| history.0[n][i]).sum::<f64>() / w as f64)
                .fold(0.0f64, f64::max);
            let got = summary.window_force_max_n[i];
            assert!(want > 0.0, "point {i} bears a force");
            assert!(
                (got - want).abs() <= 1e-9 * want,
                "point {i}: {got} N against {want} N"
            );
        }
    }
}
