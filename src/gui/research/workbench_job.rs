//! The identification workbench's identification, off the UI thread (no
//! egui here): the scene's ring sampled or its measured file read, LSCE
//! with its whole stabilisation diagram, and the workbench made from them;
//! for a measured file of FRFs (UFF), also their frequency-domain fit
//! (method §6.5).

use crate::gui::jobs::Job;
use crate::identify::frequency::{FrfIdentification, FrfOptions, identify_frfs};
use crate::identify::identify_tyre;
use crate::identify::workbench::Workbench;
use crate::model::measured::frf::{FrfRequest, holds_frfs};
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

/// The frequency-domain fit of a measured tyre's UFF file of FRFs (its
/// nodes, its band); `None` for any other tyre or file.
pub fn frf_fit_of(scene: &Scene) -> Option<Result<FrfIdentification, String>> {
    let Tyre::Measured {
        file,
        identification,
        nodes,
    } = &scene.tyre
    else {
        return None;
    };
    let path = crate::identify::data_path(scene, file);
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if !(ext == "uff" || ext == "unv") || !holds_frfs(&path).unwrap_or(false) {
        return None;
    }
    let opts = FrfOptions {
        request: FrfRequest {
            band_hz: Some(identification.band_hz),
            nodes: (!nodes.is_empty()).then(|| nodes.clone()),
            flip: Vec::new(),
        },
        ..FrfOptions::default()
    };
    Some(identify_frfs(&path, &opts).map_err(|e| e.to_string()))
}

/// What the workbench job gives: the LSCE workbench, and the FRF fit of a
/// file of FRFs.
#[derive(Debug)]
pub struct WorkbenchOutcome {
    pub bench: Result<Workbench, String>,
    pub frf: Option<Result<FrfIdentification, String>>,
}

/// A workbench identification under way, and what it is for.
#[derive(Debug)]
pub struct WorkbenchJob {
    pub key: WorkbenchKey,
    job: Job<WorkbenchOutcome>,
}

impl WorkbenchJob {
    pub fn spawn(scene: &Scene, key: WorkbenchKey) -> Result<Self, String> {
        let scene = scene.clone();
        let job = Job::spawn("identification workbench", 2, move |progress| {
            let bench = workbench_of(&scene);
            progress.add(1);
            let frf = frf_fit_of(&scene);
            progress.add(1);
            WorkbenchOutcome { bench, frf }
        })?;
        Ok(WorkbenchJob { key, job })
    }

    /// The result, once the thread has finished.
    pub fn poll(&self) -> Option<WorkbenchOutcome> {
        self.job.poll().map(|r| match r {
            Ok(o) => o,
            Err(e) => WorkbenchOutcome {
                bench: Err(e),
                frf: None,
            },
        })
    }
}
