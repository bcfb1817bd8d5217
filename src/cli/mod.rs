//! Headless command line: one file per subcommand.

pub mod bench;
pub mod check;
pub mod identify;
pub mod run;
pub mod sweep;

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

/// A boxed error for the command line, printed as `error: ...`.
pub type CliResult = Result<(), Box<dyn std::error::Error>>;
