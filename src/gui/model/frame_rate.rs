//! Frame rate measured over one-second windows (logged to stderr when
//! `TIRECONTACT_FPS_LOG` is set, for measurements under Xvfb).

use web_time::Instant;

/// Frames per second measured over one-second windows.
#[derive(Debug, Clone)]
pub struct FrameRate {
    start: Instant,
    frames: u32,
    busy_s: f64,
    pub fps: f64,
    /// Mean wall time per frame spent in the app's own code (solver steps
    /// and UI building, without rendering), in ms.
    pub app_ms: f64,
    log: bool,
}

impl FrameRate {
    pub fn new() -> Self {
        FrameRate {
            start: Instant::now(),
            frames: 0,
            busy_s: 0.0,
            fps: 0.0,
            app_ms: 0.0,
            log: std::env::var_os("TIRECONTACT_FPS_LOG").is_some(),
        }
    }
    pub fn tick(&mut self, t_s: f64, playing: bool, busy_s: f64) {
        self.frames += 1;
        self.busy_s += busy_s;
        let el = self.start.elapsed().as_secs_f64();
        if el >= 1.0 {
            self.fps = self.frames as f64 / el;
            self.app_ms = 1e3 * self.busy_s / self.frames as f64;
            if self.log {
                eprintln!(
                    "fps {:.1} app_ms {:.1} t_s {t_s:.5} playing {playing} window_s {el:.3}",
                    self.fps, self.app_ms
                );
            }
            self.frames = 0;
            self.busy_s = 0.0;
            self.start = Instant::now();
        }
    }
}

impl Default for FrameRate {
    fn default() -> Self {
        Self::new()
    }
}
