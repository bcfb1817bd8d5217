//! Bounded time histories of a run, and min/max decimation for drawing.
//!
//! The samples are the run sampler's ([`Sampler`]) with windows that
//! double: one step per window at first, each window's mean force (so
//! impulses are kept) and the state at its end. When the buffers are full,
//! pairs of windows merge and the windows double: memory stays bounded
//! however long the run, the whole run stays visible at a coarser
//! resolution, and the samples are those of the doubled windows from the
//! start. Values are kept as `f32`.

use crate::Simulation;
pub use crate::output::impacts::paper_impact_n;
use crate::output::record::Recording;
use crate::output::sampler::{LastWindow, Merge, Sampler, Stride, merge_column};

/// Samples kept across all series (bounds memory to a few tens of MB).
pub const DEFAULT_BUDGET: usize = 8_000_000;

/// Which quantity of a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Displacement `u_i` (m) at the window's end.
    Displacement,
    /// Window-mean contact force `q_i` (N).
    Force,
    /// Window-mean contact force without the impulses of impacts (N): the
    /// force a plot's range should fit (an impact adds impulse / dt). The
    /// located scheme reports its impacts' impulses; the paper scheme
    /// (`contact_scheme: Paper`) locates none, and there a landing step
    /// counts as the impact (see [`paper_impact_n`]).
    ForceWithoutImpacts,
    /// Gap `u_i - r_i` (m) at the window's end.
    Gap,
    /// Contact state (0/1): in contact at some step of the window.
    Contact,
}

/// Per-point time histories.
#[derive(Debug, Clone)]
pub struct History {
    p: usize,
    /// Samples kept at most, the one at `t = 0` included (even).
    capacity: usize,
    sampler: Sampler,
    /// Samples before the windows: 1 once the state at `t = 0` is recorded.
    first: usize,
    t: Vec<f64>,
    u: Vec<Vec<f32>>,
    q: Vec<Vec<f32>>,
    /// Impact part of `q` (N).
    q_impact: Vec<Vec<f32>>,
    gap: Vec<Vec<f32>>,
    contact: Vec<Vec<u8>>,
}

impl History {
    /// Histories for `p` points within a budget of `budget` samples; every
    /// buffer is allocated here, so that recording a step allocates nothing.
    pub fn new(p: usize, budget: usize) -> Self {
        let capacity = (budget / (5 * p.max(1) + 1)).max(1024) & !1;
        // the window that fills the buffers is stored before its pairs merge
        let room = capacity + 1;
        // (one `Vec` per point, each with its room: `vec![v; p]` clones
        // without the capacity)
        fn with_room<T>(p: usize, room: usize) -> Vec<Vec<T>> {
            (0..p).map(|_| Vec::with_capacity(room)).collect()
        }
        History {
            p,
            capacity,
            sampler: Self::sampler(p, capacity),
            first: 0,
            t: Vec::with_capacity(room),
            u: with_room(p, room),
            q: with_room(p, room),
            q_impact: with_room(p, room),
            gap: with_room(p, room),
            contact: with_room(p, room),
        }
    }

