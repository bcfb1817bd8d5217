//! The visualiser (feature `gui`): edit a scene, play it, watch it, save it,
//! export plots and runs.
//!
//! Data flow is one way: `Scene` → `Simulation` (stepped within a per-frame
//! time budget, so the UI stays responsive however slow the solver) →
//! `History` → views. Panels push `Command`s; `App::apply` is the only place
//! that changes state; views only read.

pub mod app;
pub mod chrome;
pub mod classroom;
pub mod jobs;
pub mod model;
pub mod panels;
pub mod research;
pub mod views;
pub mod widgets;

pub use app::App;
pub use model::command::Command;
// The types of `Command`'s variants and of what `App` reports, at the root
// with `App` and `Command`: a caller (the GUI tests) drives and reads the app
// through these without knowing the module layout.
pub use model::command::ResearchCommand;
pub use model::command::{Discarding, View};
pub use model::history::{History, Quantity};
pub use model::time_control::Speed;
pub use research::sweep_job::SweepState;

/// Opens the visualiser window on the last session, else the embedded
/// default preset.
#[cfg(not(target_arch = "wasm32"))]
pub fn run() -> eframe::Result {
    run_with_preset(None)
}

/// Opens the visualiser on `preset` (a broken file shows its error over the
/// default preset), or as [`run`] when `None`.
#[cfg(not(target_arch = "wasm32"))]
pub fn run_with_preset(preset: Option<std::path::PathBuf>) -> eframe::Result {
    run_with_options(preset, false)
}

/// [`run_with_preset`], starting in classroom mode when `classroom`.
#[cfg(not(target_arch = "wasm32"))]
pub fn run_with_options(preset: Option<std::path::PathBuf>, classroom: bool) -> eframe::Result {
    leave_a_core_to_the_solver();
    let mut options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("tirecontact")
            .with_inner_size([1500.0, 950.0])
            .with_min_inner_size([900.0, 600.0]),
        ..Default::default()
    };
    // Software GL (Xvfb, remote desktops) can block on vsync; allow turning it off.
    if std::env::var_os("TIRECONTACT_NO_VSYNC").is_some() {
        options.glow_options.vsync = false;
    }
    eframe::run_native(
        "tirecontact",
        options,
        Box::new(move |cc| {
            let app = match preset {
                Some(path) => App::open_at_start(&path),
                None => App::restore(cc.storage),
            };
            let mut app = app;
            if let Some(gl) = &cc.gl {
                use eframe::glow::HasContext;
                // SAFETY: a string query of the context eframe has just
                // made current on this thread
                let renderer = unsafe { gl.get_parameter_string(eframe::glow::RENDERER) };
                app.set_software_renderer(model::time_control::is_software_renderer(&renderer));
            }
            if classroom {
                app.apply(Command::SetClassroom(true));
            }
            Ok(Box::new(app))
        }),
    )
}

