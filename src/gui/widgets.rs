//! Widgets of the editing panels: numeric fields that refuse bad values
//! with the reason, and what each field means; and the width below which
//! the window is laid out for a phone.

pub mod field_help;
pub mod fields;
pub mod number;

/// Below this window width (logical px: a phone) the editing panel hides
/// behind a button instead of covering the views, and the menu bar folds
/// into a few menus.
pub const NARROW_PX: f32 = 700.0;
