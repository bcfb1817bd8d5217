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
pub use model::command::{Discarding, View};
pub use model::history::{History, Quantity};
pub use model::time_control::Speed;
pub use research::ResearchCommand;
pub use research::sweep_job::SweepState;

/// Opens the visualiser window on the last session, else the embedded
/// default preset.
pub fn run() -> eframe::Result {
    run_with_preset(None)
}

/// Opens the visualiser on `preset` (a broken file shows its error over the
/// default preset), or as [`run`] when `None`.
pub fn run_with_preset(preset: Option<std::path::PathBuf>) -> eframe::Result {
    run_with_options(preset, false)
}

/// [`run_with_preset`], starting in classroom mode when `classroom`.
pub fn run_with_options(preset: Option<std::path::PathBuf>, classroom: bool) -> eframe::Result {
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
            if classroom {
                app.apply(Command::SetClassroom(true));
            }
            Ok(Box::new(app))
        }),
    )
}
