//! The visualiser, driven headless with egui_kittest (no window and no GPU:
//! the tests read egui's painted shapes and its accessibility tree).
//! Every module is one subject of the app; `harness` holds the shared
//! kittest set-up and the readers of painted shapes.
#![cfg(feature = "gui")]

#[allow(dead_code)] // each test binary uses a part of the shared helpers
#[path = "../support/mod.rs"]
mod support;

mod harness;

mod app;
mod classroom;
mod compare;
mod controls_by_pointer;
mod dialog_place;
mod edited_description;
mod editor_scroll;
mod field_help;
mod frames_export;
mod guidance;
mod identify_thread;
mod keyboard_prompts;
mod legends_clear;
mod mode_fields;
mod narrow_axes;
mod native_dialog;
mod panel_edge;
mod patch_panel;
mod patch_view;
mod phone;
mod phone_touch;
mod research;
mod run_ahead;
mod save_as;
mod scene_view;
mod share_window;
mod status;
mod time_plots;
mod undo;
