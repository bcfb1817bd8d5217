//! What a new scene needs before it can run, off the UI thread: its preset
//! file read (Open), its measured road's file read, its ring tyre
//! identified (method §5-6; a tenth of a second or more, longer in a debug
//! build). The edit or the document waits here while the window keeps
//! drawing and the current run goes on, then is applied from what was
//! prepared (the identified modes are also kept in the app's
//! [`ModeCache`], which the job shares). A file that cannot be read, or a
//! scene that cannot run, is refused then, with the current scene kept.

use crate::gui::jobs::{Job, Progress};
use crate::gui::model::prepared::Prepared;
use crate::identify::{ModeCache, PreparedModel, PreparedModelRun};
use crate::model::road::Road;
use crate::scene::Mode;
use crate::solver::simulation::{Simulation, SimulationBuild, SolverOptions};
use crate::{Scene, SceneError};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// Scenes of more points than this build their solver's tables off the UI
/// thread (a patch of a thousand points takes seconds; ten points, well
/// under a frame).
pub const LARGE_SET_UP_POINTS: usize = 100;

/// A simulation built on the preparation's thread, and its modes.
pub type Built = Result<(Simulation, Vec<Mode>), SceneError>;

/// What waits for the preparation.
#[derive(Debug, Clone, PartialEq)]
pub enum Then {
    /// An edit of the current scene that restarts the run
    /// ([`crate::gui::model::command::Command::EditScene`]).
    Edit(Scene),
    /// A live edit of the road to a measured profile: its file is read.
    Road(Scene),
    /// A new document: a preset, a guided tour, a new scene.
    Replace {
        scene: Scene,
        path: Option<PathBuf>,
        what: String,
    },
    /// A preset file to read and open.
    Open(PathBuf),
}

/// Whether applying `scene` reads a file (a measured road) or identifies a
/// ring tyre not in `cache`: then it is prepared by a [`PrepareJob`].
/// So does a scene of more than [`LARGE_SET_UP_POINTS`] points: its
/// simulation is built there too.
pub fn needs_preparing(scene: &Scene, cache: &ModeCache) -> bool {
    reads_road_file(&scene.road)
        || !cache.has_modes(scene)
        || scene.num_points() > LARGE_SET_UP_POINTS
}

/// Whether sampling `road` needs its file read or its grid generated
/// (a surface file of millions of nodes, a texture): off the UI thread.
pub fn reads_road_file(road: &Road) -> bool {
    matches!(
        road,
        Road::Measured { .. } | Road::Surface { .. } | Road::Crg { .. } | Road::Texture { .. }
    )
}

/// A preparation running on its own thread (in the browser, in slices
/// within the frames), and what waits for it.
pub struct PrepareJob {
    job: Job<Result<Prepared, String>>,
    pub then: Then,
    /// The simulation of a prepared model, built by the job.
    built: Arc<Mutex<Option<Built>>>,
    /// What the job is doing now, for its progress line.
    doing: Arc<Mutex<&'static str>>,
}

/// Where a staged preparation is.
enum Stage {
    /// The scene checked, its tyre identified, its road read
    /// ([`PreparedModelRun`], method §5-6).
    Model(Box<PreparedModelRun>),
    /// The solver's tables built ([`SimulationBuild`], method §3-4), and
    /// the model they are built from.
    Build(Box<(SimulationBuild, PreparedModel)>),
}

impl PrepareJob {
    /// Prepares what `then` needs on a new thread (in the browser, in
    /// slices within the polls: [`Job::spawn_sliced`]), identifying into
    /// `cache` (kept there even if a later edit replaces this job).
    pub fn spawn(then: Then, cache: Arc<ModeCache>) -> Result<Self, String> {
        Self::start(then, cache, false)
    }

    /// The preparation run on the caller's thread a slice at each poll
    /// ([`Job::in_slices`]): how a page in the browser runs it. It ends
    /// with the threaded one's model and simulation.
    pub fn spawn_in_slices(then: Then, cache: Arc<ModeCache>) -> Result<Self, String> {
        Self::start(then, cache, true)
    }

