//! Headless command line: one file per subcommand.

pub mod bench;
pub mod check;
pub mod identify;
pub mod paths;
pub mod run;
pub mod share;
pub mod study;
pub mod sweep;
pub mod values;

use std::path::{Path, PathBuf};
use tirecontact::{DEFAULT_PRESET, DEFAULT_PRESET_NAME, Scene, SceneError};

/// Loads a preset file, or the embedded default when `path` is `None`.
pub fn load_scene(path: Option<&Path>) -> Result<Scene, SceneError> {
    match path {
        Some(p) => Scene::load(p),
        None => {
            let mut s = Scene::parse(DEFAULT_PRESET, DEFAULT_PRESET_NAME)?;
            s.base_dir = Some(PathBuf::from("presets"));
            Ok(s)
        }
    }
}

/// Loads a preset (or the embedded default), applies the `--dt` and
/// `--duration` overrides and validates the result.
pub fn load_with_overrides(
    path: Option<&Path>,
    dt_s: Option<f64>,
    duration_s: Option<f64>,
) -> Result<Scene, SceneError> {
    let mut scene = load_scene(path)?;
    if let Some(dt) = dt_s {
        scene.dt_s = dt;
    }
    if let Some(d) = duration_s {
        scene.duration_s = d;
    }
    let file = path.map_or("(embedded preset)".to_string(), |p| p.display().to_string());
    scene.validate().map_err(|errors| SceneError::Invalid {
        file,
        errors,
        at: Vec::new(),
    })?;
    Ok(scene)
}

/// A boxed error for the command line, printed as `error: ...`.
pub type CliResult = Result<(), Box<dyn std::error::Error>>;
