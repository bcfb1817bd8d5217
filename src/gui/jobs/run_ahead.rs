//! The run's steps on a thread of their own between two frames, while the
//! renderer draws: what "as fast as possible" does on the desktop.
//!
//! In a frame the UI reads the simulation and its histories; after it,
//! eframe tessellates and the GL driver rasterises and swaps, which under
//! software GL is most of the frame. The UI lends the run's state ([`Live`])
//! to the worker at the end of its frame and takes it back at the start of
//! the next ([`RunAhead::reclaim`] stops the worker after the step it is in,
//! tens of microseconds at most), so the steps go on while the frame is
//! drawn and nothing reads the state while it is lent. The steps are the
//! ones the UI thread would take: the same simulation, probes and order.
//!
//! A page in the browser has no threads: there the steps stay in the frame,
//! within its budget.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::time::Duration;
use web_time::Instant;

use crate::Simulation;
use crate::gui::model::history::History;
use crate::solver::drive::{self, Probe, Watch};
use crate::solver::error::RunError;
use crate::solver::phase::PhaseTracker;

/// Longest lease (s): a window that stops drawing (minimised, or a stalled
/// renderer) lets the run go on for at most this long.
pub const MAX_LEASE_S: f64 = 1.0;

/// What a run's steps change: the simulation, the histories the views draw
/// and the contact phases.
pub struct Live {
    pub sim: Simulation,
    pub history: History,
    pub phases: PhaseTracker,
}

/// A lease's end: the state back, the steps it took and how the run ended
/// (an error pauses the run with its message).
pub struct Returned {
    pub live: Box<Live>,
    pub taken: u64,
    pub result: Result<u64, RunError>,
}

/// The worker thread and the lease under way.
pub struct RunAhead {
    lend_tx: Option<Sender<(Box<Live>, Instant)>>,
    back_rx: Receiver<Returned>,
    stop: Arc<AtomicBool>,
    /// Whether the state is with the worker.
    lent: bool,
}

impl std::fmt::Debug for RunAhead {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RunAhead")
            .field("lent", &self.lent)
            .finish()
    }
}

/// The probes of a lease, and the UI's request to stop, looked at after
/// every step.
struct UntilAsked<'a, P> {
    inner: P,
    stop: &'a AtomicBool,
}

impl<P: Probe> Probe for UntilAsked<'_, P> {
    fn start(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.inner.start(sim)
    }
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.inner.after_step(sim)
    }
    fn satisfied(&self) -> bool {
        self.inner.satisfied() || self.stop.load(Ordering::Acquire)
    }
}

impl RunAhead {
    /// Starts the worker (it waits for a lease).
    pub fn spawn() -> std::io::Result<Self> {
        let (lend_tx, lend_rx) = channel::<(Box<Live>, Instant)>();
        let (back_tx, back_rx) = channel();
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        std::thread::Builder::new()
            .name("run-ahead".into())
            .spawn(move || {
                for (mut live, deadline) in lend_rx {
                    let before = live.sim.steps();
                    let mut probe = UntilAsked {
                        inner: (&mut live.history, &mut live.phases),
                        stop: &flag,
                    };
                    let result =
                        drive::run(&mut live.sim, u64::MAX, &mut probe, Watch::until(deadline));
                    let taken = live.sim.steps() - before;
                    if back_tx
                        .send(Returned {
                            live,
                            taken,
                            result,
                        })
                        .is_err()
                    {
                        break;
                    }
                }
            })?;
        Ok(RunAhead {
            lend_tx: Some(lend_tx),
            back_rx,
            stop,
            lent: false,
        })
    }

    /// Whether the state is with the worker.
    pub fn is_lent(&self) -> bool {
        self.lent
    }

    /// Lends `live` to the worker, which steps until [`RunAhead::reclaim`],
    /// the end of the run or [`MAX_LEASE_S`]; gives it back if the worker
    /// is gone.
    pub fn lend(&mut self, live: Box<Live>) -> Result<(), Box<Live>> {
        if self.lent {
            return Err(live);
        }
        self.stop.store(false, Ordering::Release);
        let deadline = Instant::now() + Duration::from_secs_f64(MAX_LEASE_S);
        match self.lend_tx.as_ref() {
            Some(tx) => match tx.send((live, deadline)) {
                Ok(()) => {
                    self.lent = true;
                    Ok(())
                }
                Err(e) => Err(e.0.0),
            },
            None => Err(live),
        }
    }

