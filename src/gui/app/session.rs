//! The session kept in eframe's storage between runs of the app: the scene
//! (with its file and unsaved-changes state), classroom mode with its
//! chosen point, and whether the mode bars are shown, restored at the next
//! start.

use super::*;

/// eframe storage key of the last session.
pub(super) const SESSION_KEY: &str = "tirecontact.session";

/// What is persisted between sessions.
#[derive(Debug, Serialize, Deserialize)]
pub(super) struct Session {
    scene_ron: String,
    path: Option<PathBuf>,
    dirty: bool,
    /// Classroom mode was on, or chosen and set aside while the window is
    /// a phone's width (absent from sessions before it was saved).
    #[serde(default)]
    classroom: bool,
    /// Classroom mode was set aside at a phone's width: egui's theme
    /// preference is then the user's own, not classroom mode's light one.
    #[serde(default)]
    classroom_set_aside: bool,
    /// The point classroom mode's plot and bars show.
    #[serde(default)]
    classroom_point: usize,
    /// The mode bars were shown beside the views (absent from older
    /// sessions: off).
    #[serde(default)]
    mode_bars: bool,
    /// The theme preference to give back when classroom mode ends (egui
    /// keeps classroom mode's light one between runs).
    #[serde(default)]
    theme_before_classroom: Option<egui::ThemePreference>,
    /// The scene came from a scene link (and has no file): the title and
    /// the status bar say "from a link" (absent from older sessions).
    #[serde(default)]
    from_link: bool,
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
                        app.doc.saved = s
                            .path
                            .as_deref()
                            .and_then(|p| Scene::load(p).ok())
                            .unwrap_or_else(default_scene);
                    }
                    if s.classroom {
                        // set aside at a phone's width: the theme egui
                        // kept is the user's, taken when classroom mode
                        // starts; else a session of a version that did not
                        // keep it: the app has no theme setting, so the
                        // system's
                        app.classroom.theme_before = if s.classroom_set_aside {
                            None
                        } else {
                            Some(
                                s.theme_before_classroom
                                    .unwrap_or(egui::ThemePreference::System),
                            )
                        };
                        app.set_classroom(true);
                    }
                    app.doc.from_link = s.from_link && s.path.is_none();
                    app.classroom.bars = s.mode_bars;
                    let last = app.doc.scene.num_points().saturating_sub(1);
                    app.classroom.point = s.classroom_point.min(last);
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

    /// The session to keep: the scene as edited, unsaved changes included
    /// (a window closed by the system keeps them), except after a quit
    /// that discarded them, which keeps the last saved version.
    pub(super) fn session(&self) -> Session {
        let (scene, dirty) = if self.allow_close {
            (&self.doc.saved, false)
        } else {
            (&self.doc.scene, self.is_dirty())
        };
        Session {
            scene_ron: scene.to_ron_string(),
            path: self.doc.path.clone(),
            dirty,
            // the mode the user chose: one set aside at a phone's width
            // comes back on a wide window
            classroom: self.classroom.on || self.classroom.back_when_wide,
            classroom_set_aside: !self.classroom.on && self.classroom.back_when_wide,
            classroom_point: self.classroom.point,
            mode_bars: self.classroom.bars,
            theme_before_classroom: self.classroom.user_theme(),
            from_link: self.doc.from_link,
        }
    }

    /// Writes the session to eframe's storage (`eframe::App::save`).
    pub(super) fn save_session(&self, storage: &mut dyn eframe::Storage) {
        if let Ok(text) = ron::to_string(&self.session()) {
            storage.set_string(SESSION_KEY, text);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::share;
    use eframe::Storage as _;
    use std::collections::HashMap;

    #[derive(Default)]
    struct MemStorage(HashMap<String, String>);

    impl eframe::Storage for MemStorage {
        fn get_string(&self, key: &str) -> Option<String> {
            self.0.get(key).cloned()
        }
        fn set_string(&mut self, key: &str, value: String) {
            self.0.insert(key.to_string(), value);
        }
        fn remove_string(&mut self, key: &str) {
            self.0.remove(key);
        }
        fn flush(&mut self) {}
    }

    /// The mode bars shown at the end of a session are shown at the next,
    /// and hidden ones stay hidden.
    #[test]
    fn the_mode_bars_are_restored() {
        for shown in [true, false] {
            let mut app = App::with_default_preset();
            app.apply(Command::ShowModeBars(shown));
            let mut storage = MemStorage::default();
            app.save_session(&mut storage);
            assert_eq!(App::restore(Some(&storage)).classroom.bars, shown);
        }
    }

    #[test]
    fn classroom_mode_and_its_point_are_restored() {
        let mut app = App::with_default_preset();
        assert_eq!(app.doc.scene.num_points(), 5);
        app.apply(Command::SetClassroom(true));
        app.classroom.point = 3;
        let mut storage = MemStorage::default();
        app.save_session(&mut storage);
        let restored = App::restore(Some(&storage));
        assert!(restored.classroom(), "classroom mode comes back on");
        assert_eq!(restored.classroom.point, 3);
        assert_eq!(restored.view, View::Scene);
        assert_eq!(
            restored.time.speed(),
            Speed::Factor(classroom::SLOW_MOTION),
            "with its slow motion"
        );

        // off stays off
        app.apply(Command::SetClassroom(false));
        app.save_session(&mut storage);
        assert!(!App::restore(Some(&storage)).classroom());
    }

    #[test]
    fn a_scene_from_a_link_is_still_from_a_link_after_a_restart() {
        let scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/single_mode.ron"
            )),
            "single_mode",
        )
        .unwrap();
        let link = share::link(&scene, share::DEFAULT_BASE_URL).unwrap();
        let app = App::open_link(&link, None);
        assert!(app.title().contains("(from a link)"), "{}", app.title());
        let mut storage = MemStorage::default();
        app.save_session(&mut storage);
        let restored = App::restore(Some(&storage));
        assert_eq!(restored.doc.scene.name, scene.name);
        assert_eq!(restored.title(), app.title());
        assert!(restored.doc.from_link);
        // a scene with its file is not from a link
        let mut storage = MemStorage::default();
        App::with_default_preset().save_session(&mut storage);
        assert!(!App::restore(Some(&storage)).title().contains("from a link"));
    }

    /// Unsaved edits come back after a restart, but not once "Discard
    /// changes" answered the quit: the next session has the saved scene.
    #[test]
    fn edits_discarded_on_quit_do_not_come_back() {
        let mut app = App::with_default_preset();
        let saved_speed = app.doc.scene.speed_mps;
        let mut edited = app.doc.scene.clone();
        edited.speed_mps = saved_speed / 2.0;
        app.apply(Command::EditScene(Box::new(edited)));
        assert!(app.is_dirty());
        let mut storage = MemStorage::default();
        app.save_session(&mut storage);
        let restored = App::restore(Some(&storage));
        assert_eq!(restored.doc.scene.speed_mps, saved_speed / 2.0, "kept");
        assert!(restored.is_dirty());
        app.apply(Command::Quit);
        assert!(matches!(app.confirm, Some(Discarding::Quit)), "asks first");
        app.discard_and(Discarding::Quit);
        app.save_session(&mut storage);
        let restored = App::restore(Some(&storage));
        assert_eq!(restored.doc.scene.speed_mps, saved_speed, "discarded");
        assert!(!restored.is_dirty());
    }

    #[test]
    fn a_point_beyond_the_restored_scene_is_clamped() {
        let mut app = App::with_default_preset();
        app.apply(Command::SetClassroom(true));
        app.classroom.point = 4;
        let mut session = app.session();
        session.classroom_point = 99;
        let mut storage = MemStorage::default();
        storage.set_string(SESSION_KEY, ron::to_string(&session).unwrap());
        assert_eq!(App::restore(Some(&storage)).classroom.point, 4);
    }

    #[test]
    fn a_session_saved_before_classroom_was_saved_still_loads() {
        let app = App::with_default_preset();
        // the session format of earlier versions: no classroom fields
        let old = format!(
            "(scene_ron:{},path:None,dirty:true)",
            ron::to_string(&app.doc.scene.to_ron_string()).unwrap()
        );
        let mut storage = MemStorage::default();
        storage.set_string(SESSION_KEY, old.clone());
        let restored = App::restore(Some(&storage));
        assert_eq!(
            restored.message().map(|m| m.text.as_str()),
            Some("restored the last session"),
            "{old}"
        );
        assert!(!restored.classroom());
        assert_eq!(restored.classroom.point, 0);
    }
}
