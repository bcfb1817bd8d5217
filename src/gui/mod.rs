//! The visualiser (feature `gui`): edit a scene, play it, watch it, save it,
//! export plots and runs.
//!
//! Data flow is one way: `Scene` → `Simulation` (stepped within a per-frame
//! time budget, so the UI stays responsive however slow the solver) →
//! `History` → views. Panels push `Command`s; `App::apply` is the only place
//! that changes state; views only read.

pub mod app;
pub mod command;
pub mod dialogs;
pub mod export;
pub mod fields;
pub mod history;
pub mod panels;
pub mod presets;
pub mod time_control;
pub mod views;

pub use app::App;
pub use command::Command;

/// Opens the visualiser window on the last session, else the embedded
/// default preset.
pub fn run() -> eframe::Result {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("tirecontact")
            .with_inner_size([1500.0, 950.0])
            .with_min_inner_size([900.0, 600.0]),
        ..Default::default()
    };
    eframe::run_native(
        "tirecontact",
        options,
        Box::new(|cc| Ok(Box::new(App::restore(cc.storage)))),
    )
}
