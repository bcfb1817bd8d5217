//! The one sampler of a run's time histories: the run CSV
//! ([`super::csv::RunWriter`]), its arrays ([`super::arrays::RunArrays`]),
//! the figures' recording ([`super::record::Recording`]) and the
//! visualiser's history all take their samples from a [`Sampler`].
//!
//! A sample closes a *window* of solver steps. Its values are of two kinds:
//!
//! | values | kind | kept by |
//! |---|---|---|
//! | contact force `q` (N) | window mean | all four |
//! | impact part of `q` (N) | window mean | recording, history |
//! | in contact at some step of the window | any over the steps | recording, history |
//! | time, displacement `u`, velocity `v`, road `r`, gap `u − r`, contact state | the state at the window's end, read from the simulation | all four (the CSV's and arrays' contact column is this state) |
//!
//! The force the solver reports for a step is its mean, impulse / dt
//! (docs/method.md §4.3, step 5), so the mean over a window of `n` steps is
//! the window's impulse over its duration `n dt`: an impact inside the
//! window is kept, however long the window. The impact part is the located
//! impacts' impulses / dt (docs/method.md §4.4), or under the paper's
//! scheme the landing steps ([`super::impacts::paper_impact_n`]). A step
//! counts as in contact with a positive step-mean force or in contact at
//! its end.
//!
//! The first sample ([`Sampler::start`]) is the state at `t = 0`: no
//! steps, zero force (the CSV, the arrays and the history keep it; the
//! recording starts with the first window). Windows then have `every`
//! steps. At the run's end the steps after the last whole window close a
//! shorter window ([`LastWindow::Partial`]: the CSV, the arrays, the
//! recording) or are left out ([`LastWindow::WholeOnly`]: the history).
//!
//! **Doubling windows** (the history). With [`Stride::Doubling`], once
//! `capacity` windows are kept the sampler doubles `every` and tells the
//! recorder to merge its windows in pairs ([`Window::merge_pairs`],
//! [`merge_column`]). A merged pair is what a window twice as long gives:
//! the mean of the two means of equal windows is the mean over both, the
//! end state is the later one's, the contact is either's ([`Merge`]). So
//! the samples after any number of doublings are those of a sampler that
//! had the final `every` from the start, and memory stays bounded however
//! long the run.
//!
//! Every buffer is sized by [`Sampler::new`]: a step allocates nothing.

use crate::output::impacts::ImpactTracker;
use tirecontact_core::solver::simulation::Simulation;

/// What closes the steps after the last whole window when the run ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LastWindow {
    /// The run's last step closes a shorter window (its mean is over its
    /// own steps): every step of the run is in a sample.
    Partial,
    /// Only whole windows are sampled: the steps after the last one are
    /// left out (windows that double stay aligned).
    WholeOnly,
}

/// How the window length is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stride {
    /// Windows of `every` steps (at least 1).
    Every(u64),
    /// Windows of one step at first, doubling whenever `capacity` windows
    /// (rounded down to an even number, at least 2) are kept.
    Doubling { capacity: usize },
}

/// The window-mean sampler of a run's `p` points.
#[derive(Debug, Clone)]
pub struct Sampler {
    every: u64,
    /// Windows kept before they merge in pairs (even); `None`: fixed
    /// windows.
    capacity: Option<usize>,
    last: LastWindow,
    /// Windows closed since the start (after the merges).
    windows: usize,
    /// Steps in the window under way.
    count: u64,
    q_sum: Vec<f64>,
    q_impact_sum: Vec<f64>,
    /// In contact at some step of the window under way.
    touched: Vec<bool>,
    /// The impact part of each step's force; `None`: not tracked.
    impacts: Option<ImpactTracker>,
    /// The last closed window (or the first sample): its steps, values,
    /// and whether the stored windows merge after it.
    steps: u64,
    q_mean: Vec<f64>,
    q_impact_mean: Vec<f64>,
    contact: Vec<bool>,
    merge_pairs: bool,
}

