//! The visualiser's state without egui: commands and the data they carry
//! (a sweep's request and end, what a preparation made ready), the
//! play/pause/speed control, the run's history, mode mutes, shipped and
//! guided presets, the frame rate and the undo stacks of scene edits. Unit-tested without a window.

pub mod command;
pub mod frame_rate;
pub mod history;
pub mod mute_set;
pub mod prepared;
pub mod presets;
pub mod sweep_request;
pub mod time_control;
pub mod undo;
