//! Spectra of the steady part of the current run, from the recorded
//! History samples (no egui here): the uniformly spaced samples after the
//! ramp, their Hann-windowed spectra (`crate::analysis::spectrum`), and a cache keyed
//! by the history's length so they are recomputed only when the run moved.

use crate::analysis::spectrum::run::RunSpectra;
use crate::analysis::spectrum::{Spectrum, Window, spectrum};
use crate::gui::model::history::{History, Quantity};

/// The part of the history a spectrum was computed from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadySpan {
    /// Time of the first and last sample used (s).
    pub t0_s: f64,
    pub t1_s: f64,
    /// Samples used.
    pub samples: usize,
    /// Sample rate `1 / (stride dt)` (Hz).
    pub sample_rate_hz: f64,
}

impl SteadySpan {
    /// Bin width `Δf = f_s / N` (Hz).
    pub fn df_hz(&self) -> f64 {
        self.sample_rate_hz / self.samples.max(1) as f64
    }
}

/// Spectra of the current run with the span they describe.
#[derive(Debug, Clone)]
pub struct HistorySpectra {
    pub spectra: RunSpectra,
    pub span: SteadySpan,
}

impl HistorySpectra {
    /// `Hann, t = a…b s, Δf = … Hz` for captions.
    pub fn caption(&self) -> String {
        let s = &self.span;
        format!(
            "{} window, t = {:.4}…{:.4} s ({} samples at {:.0} Hz), Δf = {:.2} Hz, mean removed, RMS levels",
            self.spectra.total_force.window.name(),
            s.t0_s,
            s.t1_s,
            s.samples,
            s.sample_rate_hz,
            s.df_hz()
        )
    }
}

/// Indices `[k0, len)` of the uniformly spaced samples whose averaging
/// window starts at or after `ramp_s` (`spacing_s` apart).
pub fn steady_range(t: &[f64], ramp_s: f64, spacing_s: f64) -> (usize, usize) {
    let eps = 1e-6 * spacing_s;
    // sample k averages the steps in (t_k - spacing, t_k]
    let mut k0 = t.partition_point(|&x| x - spacing_s < ramp_s - eps);
    // keep the longest uniformly spaced tail
    for k in (k0 + 1..t.len()).rev() {
        if ((t[k] - t[k - 1]) - spacing_s).abs() > 1e-3 * spacing_s {
            k0 = k;
            break;
        }
    }
    (k0.min(t.len()), t.len())
}

/// Spectra of the steady part (`t >= ramp_s`) of `h`, recorded every
/// `h.stride()` steps of `dt_s`.
pub fn history_spectra(
    h: &History,
    ramp_s: f64,
    dt_s: f64,
    window: Window,
) -> Result<HistorySpectra, String> {
    SpectraInput::of_history(h, ramp_s, dt_s)?.compute(window, &|| false, &|| {})
}

/// The samples a spectrum is computed from, copied out of the history (so
/// that the transforms can run on another thread).
#[derive(Debug, Clone)]
pub struct SpectraInput {
    /// Force and displacement of each point over the steady span.
    force_n: Vec<Vec<f64>>,
    disp_m: Vec<Vec<f64>>,
    span: SteadySpan,
}

impl SpectraInput {
    /// The steady part (`t >= ramp_s`) of `h`, recorded every `h.stride()`
    /// steps of `dt_s`; an error says why there is no spectrum yet.
    pub fn of_history(h: &History, ramp_s: f64, dt_s: f64) -> Result<Self, String> {
        let spacing = h.stride() as f64 * dt_s;
        if !(spacing > 0.0 && spacing.is_finite()) {
            return Err(format!(
                "sample spacing {spacing} s: expected a finite time > 0 s"
            ));
        }
        let (k0, k1) = steady_range(h.times(), ramp_s, spacing);
        let n = k1 - k0;
        if n < crate::analysis::spectrum::MIN_SAMPLES {
            return Err(format!(
                "{n} sample(s) after the ramp (t ≥ {ramp_s} s): play the run further (at least {} samples are needed)",
                crate::analysis::spectrum::MIN_SAMPLES
            ));
        }
        let signal = |what: Quantity, i: usize| -> Vec<f64> {
            (k0..k1).map(|k| h.value(what, i, k)).collect()
        };
        let p = h.num_points();
        let t = h.times();
        Ok(SpectraInput {
            force_n: (0..p).map(|i| signal(Quantity::Force, i)).collect(),
            disp_m: (0..p).map(|i| signal(Quantity::Displacement, i)).collect(),
            span: SteadySpan {
                t0_s: t[k0],
                t1_s: t[k1 - 1],
                samples: n,
                sample_rate_hz: 1.0 / spacing,
            },
        })
    }

    /// Spectra to compute: force and displacement per point, total force.
    pub fn num_spectra(&self) -> usize {
        2 * self.force_n.len() + 1
    }

    /// Samples transformed in all (the cost of [`Self::compute`]).
    pub fn work(&self) -> usize {
        self.num_spectra() * self.span.samples
    }

