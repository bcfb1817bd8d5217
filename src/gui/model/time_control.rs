//! Play / pause / step / speed: how many solver steps to take this frame.
//!
//! Pure logic, no egui: the app feeds it the wall-clock time of each frame
//! and the solver's time step, and it answers how many steps to take. The app
//! then takes at most that many within its per-frame time budget and reports
//! back what it did, so that the real-time factor actually achieved can be
//! shown.

/// Playback speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Speed {
    /// Simulated seconds per wall-clock second (1 = real time, 0.01 = slow motion).
    Factor(f64),
    /// As fast as the per-frame budget allows.
    Max,
}

impl Speed {
    /// The speeds offered in the toolbar.
    pub const CHOICES: [Speed; 10] = [
        Speed::Factor(0.001),
        Speed::Factor(0.01),
        // classroom mode's slow motion
        Speed::Factor(0.05),
        Speed::Factor(0.1),
        Speed::Factor(0.25),
        Speed::Factor(0.5),
        Speed::Factor(1.0),
        Speed::Factor(2.0),
        Speed::Factor(10.0),
        Speed::Max,
    ];

    /// Short label, e.g. `0.1x` or `max`.
    pub fn label(self) -> String {
        match self {
            Speed::Factor(f) => format!("{f}x"),
            Speed::Max => "max".to_string(),
        }
    }
}

/// Shortest wall-clock time a freshly opened run should take to play (s):
/// the paper preset's 0.2 s at 1x would be over in a blink.
pub const MIN_WATCH_S: f64 = 4.0;

impl Speed {
    /// The speed a freshly opened scene plays at: real time if the run lasts
    /// at least [`MIN_WATCH_S`], else the fastest offered slow motion that
    /// makes it last that long (0.2 s → 0.05x, 0.5 s → 0.1x).
    pub fn watchable(duration_s: f64) -> Speed {
        Speed::CHOICES
            .iter()
            .rev()
            .copied()
            .find(|s| match *s {
                Speed::Factor(f) => f <= 1.0 && duration_s / f >= MIN_WATCH_S * (1.0 - 1e-12),
                Speed::Max => false,
            })
            .unwrap_or(Speed::CHOICES[0])
    }
}

/// Longest wall-clock frame time honoured (s): after a stall (a file dialog,
/// a dragged window) the simulation does not try to catch up. A renderer
/// that draws three frames a second (software WebGL) still plays in real
/// time.
pub const MAX_FRAME_S: f64 = 0.35;

/// Wall time per frame the solver may use at least (s): at 60 frames a
/// second the UI stays above 30.
pub const MIN_STEP_BUDGET_S: f64 = 0.012;

/// Wall time per frame the solver may use at most (s).
pub const MAX_STEP_BUDGET_S: f64 = 0.1;

/// The solver's wall-time budget in a frame that came `frame_s` after the
/// last (s): [`MIN_STEP_BUDGET_S`], or half the frame interval where
/// frames are slower, up to [`MAX_STEP_BUDGET_S`]. Where drawing is slow
/// (software rendering, a large patch's heat map), the run keeps pace with
/// its speed instead of being held to a fixed share of a fast frame; since
/// the interval includes the solver's own time, the solver never takes
/// more than the drawing does, so the frame rate at most halves.
pub fn step_budget_s(frame_s: f64) -> f64 {
    if !frame_s.is_finite() || frame_s <= 0.0 {
        return MIN_STEP_BUDGET_S;
    }
    (0.5 * frame_s).clamp(MIN_STEP_BUDGET_S, MAX_STEP_BUDGET_S)
}

/// Share of the wall time that drawing may take while the run steps on its
/// own thread ("as fast as possible" on the desktop) under a software
/// renderer ([`is_software_renderer`]), whose threads and the solver share
/// the cores: the frames wait twice as long as they take to draw (input
/// still brings a frame at once). A GPU's frames are not paced.
pub const DRAW_SHARE_AT_MAX: f64 = 1.0 / 3.0;

/// Whether the GL renderer named `renderer` (`GL_RENDERER`) draws on the
/// processor (Mesa's llvmpipe and softpipe, SwiftShader): there drawing
/// competes with the solver for the cores, and frames are paced.
pub fn is_software_renderer(renderer: &str) -> bool {
    let name = renderer.to_ascii_lowercase();
    ["llvmpipe", "softpipe", "swiftshader", "software rasterizer"]
        .iter()
        .any(|k| name.contains(k))
}

/// Longest wait between two frames while the run steps on its own thread (s).
pub const MAX_PACE_DELAY_S: f64 = 0.5;

