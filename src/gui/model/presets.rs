//! Presets shipped with the app: those of the Presets menu (inside the
//! binary, and on the desktop those reading a file beside them, from a
//! `presets/` folder), and the guided tour's (classroom mode) pairs of presets that differ in one thing
//! (tyre stiffness, damping, speed, road wavelength), each with a
//! description of what to watch, shown large in classroom mode.

/// `(menu name, file name, RON text)` of every shipped preset.
pub const SHIPPED: &[(&str, &str, &str)] = &[
    (
        "Single mode on a sine road",
        "single_mode.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/single_mode.ron"
        )),
    ),
    (
        "Three points",
        "three_points.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/three_points.ron"
        )),
    ),
    (
        "Paper: ring tyre, five points",
        "paper.ron",
        include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/paper.ron")),
    ),
    (
        "Three points on a random road (ISO 8608 class C)",
        "random_road.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/random_road.ron"
        )),
    ),
    (
        "Patch on a road texture (plate tyre, 96 points)",
        "patch_texture.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/patch_texture.ron"
        )),
    ),
];

/// `(menu name, file name)` of the shipped presets that read a file beside
/// them (a road or a tyre's): listed in the desktop's Presets menu when a
/// `presets/` folder holds them ([`shipped_with_files_path`]), and opened
/// from there (so that their files are found).
pub const SHIPPED_WITH_FILES: &[(&str, &str)] = &[
    (
        "Patch on a chip seal (surface file, 96 points)",
        "patch_chip_seal.ron",
    ),
    (
        "Patch across a wheel path (surface file, 96 points)",
        "patch_wheel_path.ron",
    ),
    (
        "Patch on a Belgian block track (OpenCRG file)",
        "patch_belgian_block.ron",
    ),
    (
        "Measured: five points from a UFF file",
        "measured_example.ron",
    ),
    ("FE modes of a plate (UFF file)", "fe_plate.ron"),
];

/// The path of a [`SHIPPED_WITH_FILES`] preset: the first of
/// [`preset_dirs`] that holds it.
pub fn shipped_with_files_path(file: &str) -> Option<std::path::PathBuf> {
    preset_dirs()
        .into_iter()
        .map(|dir| dir.join(file))
        .find(|p| p.is_file())
}

/// Where the presets that read files are looked for, in order: a `presets/`
/// folder beside the executable (an installed copy and its presets), one in
/// the working folder, then the repository's the program was built from.
pub fn preset_dirs() -> Vec<std::path::PathBuf> {
    let beside = std::env::current_exe()
        .ok()
        .and_then(|exe| exe.parent().map(|d| d.join("presets")));
    let here = std::env::current_dir().ok().map(|d| d.join("presets"));
    let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    beside.into_iter().chain(here).chain([repo]).collect()
}

/// `(menu name, file name, RON text)` of every guided preset, in tour order.
pub const GUIDED: &[(&str, &str, &str)] = &[
    (
        "1a Soft tyre",
        "guided_1a_soft_tyre.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/guided_1a_soft_tyre.ron"
        )),
    ),
    (
        "1b Stiff tyre",
        "guided_1b_stiff_tyre.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/guided_1b_stiff_tyre.ron"
        )),
    ),
    (
        "2a Low damping",
        "guided_2a_low_damping.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/guided_2a_low_damping.ron"
        )),
    ),
    (
        "2b High damping",
        "guided_2b_high_damping.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/guided_2b_high_damping.ron"
        )),
    ),
    (
        "3a Slow rolling",
        "guided_3a_slow.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/guided_3a_slow.ron"
        )),
    ),
    (
        "3b Fast rolling",
        "guided_3b_fast.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/guided_3b_fast.ron"
        )),
    ),
    (
        "4a Long road wavelength",
        "guided_4a_long_wavelength.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/guided_4a_long_wavelength.ron"
        )),
    ),
    (
        "4b Short road wavelength",
        "guided_4b_short_wavelength.ron",
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/guided_4b_short_wavelength.ron"
        )),
    ),
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scene;

    #[test]
    fn every_guided_preset_parses_and_explains() {
        for (name, file, text) in GUIDED {
            let s = Scene::parse(text, file).unwrap_or_else(|e| panic!("{file}: {e}"));
            let sentences = s.description.matches(". ").count() + 1;
            assert!(
                (2..=5).contains(&sentences),
                "{name}: {sentences} sentences"
            );
            assert!(s.description.contains("atch"), "{name}: says what to watch");
        }
        // every file of presets/guided_* is in the tour
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
        let on_disk = std::fs::read_dir(dir)
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .file_name()
                    .to_string_lossy()
                    .starts_with("guided_")
            })
            .count();
        assert_eq!(on_disk, GUIDED.len());
    }

    /// An installed copy's presets (beside the executable) come before the
    /// working folder's and the repository's the program was built from.
    #[test]
    fn presets_beside_the_executable_come_first() {
        let dirs = preset_dirs();
        let exe_dir = std::env::current_exe()
            .unwrap()
            .parent()
            .unwrap()
            .to_path_buf();
        assert_eq!(dirs[0], exe_dir.join("presets"));
        assert_eq!(
            dirs.last().unwrap(),
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets")
        );
        assert_eq!(dirs.len(), 3, "{dirs:?}");
    }

    /// Every preset of the repository's `presets/` folder is in a menu:
    /// built in, guided, or opened from the folder (those reading a file
    /// beside them), and each of the latter opens with its file.
    #[test]
    fn every_shipped_preset_is_in_a_menu_and_opens() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
        let listed: Vec<&str> = SHIPPED
            .iter()
            .map(|(_, f, _)| *f)
            .chain(GUIDED.iter().map(|(_, f, _)| *f))
            .chain(SHIPPED_WITH_FILES.iter().map(|(_, f)| *f))
            .collect();
        for entry in std::fs::read_dir(&dir).unwrap() {
            let name = entry.unwrap().file_name().into_string().unwrap();
            if name.ends_with(".ron") {
                assert!(listed.contains(&name.as_str()), "{name} is in no menu");
            }
        }
        for (_, file) in SHIPPED_WITH_FILES {
            let path = shipped_with_files_path(file).expect(file);
            if let Err(e) = Scene::load(&path) {
                panic!("{}: {e}", path.display());
            }
        }
    }
}
