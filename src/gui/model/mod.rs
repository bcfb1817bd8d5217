//! The visualiser's state without egui: commands, the play/pause/speed
//! control, the run's history, mode mutes, shipped presets and the frame
//! rate. Unit-tested without a window.

pub mod command;
pub mod frame_rate;
pub mod history;
pub mod mute_set;
pub mod presets;
pub mod time_control;