/// Frame pacing while the run steps on its own thread: from the interval
/// between frames and the wait asked before it, the drawing's time, and
/// the wait that keeps it to [`DRAW_SHARE_AT_MAX`] of the wall time.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FramePacer {
    /// Smoothed time to draw a frame (s).
    draw_s: f64,
    /// The wait asked after the last frame (s).
    delay_s: f64,
}

impl FramePacer {
    /// The wait before the next frame, after one that came `frame_s` after
    /// the last.
    pub fn next_delay_s(&mut self, frame_s: f64) -> f64 {
        if !frame_s.is_finite() || frame_s < 0.0 {
            return self.delay_s;
        }
        let draw_s = (frame_s - self.delay_s).clamp(0.0, MAX_FRAME_S);
        self.draw_s = if self.draw_s == 0.0 {
            draw_s
        } else {
            0.7 * self.draw_s + 0.3 * draw_s
        };
        self.delay_s = (self.draw_s * (1.0 / DRAW_SHARE_AT_MAX - 1.0)).clamp(0.0, MAX_PACE_DELAY_S);
        self.delay_s
    }
}

/// Steps requested per frame at `Speed::Max` (the time budget cuts it short).
pub const MAX_SPEED_STEPS: u64 = 1 << 40;

/// Playback state of the simulation clock.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeControl {
    playing: bool,
    speed: Speed,
    /// Single steps requested while paused and not yet taken.
    pending_steps: u64,
    /// Fraction of a step owed from earlier frames (0..1).
    carry: f64,
    /// Smoothed achieved real-time factor (simulated s per wall s).
    achieved: f64,
}

impl Default for TimeControl {
    fn default() -> Self {
        TimeControl {
            playing: false,
            speed: Speed::Factor(1.0),
            pending_steps: 0,
            carry: 0.0,
            achieved: 0.0,
        }
    }
}

impl TimeControl {
    pub fn is_playing(&self) -> bool {
        self.playing
    }
    pub fn speed(&self) -> Speed {
        self.speed
    }
    /// Real-time factor achieved over the last frames (smoothed).
    pub fn achieved_factor(&self) -> f64 {
        self.achieved
    }
    /// Steps requested by Step(n) and not yet taken.
    pub fn pending_steps(&self) -> u64 {
        self.pending_steps
    }

    pub fn play(&mut self) {
        self.playing = true;
        self.pending_steps = 0;
        self.carry = 0.0;
    }

    pub fn pause(&mut self) {
        self.playing = false;
        self.pending_steps = 0;
        self.carry = 0.0;
        self.achieved = 0.0;
    }

    pub fn toggle(&mut self) {
        if self.playing {
            self.pause()
        } else {
            self.play()
        }
    }

    /// Pauses and queues `n` steps (taken over the next frames if the budget
    /// does not allow them all at once).
    pub fn step(&mut self, n: u64) {
        self.pause();
        self.pending_steps = n;
    }

    /// Back to a paused clock (speed kept).
    pub fn reset(&mut self) {
        self.pause();
    }

    pub fn set_speed(&mut self, speed: Speed) {
        self.speed = match speed {
            Speed::Factor(f) if f.is_finite() && f > 0.0 => Speed::Factor(f),
            Speed::Factor(_) => self.speed,
            Speed::Max => Speed::Max,
        };
        self.carry = 0.0;
    }

    /// How many solver steps to take in a frame that lasted `frame_s` of wall
    /// time, for a solver step of `dt_s`.
    pub fn steps_this_frame(&mut self, frame_s: f64, dt_s: f64) -> u64 {
        if !self.playing {
            return self.pending_steps;
        }
        if dt_s.is_nan() || dt_s <= 0.0 {
            return 0;
        }
        match self.speed {
            Speed::Max => MAX_SPEED_STEPS,
            Speed::Factor(f) => {
                let frame_s = if frame_s.is_finite() {
                    frame_s.clamp(0.0, MAX_FRAME_S)
                } else {
                    0.0
                };
                let want = frame_s * f / dt_s + self.carry;
                // tolerate round-off so that e.g. 0.01 s / 1e-5 s is 1000 steps, not 999
                let n = (want + 1e-9 * want.max(1.0))
                    .floor()
                    .min(MAX_SPEED_STEPS as f64);
                self.carry = (want - n).clamp(0.0, 1.0);
                n as u64
            }
        }
    }

    /// Reports what the frame did: `taken` steps of `dt_s` in a frame of
    /// `frame_s` wall seconds. Steps the budget could not take are dropped
    /// (the run goes slower than asked, it does not pile up a debt).
    pub fn report(&mut self, taken: u64, dt_s: f64, frame_s: f64) {
        self.record(taken, dt_s, frame_s.min(MAX_FRAME_S));
    }