    /// Stops the worker after the step it is in and takes the state back;
    /// `None` when nothing is lent, or when the worker died with it (the
    /// caller rebuilds the run).
    pub fn reclaim(&mut self) -> Option<Returned> {
        if !self.lent {
            return None;
        }
        self.lent = false;
        self.stop.store(true, Ordering::Release);
        self.back_rx.recv().ok()
    }
}

impl Drop for RunAhead {
    fn drop(&mut self) {
        // a lease under way ends at its next step; the closed channel ends
        // the worker's loop
        self.stop.store(true, Ordering::Release);
        self.lend_tx = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gui::model::history::{DEFAULT_BUDGET, Quantity};
    use crate::{Scene, SceneSimulation};

    fn live(scene: &Scene) -> Box<Live> {
        let sim = Simulation::from_scene(scene).unwrap();
        let mut history = History::new(scene.num_points(), DEFAULT_BUDGET);
        history.record_initial(&sim);
        let phases = PhaseTracker::new(scene.num_points(), 0.0);
        Box::new(Live {
            sim,
            history,
            phases,
        })
    }

    fn preset(name: &str) -> Scene {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("presets")
            .join(name);
        Scene::load(&path).unwrap()
    }

    /// Leases of any length give the run the UI thread would take, to the
    /// bit: the same steps, histories and phases.
    #[test]
    fn leased_steps_are_the_steps_of_the_ui_thread() {
        for name in ["three_points.ron", "patch_texture.ron"] {
            let mut scene = preset(name);
            scene.duration_s = scene.duration_s.min(400.0 * scene.dt_s);
            let mut ahead = RunAhead::spawn().unwrap();
            let mut leased = live(&scene);
            let mut leases = 0;
            while !leased.sim.finished() {
                ahead.lend(leased).map_err(|_| ()).unwrap();
                assert!(ahead.is_lent());
                // leases of different lengths, down to none at all
                std::thread::sleep(Duration::from_micros(50 * (leases % 5)));
                let back = ahead.reclaim().expect("the worker gives the state back");
                assert!(!ahead.is_lent());
                back.result.unwrap();
                leased = back.live;
                leases += 1;
                assert!(leases < 100_000, "{name}: the leases make no progress");
            }
            let mut direct = live(&scene);
            drive::run(
                &mut direct.sim,
                u64::MAX,
                &mut (&mut direct.history, &mut direct.phases),
                Watch::none(),
            )
            .unwrap();
            assert_eq!(leased.sim.steps(), direct.sim.steps(), "{name}");
            assert_eq!(leased.history.len(), direct.history.len(), "{name}");
            let (t0, t1) = (0.0, scene.duration_s);
            for i in 0..scene.num_points() {
                for what in [Quantity::Displacement, Quantity::Force, Quantity::Gap] {
                    let a = leased.history.decimated(what, i, t0, t1, 1 << 20, 1.0);
                    let b = direct.history.decimated(what, i, t0, t1, 1 << 20, 1.0);
                    assert_eq!(a, b, "{name}: point {i}, {what:?}");
                }
                assert_eq!(
                    leased.sim.force_n()[i].to_bits(),
                    direct.sim.force_n()[i].to_bits(),
                    "{name}: point {i}"
                );
            }
            assert_eq!(leased.phases, direct.phases, "{name}");
        }
    }

    /// A lease ends by itself at its deadline, and at the end of the run.
    #[test]
    fn a_lease_ends_at_the_end_of_the_run() {
        let mut scene = preset("single_mode.ron");
        scene.duration_s = 1000.0 * scene.dt_s;
        let mut ahead = RunAhead::spawn().unwrap();
        ahead.lend(live(&scene)).map_err(|_| ()).unwrap();
        // the run is 1000 steps: far inside a lease
        std::thread::sleep(Duration::from_millis(200));
        let back = ahead.reclaim().unwrap();
        assert_eq!(back.taken, 1000);
        assert_eq!(back.result.unwrap(), 1000);
        assert!(back.live.sim.finished());
    }
}
