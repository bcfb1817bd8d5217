//! The identification workbench's identification, off the UI thread (no
//! egui here): the scene's ring sampled or its measured file read, LSCE
//! with its whole stabilisation diagram, and the workbench made from them;
//! for a measured file of FRFs (UFF), also their frequency-domain fit
//! (method §6.5).

use crate::gui::jobs::{Job, Progress};
use crate::identify::frequency::{FrfIdentification, FrfOptions, identify_frfs};
use crate::identify::workbench::Workbench;
use crate::identify::{RingIdentifyRun, identify_tyre};
use crate::readers::measured::frf::{FrfRequest, holds_frfs};
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
    /// Identifies `scene`'s tyre on a new thread (in the browser, a ring
    /// in slices within the polls: [`Job::spawn_sliced`]).
    pub fn spawn(scene: &Scene, key: WorkbenchKey) -> Result<Self, String> {
        Self::start(scene, key, false)
    }

    /// The identification run on the caller's thread, a slice at each
    /// poll ([`Job::in_slices`]): how a page in the browser runs a ring's
    /// ([`RingIdentifyRun`] a stage at a time). Its workbench equals the
    /// threaded job's.
    pub fn spawn_in_slices(scene: &Scene, key: WorkbenchKey) -> Result<Self, String> {
        Self::start(scene, key, true)
    }

    fn start(scene: &Scene, key: WorkbenchKey, in_slices: bool) -> Result<Self, String> {
        let scene = scene.clone();
        let mut ring = match &scene.tyre {
            Tyre::Ring {
                ring,
                identification,
            } => {
                let x_m: Vec<f64> = scene.points.iter().map(|p| p.x_m).collect();
                Some(
                    RingIdentifyRun::new(ring, &x_m, identification)
                        .map(|run| (run, identification.band_hz)),
                )
            }
            _ => None,
        };
        let failed = |e: String| WorkbenchOutcome {
            bench: Err(e),
            frf: None,
        };
        let work = move |progress: &Progress, deadline: Option<web_time::Instant>| {
            let (run, band_hz) = match &mut ring {
                // a measured tyre's file (which the browser cannot read)
                None => {
                    let bench = workbench_of(&scene);
                    let frf = frf_fit_of(&scene);
                    progress.set(2);
                    return Some(WorkbenchOutcome { bench, frf });
                }
                Some(Err(e)) => return Some(failed(e.to_string())),
                Some(Ok(r)) => r,
            };
            progress.set_total(run.num_stages() as u64 + 1);
            loop {
                if progress.cancelled() {
                    return Some(failed("cancelled".to_string()));
                }
                match run.stage() {
                    Err(e) => return Some(failed(e.to_string())),
                    Ok(None) => progress.set(run.stages_done() as u64),
                    Ok(Some(id)) => {
                        let bench = Workbench::new(id.responses, id.identification, *band_hz)
                            .map_err(|e| e.to_string());
                        progress.set(run.num_stages() as u64 + 1);
                        return Some(WorkbenchOutcome { bench, frf: None });
                    }
                }
                if deadline.is_some_and(|d| web_time::Instant::now() >= d) {
                    return None;
                }
            }
        };
        let job = if in_slices {
            Job::in_slices("identification workbench", 2, work)
        } else {
            Job::spawn_sliced("identification workbench", 2, work)?
        };
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper preset's workbench identified in slices (the browser's
    /// way: the ring a stage at a time) is the one identified at once, and
    /// took more than one poll.
    #[test]
    fn a_ring_workbench_in_slices_is_the_whole_identification_s() {
        let scene = Scene::parse(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/paper.ron")),
            "paper",
        )
        .unwrap();
        let want = workbench_of(&scene).unwrap();
        let job = WorkbenchJob::spawn_in_slices(&scene, scene_key(&scene)).unwrap();
        let mut polls = 0;
        let got = loop {
            polls += 1;
            if let Some(o) = job.poll() {
                break o;
            }
        };
        assert!(polls >= 2, "one poll ran the whole identification");
        assert!(got.frf.is_none());
        let got = got.bench.unwrap();
        assert_eq!(format!("{got:?}"), format!("{want:?}"));
        assert!(!got.pair_fits().is_empty());
    }
}
