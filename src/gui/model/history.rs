//! Bounded time histories of a run, and min/max decimation for drawing.
//!
//! Samples are recorded every `stride` solver steps (forces averaged over the
//! stride, so impulses are kept). When the buffers are full, pairs of samples
//! are merged and the stride doubles: memory stays bounded however long the
//! run, and the whole run stays visible at a coarser resolution.

use crate::Simulation;
use crate::output::impacts::ImpactTracker;
pub use crate::output::impacts::paper_impact_n;
use crate::output::record::Recording;

/// Samples kept across all series (bounds memory to a few tens of MB).
pub const DEFAULT_BUDGET: usize = 8_000_000;

/// Which quantity of a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Displacement `u_i` (m).
    Displacement,
    /// Step-mean contact force `q_i` (N).
    Force,
    /// Step-mean contact force without the impulses of impacts (N): the
    /// force a plot's range should fit (an impact adds impulse / dt). The
    /// located scheme reports its impacts' impulses; the paper scheme
    /// (`contact_scheme: Paper`) locates none, and there a landing step
    /// counts as the impact (see [`paper_impact_n`]).
    ForceWithoutImpacts,
    /// Gap `u_i - r_i` (m).
    Gap,
    /// Contact state (0/1).
    Contact,
}

/// Per-point time histories.
#[derive(Debug, Clone)]
pub struct History {
    p: usize,
    capacity: usize,
    stride: u64,
    /// Steps since the last recorded sample.
    count: u64,
    q_sum: Vec<f64>,
    /// Sum of the impact impulses / dt since the last sample.
    q_impact_sum: Vec<f64>,
    contact_any: Vec<bool>,
    t: Vec<f64>,
    u: Vec<Vec<f32>>,
    q: Vec<Vec<f32>>,
    /// Impact part of `q` (N).
    q_impact: Vec<Vec<f32>>,
    gap: Vec<Vec<f32>>,
    contact: Vec<Vec<u8>>,
    /// The impact part of each step's forces: located impulses / dt, or
    /// the paper scheme's landing steps (see [`paper_impact_n`]).
    impacts: ImpactTracker,
}

impl History {
    /// Histories for `p` points within a budget of `budget` samples.
    pub fn new(p: usize, budget: usize) -> Self {
        let capacity = (budget / (5 * p.max(1) + 1)).max(1024) & !1;
        History {
            p,
            capacity,
            stride: 1,
            count: 0,
            q_sum: vec![0.0; p],
            q_impact_sum: vec![0.0; p],
            contact_any: vec![false; p],
            t: Vec::new(),
            u: vec![Vec::new(); p],
            q: vec![Vec::new(); p],
            q_impact: vec![Vec::new(); p],
            gap: vec![Vec::new(); p],
            contact: vec![Vec::new(); p],
            impacts: ImpactTracker::default(),
        }
    }

