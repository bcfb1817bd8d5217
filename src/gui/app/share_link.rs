//! Share: the current scene as a link (`scene::share`), copied to the
//! clipboard; in a browser the page's address takes it too. A link opened
//! at start (the page's fragment) comes before the saved session. Beside
//! `scene=`, the fragment may hold `view=K` (the view of key K, 1 to 9,
//! which Share writes) and `speed=F` (a real-time factor, or `max`).

use super::*;
use crate::gui::chrome::web;
use crate::scene::share;

impl App {
    /// The app on the scene of `link` (a page address or its fragment);
    /// without a scene in it, the last session from `storage`. A refused
    /// link opens the last session with the reason in the banner.
    pub fn open_link(link: &str, storage: Option<&dyn eframe::Storage>) -> Self {
        match share::scene_in(link) {
            Ok(None) => App::restore(storage),
            Ok(Some(scene)) => {
                let name = scene.name.clone();
                match App::new(scene, None) {
                    Ok(mut app) => {
                        app.doc.from_link = true;
                        app.info(format!("opened \"{name}\" from the link"));
                        app.link_options(link);
                        app
                    }
                    Err(e) => {
                        let mut app = App::restore(storage);
                        app.error(format!("The link's scene does not run: {e}"));
                        app
                    }
                }
            }
            Err(e) => {
                let mut app = App::restore(storage);
                match e {
                    // whole sentences that say what to do
                    share::ShareError::Damaged { .. } | share::ShareError::Newer { .. } => {
                        app.error(e.to_string())
                    }
                    e => app.error(format!("The link's scene was refused: {e}")),
                }
                app
            }
        }
    }

    /// The `view=` and `speed=` of a link's fragment (others are ignored,
    /// as are values out of range).
    fn link_options(&mut self, link: &str) {
        let fragment = link.split_once('#').map_or(link, |(_, f)| f);
        for (key, value) in fragment.split('&').filter_map(|kv| kv.split_once('=')) {
            match key {
                "view" => {
                    let k = value.parse::<usize>().unwrap_or(0);
                    if let Some(&v) = k.checked_sub(1).and_then(|k| View::ALL.get(k)) {
                        self.show_view(v);
                    }
                }
                "speed" => match value {
                    "max" => self.time.set_speed(Speed::Max),
                    f => {
                        if let Ok(f) = f.parse::<f64>()
                            && f.is_finite()
                            && f > 0.0
                        {
                            self.time.set_speed(Speed::Factor(f));
                        }
                    }
                },
                _ => {}
            }
        }
    }

    /// Open, Save As and the exports in a browser: the browser's picker
    /// and downloads for presets, a download for the run's CSV; the other
    /// exports need the desktop app.
    pub(super) fn browser_file(&mut self, action: FileAction, stem: &str) {
        match action {
            FileAction::Open => web::pick_preset(),
            FileAction::SaveAs => {
                let mut out = self.doc.scene.clone();
                out.description = crate::scene::described_with_edits(
                    &self.doc.scene.description,
                    &self.doc.saved.name,
                    &self.edits(),
                );
                let name = format!("{stem}.ron");
                web::download(&name, out.to_ron_string().into_bytes());
                self.undo
                    .described(&self.doc.scene.description, &out.description);
                self.doc.scene.description = out.description;
                self.doc.saved = self.doc.scene.clone();
                self.info(format!("{name} offered as a download"));
            }
            // re-run in slices within the frames, then downloaded
            FileAction::ExportCsv => self.export_csv(PathBuf::from(format!("{stem}.csv"))),
            _ => self.not_in_browser(action.title()),
        }
    }

    /// What a browser page cannot do, in the banner.
    pub(super) fn not_in_browser(&mut self, what: &str) {
        self.error(format!(
            "{what}: not in the browser. {}",
            web::BROWSER_LIMITS
        ));
    }

    /// The preset the browser's picker read, as a command.
    pub(super) fn poll_picked(&self) -> Option<Command> {
        let (name, bytes) = web::take_picked()?;
        Some(Command::OpenText {
            text: String::from_utf8_lossy(&bytes).into_owned(),
            name,
        })
    }