/// A closed window (or the first sample): its means, and what the recorder
/// does with it. The state at its end is the simulation's when it closes.
#[derive(Debug, Clone, Copy)]
pub struct Window<'a> {
    /// Steps in the window: 0 for the first sample (`t = 0`), `every` for
    /// a whole window, fewer for a partial last one.
    pub steps: u64,
    /// Window-mean contact force of each point (N): impulse over the
    /// window's duration; 0 in the first sample.
    pub q_n: &'a [f64],
    /// Window mean of its impact part (N); zeros when impacts are not
    /// tracked ([`Sampler::with_impacts`]).
    pub q_impact_n: &'a [f64],
    /// Each point in contact at some step of the window (a positive
    /// step-mean force, or in contact at the step's end); in the first
    /// sample, in contact at `t = 0`.
    pub contact: &'a [bool],
    /// Once this window is stored, merge the stored windows in pairs
    /// ([`merge_windows`] with factor 2; the first sample is not a window
    /// and stays): the sampler's windows have just doubled.
    pub merge_pairs: bool,
}

/// One step's values for [`Sampler::add`].
#[derive(Debug, Clone, Copy)]
pub struct Step<'a> {
    /// Step-mean contact force of each point (N).
    pub q_n: &'a [f64],
    /// Its impact part (N); may be empty (no impacts).
    pub q_impact_n: &'a [f64],
    /// Contact state at the step's end.
    pub in_contact: &'a [bool],
    /// Whether this is the run's last step.
    pub last: bool,
}

impl Default for Sampler {
    /// A sampler of no points, one step per window.
    fn default() -> Self {
        Sampler::new(0, Stride::Every(1), LastWindow::Partial)
    }
}

impl Sampler {
    /// A sampler of `p` points; every buffer is allocated here.
    pub fn new(p: usize, stride: Stride, last: LastWindow) -> Self {
        let (every, capacity) = match stride {
            Stride::Every(every) => (every.max(1), None),
            Stride::Doubling { capacity } => (1, Some((capacity & !1).max(2))),
        };
        Sampler {
            every,
            capacity,
            last,
            windows: 0,
            count: 0,
            q_sum: vec![0.0; p],
            q_impact_sum: vec![0.0; p],
            touched: vec![false; p],
            impacts: None,
            steps: 0,
            q_mean: vec![0.0; p],
            q_impact_mean: vec![0.0; p],
            contact: vec![false; p],
            merge_pairs: false,
        }
    }

    /// Also the impact part of the force ([`Window::q_impact_n`]), from the
    /// simulation's steps ([`Self::after_step`]).
    pub fn with_impacts(mut self) -> Self {
        self.impacts = Some(ImpactTracker::zeros(self.q_sum.len()));
        self
    }

    /// Points sampled.
    pub fn num_points(&self) -> usize {
        self.q_sum.len()
    }

    /// Steps per window.
    pub fn every(&self) -> u64 {
        self.every
    }

    /// Windows kept before they merge in pairs (`None`: fixed windows).
    pub fn capacity(&self) -> Option<usize> {
        self.capacity
    }

    /// Whole and partial windows closed since the start (after merges).
    pub fn windows(&self) -> usize {
        self.windows
    }

    /// Steps in the window under way.
    pub fn pending_steps(&self) -> u64 {
        self.count
    }