    /// Reports steps taken between two frames `frame_s` apart, by the
    /// stepping thread over that whole interval (however long: nothing was
    /// asked per frame, so nothing is cut at [`MAX_FRAME_S`]).
    pub fn report_between_frames(&mut self, taken: u64, dt_s: f64, frame_s: f64) {
        self.record(taken, dt_s, frame_s);
    }

    fn record(&mut self, taken: u64, dt_s: f64, span_s: f64) {
        self.pending_steps = self.pending_steps.saturating_sub(taken);
        if self.playing && span_s > 0.0 && span_s.is_finite() {
            let f = taken as f64 * dt_s / span_s;
            self.achieved = if self.achieved == 0.0 {
                f
            } else {
                0.9 * self.achieved + 0.1 * f
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DT: f64 = 1e-5;

    /// Frames that take `draw_s` to draw and then wait as asked settle to
    /// drawing a third of the time, for slow and fast renderers; the wait
    /// stays bounded, and nonsense intervals change nothing.
    #[test]
    fn paced_frames_draw_a_third_of_the_time() {
        for draw_s in [0.002, 0.016, 0.06, 0.14] {
            let mut pacer = FramePacer::default();
            let mut delay_s = 0.0;
            for _ in 0..60 {
                delay_s = pacer.next_delay_s(draw_s + delay_s);
            }
            let share = draw_s / (draw_s + delay_s);
            assert!(
                (share - DRAW_SHARE_AT_MAX).abs() < 1e-6,
                "{draw_s}: {share}"
            );
            for bad in [f64::NAN, -1.0, f64::INFINITY] {
                assert_eq!(pacer.next_delay_s(bad), delay_s);
            }
        }
        let mut pacer = FramePacer::default();
        let mut delay_s = 0.0;
        for _ in 0..60 {
            delay_s = pacer.next_delay_s(0.3 + delay_s);
        }
        assert_eq!(delay_s, MAX_PACE_DELAY_S);
    }

    #[test]
    fn software_renderers_are_told_from_gpus() {
        for soft in [
            "llvmpipe (LLVM 19.1.7, 256 bits)",
            "softpipe",
            "Google SwiftShader",
            "ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device (Subzero)), SwiftShader driver)",
        ] {
            assert!(is_software_renderer(soft), "{soft}");
        }
        for gpu in [
            "Mesa Intel(R) UHD Graphics 620 (KBL GT2)",
            "NVIDIA GeForce RTX 3060/PCIe/SSE2",
            "AMD Radeon RX 6600 (radeonsi, navi23, LLVM 15.0.6, DRM 3.49)",
            "Apple M2",
        ] {
            assert!(!is_software_renderer(gpu), "{gpu}");
        }
    }

    #[test]
    fn paused_takes_no_steps() {
        let mut tc = TimeControl::default();
        assert_eq!(tc.steps_this_frame(1.0 / 60.0, DT), 0);
    }

    #[test]
    fn real_time_takes_frame_over_dt_steps() {
        let mut tc = TimeControl::default();
        tc.play();
        // 10 ms frame at 1x with dt 1e-5: 1000 steps
        assert_eq!(tc.steps_this_frame(0.01, DT), 1000);
    }

    #[test]
    fn slow_motion_accumulates_fractions() {
        let mut tc = TimeControl::default();
        tc.set_speed(Speed::Factor(0.001));
        tc.play();
        // 0.001 * 0.004 s / 1e-5 = 0.4 step per frame: 2 steps in 5 frames
        let total: u64 = (0..5).map(|_| tc.steps_this_frame(0.004, DT)).sum();
        assert_eq!(total, 2);
        let total: u64 = (0..500).map(|_| tc.steps_this_frame(0.004, DT)).sum();
        assert_eq!(total, 200);
    }

    /// Fast frames keep the fixed budget; slow ones give the solver half
    /// the interval, never more than the cap: at the fixed point (solver
    /// time = half of draw + solver) it takes no more than drawing does.
    #[test]
    fn the_step_budget_follows_slow_frames() {
        assert_eq!(step_budget_s(1.0 / 60.0), MIN_STEP_BUDGET_S);
        assert_eq!(step_budget_s(1.0 / 144.0), MIN_STEP_BUDGET_S);
        assert!((step_budget_s(0.1) - 0.05).abs() < 1e-15);
        assert_eq!(step_budget_s(0.25), MAX_STEP_BUDGET_S);
        assert_eq!(step_budget_s(5.0), MAX_STEP_BUDGET_S);
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(step_budget_s(bad), MIN_STEP_BUDGET_S);
        }
        // a renderer at 4 frames/s (0.24 s to draw): the solver's share
        // settles where it is at most what drawing takes
        let draw_s = 0.24;
        let mut solver_s = MIN_STEP_BUDGET_S;
        for _ in 0..50 {
            solver_s = step_budget_s(draw_s + solver_s);
        }
        assert!(
            solver_s <= draw_s && solver_s > MIN_STEP_BUDGET_S,
            "{solver_s}"
        );
        // and real time at 1x is asked for over those frames
        let mut tc = TimeControl::default();
        tc.play();
        let frame_s = draw_s + solver_s;
        assert_eq!(
            tc.steps_this_frame(frame_s, DT),
            (frame_s / DT).round() as u64
        );
    }

    #[test]
    fn long_frames_are_clamped() {
        let mut tc = TimeControl::default();
        tc.play();
        assert_eq!(
            tc.steps_this_frame(5.0, DT),
            (MAX_FRAME_S / DT).round() as u64
        );
        assert_eq!(tc.steps_this_frame(f64::NAN, DT), 0);
    }

    #[test]
    fn step_n_pauses_and_counts_down() {
        let mut tc = TimeControl::default();
        tc.play();
        tc.step(5);
        assert!(!tc.is_playing());
        assert_eq!(tc.steps_this_frame(0.016, DT), 5);
        tc.report(3, DT, 0.016);
        assert_eq!(tc.steps_this_frame(0.016, DT), 2);
        tc.report(2, DT, 0.016);
        assert_eq!(tc.steps_this_frame(0.016, DT), 0);
    }

    #[test]
    fn max_speed_asks_for_as_many_as_possible() {
        let mut tc = TimeControl::default();
        tc.set_speed(Speed::Max);
        tc.play();
        assert_eq!(tc.steps_this_frame(0.016, DT), MAX_SPEED_STEPS);
    }

    #[test]
    fn invalid_speed_is_ignored() {
        let mut tc = TimeControl::default();
        tc.set_speed(Speed::Factor(2.0));
        tc.set_speed(Speed::Factor(-1.0));
        tc.set_speed(Speed::Factor(f64::NAN));
        assert_eq!(tc.speed(), Speed::Factor(2.0));
    }

    /// Steps taken between frames are counted over the whole interval,
    /// even past the longest frame honoured in the frame's own steps.
    #[test]
    fn steps_between_slow_frames_give_their_own_factor() {
        let mut tc = TimeControl::default();
        tc.set_speed(Speed::Max);
        tc.play();
        // 0.6 s apart, 0.18 s of simulated time: 0.3x, not 0.18 / 0.35
        for _ in 0..50 {
            tc.report_between_frames(18_000, DT, 0.6);
        }
        assert!(
            (tc.achieved_factor() - 0.3).abs() < 1e-9,
            "{}",
            tc.achieved_factor()
        );
        let mut cut = TimeControl::default();
        cut.play();
        cut.report(18_000, DT, 0.6);
        assert!((cut.achieved_factor() - 0.18 / MAX_FRAME_S).abs() < 1e-9);
    }

    #[test]
    fn achieved_factor_reflects_budget_cuts() {
        let mut tc = TimeControl::default();
        tc.play();
        let want = tc.steps_this_frame(0.02, DT);
        assert_eq!(want, 2000);
        // the budget allowed only half
        tc.report(1000, DT, 0.02);
        assert!((tc.achieved_factor() - 0.5).abs() < 1e-12);
        // no debt: the next frame asks for one frame's worth again
        assert_eq!(tc.steps_this_frame(0.02, DT), 2000);
    }

    #[test]
    fn toggle_and_reset() {
        let mut tc = TimeControl::default();
        tc.toggle();
        assert!(tc.is_playing());
        tc.toggle();
        assert!(!tc.is_playing());
        tc.play();
        tc.reset();
        assert!(!tc.is_playing());
        assert_eq!(tc.steps_this_frame(0.016, DT), 0);
    }

    #[test]
    fn classroom_slow_motion_is_one_of_the_offered_speeds() {
        let slow = Speed::Factor(crate::gui::classroom::SLOW_MOTION);
        assert!(Speed::CHOICES.contains(&slow));
        assert!(Speed::CHOICES.windows(2).all(|w| match (w[0], w[1]) {
            (Speed::Factor(a), Speed::Factor(b)) => a < b,
            (Speed::Factor(_), Speed::Max) => true,
            _ => false,
        }));
    }

    #[test]
    fn fresh_runs_play_slowly_enough_to_be_watched() {
        assert_eq!(Speed::watchable(0.2), Speed::Factor(0.05));
        assert_eq!(Speed::watchable(0.5), Speed::Factor(0.1));
        assert_eq!(Speed::watchable(2.0), Speed::Factor(0.5));
        assert_eq!(Speed::watchable(4.0), Speed::Factor(1.0));
        assert_eq!(Speed::watchable(3600.0), Speed::Factor(1.0));
        assert_eq!(Speed::watchable(1e-6), Speed::Factor(0.001));
    }
}
