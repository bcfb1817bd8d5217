//! The shipped patch presets in the work-precision study: cut to a few
//! points and a short run, on their own tread springs.

use super::Config;
use tirecontact_io::scene::{Contact, Points, Scene};

/// How a patch preset is cut for the default study: the middle `along` ×
/// `across` points of its grid and a shorter ramp (s), so that a run of a
/// few hundredths of a second rolls on the road pressed in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchCut {
    pub along: usize,
    pub across: usize,
    pub ramp_s: f64,
    /// The run's length (s).
    pub duration_s: f64,
}

impl PatchCut {
    /// The default study's cut: 6 × 2 points (30 mm along, 20 mm across,
    /// in the footprint's middle), a 5 ms ramp, 0.025 s.
    pub fn default_study() -> Self {
        PatchCut {
            along: 6,
            across: 2,
            ramp_s: 0.005,
            duration_s: 0.025,
        }
    }
}

/// `scene` (a patch preset: points on a `Grid(...)`) cut to `cut`: the
/// grid's spacing and preload kept, `along` × `across` points, its ramp
/// and run length those of the cut, its name saying the size. `None` when
/// the scene's points are not a grid or the cut is larger than it.
pub fn patch_scene(scene: &Scene, cut: &PatchCut) -> Option<Scene> {
    let grid = *scene.points.grid()?;
    if cut.along > grid.along || cut.across > grid.across || cut.along * cut.across == 0 {
        return None;
    }
    let mut s = scene.clone();
    s.points = Points::from_grid(tirecontact_io::scene::PointGrid {
        along: cut.along,
        across: cut.across,
        ..grid
    });
    s.ramp_s = cut.ramp_s;
    s.duration_s = cut.duration_s;
    s.name = format!(
        "{} ({} x {} points, {} s)",
        scene.name, cut.along, cut.across, cut.duration_s
    );
    Some(s)
}

/// The default study's patch row: `preset` (a patch preset) cut to
/// [`PatchCut::default_study`], or as shipped with `full`, and the study
/// of it, [`Config::patch`] over its run length. `None` when the preset's
/// points are not a grid large enough for the cut.
pub fn patch_study(preset: &Scene, full: bool) -> Option<(Scene, Config)> {
    let scene = if full {
        preset.clone()
    } else {
        patch_scene(preset, &PatchCut::default_study())?
    };
    let cfg = Config::patch(scene.duration_s);
    Some((scene, cfg))
}

/// Whether `scene` carries tread springs (`contact: Compliant`).
pub(super) fn has_tread_springs(scene: &Scene) -> bool {
    matches!(scene.contact, Contact::Compliant { .. })
}