    fn start(then: Then, cache: Arc<ModeCache>, in_slices: bool) -> Result<Self, String> {
        let what = then.clone();
        let built = Arc::new(Mutex::new(None));
        let doing = Arc::new(Mutex::new("checking the scene"));
        let (slot, said) = (Arc::clone(&built), Arc::clone(&doing));
        let mut stage = match &then {
            Then::Edit(scene) | Then::Replace { scene, .. } => {
                Some(Stage::Model(Box::new(PreparedModelRun::new(scene, &cache))))
            }
            Then::Road(_) | Then::Open(_) => None,
        };
        let mut model_stages = 0;
        let work = move |progress: &Progress, deadline: Option<web_time::Instant>| {
            let Some(current) = &mut stage else {
                // a file read at once (the browser reads none)
                let r = prepare(&what, &cache).map_err(|e| e.to_string());
                progress.set(1);
                return Some(r);
            };
            loop {
                if progress.cancelled() {
                    return Some(Err("cancelled".to_string()));
                }
                match current {
                    Stage::Model(run) => match run.stage(&cache) {
                        Err(e) => return Some(Err(e.to_string())),
                        Ok(None) => {
                            progress.set_total((run.num_stages() + 1) as u64);
                            progress.set(run.stages_done() as u64);
                            set(&said, run.next_stage());
                        }
                        Ok(Some(model)) => {
                            let b = Simulation::build_in_stages(
                                model.problem().clone(),
                                SolverOptions::default(),
                            );
                            model_stages = run.stages_done() as u64;
                            progress.set_total(model_stages + b.num_stages() as u64);
                            set(&said, "building the solver's tables");
                            *current = Stage::Build(Box::new((b, model)));
                        }
                    },
                    Stage::Build(built) => {
                        let b = &mut built.0;
                        let r = b.stage().map_err(SceneError::from);
                        progress.set_total(model_stages + b.num_stages() as u64);
                        progress.set(model_stages + b.stages_done() as u64);
                        match r {
                            Err(e) => return Some(Err(e.to_string())),
                            Ok(None) => {}
                            Ok(Some(sim)) => {
                                let Some(Stage::Build(built)) = stage.take() else {
                                    unreachable!("building");
                                };
                                let model = built.1;
                                let modes = model.modes().to_vec();
                                if let Ok(mut s) = slot.lock() {
                                    *s = Some(Ok((sim, modes)));
                                }
                                return Some(Ok(Prepared::Model(Box::new(model))));
                            }
                        }
                    }
                }
                if deadline.is_some_and(|d| web_time::Instant::now() >= d) {
                    return None;
                }
            }
        };
        let job = if in_slices {
            Job::in_slices("preparation", 1, work)
        } else {
            Job::spawn_sliced("preparation", 1, work)?
        };
        Ok(PrepareJob {
            job,
            then,
            built,
            doing,
        })
    }

    /// The simulation built from the prepared model, once (after
    /// [`Self::poll`] gave the model).
    pub fn take_built(&self) -> Option<Built> {
        self.built.lock().ok().and_then(|mut s| s.take())
    }

    /// The result, once the job has finished.
    pub fn poll(&self) -> Option<Result<Prepared, String>> {
        self.job.poll().map(Result::flatten)
    }

    /// Fraction of the stages done (0..=1).
    pub fn progress(&self) -> f64 {
        self.job.fraction()
    }

    /// Stages done so far.
    pub fn stages_done(&self) -> u64 {
        self.job.done()
    }

    /// What the job is doing now ("sampling the ring's responses", …).
    pub fn doing(&self) -> &'static str {
        self.doing.lock().map_or("preparing", |d| *d)
    }

    /// Asks the job to stop at its next stage.
    pub fn cancel(&self) {
        self.job.cancel();
    }
}

