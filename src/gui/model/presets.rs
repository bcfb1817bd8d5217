//! Presets shipped inside the binary, for the Presets menu.

/// `(menu name, file name, RON text)` of every shipped preset.
pub const SHIPPED: &[(&str, &str, &str)] = &[
    (
        "Single mode on a sine road",
        "single_mode.ron",
        include_str!("../../../presets/single_mode.ron"),
    ),
    (
        "Three points",
        "three_points.ron",
        include_str!("../../../presets/three_points.ron"),
    ),
    (
        "Paper: ring tyre, five points",
        "paper.ron",
        include_str!("../../../presets/paper.ron"),
    ),
    (
        "Three points on a random road (ISO 8608 class C)",
        "random_road.ron",
        include_str!("../../../presets/random_road.ron"),
    ),
];