/// Software GL (Mesa's llvmpipe: Xvfb, remote desktops, machines without
/// a GPU driver) rasterises on as many threads as there are cores, while
/// "as fast as possible" steps the run on a thread of its own: on two
/// cores the three shared them and the run went at half its speed. Unless
/// the user set `LP_NUM_THREADS`, the renderer gets one thread fewer than
/// the cores (at least one); other GL drivers ignore the variable.
#[cfg(not(target_arch = "wasm32"))]
fn leave_a_core_to_the_solver() {
    if std::env::var_os("LP_NUM_THREADS").is_some() {
        return;
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    // SAFETY: called on the main thread before eframe starts, when no
    // other thread of the process reads or writes the environment.
    unsafe { std::env::set_var("LP_NUM_THREADS", cores.saturating_sub(1).max(1).to_string()) };
}

/// Starts the visualiser in the page's `canvas` (in a browser): on the
/// scene of the page's link (`#scene=…`) if it has one, else on the last
/// session kept in the browser's storage.
#[cfg(target_arch = "wasm32")]
pub async fn start_in_page(
    canvas: eframe::web_sys::HtmlCanvasElement,
) -> Result<(), eframe::wasm_bindgen::JsValue> {
    eframe::WebRunner::new()
        .start(
            canvas,
            eframe::WebOptions::default(),
            Box::new(|cc| {
                let link = chrome::web::page_fragment().unwrap_or_default();
                Ok(Box::new(App::open_link(&link, cc.storage)))
            }),
        )
        .await
}

/// The folders of `ARCHITECTURE.md`'s visualiser table: every folder
/// imports only from the folders below it (tests inside a file may import
/// anything).
#[cfg(test)]
mod layers {
    use std::collections::BTreeMap;
    use std::path::Path;

    /// The GUI's folders, highest first: each may import from those after
    /// it, never from those before it.
    const FOLDERS: &[&str] = &[
        "app",
        "classroom",
        "views",
        "research",
        "panels",
        "chrome",
        "widgets",
        "jobs",
        "model",
    ];

    fn place(folder: &str) -> Option<usize> {
        FOLDERS.iter().position(|f| *f == folder)
    }

    /// Code without its `#[cfg(test)]` items and its comment lines (the
    /// whole file is read: a test module in the middle hides nothing
    /// below it).
    use crate::layers::code;

    fn ident(text: &str) -> &str {
        let end = text
            .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == '*'))
            .unwrap_or(text.len());
        &text[..end]
    }

    /// The paths imported at `text`, each with its first name: `a::b;`
    /// gives `a::b` (`a`), `{a::b, c}` gives `a::b` (`a`) and `c` (`c`).
    fn paths(text: &str) -> Vec<(String, String)> {
        let path = |p: &str| {
            let p = p.split_whitespace().collect::<Vec<_>>().join(" ");
            let head = ident(&p).to_string();
            (p, head)
        };
        let Some(group) = text.strip_prefix('{') else {
            let mut end = text
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == '*' || c == ':'))
                .unwrap_or(text.len());
            // `a::{b, c}` is shown whole
            if text[end..].starts_with('{') {
                let mut depth = 0;
                for (k, c) in text[end..].char_indices() {
                    depth += match c {
                        '{' => 1,
                        '}' => -1,
                        _ => 0,
                    };
                    if depth == 0 {
                        end += k + 1;
                        break;
                    }
                }
            }
            return vec![path(text[..end].trim_end_matches(':'))];
        };
        let (mut depth, mut start, mut out) = (0, 0, Vec::new());
        for (k, c) in group.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth == 0 => {
                    out.push(path(&group[start..k]));
                    break;
                }
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    out.push(path(&group[start..k]));
                    start = k + 1;
                }
                _ => {}
            }
        }
        out.retain(|(_, head)| !head.is_empty() && head != "self");
        out
    }

    /// The names re-exported at the GUI's root (`gui.rs`), by folder.
    fn root_exports(root: &str) -> BTreeMap<String, String> {
        let mut out = BTreeMap::new();
        for line in code(root).lines() {
            let Some(path) = line.trim().strip_prefix("pub use ") else {
                continue;
            };
            let path = path.trim_end_matches(';');
            let folder = ident(path).to_string();
            let last = match path.find('{') {
                Some(k) => &path[k..],
                None => path.rsplit("::").next().unwrap_or(""),
            };
            let names = last.trim_matches(|c| c == '{' || c == '}');
            for name in names.split(',') {
                // `a::B as C` is known as `C`
                let name = name.rsplit(" as ").next().unwrap_or("").trim();
                let name = name.rsplit("::").next().unwrap_or("").trim();
                out.insert(name.to_string(), folder.clone());
            }
        }
        out
    }

    /// What a file `depth` modules below the GUI's root (`app.rs` 1,
    /// `app/run.rs` 2, `chrome.rs` 1) imports from the root: each
    /// `crate::gui::…` and each `super::…` that climbs to the root, as
    /// (the import as written, the name after the root).
    fn imports(text: &str, depth: usize) -> Vec<(String, String)> {
        let code = code(text);
        let mut out = Vec::new();
        let mut take = |at: usize, written: &str| {
            for (path, head) in paths(&code[at..]) {
                out.push((format!("{written}{path}"), head));
            }
        };
        for (k, _) in code.match_indices("crate::gui::") {
            take(k + "crate::gui::".len(), "crate::gui::");
        }
        let mut k = 0;
        while let Some(found) = code[k..].find("super::") {
            let start = k + found;
            let before = code[..start].chars().next_back();
            let mut end = start;
            let mut ups = 0;
            while code[end..].starts_with("super::") {
                end += "super::".len();
                ups += 1;
            }
            k = end;
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            if ups == depth {
                take(end, &"super::".repeat(ups));
            }
        }
        out
    }

    #[test]
    fn every_gui_folder_imports_only_from_folders_below_it() {
        let gui = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/gui");
        let exports = root_exports(&std::fs::read_to_string(gui.with_extension("rs")).unwrap());
        assert!(exports.contains_key("App"), "root re-exports not read");
        let mut files = Vec::new();
        crate::layers::sources(&gui, &mut files);
        let mut upward = Vec::new();
        let mut seen = 0;
        for file in &files {
            let rel = file.strip_prefix(&gui).unwrap();
            let mut modules: Vec<String> = rel
                .components()
                .map(|c| {
                    c.as_os_str()
                        .to_string_lossy()
                        .trim_end_matches(".rs")
                        .to_string()
                })
                .collect();
            if modules.last().is_some_and(|m| m == "mod") {
                modules.pop();
            }
            let Some(own) = modules.first() else {
                continue; // the root, above every folder
            };
            let shown = format!("src/gui/{}", rel.display());
            let own_place = place(own).unwrap_or_else(|| {
                panic!(
                    "{shown}: folder `{own}` has no place: add it to FOLDERS and ARCHITECTURE.md"
                )
            });
            let text = std::fs::read_to_string(file).unwrap();
            for (import, head) in imports(&text, modules.len()) {
                let target = match place(&head) {
                    Some(_) => head.clone(),
                    None => exports.get(&head).cloned().unwrap_or_else(|| {
                        panic!("{shown}: `{import}` names `{head}`, neither a folder nor re-exported at the root")
                    }),
                };
                let target_place = place(&target).unwrap();
                if target == *own {
                    continue;
                }
                seen += 1;
                if target_place < own_place {
                    upward.push(format!(
                        "{shown}: `{import}` imports from {target}/, above {own}/"
                    ));
                }
            }
        }
        assert!(
            seen > 100,
            "only {seen} imports across folders read: the scan is broken"
        );
        assert!(upward.is_empty(), "imports pointing up: {upward:#?}");
    }

    #[test]
    fn the_scan_sees_every_import_form() {
        let text = "use super::super::views::X;\nuse super::sibling::Y;\n\
                    use crate::gui::{app::App, model::command::{Command, View}};\n\
                    // crate::gui::panels\nfn f() { crate::gui::jobs::Job::spawn(); }\n\
                    use crate::gui::Speed;\n#[cfg(test)]\nmod tests { use crate::gui::app; }";
        let heads: Vec<String> = imports(text, 2).into_iter().map(|(_, h)| h).collect();
        assert_eq!(heads, ["app", "model", "jobs", "Speed", "views"]);
        let (import, _) = &imports("use super::research::state::X;", 1)[0];
        assert_eq!(import, "super::research::state::X");
        let (import, _) = &imports("use crate::gui::{app::{App,\n Message}};", 2)[0];
        assert_eq!(import, "crate::gui::app::{App, Message}");
        let (import, _) = &imports("use crate::gui::app::{App, Message};", 2)[0];
        assert_eq!(import, "crate::gui::app::{App, Message}");
        assert!(imports("use super::state::X;", 2).is_empty());
        let exports =
            root_exports("pub use app::App;\npub use model::command::{Discarding, View};");
        assert_eq!(exports["App"], "app");
        assert_eq!(exports["View"], "model");
    }

    #[test]
    fn architecture_md_lists_the_folders_in_this_order() {
        let doc =
            std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("ARCHITECTURE.md"))
                .unwrap();
        let section = doc
            .split("## The visualiser (`src/gui/`)")
            .nth(1)
            .expect("ARCHITECTURE.md has the visualiser's section");
        let listed: Vec<&str> = section
            .lines()
            .skip_while(|l| !l.starts_with('|'))
            .take_while(|l| l.starts_with('|'))
            .filter_map(|l| l.strip_prefix("| `"))
            .filter_map(|l| l.split("/`").next())
            .collect();
        assert_eq!(
            listed, FOLDERS,
            "ARCHITECTURE.md's visualiser table (left) and FOLDERS (right) differ"
        );
    }
}
