//! What a sweep from the GUI asks for and what it gives back (no egui,
//! no thread here): the request (checked against the scene), the finished
//! sweep, and how the sweep ended. The sweep runs in `research::sweep_job`.

use crate::Scene;
use crate::studies::sweep::{self, Sweep, SweepError, SweepPoint};

/// What the user asked to sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRequest {
    /// Parameter path (`speed_mps`, `points[*].h_m`, ...; see `sweep::param_paths`).
    pub param: String,
    pub from: f64,
    pub to: f64,
    /// Values, both ends included (>= 1).
    pub steps: usize,
}

impl SweepRequest {
    /// The sweep of `base` this asks for, checked: known parameter, valid
    /// scene at both ends, at least one value.
    pub fn to_sweep(&self, base: &Scene, threads: usize) -> Result<Sweep, SweepError> {
        sweep::get_param(base, &self.param)?;
        let values = sweep::linspace(self.from, self.to, self.steps)?;
        for v in [self.from, self.to] {
            sweep::set_param(&mut base.clone(), &self.param, v)?;
        }
        Ok(Sweep {
            param: self.param.trim().to_string(),
            values,
            threads: threads.max(1),
        })
    }
}

/// A finished sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepResult {
    pub request: SweepRequest,
    /// The base scene as it was when the sweep started (its name names the
    /// results): the results are its, and say so once the scene is edited.
    pub base: Box<crate::Scene>,
    /// What the runs' tables and plots hold (per point, or the patch's).
    pub columns: crate::studies::sweep::report::Columns,
    pub points: Vec<SweepPoint>,
    /// Wall time of the sweep (s), shown, never asserted.
    pub wall_s: f64,
    pub threads: usize,
}

impl SweepResult {
    /// Whether `scene` is not the one swept (its name and folder aside).
    pub fn differs_from(&self, scene: &crate::Scene) -> bool {
        let mut base = (*self.base).clone();
        base.name.clone_from(&scene.name);
        base.base_dir.clone_from(&scene.base_dir);
        base != *scene
    }

    /// Runs that failed.
    pub fn failed(&self) -> usize {
        self.points.iter().filter(|p| p.result.is_err()).count()
    }
}

/// How a sweep job ended.
#[derive(Debug, Clone, PartialEq)]
pub enum SweepEnd {
    Done(SweepResult),
    Cancelled,
    Failed(String),
}