    /// The link of the last Share, if any.
    pub fn shared_link(&self) -> Option<&str> {
        self.handles.shared_link.as_deref()
    }

    /// Makes the link of the current scene; the frame copies it.
    pub(super) fn share(&mut self) {
        let base = web::page_address().unwrap_or_else(|| share::DEFAULT_BASE_URL.to_string());
        let view = View::ALL.iter().position(|&v| v == self.view).unwrap_or(0) + 1;
        match share::link(&self.doc.scene, &base).map(|l| format!("{l}&view={view}")) {
            Ok(link) => {
                web::show_link(&link);
                let place = if web::IN_BROWSER {
                    "it is also in the address bar"
                } else {
                    "it opens in the visualiser's web page: put the page's address before `#`"
                };
                self.info(format!(
                    "Link to \"{}\" copied ({} characters); {place}.",
                    self.doc.scene.name,
                    link.len()
                ));
                self.handles.shared_link = Some(link);
                self.handles.copy_link = true;
            }
            Err(e) => self.error(format!("Share refused: {e}")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn share_makes_the_link_of_the_scene_and_opening_it_restores_the_scene() {
        let mut app = App::with_default_preset();
        let mut scene = app.scene().clone();
        scene.speed_mps = 17.0;
        scene.name = "Faster".into();
        app.apply(Command::EditScene(Box::new(scene.clone())));
        app.apply(Command::Share);
        let link = app.shared_link().expect("a link").to_string();
        assert!(link.starts_with("index.html#scene=v2."), "{link}");
        assert!(!app.message().unwrap().error, "{:?}", app.message());
        assert!(link.ends_with("&view=1"), "{link}");
        let opened = App::open_link(&link, None);
        assert_eq!(opened.scene().speed_mps, 17.0);
        assert_eq!(opened.scene().name, "Faster");
        assert!(!opened.is_dirty());
        assert!(opened.message().unwrap().text.contains("from the link"));
        assert_eq!(opened.view(), View::TimePlots);
        // the view and a speed in the fragment
        let opened = App::open_link(&format!("{link}&view=2&speed=max"), None);
        assert_eq!(opened.view(), View::Scene);
        assert_eq!(opened.time_control().speed(), Speed::Max);
        let opened = App::open_link(&format!("{link}&view=10&speed=-1"), None);
        assert_eq!(opened.view(), View::TimePlots);
        assert_eq!(opened.time_control().speed(), Speed::watchable(0.2));
        let opened = App::open_link(&format!("{link}&speed=0.5"), None);
        assert_eq!(opened.time_control().speed(), Speed::Factor(0.5));
    }

    #[test]
    fn a_measured_road_is_not_shared_and_a_broken_link_says_why() {
        let mut app = App::with_default_preset();
        let mut scene = app.scene().clone();
        scene.road = crate::model::road::Road::Measured {
            file: "road.csv".into(),
            looped: true,
        };
        app.doc.scene = scene;
        app.apply(Command::Share);
        assert!(app.shared_link().is_none());
        let m = app.message().unwrap();
        assert!(
            m.error && m.text.contains("reads its measured road from road.csv"),
            "{m:?}"
        );

        let app = App::open_link("index.html#scene=v1.%%%", None);
        let m = app.message().unwrap();
        assert!(
            m.error
                && m.text
                    .starts_with("This link is damaged or cut short (it holds `%`"),
            "{m:?}"
        );
        assert_eq!(app.scene().name, default_scene().name);
        // a link cut short: refused, the last session kept
        let mut maker = App::with_default_preset();
        maker.apply(Command::Share);
        let link = maker.shared_link().unwrap().to_string();
        let cut = &link[..link.len() / 2];
        let app = App::open_link(cut, None);
        let m = app.message().unwrap();
        assert!(
            m.error
                && m.text.starts_with("This link is damaged or cut short (")
                && m.text
                    .ends_with("use File > Share link in the visualiser to make a new one."),
            "{m:?}"
        );
        assert_eq!(app.scene(), &default_scene());
        // no scene in the fragment: the last session (here none: the default)
        let app = App::open_link("index.html#view=scene", None);
        assert_eq!(app.scene(), &default_scene());
    }
}
