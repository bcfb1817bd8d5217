//! The one run driver: steps a [`Simulation`] and tells a [`Probe`] after
//! every step, watching a cancel flag and reporting progress. Every caller
//! that runs a scene (the command line, sweeps, the bench, the visualiser's
//! exports) goes through [`run`] or [`run_to_end`]; what a caller keeps of
//! the run (a CSV, a figure recording, the steady part for spectra, the
//! visualiser's history) is a `Probe`.
//!
//! Probes combine: `Option<P>` is a probe that may be absent, and tuples of
//! probes are told in order, so `(&mut csv, &mut figure, &mut steady)` is
//! one probe.
//!
//! (an example that runs a preset to its end is in the `tirecontact` crate's
//! documentation, where scenes are read).

use crate::solver::error::RunError;
use crate::solver::simulation::Simulation;
use std::sync::atomic::{AtomicBool, Ordering};
use web_time::Instant;

/// What a run tells its observer.
pub trait Probe {
    /// The state at `t = 0`, before the first step ([`run_to_end`] calls it
    /// on a simulation that has not stepped yet).
    fn start(&mut self, _sim: &Simulation) -> std::io::Result<()> {
        Ok(())
    }

    /// After every step.
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()>;

    /// Whether this observer needs no more steps (the frames of an
    /// animation all drawn before the scene ends): the run stops early.
    fn satisfied(&self) -> bool {
        false
    }
}

/// No observer: a bare run (timings).
impl Probe for () {
    fn after_step(&mut self, _sim: &Simulation) -> std::io::Result<()> {
        Ok(())
    }
}

impl<P: Probe + ?Sized> Probe for &mut P {
    fn start(&mut self, sim: &Simulation) -> std::io::Result<()> {
        (**self).start(sim)
    }
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        (**self).after_step(sim)
    }
    fn satisfied(&self) -> bool {
        (**self).satisfied()
    }
}

impl<P: Probe> Probe for Option<P> {
    fn start(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.as_mut().map_or(Ok(()), |p| p.start(sim))
    }
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.as_mut().map_or(Ok(()), |p| p.after_step(sim))
    }
    /// An absent observer never ends a run.
    fn satisfied(&self) -> bool {
        self.as_ref().is_some_and(|p| p.satisfied())
    }
}

macro_rules! tuple_probe {
    ($($p:ident $i:tt),+) => {
        impl<$($p: Probe),+> Probe for ($($p,)+) {
            fn start(&mut self, sim: &Simulation) -> std::io::Result<()> {
                $(self.$i.start(sim)?;)+
                Ok(())
            }
            fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
                $(self.$i.after_step(sim)?;)+
                Ok(())
            }
            /// Satisfied when every member is.
            fn satisfied(&self) -> bool {
                true $(&& self.$i.satisfied())+
            }
        }
    };
}
tuple_probe!(A 0, B 1);
tuple_probe!(A 0, B 1, C 2);
tuple_probe!(A 0, B 1, C 2, D 3);
tuple_probe!(A 0, B 1, C 2, D 3, E 4);

/// The visualiser's contact phases follow the run.
impl Probe for crate::solver::phase::PhaseTracker {
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        crate::solver::phase::PhaseTracker::after_step(
            self,
            sim.time_s(),
            sim.in_contact(),
            sim.force_n(),
        );
        Ok(())
    }
}

/// Steps between two looks at the cancel flag and two progress reports.
pub const CHECK_EVERY: u64 = 1024;

/// A progress callback: the steps done so far in this call, and the run.
pub type Progress<'a> = dyn FnMut(u64, &Simulation) + 'a;

/// How a run is watched from outside: a flag that stops it, a callback
/// told the steps done so far in this call (every [`CHECK_EVERY`] steps and
/// at the end) with the simulation, for a progress bar or a time label, and
/// a wall-clock deadline after which the call returns (the visualiser's
/// share of a frame).
#[derive(Default)]
pub struct Watch<'a> {
    pub cancel: Option<&'a AtomicBool>,
    pub progress: Option<&'a mut Progress<'a>>,
    /// Looked at after every step; reaching it ends the call normally.
    pub deadline: Option<Instant>,
}

impl<'a> Watch<'a> {
    /// Nobody watching: the run cannot be stopped and reports nothing.
    pub fn none() -> Self {
        Self::default()
    }

    /// Stopped when `cancel` is set.
    pub fn cancel(cancel: &'a AtomicBool) -> Self {
        Watch {
            cancel: Some(cancel),
            ..Self::default()
        }
    }

    /// Returns after the step that reaches `deadline`.
    pub fn until(deadline: Instant) -> Self {
        Watch {
            deadline: Some(deadline),
            ..Self::default()
        }
    }

    /// Also told the progress.
    pub fn with_progress(mut self, progress: &'a mut Progress<'a>) -> Self {
        self.progress = Some(progress);
        self
    }
}

