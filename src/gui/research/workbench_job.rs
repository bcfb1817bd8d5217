//! The identification workbench's identification, off the UI thread (no
//! egui here): the scene's ring sampled or its measured file read, LSCE
//! with its whole stabilisation diagram, and the workbench made from them.

use crate::gui::jobs::Job;
use crate::identify::workbench::Workbench;
use crate::identify::{data_path, identify_measured, identify_ring};
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

/// Identifies `scene`'s tyre into a workbench (the automatic choice).
pub fn workbench_of(scene: &Scene) -> Result<Workbench, String> {
    let e = |e: &dyn std::fmt::Display| e.to_string();
    match &scene.tyre {
        Tyre::Ring {
            ring,
            identification,
        } => {
            let x: Vec<f64> = scene.points.iter().map(|p| p.x_m).collect();
            let id = identify_ring(ring, &x, identification).map_err(|x| e(&x))?;
            Workbench::new(id.responses, id.identification, identification.band_hz)
                .map_err(|x| e(&x))
        }
        Tyre::Measured {
            file,
            identification,
            nodes,
        } => {
            let id = identify_measured(
                &data_path(scene, file),
                (!nodes.is_empty()).then_some(nodes.as_slice()),
                scene.num_points(),
                identification,
            )
            .map_err(|x| e(&x))?;
            Workbench::new(id.responses, id.identification, identification.band_hz)
                .map_err(|x| e(&x))
        }
        Tyre::Modal { .. } => Err("a modal tyre: nothing to identify".into()),
    }
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
