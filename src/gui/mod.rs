//! The visualiser (feature `gui`): edit a scene, play it, watch it, save it,
//! export plots and runs.
//!
//! Data flow is one way: `Scene` → `Simulation` (stepped within a per-frame
//! time budget, so the UI stays responsive however slow the solver) →
//! `History` → views. Panels push `Command`s; `App::apply` is the only place
//! that changes state; views only read.

pub mod app;
pub mod banner_text;
pub mod classroom;
pub mod command;
pub mod dialogs;
pub mod export;
pub mod field_help;
pub mod fields;
pub mod file_prompt;
pub mod frame_rate;
pub mod frames;
pub mod guided;
pub mod history;
pub mod identify_job;
pub mod jobs;
pub mod mutes;
pub mod native_dialog;
pub mod panels;
pub mod presets;
pub mod research;
pub mod status_bar;
pub mod time_control;
pub mod views;

pub use app::App;
pub use command::Command;
// The types of `Command`'s variants and of what `App` reports, at the root
// with `App` and `Command`: a caller (the GUI tests) drives and reads the app
// through these without knowing the module layout.
pub use command::{Discarding, View};
pub use history::{History, Quantity};
pub use research::ResearchCommand;
pub use research::sweep_job::SweepState;
pub use time_control::Speed;

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