/// Runs `steps` more steps of `sim` (fewer if the scene ends or the probe is
/// [`Probe::satisfied`] first), telling `probe` after each. Stops with [`RunError::Cancelled`] when the watch's
/// flag is set (looked at every [`CHECK_EVERY`] steps), with the solver's
/// or the probe's error when a step or an output fails. Returns the steps
/// taken.
pub fn run(
    sim: &mut Simulation,
    steps: u64,
    probe: &mut impl Probe,
    mut watch: Watch,
) -> Result<u64, RunError> {
    let mut done = 0;
    while done < steps && !sim.finished() && !probe.satisfied() {
        sim.step()?;
        probe.after_step(sim)?;
        done += 1;
        if watch.deadline.is_some_and(|d| Instant::now() >= d) {
            break;
        }
        if done % CHECK_EVERY == 0 {
            if let Some(p) = watch.progress.as_mut() {
                p(done, sim);
            }
            if watch.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                return Err(RunError::Cancelled { steps: sim.steps() });
            }
        }
    }
    if done % CHECK_EVERY != 0
        && let Some(p) = watch.progress.as_mut()
    {
        p(done, sim);
    }
    Ok(done)
}

/// Runs `sim` to the end of its scene: [`Probe::start`] first if it has
/// not stepped yet, then [`run`].
pub fn run_to_end(
    sim: &mut Simulation,
    probe: &mut impl Probe,
    watch: Watch,
) -> Result<u64, RunError> {
    if sim.steps() == 0 {
        probe.start(sim)?;
    }
    let left = sim.problem().num_steps().saturating_sub(sim.steps());
    run(sim, left, probe, watch)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Counts the calls, and fails at a given step.
    #[derive(Default)]
    struct Count {
        starts: u32,
        steps: u64,
        last_t_s: f64,
        fail_at: Option<u64>,
    }

    impl Probe for Count {
        fn start(&mut self, sim: &Simulation) -> std::io::Result<()> {
            assert_eq!(sim.steps(), 0);
            self.starts += 1;
            Ok(())
        }
        fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
            self.steps += 1;
            assert_eq!(sim.steps(), self.steps, "told once per step, in order");
            assert!(sim.time_s() > self.last_t_s);
            self.last_t_s = sim.time_s();
            if self.fail_at == Some(self.steps) {
                return Err(std::io::Error::other("disk full"));
            }
            Ok(())
        }
    }

    fn single_mode(duration_s: f64) -> Simulation {
        let mut scene = crate::solver::test_problem::problem(include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/single_mode.ron"
        )));
        scene.duration_s = duration_s;
        Simulation::new(&scene, crate::SolverOptions::default()).unwrap()
    }

    #[test]
    fn every_step_is_told_once_and_the_run_ends_with_its_scene() {
        let mut sim = single_mode(0.05);
        let n = sim.problem().num_steps();
        let (mut a, mut b) = (Count::default(), Some(Count::default()));
        let mut reports = Vec::new();
        let mut progress = |done: u64, _: &Simulation| reports.push(done);
        let done = run_to_end(
            &mut sim,
            &mut (&mut a, &mut b),
            Watch::none().with_progress(&mut progress),
        )
        .unwrap();
        assert_eq!(done, n);
        assert!(sim.finished());
        assert_eq!((a.starts, a.steps), (1, n));
        assert_eq!(b.as_ref().map(|b| (b.starts, b.steps)), Some((1, n)));
        // every CHECK_EVERY steps, and the end
        assert_eq!(reports.len() as u64, n.div_ceil(CHECK_EVERY));
        assert_eq!(reports.last(), Some(&n));
        // past the end: nothing more
        assert_eq!(run(&mut sim, 10, &mut a, Watch::none()).unwrap(), 0);
        assert_eq!(a.steps, n);
    }

    #[test]
    fn a_run_in_pieces_tells_the_same_steps_as_one_run() {
        let mut whole = single_mode(0.02);
        let mut a = Count::default();
        run_to_end(&mut whole, &mut a, Watch::none()).unwrap();
        let mut pieces = single_mode(0.02);
        let mut c = Count::default();
        while run(&mut pieces, 7, &mut c, Watch::none()).unwrap() > 0 {}
        assert_eq!(a.steps, c.steps);
        assert_eq!(c.starts, 0, "run alone never calls start");
        assert_eq!(whole.displacement_m(), pieces.displacement_m());
        assert_eq!(whole.force_n(), pieces.force_n());
    }

    #[test]
    fn a_cancelled_run_stops_at_the_next_check_and_a_probe_error_at_once() {
        let mut sim = single_mode(0.1);
        let flag = AtomicBool::new(true);
        let mut a = Count::default();
        let e = run_to_end(&mut sim, &mut a, Watch::cancel(&flag)).unwrap_err();
        assert!(matches!(e, RunError::Cancelled { steps } if steps == CHECK_EVERY));
        assert_eq!(a.steps, CHECK_EVERY);

        let mut sim = single_mode(0.1);
        let mut b = Count {
            fail_at: Some(5),
            ..Count::default()
        };
        let e = run_to_end(&mut sim, &mut b, Watch::none()).unwrap_err();
        assert!(e.to_string().contains("disk full"), "{e}");
        assert_eq!(sim.steps(), 5);
    }

    #[test]
    fn a_deadline_passed_ends_the_call_after_one_step() {
        let mut sim = single_mode(0.1);
        let mut a = Count::default();
        let done = run(&mut sim, 1000, &mut a, Watch::until(Instant::now())).unwrap();
        assert_eq!((done, a.steps), (1, 1));
        let later = Instant::now() + std::time::Duration::from_secs(3600);
        assert_eq!(run(&mut sim, 10, &mut a, Watch::until(later)).unwrap(), 10);
    }
}
