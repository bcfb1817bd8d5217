//! The stacked time plots and their PNG export: shared time axis, legends
//! off the curves, and the clipping of impact spikes (both contact schemes).

mod axes_align;
mod contact_lanes;
mod export_clip;
mod export_layout;
mod header_notes;
mod legend_ink;
mod legends;
mod paper_clip;
mod patch_export;
mod run_fit;
mod solid_curves;
mod time_labels;