    /// The spectra; `cancelled` is asked between two spectra (an error
    /// then), `done` is called after each.
    pub fn compute(
        &self,
        window: Window,
        cancelled: &dyn Fn() -> bool,
        done: &dyn Fn(),
    ) -> Result<HistorySpectra, String> {
        let mut run = SpectraRun::new(self.clone(), window);
        loop {
            if cancelled() {
                return Err("cancelled".to_string());
            }
            let r = run.stage()?;
            done();
            if let Some(s) = r {
                return Ok(s);
            }
        }
    }
}

/// [`SpectraInput::compute`] a spectrum at a time, for a caller that must
/// return between them (a page in the browser has one thread): per point
/// its force then its displacement, then the total force, as
/// [`SpectraInput::compute`] takes them: the same spectra to the bit.
#[derive(Debug)]
pub struct SpectraRun {
    input: SpectraInput,
    window: Window,
    force: Vec<Spectrum>,
    disp: Vec<Spectrum>,
    /// The total force summed over the points transformed so far.
    total: Vec<f64>,
}

impl SpectraRun {
    pub fn new(input: SpectraInput, window: Window) -> Self {
        let p = input.force_n.len();
        SpectraRun {
            total: vec![0.0; input.span.samples],
            force: Vec::with_capacity(p),
            disp: Vec::with_capacity(p),
            input,
            window,
        }
    }

    /// Spectra done so far.
    pub fn done(&self) -> usize {
        self.force.len() + self.disp.len()
    }

    /// Computes the next spectrum; all of them once the last one is done.
    pub fn stage(&mut self) -> Result<Option<HistorySpectra>, String> {
        let fs = self.input.span.sample_rate_hz;
        let one = |x: &[f64]| spectrum(x, fs, self.window, true).map_err(|e| e.to_string());
        let i = self.done();
        if i < 2 * self.input.force_n.len() {
            let point = i / 2;
            if i.is_multiple_of(2) {
                let q = &self.input.force_n[point];
                for (t, x) in self.total.iter_mut().zip(q) {
                    *t += x;
                }
                self.force.push(one(q)?);
            } else {
                self.disp.push(one(&self.input.disp_m[point])?);
            }
            return Ok(None);
        }
        let total_force = one(&self.total)?;
        Ok(Some(HistorySpectra {
            spectra: RunSpectra {
                force: std::mem::take(&mut self.force),
                displacement: std::mem::take(&mut self.disp),
                total_force,
                start_s: self.input.span.t0_s,
            },
            span: self.input.span,
        }))
    }
}

/// What identifies the history a result was computed from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HistoryKey {
    pub len: usize,
    pub stride: u64,
    pub last_time_bits: u64,
    pub points: usize,
}

impl HistoryKey {
    pub fn of(h: &History) -> Self {
        HistoryKey {
            len: h.len(),
            stride: h.stride(),
            last_time_bits: h.last_time().unwrap_or(-1.0).to_bits(),
            points: h.num_points(),
        }
    }
}

/// A cached value recomputed when its history changed: at once when the run
/// is paused (or restarted), and while it plays only once the history grew
/// by `grow` (a fraction) since the last computation, so long runs are not
/// transformed every frame.
#[derive(Debug, Clone)]
pub struct HistoryCache<T> {
    key: Option<HistoryKey>,
    value: Option<T>,
    /// Computations so far (for tests and the status line).
    pub computations: u64,
    pub grow: f64,
}

impl<T> Default for HistoryCache<T> {
    fn default() -> Self {
        HistoryCache {
            key: None,
            value: None,
            computations: 0,
            grow: 0.25,
        }
    }
}

impl<T> HistoryCache<T> {
    /// Whether a history of key `now` needs a new computation.
    pub fn stale(&self, now: &HistoryKey, playing: bool) -> bool {
        self.stale_since(self.key.as_ref(), now, playing)
    }

    /// Whether a value computed for the history `old` is stale for `now`
    /// (by this cache's rule; `old` may be a computation under way).
    pub fn stale_since(&self, old: Option<&HistoryKey>, now: &HistoryKey, playing: bool) -> bool {
        let Some(old) = old else { return true };
        if old == now {
            return false;
        }
        if !playing || now.len < old.len || now.points != old.points || now.stride != old.stride {
            return true;
        }
        now.len as f64 >= old.len as f64 * (1.0 + self.grow)
    }

    /// Recomputes with `f` when stale (or when `force`), then returns the value.
    pub fn refresh(
        &mut self,
        now: HistoryKey,
        playing: bool,
        force: bool,
        f: impl FnOnce() -> T,
    ) -> Option<&T> {
        if force || self.stale(&now, playing) {
            self.value = Some(f());
            self.key = Some(now);
            self.computations += 1;
        }
        self.value.as_ref()
    }

    pub fn get(&self) -> Option<&T> {
        self.value.as_ref()
    }

    /// The history the value was computed from.
    pub fn key(&self) -> Option<&HistoryKey> {
        self.key.as_ref()
    }

