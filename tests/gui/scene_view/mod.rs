//! The scene view: the force arrows' value labels and legend entry, and the
//! displaced tyre line's contrast in both themes.

mod contrast;
mod force_label_tyre;
mod force_labels;
mod force_legend;
mod layout;
mod patch_rows;
mod phone_legend;
