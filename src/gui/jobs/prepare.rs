//! What a new scene needs before it can run, off the UI thread: its preset
//! file read (Open), its measured road's file read, its ring tyre
//! identified (method §5-6; a tenth of a second or more, longer in a debug
//! build). The edit or the document waits here while the window keeps
//! drawing and the current run goes on, then is applied from what was
//! prepared (the identified modes are also kept in the app's
//! [`ModeCache`], which the job shares). A file that cannot be read, or a
//! scene that cannot run, is refused then, with the current scene kept.

use crate::gui::jobs::Job;
use crate::gui::model::prepared::Prepared;
use crate::identify::{ModeCache, PreparedModel};
use crate::model::road::{Road, RoadProfile};
use crate::scene::Mode;
use crate::solver::simulation::{Simulation, SolverOptions};
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
        Road::Measured { .. } | Road::Surface { .. } | Road::Texture { .. }
    )
}

/// A preparation running on its own thread, and what waits for it.
pub struct PrepareJob {
    job: Job<Result<Prepared, String>>,
    pub then: Then,
    /// The simulation of a prepared model, built on the job's thread.
    built: Arc<Mutex<Option<Built>>>,
}

impl PrepareJob {
    /// Prepares what `then` needs on a new thread, identifying into
    /// `cache` (kept there even if a later edit replaces this job).
    pub fn spawn(then: Then, cache: Arc<ModeCache>) -> Result<Self, String> {
        let what = then.clone();
        let built = Arc::new(Mutex::new(None));
        let slot = Arc::clone(&built);
        let job = Job::spawn("preparation", 1, move |progress| {
            let r = prepare(&what, &cache);
            if let Ok(Prepared::Model(m)) = &r {
                let b = Simulation::new(m, SolverOptions::default())
                    .map(|sim| (sim, m.modes().to_vec()));
                if let Ok(mut s) = slot.lock() {
                    *s = Some(b);
                }
            }
            progress.add(1);
            r.map_err(|e| e.to_string())
        })?;
        Ok(PrepareJob { job, then, built })
    }

    /// The simulation built from the prepared model, once (after
    /// [`Self::poll`] gave the model).
    pub fn take_built(&self) -> Option<Built> {
        self.built.lock().ok().and_then(|mut s| s.take())
    }

    /// The result, once the thread has finished.
    pub fn poll(&self) -> Option<Result<Prepared, String>> {
        self.job.poll().map(Result::flatten)
    }
}

fn prepare(then: &Then, cache: &ModeCache) -> Result<Prepared, SceneError> {
    let model =
        |scene: &Scene| PreparedModel::new(scene, cache).map(|m| Prepared::Model(Box::new(m)));
    match then {
        Then::Edit(scene) | Then::Replace { scene, .. } => model(scene),
        Then::Road(scene) => {
            RoadProfile::new(&scene.road, scene.base_dir.as_deref()).map(Prepared::Road)
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