    /// Starts anew at `sim`'s state (`t = 0`, or after a reset): forgets
    /// the window under way, and with [`Stride::Doubling`] the windows
    /// return to one step. Returns the first sample: zero force, contact
    /// as at `sim`'s time.
    pub fn start(&mut self, sim: &Simulation) -> Window<'_> {
        if let Some(tracker) = &mut self.impacts {
            tracker.restart(sim);
        }
        self.restart(sim.in_contact())
    }

    /// [`Self::start`] from the contact state at the start (points beyond
    /// `in_contact` out of contact), the impact part's tracking left as it
    /// is.
    pub fn restart(&mut self, in_contact: &[bool]) -> Window<'_> {
        if self.capacity.is_some() {
            self.every = 1;
        }
        self.windows = 0;
        self.clear_window();
        self.q_mean.fill(0.0);
        self.q_impact_mean.fill(0.0);
        self.contact.fill(false);
        for (c, &touching) in self.contact.iter_mut().zip(in_contact) {
            *c = touching;
        }
        self.steps = 0;
        self.merge_pairs = false;
        self.last_window()
    }

    /// Adds the step `sim` just took; a window that closes is returned.
    pub fn after_step(&mut self, sim: &Simulation) -> Option<Window<'_>> {
        if let Some(tracker) = &mut self.impacts {
            tracker.add_step(sim, &mut self.q_impact_sum);
        }
        self.add_forces(sim.force_n(), sim.in_contact());
        self.close_if_due(sim.finished())
    }

    /// Adds one step given by its values; a window that closes is returned.
    pub fn add(&mut self, step: Step<'_>) -> Option<Window<'_>> {
        for (s, &q) in self.q_impact_sum.iter_mut().zip(step.q_impact_n) {
            *s += q;
        }
        self.add_forces(step.q_n, step.in_contact);
        self.close_if_due(step.last)
    }

    fn add_forces(&mut self, q_n: &[f64], in_contact: &[bool]) {
        for (((s, t), &q), &c) in self
            .q_sum
            .iter_mut()
            .zip(self.touched.iter_mut())
            .zip(q_n)
            .zip(in_contact)
        {
            *s += q;
            *t |= q > 0.0 || c;
        }
        self.count += 1;
    }

    fn close_if_due(&mut self, last_step: bool) -> Option<Window<'_>> {
        let due = self.count >= self.every || (last_step && self.last == LastWindow::Partial);
        if !due {
            return None;
        }
        let n = self.count;
        let steps = n as f64;
        for (m, s) in self.q_mean.iter_mut().zip(&self.q_sum) {
            *m = s / steps;
        }
        for (m, s) in self.q_impact_mean.iter_mut().zip(&self.q_impact_sum) {
            *m = s / steps;
        }
        self.contact.copy_from_slice(&self.touched);
        self.clear_window();
        self.steps = n;
        self.windows += 1;
        // (a partial last window does not merge: pairs stay equal windows)
        self.merge_pairs = self.capacity.is_some_and(|c| self.windows >= c) && n == self.every;
        if self.merge_pairs {
            self.windows /= 2;
            self.every *= 2;
        }
        Some(self.last_window())
    }

    fn clear_window(&mut self) {
        self.count = 0;
        self.q_sum.fill(0.0);
        self.q_impact_sum.fill(0.0);
        self.touched.fill(false);
    }

    /// The last closed window, or the first sample if none closed since
    /// the start.
    pub fn last_window(&self) -> Window<'_> {
        Window {
            steps: self.steps,
            q_n: &self.q_mean,
            q_impact_n: &self.q_impact_mean,
            contact: &self.contact,
            merge_pairs: self.merge_pairs,
        }
    }
}

/// How samples of a quantity merge into a longer window.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Merge {
    /// The mean of the windows' means (equal windows: the mean over all
    /// their steps): the force and its impact part.
    Mean,
    /// The last window's value, the state at the merged window's end: time,
    /// displacement, velocity, road, gap.
    End,
    /// Whether any window had it: contact.
    Any,
}

/// A value stored in a sample column: the visualiser's history keeps `f32`
/// and `u8`, the recordings `f64` and `bool`.
pub trait SampleValue: Copy {
    fn to_f64(self) -> f64;
    fn from_f64(x: f64) -> Self;
}

impl SampleValue for f64 {
    fn to_f64(self) -> f64 {
        self
    }
    fn from_f64(x: f64) -> Self {
        x
    }
}

impl SampleValue for f32 {
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    fn from_f64(x: f64) -> Self {
        x as f32
    }
}

impl SampleValue for bool {
    fn to_f64(self) -> f64 {
        f64::from(u8::from(self))
    }
    fn from_f64(x: f64) -> Self {
        x != 0.0
    }
}

impl SampleValue for u8 {
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    fn from_f64(x: f64) -> Self {
        x as u8
    }
}

/// Merges every `factor` consecutive windows of `column` into one, in
/// place, as if sampled with windows `factor` times longer; returns the
/// number of merged windows, which are `column[..n]` (the last gathers the
/// windows left over, fewer than `factor` if the length is not a multiple).
/// Means are taken in `f64`.
pub fn merge_windows<T: SampleValue>(column: &mut [T], factor: usize, how: Merge) -> usize {
    let factor = factor.max(1);
    let n = column.len().div_ceil(factor);
    for k in 0..n {
        let chunk = &column[k * factor..((k + 1) * factor).min(column.len())];
        column[k] = match how {
            Merge::Mean => {
                T::from_f64(chunk.iter().map(|x| x.to_f64()).sum::<f64>() / chunk.len() as f64)
            }
            Merge::End => chunk[chunk.len() - 1],
            Merge::Any => T::from_f64(if chunk.iter().any(|x| x.to_f64() != 0.0) {
                1.0
            } else {
                0.0
            }),
        };
    }
    n
}