    /// Stores a value computed elsewhere (a background job) for `key`.
    pub fn set(&mut self, key: HistoryKey, value: T) {
        self.value = Some(value);
        self.key = Some(key);
        self.computations += 1;
    }

    /// Forgets the value (next refresh recomputes).
    pub fn invalidate(&mut self) {
        self.key = None;
    }

    /// Whether the cached value is for exactly this history.
    pub fn is_current(&self, now: &HistoryKey) -> bool {
        self.key.as_ref() == Some(now)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scene;
    use crate::SceneSimulation;
    use crate::solver::simulation::Simulation;

    fn key(len: usize) -> HistoryKey {
        HistoryKey {
            len,
            stride: 1,
            last_time_bits: (len as f64).to_bits(),
            points: 1,
        }
    }

    #[test]
    fn cache_recomputes_only_when_the_history_changed() {
        let mut c: HistoryCache<usize> = HistoryCache::default();
        assert_eq!(c.refresh(key(100), false, false, || 1), Some(&1));
        assert_eq!(c.refresh(key(100), false, false, || 2), Some(&1));
        assert_eq!(c.computations, 1);
        // paused: any change recomputes
        assert_eq!(c.refresh(key(101), false, false, || 3), Some(&3));
        // playing: small growth waits, 25 % growth recomputes
        assert_eq!(c.refresh(key(110), true, false, || 4), Some(&3));
        assert_eq!(c.refresh(key(127), true, false, || 5), Some(&5));
        // a restart (shorter history) recomputes at once
        assert_eq!(c.refresh(key(1), true, false, || 6), Some(&6));
        // the button forces it
        assert_eq!(c.refresh(key(1), true, true, || 7), Some(&7));
        assert_eq!(c.computations, 5);
        c.invalidate();
        assert!(c.stale(&key(1), true));
    }

    #[test]
    fn steady_range_skips_the_ramp_and_irregular_heads() {
        let dt = 0.5;
        let t: Vec<f64> = [0.0, 0.4]
            .into_iter()
            .chain((1..=10).map(|k| k as f64 * dt))
            .collect();
        // ramp 2 s: samples whose window (t - 0.5, t] starts at >= 2 s -> t >= 2.5
        let (a, b) = steady_range(&t, 2.0, dt);
        assert_eq!(t[a], 2.5);
        assert_eq!(b, t.len());
        // no ramp: the irregular head (0, 0.4) is dropped
        let (a, _) = steady_range(&t, 0.0, dt);
        assert_eq!(t[a], 0.5);
    }

    #[test]
    fn history_spectrum_reads_a_tone_of_the_road() {
        // one mode, sine road: the displacement follows the road at V/λ;
        // compare the tone found in the history spectrum with a spectrum
        // of the same samples recomputed here by a direct DFT at that bin
        let mut scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/single_mode.ron"
            )),
            "single_mode",
        )
        .unwrap();
        scene.duration_s = 0.3;
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut h = History::new(1, 1 << 22);
        h.record_initial(&sim);
        while !sim.finished() {
            sim.step().unwrap();
            h.after_step(&sim);
        }
        let hs = history_spectra(&h, scene.ramp_s, scene.dt_s, Window::Hann).unwrap();
        let s = &hs.spectra.displacement[0];
        assert!(hs.span.t0_s >= scene.ramp_s);
        assert_eq!(s.num_samples, hs.span.samples);
        assert!((s.df_hz - hs.span.df_hz()).abs() < 1e-12);
        let marks = crate::analysis::spectrum::markers(&scene, &[], 0.5 / scene.dt_s, 1);
        if let Some(&(_, f0)) = marks.excitation_hz.first() {
            let tone = s.tone(f0, 3.0 * s.df_hz).unwrap();
            assert!(
                (tone.freq_hz - f0).abs() <= s.df_hz,
                "{} vs {f0}",
                tone.freq_hz
            );
            // direct DFT of the windowed samples at the tone's bin
            let (k0, k1) = steady_range(h.times(), scene.ramp_s, scene.dt_s);
            let x: Vec<f64> = (k0..k1)
                .map(|k| h.value(Quantity::Displacement, 0, k))
                .collect();
            let n = x.len();
            let mean = x.iter().sum::<f64>() / n as f64;
            let w = Window::Hann.values(n);
            let kb = (tone.freq_hz / s.df_hz).round() as usize;
            let (mut re, mut im) = (0.0, 0.0);
            for (m, (&v, &wm)) in x.iter().zip(&w).enumerate() {
                let ph = -std::f64::consts::TAU * (kb * m) as f64 / n as f64;
                re += (v - mean) * wm * ph.cos();
                im += (v - mean) * wm * ph.sin();
            }
            let amp = 2.0 * (re * re + im * im).sqrt() / w.iter().sum::<f64>();
            assert!((amp - s.amplitude[kb]).abs() < 1e-9 * amp.max(1e-30));
        }
    }
}
