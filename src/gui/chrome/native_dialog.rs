//! The desktop's file dialog (rfd) on a thread of its own. rfd's dialogs
//! block the thread that calls them until the user answers; called from the
//! UI they froze the whole window (no repaint, the run stopped) while the
//! dialog was open. Here a "Choose…" click starts the dialog on a thread and
//! the UI keeps drawing; the answer is taken in the frame it arrives.

use egui::{Id, Ui};
use std::path::PathBuf;
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::sync::{Arc, Mutex, OnceLock};

/// What the dialog picks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// An existing file.
    Open,
    /// A file to write.
    Save,
    /// A folder.
    Folder,
}

/// What the dialog is asked: its kind, file-type filter (name, extension),
/// start folder and file name.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    pub kind: Kind,
    pub filter: Option<(String, String)>,
    pub directory: Option<PathBuf>,
    pub file_name: Option<String>,
}

/// A function that shows a dialog and returns the user's answer (blocking).
pub type Backend = fn(&Request) -> Option<PathBuf>;

static BACKEND: OnceLock<Mutex<Backend>> = OnceLock::new();

/// Replaces the dialog (rfd) by `f`, for the whole process: tests answer
/// with a path of their own, after a delay of their own.
pub fn set_backend(f: Backend) {
    let m = BACKEND.get_or_init(|| Mutex::new(rfd_dialog));
    if let Ok(mut b) = m.lock() {
        *b = f;
    }
}

fn backend() -> Backend {
    BACKEND
        .get_or_init(|| Mutex::new(rfd_dialog))
        .lock()
        .map_or(rfd_dialog as Backend, |b| *b)
}

/// The desktop's dialog (rfd, through the xdg desktop portal).
#[cfg(not(target_arch = "wasm32"))]
fn rfd_dialog(r: &Request) -> Option<PathBuf> {
    let mut d = rfd::FileDialog::new();
    if let Some((name, ext)) = &r.filter {
        d = d.add_filter(name, &[ext]);
    }
    if let Some(dir) = &r.directory {
        d = d.set_directory(dir);
    }
    if let Some(name) = &r.file_name {
        d = d.set_file_name(name);
    }
    match r.kind {
        Kind::Open => d.pick_file(),
        Kind::Save => d.save_file(),
        Kind::Folder => d.pick_folder(),
    }
}

/// A page in the browser has no dialog that answers with a path.
#[cfg(target_arch = "wasm32")]
fn rfd_dialog(_: &Request) -> Option<PathBuf> {
    None
}

/// The answer of a dialog still open (shared through egui's memory).
#[derive(Clone)]
struct Pending(Arc<Mutex<Receiver<Option<PathBuf>>>>);

/// A "Choose…" button under `id`: a click opens the dialog for `request()`
/// on its own thread; while it is open the button shows that and the UI
/// goes on. Returns `Some(answer)` in the frame the answer arrives (`None`
/// inside: cancelled, or no dialog on this desktop).
pub fn choose_button(
    ui: &mut Ui,
    id: Id,
    request: impl FnOnce() -> Request,
) -> Option<Option<PathBuf>> {
    let pending: Option<Pending> = ui.data(|d| d.get_temp(id));
    if let Some(Pending(rx)) = pending {
        let answer = match rx.lock().map(|r| r.try_recv()) {
            Ok(Ok(a)) => Some(a),
            Ok(Err(TryRecvError::Empty)) => None,
            // the dialog's thread ended without an answer
            Ok(Err(TryRecvError::Disconnected)) | Err(_) => Some(None),
        };
        if answer.is_some() {
            ui.data_mut(|d| d.remove::<Pending>(id));
        } else {
            ui.add_enabled(false, egui::Button::new("Choose…"))
                .on_disabled_hover_text("the desktop's file dialog is open");
            ui.spinner();
            // poll again soon: the answer comes from another thread
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_millis(100));
        }
        return answer;
    }
    if super::web::IN_BROWSER {
        ui.add_enabled(false, egui::Button::new("Choose…"))
            .on_disabled_hover_text(super::web::BROWSER_LIMITS);
        return None;
    }
    if ui
        .button("Choose…")
        .on_hover_text("the desktop's file dialog, if it has one")
        .clicked()
    {
        let req = request();
        let (tx, rx) = channel();
        let ctx = ui.ctx().clone();
        let f = backend();
        let started = std::thread::Builder::new()
            .name("file dialog".into())
            .spawn(move || {
                let _ = tx.send(f(&req));
                ctx.request_repaint();
            });
        if started.is_err() {
            return Some(None);
        }
        ui.data_mut(|d| d.insert_temp(id, Pending(Arc::new(Mutex::new(rx)))));
    }
    None
}