/// [`merge_windows`] of a column kept in a `Vec`, which is truncated to
/// the merged windows; the first `keep` values (a first sample that is not
/// a window) are left as they are.
pub fn merge_column<T: SampleValue>(column: &mut Vec<T>, keep: usize, factor: usize, how: Merge) {
    let keep = keep.min(column.len());
    let n = merge_windows(&mut column[keep..], factor, how);
    column.truncate(keep + n);
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The windows of `sampler` over the steps `(q, q_impact, in_contact)`
    /// (one point): `(steps, q, q_impact, contact)` each, merged in pairs
    /// whenever the sampler says, as a recorder stores them.
    fn windows(sampler: &mut Sampler, steps: &[(f64, f64, bool)]) -> Vec<(u64, f64, f64, bool)> {
        let mut out: [Vec<f64>; 4] = Default::default();
        for (k, &(q, qi, c)) in steps.iter().enumerate() {
            let step = Step {
                q_n: &[q],
                q_impact_n: &[qi],
                in_contact: &[c],
                last: k + 1 == steps.len(),
            };
            if let Some(w) = sampler.add(step) {
                let merge = w.merge_pairs;
                out[0].push(w.steps as f64);
                out[1].push(w.q_n[0]);
                out[2].push(w.q_impact_n[0]);
                out[3].push(f64::from(u8::from(w.contact[0])));
                if merge {
                    // (steps add up: a merged window's steps are the sum)
                    let mut s = std::mem::take(&mut out[0]);
                    let n = merge_windows(&mut s, 2, Merge::Mean);
                    s.truncate(n);
                    out[0] = s.into_iter().map(|x| 2.0 * x).collect();
                    merge_column(&mut out[1], 0, 2, Merge::Mean);
                    merge_column(&mut out[2], 0, 2, Merge::Mean);
                    merge_column(&mut out[3], 0, 2, Merge::Any);
                }
            }
        }
        (0..out[0].len())
            .map(|k| (out[0][k] as u64, out[1][k], out[2][k], out[3][k] != 0.0))
            .collect()
    }

    /// Seven steps in windows of three: means by hand, the last window
    /// partial (one step), or left out with whole windows only.
    #[test]
    fn window_means_by_hand_with_a_partial_last_window() {
        let steps = [
            (1.0, 0.0, false),
            (2.0, 0.0, false),
            (3.0, 3.0, false),
            (4.0, 0.0, false),
            (0.0, 0.0, false),
            (0.0, 0.0, true),
            (8.0, 6.0, false),
        ];
        let mut s = Sampler::new(1, Stride::Every(3), LastWindow::Partial);
        let got = windows(&mut s, &steps);
        assert_eq!(
            got,
            [
                // (1 + 2 + 3) / 3, impact 3 / 3; a positive force: contact
                (3, 2.0, 1.0, true),
                // (4 + 0 + 0) / 3; in contact at the end of the last step
                (3, 4.0 / 3.0, 0.0, true),
                // the partial window: its own one step
                (1, 8.0, 6.0, true),
            ]
        );
        let mut s = Sampler::new(1, Stride::Every(3), LastWindow::WholeOnly);
        assert_eq!(windows(&mut s, &steps), got[..2]);
        // a window without force and contact has none
        let mut s = Sampler::new(1, Stride::Every(2), LastWindow::Partial);
        let got = windows(&mut s, &[(0.0, 0.0, false), (0.0, 0.0, false)]);
        assert_eq!(got, [(2, 0.0, 0.0, false)]);
    }

    /// The first sample: no steps, zero force, the contact at the start;
    /// the window under way is forgotten.
    #[test]
    fn the_first_sample_has_no_force() {
        let mut s = Sampler::new(2, Stride::Every(4), LastWindow::Partial);
        let step = Step {
            q_n: &[5.0, 6.0],
            q_impact_n: &[],
            in_contact: &[true, true],
            last: false,
        };
        assert!(s.add(step).is_none());
        assert_eq!(s.pending_steps(), 1);
        let w = s.restart(&[false, true]);
        assert_eq!(w.steps, 0);
        assert_eq!(w.q_n, [0.0, 0.0]);
        assert_eq!(w.q_impact_n, [0.0, 0.0]);
        assert_eq!(w.contact, [false, true]);
        assert_eq!(s.pending_steps(), 0);
        // the next window starts afresh: four steps of 1 N
        let one = Step {
            q_n: &[1.0, 1.0],
            ..step
        };
        for _ in 0..3 {
            assert!(s.add(one).is_none());
        }
        let w = s.add(one).unwrap();
        assert_eq!((w.steps, w.q_n), (4, &[1.0, 1.0][..]));
    }

    #[test]
    fn merging_by_hand() {
        let v = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];
        let merged = |how| {
            let mut v = v.to_vec();
            merge_column(&mut v, 0, 3, how);
            v
        };
        assert_eq!(merged(Merge::Mean), [2.0, 5.0, 7.0]);
        assert_eq!(merged(Merge::End), [3.0, 6.0, 7.0]);
        let mut c = vec![false, false, true, false, false];
        merge_column(&mut c, 1, 2, Merge::Any);
        assert_eq!(c, [false, true, false]);
        let mut h: Vec<f32> = vec![9.0, 1.0, 2.0, 3.0, 5.0];
        merge_column(&mut h, 1, 2, Merge::Mean);
        assert_eq!(h, [9.0, 1.5, 4.0]);
    }

    /// Step forces: zero (free), small, large (impact-like) values.
    fn steps() -> impl Strategy<Value = Vec<(f64, f64, bool)>> {
        let q = prop_oneof![Just(0.0), 0.0..2e3f64, 1e4..1e6f64];
        proptest::collection::vec(
            (q, prop_oneof![Just(0.0), 0.0..1e6f64], any::<bool>()),
            1..400,
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Fixed windows: each the mean of its steps, summed in order (so
        /// exactly), the last one partial.
        #[test]
        fn fixed_windows_are_the_means_of_their_steps(steps in steps(), every in 1u64..40) {
            let mut s = Sampler::new(1, Stride::Every(every), LastWindow::Partial);
            let got = windows(&mut s, &steps);
            let want: Vec<_> = steps
                .chunks(every as usize)
                .map(|c| {
                    let n = c.len() as f64;
                    let q = c.iter().fold(0.0, |a, x| a + x.0) / n;
                    let qi = c.iter().fold(0.0, |a, x| a + x.1) / n;
                    let contact = c.iter().any(|x| x.0 > 0.0 || x.2);
                    (c.len() as u64, q, qi, contact)
                })
                .collect();
            prop_assert_eq!(got, want);
        }

        /// Doubling windows: after any number of doublings the samples are
        /// those of a sampler with the final window from the start (means of
        /// means of equal windows), whole windows only; the windows kept
        /// stay below the capacity.
        #[test]
        fn doubled_windows_are_those_of_the_final_window_from_the_start(
            steps in steps(),
            capacity in 2usize..12,
        ) {
            let mut d = Sampler::new(1, Stride::Doubling { capacity }, LastWindow::WholeOnly);
            let got = windows(&mut d, &steps);
            prop_assert!(got.len() < capacity.max(2) & !1 || got.len() < 2);
            prop_assert_eq!(d.windows(), got.len());
            let every = d.every();
            let mut f = Sampler::new(1, Stride::Every(every), LastWindow::WholeOnly);
            let want = windows(&mut f, &steps);
            prop_assert_eq!(got.len(), want.len());
            for (g, w) in got.iter().zip(&want) {
                prop_assert_eq!((g.0, g.3), (w.0, w.3));
                for (a, b) in [(g.1, w.1), (g.2, w.2)] {
                    prop_assert!((a - b).abs() <= 1e-12 * b.abs(), "{} vs {}", a, b);
                }
            }
        }

        /// Merging fixed windows by `factor` gives the windows `factor`
        /// times longer, the partial last one included.
        #[test]
        fn merged_fixed_windows_are_the_longer_windows(
            steps in steps(),
            every in 1u64..8,
            factor in 1usize..6,
        ) {
            let mut s = Sampler::new(1, Stride::Every(every), LastWindow::WholeOnly);
            let fine = windows(&mut s, &steps);
            let mut q: Vec<f64> = fine.iter().map(|w| w.1).collect();
            let mut c: Vec<bool> = fine.iter().map(|w| w.3).collect();
            // whole merged windows only: the fine windows a multiple of `factor`
            let whole = fine.len() / factor * factor;
            q.truncate(whole);
            c.truncate(whole);
            merge_column(&mut q, 0, factor, Merge::Mean);
            merge_column(&mut c, 0, factor, Merge::Any);
            let mut l = Sampler::new(1, Stride::Every(every * factor as u64), LastWindow::WholeOnly);
            let long = windows(&mut l, &steps);
            prop_assert_eq!(q.len(), long.len());
            for k in 0..q.len() {
                prop_assert!((q[k] - long[k].1).abs() <= 1e-12 * long[k].1.abs());
                prop_assert_eq!(c[k], long[k].3);
            }
        }
    }
}
