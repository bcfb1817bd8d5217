//! The session kept in eframe's storage between runs of the app: the scene
//! (with its file and unsaved-changes state), restored at the next start.

use super::*;

/// eframe storage key of the last session.
pub(super) const SESSION_KEY: &str = "tirecontact.session";

/// What is persisted between sessions.
#[derive(Debug, Serialize, Deserialize)]
pub(super) struct Session {
    scene_ron: String,
    path: Option<PathBuf>,
    dirty: bool,
}

impl App {
    /// The last session from eframe's storage, else the default preset.
    pub fn restore(storage: Option<&dyn eframe::Storage>) -> Self {
        let session = storage
            .and_then(|s| s.get_string(SESSION_KEY))
            .and_then(|text| ron::from_str::<Session>(&text).ok());
        if let Some(s) = session {
            let file = s
                .path
                .as_ref()
                .map_or("(last session)".to_string(), |p| p.display().to_string());
            if let Ok(mut scene) = Scene::parse(&s.scene_ron, &file) {
                scene.base_dir = s
                    .path
                    .as_deref()
                    .and_then(Path::parent)
                    .map(Path::to_path_buf);
                if let Ok(mut app) = App::new(scene, s.path.clone()) {
                    if s.dirty {
                        // the saved version is the file's, if it still reads
                        app.saved = s
                            .path
                            .as_deref()
                            .and_then(|p| Scene::load(p).ok())
                            .unwrap_or_else(default_scene);
                    }
                    app.message = Some(Message {
                        error: false,
                        text: "restored the last session".to_string(),
                    });
                    return app;
                }
            }
        }
        App::with_default_preset()
    }

    pub(super) fn session(&self) -> Session {
        Session {
            scene_ron: self.scene.to_ron_string(),
            path: self.path.clone(),
            dirty: self.is_dirty(),
        }
    }

    /// Writes the session to eframe's storage (`eframe::App::save`).
    pub(super) fn save_session(&self, storage: &mut dyn eframe::Storage) {
        if let Ok(text) = ron::to_string(&self.session()) {
            storage.set_string(SESSION_KEY, text);
        }
    }
}