    /// One step per window at first; once `capacity` windows are kept, they
    /// merge in pairs (the sample at `t = 0` besides them keeps the total
    /// within `capacity`).
    fn sampler(p: usize, capacity: usize) -> Sampler {
        Sampler::new(p, Stride::Doubling { capacity }, LastWindow::WholeOnly).with_impacts()
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
    /// Solver steps per recorded sample (the window).
    pub fn stride(&self) -> u64 {
        self.sampler.every()
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

    /// Forgets everything (same points and budget, one step per window).
    pub fn clear(&mut self) {
        self.t.clear();
        for i in 0..self.p {
            self.u[i].clear();
            self.q[i].clear();
            self.q_impact[i].clear();
            self.gap[i].clear();
            self.contact[i].clear();
        }
        self.first = 0;
        self.sampler.restart(&[]);
    }

    /// Starts the history at `sim`'s state (`t = 0`, or after a reset):
    /// earlier samples are forgotten.
    pub fn record_initial(&mut self, sim: &Simulation) {
        self.clear();
        self.sampler.start(sim);
        self.push(sim);
        self.first = 1;
    }

    /// Call after every solver step.
    pub fn after_step(&mut self, sim: &Simulation) {
        let Some(merge) = self.sampler.after_step(sim).map(|w| w.merge_pairs) else {
            return;
        };
        self.push(sim);
        if merge {
            self.merge_pairs();
        }
    }

    /// Stores the sampler's last window: its means, and `sim`'s state at its end.
    fn push(&mut self, sim: &Simulation) {
        let w = self.sampler.last_window();
        self.t.push(sim.time_s());
        for i in 0..self.p.min(sim.num_points()) {
            self.u[i].push(sim.displacement_m()[i] as f32);
            self.q[i].push(w.q_n[i] as f32);
            self.q_impact[i].push(w.q_impact_n[i] as f32);
            self.gap[i].push(sim.gap_m(i) as f32);
            self.contact[i].push(u8::from(w.contact[i]));
        }
    }

    /// Merges the windows in pairs (the sampler's windows have doubled):
    /// the later time and state, the mean force, contact if either had it.
    /// The sample at `t = 0` stays.
    fn merge_pairs(&mut self) {
        let keep = self.first;
        merge_column(&mut self.t, keep, 2, Merge::End);
        for i in 0..self.p {
            merge_column(&mut self.u[i], keep, 2, Merge::End);
            merge_column(&mut self.gap[i], keep, 2, Merge::End);
            merge_column(&mut self.q[i], keep, 2, Merge::Mean);
            merge_column(&mut self.q_impact[i], keep, 2, Merge::Mean);
            merge_column(&mut self.contact[i], keep, 2, Merge::Any);
        }
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

    /// At every sample: the points' window-mean forces summed (N), and how
    /// many points carry force. A pass down each point's column, so that a
    /// patch's totals over a long run cost a millisecond a frame.
    pub fn totals(&self) -> (Vec<f64>, Vec<f64>) {
        let n = self.t.len();
        let mut force_n = vec![0.0; n];
        let mut carrying = vec![0.0; n];
        for q in &self.q {
            for ((f, c), &v) in force_n.iter_mut().zip(carrying.iter_mut()).zip(q) {
                *f += f64::from(v);
                if v > 0.0 {
                    *c += 1.0;
                }
            }
        }
        (force_n, carrying)
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
            self.stride(),
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

impl crate::solver::drive::Probe for History {
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
    use crate::SceneSimulation;

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

    /// The column-wise totals are the sums over the points sample by
    /// sample, on a patch whose points come and go, through merged windows.
    #[test]
    fn totals_sum_the_points_sample_by_sample() {
        let mut scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/patch_texture.ron"
            )),
            "patch_texture",
        )
        .unwrap();
        // more steps than the least capacity (1024 samples): windows merge
        scene.duration_s = 2500.0 * scene.dt_s;
        scene.ramp_s = 100.0 * scene.dt_s;
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let p = scene.num_points();
        let mut h = History::new(p, 0);
        h.record_initial(&sim);
        while !sim.finished() {
            sim.step().unwrap();
            h.after_step(&sim);
        }
        assert!(h.stride() > 1, "the windows merged");
        let (force_n, carrying) = h.totals();
        assert_eq!(force_n.len(), h.len());
        let mut some_carry = false;
        for k in 0..h.len() {
            let f: f64 = (0..p).map(|i| h.value(Quantity::Force, i, k)).sum();
            let c = (0..p)
                .filter(|&i| h.value(Quantity::Force, i, k) > 0.0)
                .count();
            assert!(
                (force_n[k] - f).abs() <= 1e-9 * f.abs().max(1.0),
                "sample {k}"
            );
            assert_eq!(carrying[k], c as f64, "sample {k}");
            some_carry |= c > 0 && c < p;
        }
        assert!(some_carry, "some samples have points on and off the road");
    }

    #[test]
    fn history_stays_bounded_and_doubles_stride() {
        let scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/single_mode.ron"
            )),
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
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/single_mode.ron"
            )),
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

    /// The visualiser's history and the command line's recorders, fed the
    /// same run: after its windows doubled three times (one step, then 2,
    /// 4, 8), the history holds what the figures' recording and the CSV
    /// rows with windows of 8 steps from the start hold, to `f32`: times,
    /// displacements, gaps and contact exactly, window-mean forces and
    /// their impact parts to a few `f32` roundings. Both contact schemes.
    #[test]
    fn after_doubling_the_history_holds_the_command_lines_samples() {
        use crate::output::csv::RunWriter;
        use crate::scene::ContactScheme;
        for scheme in [ContactScheme::Located, ContactScheme::Paper] {
            let mut scene = Scene::parse(
                include_str!(concat!(
                    env!("CARGO_MANIFEST_DIR"),
                    "/presets/three_points.ron"
                )),
                "three_points",
            )
            .unwrap();
            scene.contact_scheme = scheme;
            scene.duration_s = 5000.0 * scene.dt_s;
            let (p, n) = (scene.num_points(), scene.num_steps());
            assert_eq!(n, 5000);
            let mut sim = Simulation::from_scene(&scene).unwrap();
            // 1024 windows kept: they merge after steps 1024, 2048 and 4096
            let mut h = History::new(p, 1024 * (5 * p + 1));
            assert_eq!(h.capacity(), 1024);
            let mut rec = Recording::new(p, n, 625);
            assert_eq!(rec.every(), 8);
            let mut csv = RunWriter::new(Vec::new(), p, 8).unwrap();
            h.record_initial(&sim);
            csv.write_initial(&sim).unwrap();
            while !sim.finished() {
                sim.step().unwrap();
                h.after_step(&sim);
                rec.after_step(&sim);
                csv.after_step(&sim).unwrap();
            }
            assert_eq!(h.stride(), 8, "{scheme:?}");
            // the first sample (t = 0) and 625 windows of 8 steps
            assert_eq!((h.len(), rec.len()), (626, 625), "{scheme:?}");
            let text = String::from_utf8(csv.finish().unwrap()).unwrap();
            let rows: Vec<Vec<&str>> = text
                .lines()
                .skip(1)
                .map(|l| l.split(',').collect())
                .collect();
            assert_eq!(rows.len(), h.len());
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * b.abs() + 1e-9;
            for k in 0..rec.len() {
                let (row, s) = (&rows[k + 1], k + 1);
                assert_eq!(h.times()[s], rec.t_s[k]);
                assert_eq!(row[0], format!("{:.9e}", rec.t_s[k]));
                for i in 0..p {
                    let v = |what| h.value(what, i, s);
                    let f32_of = |x: f64| f64::from(x as f32);
                    assert_eq!(v(Quantity::Displacement), f32_of(rec.u_m[i][k]));
                    assert_eq!(v(Quantity::Gap), f32_of(rec.u_m[i][k] - rec.r_m[i][k]));
                    assert_eq!(v(Quantity::Contact) == 1.0, rec.contact[i][k]);
                    let (q, qi) = (rec.q_n[i][k], rec.q_impact_n[i][k]);
                    assert!(
                        close(v(Quantity::Force), q),
                        "{scheme:?} {k} {i}: {} vs {q}",
                        v(Quantity::Force)
                    );
                    let smooth = v(Quantity::ForceWithoutImpacts);
                    assert!(
                        (smooth - (q - qi)).abs() <= 1e-6 * (q.abs() + qi.abs()) + 1e-9,
                        "{scheme:?} {k} {i}: {smooth} vs {q} - {qi}"
                    );
                    // the CSV: the recording's numbers; its contact is the
                    // state at the row's time, within the window's contact
                    assert_eq!(row[1 + i], format!("{:.9e}", rec.u_m[i][k]));
                    assert_eq!(row[1 + 2 * p + i], format!("{:.9e}", q));
                    assert!(row[1 + 4 * p + i] == "0" || rec.contact[i][k]);
                }
            }
            // the run has impacts, and contact of both kinds
            let flat = |v: &Vec<Vec<f64>>| v.iter().flatten().copied().fold(0.0, f64::max);
            assert!(flat(&rec.q_impact_n) > 0.0, "{scheme:?}");
            assert!(rec.contact.iter().flatten().any(|&c| c));
            assert!(rec.contact.iter().flatten().any(|&c| !c));
        }
    }

    /// The PNG export merges the history's windows after its t = 0 sample:
    /// its samples are those of a command-line recording whose windows are
    /// that many times longer from the start.
    #[test]
    fn merged_for_export_the_history_holds_the_longer_windows_of_the_command_line() {
        let mut scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/three_points.ron"
            )),
            "three_points",
        )
        .unwrap();
        scene.duration_s = 3000.0 * scene.dt_s;
        let (p, n) = (scene.num_points(), scene.num_steps());
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut h = History::new(p, 1 << 20);
        // 3000 one-step windows kept; merged by 30 they are 100 windows
        let mut rec = Recording::new(p, n, 100);
        assert_eq!(rec.every(), 30);
        h.record_initial(&sim);
        while !sim.finished() {
            sim.step().unwrap();
            h.after_step(&sim);
            rec.after_step(&sim);
        }
        assert_eq!(h.stride(), 1);
        let merged = h.to_recording().merged_after_start(30);
        assert_eq!(merged.every(), 30);
        // the t = 0 sample, then the command line's 100 windows
        assert_eq!((merged.len(), rec.len()), (101, 100));
        assert_eq!(merged.t_s[0], 0.0);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * b.abs() + 1e-9;
        for k in 0..rec.len() {
            assert_eq!(merged.t_s[k + 1], rec.t_s[k], "{k}");
            for i in 0..p {
                assert_eq!(merged.u_m[i][k + 1], f64::from(rec.u_m[i][k] as f32));
                assert_eq!(merged.contact[i][k + 1], rec.contact[i][k], "{k} {i}");
                let (a, b) = (merged.q_n[i][k + 1], rec.q_n[i][k]);
                assert!(close(a, b), "{k} {i}: {a} vs {b}");
            }
        }
        // merged from the first sample on, the windows would be shifted
        let shifted = h.to_recording().merged(30);
        assert_ne!(shifted.t_s[0], rec.t_s[0]);
    }
}
