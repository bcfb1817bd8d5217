//! The identification workbench's identification, off the UI thread (no
//! egui here): the scene's ring sampled or its measured file read, LSCE
//! with its whole stabilisation diagram, and the workbench made from them.

use crate::gui::jobs::Job;
use crate::identify::identify_tyre;
use crate::identify::workbench::Workbench;
use crate::scene::{Scene, Tyre};

/// What a workbench depends on: the tyre and the points' positions (m).
pub type WorkbenchKey = (Tyre, Vec<f64>);

/// The key of `scene`'s workbench; `None` for a modal tyre (nothing to
/// identify).
pub fn key_of(scene: &Scene) -> Option<WorkbenchKey> {
    (!matches!(scene.tyre, Tyre::Modal { .. })).then(|| {
        (
            scene.tyre.clone(),
            scene.points.iter().map(|p| p.x_m).collect(),
        )
    })
}

/// The tyre and points of `scene`, whatever its tyre.
pub fn scene_key(scene: &Scene) -> WorkbenchKey {
    (
        scene.tyre.clone(),
        scene.points.iter().map(|p| p.x_m).collect(),
    )
}

/// Identifies `scene`'s tyre into a workbench (the automatic choice).
pub fn workbench_of(scene: &Scene) -> Result<Workbench, String> {
    let id = identify_tyre(scene)
        .ok_or_else(|| "a modal tyre: nothing to identify".to_string())?
        .map_err(|e| e.to_string())?;
    Workbench::new(id.responses, id.identification, id.band_hz).map_err(|e| e.to_string())
}

/// A workbench identification under way, and what it is for.
#[derive(Debug)]
pub struct WorkbenchJob {
    pub key: WorkbenchKey,
    job: Job<Result<Workbench, String>>,
}

impl WorkbenchJob {
    pub fn spawn(scene: &Scene, key: WorkbenchKey) -> Result<Self, String> {
        let scene = scene.clone();
        let job = Job::spawn("identification workbench", 1, move |progress| {
            let r = workbench_of(&scene);
            progress.add(1);
            r
        })?;
        Ok(WorkbenchJob { key, job })
    }

    /// The result, once the thread has finished.
    pub fn poll(&self) -> Option<Result<Workbench, String>> {
        self.job.poll().map(Result::flatten)
    }
}
