//! A scene made ready to simulate ([`PreparedModel`]): validated, its
//! modes taken from the cache or identified, its road loaded; at once or a
//! stage at a time ([`PreparedModelRun`]); and the solver's [`Problem`] of
//! it.

use super::cache::cache_key;
use super::{ModeCache, RingIdentifyRun, positions};
use crate::scene::{Scene, SceneError, Tyre};
use std::sync::Arc;
use tirecontact_core::base::modal::Mode;
use tirecontact_core::model::lsce::LsceRun;
use tirecontact_core::model::road::RoadProfile;
use tirecontact_core::solver::problem::Problem;
use tirecontact_core::{Simulation, SolverOptions};

fn validate_scene(scene: &Scene) -> Result<(), SceneError> {
    scene.validate().map_err(|errors| SceneError::Invalid {
        file: scene.name.clone(),
        errors,
        at: Vec::new(),
    })
}

/// [`PreparedModel::new`] a stage at a time, for a caller that must return
/// between stages (a page in the browser has one thread): the scene
/// checked, then a ring tyre not in the cache identified a stage at a time
/// ([`RingIdentifyRun`]; other tyres' modes at once), then the road. The
/// same steps as [`PreparedModel::new`]: the same model, and the ring's
/// modes kept in the cache as it keeps them.
#[derive(Debug)]
pub struct PreparedModelRun {
    scene: Scene,
    /// The ring being identified and its key in the cache.
    ring: Option<(String, RingIdentifyRun)>,
    modes: Option<Arc<Vec<Mode>>>,
    stages_done: usize,
    num_stages: usize,
}

impl PreparedModelRun {
    /// The preparation of `scene`, its modes to come from (or be kept in)
    /// `cache`.
    pub fn new(scene: &Scene, cache: &ModeCache) -> Self {
        let identifies = match &scene.tyre {
            Tyre::Ring { identification, .. } if !cache.has_modes(scene) => {
                let p = scene.num_points();
                p + LsceRun::stages_for(p * (p + 1) / 2, identification) + 1
            }
            _ => 0,
        };
        PreparedModelRun {
            scene: scene.clone(),
            ring: None,
            modes: None,
            stages_done: 0,
            num_stages: 2 + identifies,
        }
    }

    /// Stages of the whole preparation.
    pub fn num_stages(&self) -> usize {
        self.num_stages
    }

    /// Stages done so far.
    pub fn stages_done(&self) -> usize {
        self.stages_done
    }

    /// What the next stage does, for a progress line.
    pub fn next_stage(&self) -> &'static str {
        match (&self.ring, &self.modes) {
            (Some((_, run)), _) => run.next_stage(),
            (None, Some(_)) => "reading the road",
            (None, None) => "checking the scene",
        }
    }

    /// Runs the next stage; the model once the last one ran. A ring
    /// identified here is kept in `cache`.
    pub fn stage(&mut self, cache: &ModeCache) -> Result<Option<PreparedModel>, SceneError> {
        self.stages_done += 1;
        let scene = &self.scene;
        if let Some((key, run)) = &mut self.ring {
            let id = run.stage().map_err(|e| SceneError::Identification {
                scene: scene.name.clone(),
                message: e.to_string(),
            })?;
            if let Some(id) = id {
                let modes = Arc::new(id.identification.modes);
                cache.store(std::mem::take(key), Arc::clone(&modes));
                self.modes = Some(modes);
                self.ring = None;
            }
            return Ok(None);
        }
        let Some(modes) = &self.modes else {
            validate_scene(scene)?;
            match &scene.tyre {
                Tyre::Ring {
                    ring,
                    identification,
                } if !cache.has_modes(scene) => {
                    let x_m = positions(scene);
                    let run = RingIdentifyRun::new(ring, &x_m, identification).map_err(|e| {
                        SceneError::Identification {
                            scene: scene.name.clone(),
                            message: e.to_string(),
                        }
                    })?;
                    self.ring = Some((cache_key(ring, &x_m, identification), run));
                }
                _ => self.modes = Some(cache.modes(scene)?),
            }
            return Ok(None);
        };
        PreparedModel::with_modes(scene, Arc::clone(modes)).map(Some)
    }

    /// Runs every stage left.
    pub fn finish(mut self, cache: &ModeCache) -> Result<PreparedModel, SceneError> {
        loop {
            if let Some(m) = self.stage(cache)? {
                return Ok(m);
            }
        }
    }
}