fn set(doing: &Mutex<&'static str>, what: &'static str) {
    if let Ok(mut d) = doing.lock() {
        *d = what;
    }
}

fn prepare(then: &Then, cache: &ModeCache) -> Result<Prepared, SceneError> {
    let model =
        |scene: &Scene| PreparedModel::new(scene, cache).map(|m| Prepared::Model(Box::new(m)));
    match then {
        Then::Edit(scene) | Then::Replace { scene, .. } => model(scene),
        Then::Road(scene) => {
            crate::scene::load_road(&scene.road, scene.base_dir.as_deref()).map(Prepared::Road)
        }
        Then::Open(path) => {
            let scene = Scene::load(path)?;
            // a measured tyre's data may have changed since it was read
            cache.forget(&scene);
            model(&scene)
        }
    }
}

/// The banner while a scene is prepared.
pub fn waiting_note(then: &Then, identifies: bool) -> String {
    let what = match then {
        Then::Edit(_) | Then::Road(_) => "for the edited scene",
        Then::Replace { .. } => "for the new scene",
        Then::Open(p) => return format!("Opening {}…", p.display()),
    };
    let (large, texture) = match then {
        Then::Edit(s) | Then::Replace { scene: s, .. } | Then::Road(s) => {
            (s.num_points(), matches!(s.road, Road::Texture { .. }))
        }
        Then::Open(_) => (0, false),
    };
    if identifies {
        format!(
            "Identifying the tyre's modes at the points {what} (LSCE, docs/method.md §6): \
             the current run goes on until they are ready."
        )
    } else if large > LARGE_SET_UP_POINTS {
        format!(
            "Setting up the solver for the {large} points {what} (its tables, and the road): \
             the current run goes on until it is ready."
        )
    } else if texture {
        format!("Generating the road texture {what}: the current run goes on until it is ready.")
    } else {
        format!("Reading the road file {what}: the current run goes on until it is read.")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn preset(text: &str) -> Scene {
        Scene::parse(text, "preset").unwrap()
    }

    fn paper() -> Scene {
        preset(include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/paper.ron"
        )))
    }

    /// The plate-tyre patch with `along × across` points 5 mm apart across.
    fn patch(along: usize, across: usize) -> Scene {
        let text = include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/patch_texture.ron"
        ))
        .replace("along: 16", &format!("along: {along}"))
        .replace("across: 6", &format!("across: {across}"))
        .replace("spacing_m: (0.006, 0.02)", "spacing_m: (0.006, 0.005)");
        preset(&text)
    }

    /// Polls `job` to its end; the model, the simulation and the polls
    /// it took.
    fn finish(job: &PrepareJob) -> (PreparedModel, Simulation, usize) {
        let (mut polls, started) = (0, web_time::Instant::now());
        let r = loop {
            polls += 1;
            if let Some(r) = job.poll() {
                break r;
            }
            assert!(
                started.elapsed().as_secs() < 600,
                "the preparation never ended"
            );
            std::thread::sleep(std::time::Duration::from_millis(1));
        };
        let Ok(Prepared::Model(model)) = r else {
            panic!("{r:?}");
        };
        let (sim, modes) = job.take_built().unwrap().unwrap();
        assert_eq!(modes, model.modes());
        (*model, sim, polls)
    }

    /// The forces of `steps` steps of `sim`, one after the other.
    fn forces(mut sim: Simulation, steps: usize) -> Vec<f64> {
        let mut out = Vec::new();
        for _ in 0..steps {
            sim.step().unwrap();
            out.extend_from_slice(sim.force_n());
        }
        out
    }

    /// A ring tyre prepared in slices (the browser's way: the ring's
    /// responses a row at a time, LSCE an order at a time, the tables a
    /// block at a time) ends with the model of the threaded preparation and
    /// a simulation that runs the same forces to the bit; the work came in
    /// dozens of stages, each a small part of the whole, and the modes were
    /// kept in the cache.
    #[test]
    fn a_ring_prepared_in_slices_is_the_threaded_preparation() {
        let s = paper();
        let threaded =
            PrepareJob::spawn(Then::Edit(s.clone()), Arc::new(ModeCache::new())).unwrap();
        let (want_model, want_sim, _) = finish(&threaded);
        let cache = Arc::new(ModeCache::new());
        let sliced =
            PrepareJob::spawn_in_slices(Then::Edit(s.clone()), Arc::clone(&cache)).unwrap();
        assert_eq!(
            sliced.stages_done(),
            0,
            "nothing runs before the first poll"
        );
        let (model, sim, _) = finish(&sliced);
        assert_eq!(model, want_model);
        assert_eq!(forces(sim, 3000), forces(want_sim, 3000));
        // 5 rows of responses, 40 orders of the diagram, the QR, the model:
        // no stage holds more than a few hundredths of the identification
        assert!(
            sliced.stages_done() >= 50,
            "{} stages",
            sliced.stages_done()
        );
        assert_eq!(sliced.progress(), 1.0);
        assert!(cache.has_modes(&s), "the identified ring is kept");
    }

    /// Each stage of a ring's identification and of a patch's tables is a
    /// small share of the whole: timed stage by stage, none takes a quarter
    /// of the sum (relative times, on whatever machine).
    #[test]
    fn no_stage_holds_a_large_share_of_the_preparation() {
        let shares = |mut stage: Box<dyn FnMut() -> bool>| {
            let (mut longest_s, mut sum_s, mut n): (f64, f64, usize) = (0.0, 0.0, 0);
            loop {
                let t = web_time::Instant::now();
                let done = stage();
                let dt = t.elapsed().as_secs_f64();
                longest_s = longest_s.max(dt);
                sum_s += dt;
                n += 1;
                if done {
                    return (longest_s / sum_s, n);
                }
            }
        };
        let s = paper();
        let cache = ModeCache::new();
        let mut run = PreparedModelRun::new(&s, &cache);
        let (share, n) = shares(Box::new(move || run.stage(&cache).unwrap().is_some()));
        assert!(
            n >= 50 && share < 0.25,
            "{n} stages, the longest {share:.2} of the whole"
        );
        let model = PreparedModel::of(&patch(20, 10)).unwrap();
        let mut b = Simulation::build_in_stages(model.problem().clone(), SolverOptions::default());
        let (share, n) = shares(Box::new(move || b.stage().unwrap().is_some()));
        assert!(
            n >= 20 && share < 0.25,
            "{n} stages, the longest {share:.2} of the whole"
        );
    }

    /// A patch of 200 points set up in slices has the threaded set-up's
    /// tables: the same forces, step for step; its tables took many polls'
    /// stages (blocks of rows), not one.
    #[test]
    fn a_large_patch_set_up_in_slices_is_the_threaded_set_up() {
        let s = patch(20, 10);
        assert_eq!(s.num_points(), 200);
        let then = || Then::Replace {
            scene: s.clone(),
            path: None,
            what: "test".into(),
        };
        let threaded = PrepareJob::spawn(then(), Arc::new(ModeCache::new())).unwrap();
        let (want_model, want_sim, _) = finish(&threaded);
        let sliced = PrepareJob::spawn_in_slices(then(), Arc::new(ModeCache::new())).unwrap();
        let (model, sim, _) = finish(&sliced);
        assert_eq!(model, want_model);
        assert!(
            sliced.stages_done() >= 20,
            "{} stages",
            sliced.stages_done()
        );
        assert_eq!(forces(sim, 400), forces(want_sim, 400));
    }

    /// A sliced preparation cancelled between slices stops with an error
    /// and builds nothing.
    #[test]
    fn a_preparation_in_slices_can_be_cancelled() {
        let job =
            PrepareJob::spawn_in_slices(Then::Edit(paper()), Arc::new(ModeCache::new())).unwrap();
        job.cancel();
        assert_eq!(job.poll(), Some(Err("cancelled".to_string())));
        assert!(job.take_built().is_none());
    }
}