    pub fn num_points(&self) -> usize {
        self.p
    }
    pub fn len(&self) -> usize {
        self.t.len()
    }
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }
    /// Solver steps per recorded sample.
    pub fn stride(&self) -> u64 {
        self.stride
    }
    pub fn capacity(&self) -> usize {
        self.capacity
    }
    pub fn times(&self) -> &[f64] {
        &self.t
    }
    pub fn last_time(&self) -> Option<f64> {
        self.t.last().copied()
    }

    /// Forgets everything (same points and budget).
    pub fn clear(&mut self) {
        let capacity = self.capacity;
        *self = History::new(self.p, 0);
        self.capacity = capacity;
    }

    /// Records the state at `t = 0` (or after a reset).
    pub fn record_initial(&mut self, sim: &Simulation) {
        self.q_sum.fill(0.0);
        self.q_impact_sum.fill(0.0);
        self.contact_any.fill(false);
        self.count = 0;
        self.impacts = ImpactTracker::start(sim);
        self.push(sim, 1);
    }

    /// Call after every solver step.
    pub fn after_step(&mut self, sim: &Simulation) {
        for ((s, q), c) in self
            .q_sum
            .iter_mut()
            .zip(sim.force_n())
            .zip(self.contact_any.iter_mut())
        {
            *s += q;
            *c |= *q > 0.0;
        }
        self.impacts.add_step(sim, &mut self.q_impact_sum);
        self.count += 1;
        if self.count >= self.stride {
            let n = self.count;
            self.push(sim, n);
            self.count = 0;
            self.q_sum.fill(0.0);
            self.q_impact_sum.fill(0.0);
            self.contact_any.fill(false);
        }
    }

    fn push(&mut self, sim: &Simulation, n: u64) {
        if self.t.len() >= self.capacity {
            self.compact();
        }
        self.t.push(sim.time_s());
        let contact = sim.in_contact();
        for i in 0..self.p.min(sim.num_points()) {
            self.u[i].push(sim.displacement_m()[i] as f32);
            self.q[i].push((self.q_sum[i] / n as f64) as f32);
            self.q_impact[i].push((self.q_impact_sum[i] / n as f64) as f32);
            self.gap[i].push(sim.gap_m(i) as f32);
            self.contact[i].push(u8::from(contact[i] || self.contact_any[i]));
        }
    }

    /// Merges pairs of samples: keeps the later time and state, averages the
    /// force, and keeps contact if either sample had it.
    fn compact(&mut self) {
        let n = self.t.len() / 2;
        for k in 0..n {
            self.t[k] = self.t[2 * k + 1];
        }
        self.t.truncate(n);
        for i in 0..self.p {
            for k in 0..n {
                self.u[i][k] = self.u[i][2 * k + 1];
                self.gap[i][k] = self.gap[i][2 * k + 1];
                self.q[i][k] = 0.5 * (self.q[i][2 * k] + self.q[i][2 * k + 1]);
                self.q_impact[i][k] = 0.5 * (self.q_impact[i][2 * k] + self.q_impact[i][2 * k + 1]);
                self.contact[i][k] = self.contact[i][2 * k].max(self.contact[i][2 * k + 1]);
            }
            self.u[i].truncate(n);
            self.gap[i].truncate(n);
            self.q[i].truncate(n);
            self.q_impact[i].truncate(n);
            self.contact[i].truncate(n);
        }
        self.stride *= 2;
    }

    /// The value of `what` for point `i` at sample `k` (SI units; contact 0/1).
    pub fn value(&self, what: Quantity, i: usize, k: usize) -> f64 {
        match what {
            Quantity::Displacement => f64::from(self.u[i][k]),
            Quantity::Force => f64::from(self.q[i][k]),
            Quantity::ForceWithoutImpacts => f64::from(self.q[i][k] - self.q_impact[i][k]),
            Quantity::Gap => f64::from(self.gap[i][k]),
            Quantity::Contact => f64::from(self.contact[i][k]),
        }
    }

    /// Sample indices `[lo, hi)` whose times lie in `[t0, t1]`, widened by one
    /// sample on each side so that lines reach the edges.
    pub fn index_range(&self, t0: f64, t1: f64) -> (usize, usize) {
        let lo = self.t.partition_point(|&t| t < t0).saturating_sub(1);
        let hi = (self.t.partition_point(|&t| t <= t1) + 1).min(self.t.len());
        (lo, hi.max(lo))
    }

    /// Min/max decimation of `what` for point `i` over `[t0, t1]` into at most
    /// about `2 * buckets` points `[t, value * scale]`: each bucket contributes
    /// its minimum and its maximum in time order, so peaks survive.
    pub fn decimated(
        &self,
        what: Quantity,
        i: usize,
        t0: f64,
        t1: f64,
        buckets: usize,
        scale: f64,
    ) -> Vec<[f64; 2]> {
        if i >= self.p {
            return Vec::new();
        }
        let (lo, hi) = self.index_range(t0, t1);
        decimate_min_max(
            &self.t[lo..hi],
            |k| self.value(what, i, lo + k) * scale,
            buckets,
        )
    }
}

impl History {
    /// The samples as a [`Recording`] (SI units, windows of the current
    /// stride): `u`, window-mean `q` and its impact part, the road
    /// `r = u − gap`, contact. What `run --plot` draws, drawn the same way.
    pub fn to_recording(&self) -> Recording {
        let per_point = |f: &dyn Fn(usize, usize) -> f64| -> Vec<Vec<f64>> {
            (0..self.p)
                .map(|i| (0..self.len()).map(|k| f(i, k)).collect())
                .collect()
        };
        Recording::from_samples(
            self.stride,
            self.t.clone(),
            per_point(&|i, k| f64::from(self.u[i][k])),
            per_point(&|i, k| f64::from(self.q[i][k])),
            per_point(&|i, k| f64::from(self.u[i][k]) - f64::from(self.gap[i][k])),
            per_point(&|i, k| f64::from(self.q_impact[i][k])),
            self.contact
                .iter()
                .map(|c| c.iter().map(|&b| b != 0).collect())
                .collect(),
        )
    }
}

