//! The window's frame around the views: message banner, status bar,
//! confirmations, file prompts and the desktop file dialog, the animation
//! export's dialog, and the web page around the app in a browser.

pub mod banner_text;
pub mod dialogs;
pub mod file_prompt;
pub mod frames_dialog;
pub mod native_dialog;
pub mod status_bar;
pub mod web;
