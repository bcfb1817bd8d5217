//! A ring tyre's identification (method §5-6) off the UI thread. A scene
//! whose ring has not been identified at its points yet (a new ring, moved
//! or added points, other identification options) takes a tenth of a second
//! or more to build, longer in a debug build: the edit or the opened file
//! waits for it here while the window keeps drawing and the run goes on,
//! then is applied as if nothing had been waited for (the identified modes
//! are then in the app's [`ModeCache`], which the job shares).

use crate::Scene;
use crate::gui::jobs::Job;
use crate::identify::ModeCache;
use std::path::PathBuf;
use std::sync::Arc;

/// What waits for the identification.
#[derive(Debug, Clone)]
pub enum Then {
    /// An edit of the current scene ([`crate::gui::model::command::Command::EditScene`]).
    Edit(Scene),
    /// A new document: an opened file, a preset, a new scene.
    Replace {
        scene: Scene,
        path: Option<PathBuf>,
        what: String,
    },
}

/// An identification running on its own thread, and what waits for it.
pub struct IdentifyJob {
    job: Job<Result<(), String>>,
    pub then: Then,
}

impl IdentifyJob {
    /// Identifies `scene`'s ring on a new thread into `cache` (kept there
    /// even if a later edit replaces this job).
    pub fn spawn(scene: &Scene, then: Then, cache: Arc<ModeCache>) -> Result<Self, String> {
        let scene = scene.clone();
        let job = Job::spawn("identification", 1, move |progress| {
            let r = cache.modes(&scene).map(|_| ()).map_err(|e| e.to_string());
            progress.add(1);
            r
        })?;
        Ok(IdentifyJob { job, then })
    }

    /// The result, once the thread has finished.
    pub fn poll(&self) -> Option<Result<(), String>> {
        self.job.poll().map(Result::flatten)
    }
}

/// The banner while a ring is identified.
pub fn waiting_note(then: &Then) -> String {
    let what = match then {
        Then::Edit(_) => "for the edited scene",
        Then::Replace { .. } => "for the new scene",
    };
    format!(
        "Identifying the ring tyre's modes at the points {what} (LSCE, docs/method.md §6): \
         the current run goes on until they are ready."
    )
}