/// Min/max decimation of `(t[k], y(k))` into at most `2 * buckets` points.
pub fn decimate_min_max(t: &[f64], y: impl Fn(usize) -> f64, buckets: usize) -> Vec<[f64; 2]> {
    let n = t.len();
    let buckets = buckets.max(1);
    if n <= 2 * buckets {
        return (0..n).map(|k| [t[k], y(k)]).collect();
    }
    let mut out = Vec::with_capacity(2 * buckets + 2);
    for b in 0..buckets {
        let a = b * n / buckets;
        let e = ((b + 1) * n / buckets).max(a + 1);
        let (mut kmin, mut kmax) = (a, a);
        let (mut vmin, mut vmax) = (y(a), y(a));
        for k in a + 1..e {
            let v = y(k);
            if v < vmin {
                vmin = v;
                kmin = k;
            }
            if v > vmax {
                vmax = v;
                kmax = k;
            }
        }
        if kmin <= kmax {
            out.push([t[kmin], vmin]);
            if kmax != kmin {
                out.push([t[kmax], vmax]);
            }
        } else {
            out.push([t[kmax], vmax]);
            out.push([t[kmin], vmin]);
        }
    }
    out
}

impl crate::drive::Probe for History {
    fn start(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.record_initial(sim);
        Ok(())
    }
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        History::after_step(self, sim);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scene;

    #[test]
    fn decimation_keeps_peaks_and_bounds_points() {
        let n = 1_000_000;
        let t: Vec<f64> = (0..n).map(|k| k as f64).collect();
        let y = |k: usize| {
            if k == 123_457 {
                10.0
            } else {
                (k as f64 * 0.01).sin()
            }
        };
        let d = decimate_min_max(&t, y, 500);
        assert!(d.len() <= 1000);
        assert!(d.iter().any(|p| p[1] == 10.0));
        assert!(d.windows(2).all(|w| w[0][0] <= w[1][0]));
    }

    #[test]
    fn small_series_are_not_decimated() {
        let t = [0.0, 1.0, 2.0];
        assert_eq!(decimate_min_max(&t, |k| k as f64, 10).len(), 3);
    }

    #[test]
    fn history_stays_bounded_and_doubles_stride() {
        let scene = Scene::parse(
            include_str!("../../../presets/single_mode.ron"),
            "single_mode",
        )
        .unwrap();
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut h = History::new(1, 4 * 1024 + 1);
        assert_eq!(h.capacity(), 1024);
        h.record_initial(&sim);
        for _ in 0..5000 {
            sim.step().unwrap();
            h.after_step(&sim);
        }
        assert!(h.len() <= h.capacity());
        assert!(h.stride() >= 4);
        let last = h.last_time().unwrap();
        assert!((last - sim.time_s()).abs() <= h.stride() as f64 * scene.dt_s + 1e-12);
        assert!(h.times().windows(2).all(|w| w[0] < w[1]));
    }

    /// The force without impacts is the recorded force minus the impacts'
    /// impulse / dt the solver reports, step by step; on the single-mode
    /// preset impacts dominate the force's range and the rest does not.
    #[test]
    fn force_without_impacts_removes_exactly_the_impact_impulses() {
        let scene = Scene::parse(
            include_str!("../../../presets/single_mode.ron"),
            "single_mode",
        )
        .unwrap();
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut h = History::new(1, 1 << 20);
        h.record_initial(&sim);
        let (mut impacts, mut max_q, mut max_smooth) = (0, 0.0f64, 0.0f64);
        for k in 1..=20_000 {
            let report = sim.step().unwrap();
            h.after_step(&sim);
            assert_eq!(h.stride(), 1);
            let j = sim.impact_impulse_ns()[0];
            assert!(j >= 0.0, "an impact pushes: {j}");
            if j > 0.0 {
                impacts += 1;
                assert!(report.events > 0, "impulse without an event at step {k}");
            }
            let q = h.value(Quantity::Force, 0, k);
            let smooth = h.value(Quantity::ForceWithoutImpacts, 0, k);
            let expected = (sim.force_n()[0] - j / scene.dt_s) as f32 as f64;
            assert!(
                (smooth - expected).abs() <= 1e-6 * q.abs().max(1.0),
                "{smooth} {expected}"
            );
            max_q = max_q.max(q);
            max_smooth = max_smooth.max(smooth);
        }
        assert!(impacts > 5, "the preset bounces: {impacts} impacts");
        assert!(max_q > 5.0 * max_smooth, "{max_q} vs {max_smooth}");
        assert!(max_smooth > 0.0);
    }
}
