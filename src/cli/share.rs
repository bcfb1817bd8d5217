//! `tirecontact share PRESET [--base-url URL]`: prints the link that opens
//! the preset's scene in the visualiser's web page (`scene::share`).

use super::{CliResult, load_scene};
use std::path::Path;
use tirecontact::scene::share;

pub fn share(path: &Path, base_url: &str) -> CliResult {
    let scene = load_scene(Some(path))?;
    let link = share::link(&scene, base_url).map_err(|e| format!("{}: {e}", path.display()))?;
    println!("{link}");
    Ok(())
}
