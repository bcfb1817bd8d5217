//! Read-only views of the run: time plots, the scene, the Green functions.
//! They read the scene, the simulation and the history; the only state they
//! change is their own presentation options (window, exaggeration, ...).

pub mod compare_view;
pub mod fidelity_view;
pub mod green_view;
pub mod scene_view;
pub mod spectra_view;
pub mod sweep_view;
pub mod time_plots;

use egui::Color32;

/// Okabe-Ito colour-blind-friendly palette (same order as the PNG figures).
pub const PALETTE: [Color32; 10] = [
    Color32::from_rgb(0, 114, 178),
    Color32::from_rgb(213, 94, 0),
    Color32::from_rgb(0, 158, 115),
    Color32::from_rgb(204, 121, 167),
    Color32::from_rgb(230, 159, 0),
    Color32::from_rgb(86, 180, 233),
    Color32::from_rgb(120, 120, 120),
    Color32::from_rgb(240, 228, 66),
    Color32::from_rgb(140, 86, 75),
    Color32::from_rgb(60, 60, 160),
];

/// Colour of point `i` in every view.
pub fn point_color(i: usize) -> Color32 {
    PALETTE[i % PALETTE.len()]
}

/// Colour of a point in contact / in flight in the scene view.
pub const CONTACT_COLOR: Color32 = Color32::from_rgb(0, 158, 115);
pub const FLIGHT_COLOR: Color32 = Color32::from_rgb(213, 94, 0);
