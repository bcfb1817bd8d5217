//! A ring tyre's identification (method §5-6) off the UI thread. A scene
//! whose ring has not been identified at its points yet (a new ring, moved
//! or added points, other identification options) takes a tenth of a second
//! or more to build, longer in a debug build: the edit or the opened file
//! waits for it here while the window keeps drawing and the run goes on,
//! then is applied as if nothing had been waited for (the identified modes
//! are then in the cache, [`crate::identify::ring_modes_cached`]).

use crate::Scene;
use std::path::PathBuf;
use std::sync::mpsc::{Receiver, TryRecvError, channel};

/// What waits for the identification.
#[derive(Debug, Clone)]
pub enum Then {
    /// An edit of the current scene ([`crate::gui::command::Command::EditScene`]).
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
    rx: Receiver<Result<(), String>>,
    pub then: Then,
}

impl IdentifyJob {
    /// Identifies `scene`'s ring on a new thread.
    pub fn spawn(scene: &Scene, then: Then) -> Self {
        let (tx, rx) = channel();
        let scene = scene.clone();
        std::thread::spawn(move || {
            // the receiver is gone if a later edit replaced this one or the
            // app closed: the modes are cached all the same
            let _ = tx.send(scene.modes().map(|_| ()).map_err(|e| e.to_string()));
        });
        IdentifyJob { rx, then }
    }

    /// The result, once the thread has finished.
    pub fn poll(&self) -> Option<Result<(), String>> {
        match self.rx.try_recv() {
            Ok(r) => Some(r),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => {
                Some(Err("the identification thread stopped unexpectedly".into()))
            }
        }
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
