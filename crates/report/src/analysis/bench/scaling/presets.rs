//! The shipped contact-patch presets against the scaling study's patch of
//! their size: each preset run as shipped (its own tyre, road, tread and
//! duration) and lifted off the road, and [`patch_scene`] with the same
//! grid and number of modes over the same duration, timed one after the
//! other in one process. Their ratio says whether a preset runs at the
//! rate the study reports for its size; the points on the road, which set
//! the contact's cost, are given beside it.

use super::{Regime, ScalingRow, Timing, measure_scene, patch_scene};
use crate::analysis::bench::BenchError;
use crate::output::patch::PatchLayout;
use tirecontact_io::identify::PreparedModel;
use tirecontact_io::scene::Scene;

/// A preset's rate beside the study's patch of its size.
#[derive(Debug, Clone, PartialEq)]
pub struct PresetRate {
    pub name: String,
    /// The grid: points along the rolling direction and rows across.
    pub along: usize,
    pub across: usize,
    pub dt_s: f64,
    /// The preset as shipped, with contact and off the road.
    pub preset: ScalingRow,
    /// The study's patch of the same grid and modes ([`patch_scene`]).
    pub study: ScalingRow,
}

impl PresetRate {
    /// The preset's wall time per step over the study patch's.
    pub fn ratio(&self) -> f64 {
        self.preset.step_s / self.study.step_s
    }

    /// Simulated time per wall time.
    pub fn real_time(&self) -> f64 {
        self.dt_s / self.preset.step_s
    }
}

/// Measures `scene` (a patch: at least two rows across and two points
/// along) and the study's patch of its size, the fastest of
/// `timing.repeats` runs each.
pub fn measure_preset(scene: &Scene, timing: Timing) -> Result<PresetRate, BenchError> {
    let layout = PatchLayout::of(scene)?;
    let across = layout.rows_y_m.len();
    let along = scene.num_points() / across;
    let modes = PreparedModel::of(scene)?.modes().len();
    let preset = measure_scene(scene, modes, Regime::Patch, timing)?;
    let mut study = patch_scene(along, across, modes, Regime::Tread);
    study.duration_s = scene.duration_s;
    study.dt_s = scene.dt_s;
    Ok(PresetRate {
        name: scene.name.clone(),
        along,
        across,
        dt_s: scene.dt_s,
        preset,
        study: measure_scene(&study, modes, Regime::Patch, timing)?,
    })
}

/// The markdown table of measured presets.
pub fn markdown(rates: &[PresetRate], timing: Timing) -> String {
    let mut s = format!(
        "## Shipped patch presets against the study's patch of their size\n\n\
         Each preset as shipped, then the scaling study's patch (`patch_scene`: the same grid \
         and number of modes, rank-1 modes, a sine road) over the same duration and step, in \
         one process; the fastest of {} runs each on {} thread(s), set-up excluded.\n\n\
         | preset | grid | modes | µs/step | off the road (µs/step) | on the road | events/step | factorisations/step | study patch (µs/step) | study on the road | study events/step | preset / study | real time |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        timing.repeats, timing.threads,
    );
    for r in rates {
        s.push_str(&format!(
            "| {} | {} × {} | {} | {:.1} | {:.1} | {:.0} % | {:.3} | {:.3} | {:.1} | {:.0} % | {:.3} | {:.2} | {:.3}× |\n",
            r.name,
            r.along,
            r.across,
            r.preset.modes,
            1e6 * r.preset.step_s,
            1e6 * r.preset.free_step_s,
            100.0 * r.preset.on_road,
            r.preset.events_per_step,
            r.preset.factorisations_per_step,
            1e6 * r.study.step_s,
            100.0 * r.study.on_road,
            r.study.events_per_step,
            r.ratio(),
            r.real_time(),
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small patch is measured against the study's scene of the same
    /// grid and modes; a line of points is refused as no patch.
    #[test]
    fn a_preset_is_measured_beside_the_study_patch_of_its_size() {
        let mut scene = patch_scene(4, 3, 12, Regime::Tread);
        scene.name = "small".into();
        scene.duration_s = 0.004;
        let one = Timing {
            repeats: 1,
            threads: 1,
        };
        let r = measure_preset(&scene, one).unwrap();
        assert_eq!((r.along, r.across, r.preset.modes), (4, 3, 12));
        assert_eq!(r.study.points, 12);
        assert_eq!(r.preset.steps, r.study.steps);
        // the same scene both ways: the same points on the road
        assert_eq!(r.preset.on_road, r.study.on_road, "{r:?}");
        assert!(r.preset.on_road > 0.0 && r.preset.step_s > 0.0 && r.ratio().is_finite());
        let md = markdown(&[r], one);
        assert!(md.contains("| small | 4 × 3 | 12 |"), "{md}");
        let line = crate::analysis::bench::scenes::many_points(3, 4);
        assert!(matches!(
            measure_preset(&line, one),
            Err(BenchError::Patch(_))
        ));
    }
}