/// A scene made ready to simulate: validated, its tyre's modes known
/// (identified if it is a ring) and its road profile loaded (a measured
/// road read from its file). Everything that may take time, read a file or
/// fail on the user's input happens here, once; a
/// [`Simulation`] is then built from it without I/O or
/// identification.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedModel {
    scene: Scene,
    problem: Problem,
}

impl PreparedModel {
    /// Validates `scene`, takes its modes from `cache` (identifying a ring
    /// not seen before), reads a measured road file and checks the ramp
    /// against the road (`T_ramp = 0` needs every point above it, method §4).
    pub fn new(scene: &Scene, cache: &ModeCache) -> Result<Self, SceneError> {
        validate_scene(scene)?;
        let modes = cache.modes(scene)?;
        Self::with_modes(scene, modes)
    }

    /// The rest of [`PreparedModel::new`] once the (validated) scene's
    /// modes are known: the road read and checked.
    fn with_modes(scene: &Scene, modes: Arc<Vec<Mode>>) -> Result<Self, SceneError> {
        let road = crate::scene::load_road(&scene.road, scene.base_dir.as_deref())?;
        let mut errors = scene.surface_errors(&road);
        if errors.is_empty() {
            errors = scene.crg_errors(&road);
        }
        if errors.is_empty()
            && let Some(e) = scene.ramp_error(&road)
        {
            errors.push(e);
        }
        if !errors.is_empty() {
            return Err(SceneError::Invalid {
                file: scene.name.clone(),
                errors,
                at: Vec::new(),
            });
        }
        Ok(Self {
            problem: problem_of(scene, modes, road),
            scene: scene.clone(),
        })
    }

    /// [`PreparedModel::new`] with a cache of its own: for one scene run
    /// once. Several runs of one ring tyre share a [`ModeCache`] instead.
    pub fn of(scene: &Scene) -> Result<Self, SceneError> {
        Self::new(scene, &ModeCache::new())
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The tyre's modes (given or identified).
    pub fn modes(&self) -> &[Mode] {
        &self.problem.modes
    }

    /// The road profile, loaded.
    pub fn road(&self) -> &RoadProfile {
        &self.problem.road
    }

    /// What the solver is given: the scene's points, modes, road, contact,
    /// time step, speed and ramp.
    pub fn problem(&self) -> &Problem {
        &self.problem
    }

    /// The simulation of this model with `options` (no I/O, no
    /// identification: the solver's tables only).
    pub fn simulation(&self, options: SolverOptions) -> Result<Simulation, SceneError> {
        Ok(Simulation::new(&self.problem, options)?)
    }
}

/// The solver's problem of a validated `scene` with its `modes` and loaded
/// `road`.
pub fn problem_of(scene: &Scene, modes: Arc<Vec<Mode>>, road: RoadProfile) -> Problem {
    Problem {
        name: scene.name.clone(),
        points: scene.points.to_vec(),
        modes,
        modes_identified: scene.modes_identified(),
        road: Arc::new(road),
        contact: scene.contact.clone(),
        contact_scheme: scene.contact_scheme,
        dt_s: scene.dt_s,
        duration_s: scene.duration_s,
        speed_mps: scene.speed_mps,
        ramp_s: scene.ramp_s,
    }
}

/// A [`Simulation`] built from a scene: validated, its modes taken or
/// identified, its road loaded ([`PreparedModel`]), then the solver's
/// tables. The solver itself knows no scene; this trait, in scope, gives
/// it the constructors of one.
pub trait SceneSimulation: Sized {
    /// Prepares `scene` with a cache of its own and builds its simulation
    /// with default options: for a scene run once. Runs of one ring tyre
    /// share a [`ModeCache`] and call [`PreparedModel::simulation`].
    fn from_scene(scene: &Scene) -> Result<Self, SceneError>;
    /// As [`SceneSimulation::from_scene`], with explicit [`SolverOptions`].
    fn from_scene_with(scene: &Scene, options: SolverOptions) -> Result<Self, SceneError>;
}

impl SceneSimulation for Simulation {
    fn from_scene(scene: &Scene) -> Result<Self, SceneError> {
        PreparedModel::of(scene)?.simulation(SolverOptions::default())
    }

    fn from_scene_with(scene: &Scene, options: SolverOptions) -> Result<Self, SceneError> {
        PreparedModel::of(scene)?.simulation(options)
    }
}
