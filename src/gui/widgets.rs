//! Widgets of the editing panels: numeric fields that refuse bad values
//! with the reason, and what each field means.

pub mod field_help;
pub mod fields;
pub mod number;
