//! The shipped contact-patch presets against the scaling study's patch of
//! their size: each preset run as shipped (its own tyre, road, tread and
//! duration) and lifted off the road, and [`patch_scene`] with the same
//! grid and number of modes over the same duration, timed one after the
//! other in one process. Their ratio says whether a preset runs at the
//! rate the study reports for its size; the points on the road, which set
//! the contact's cost, are given beside it. Each preset is also measured
//! against its smooth twin ([`smooth_twin`]: the same scene on a gentle
//! sine road), which prices its events: what one located event costs in
//! event-free steps, beside the speed goals ([`GOALS`]).
//!
//! The small shipped presets (one line of points) are timed per step too
//! ([`measure_steps`], [`steps_markdown`]), so that a slower step of a
//! small scene shows.

use super::{Regime, ScalingRow, Timing, fastest_run, measure_scene, patch_scene};
use crate::analysis::bench::BenchError;
use crate::output::patch::PatchLayout;
use tirecontact_core::model::road::Road;
use tirecontact_io::identify::PreparedModel;
use tirecontact_io::scene::Scene;

/// The road of a preset's smooth twin: a 0.1 mm sine of 0.3 m wavelength,
/// on which a pressed patch stays on the road.
pub const TWIN_ROAD: Road = Road::Sine {
    amplitude_m: 1e-4,
    wavelength_m: 0.3,
};

/// The speed goals the tables are read against.
pub const GOALS: [&str; 3] = [
    "one located event ≤ 1 event-free step",
    "chip seal ≤ 2.5× its smooth twin per step",
    "every shipped patch ≥ 0.4× real time at dt = 1e-5 s on one core",
];

/// Largest cost of one located event (event-free steps), goal 1.
pub const GOAL_EVENT_STEPS: f64 = 1.0;
/// Largest step of the chip seal over its smooth twin's, goal 2.
pub const GOAL_CHIP_SEAL_RATIO: f64 = 2.5;
/// Smallest real-time factor of a patch at [`GOAL_DT_S`] on one thread,
/// goal 3.
pub const GOAL_REAL_TIME: f64 = 0.4;
/// The time step (s) of goal 3.
pub const GOAL_DT_S: f64 = 1e-5;

/// `scene` on [`TWIN_ROAD`]: the same tyre, points, tread, speed, ramp,
/// step and duration, the events of a rough road gone.
pub fn smooth_twin(scene: &Scene) -> Scene {
    let mut twin = scene.clone();
    twin.road = TWIN_ROAD;
    twin.name = format!("{} (smooth twin)", scene.name);
    twin
}

/// What one located event costs in event-free steps:
/// `(step − twin step) / (events per step − twin's) / twin step`, from
/// wall times or instruction counts per step; `None` where the two have
/// the same events per step (or the result is not finite).
pub fn event_cost_steps(
    step_preset: f64,
    step_twin: f64,
    events_per_step_preset: f64,
    events_per_step_twin: f64,
) -> Option<f64> {
    let events = events_per_step_preset - events_per_step_twin;
    if events == 0.0 {
        return None;
    }
    let cost = (step_preset - step_twin) / events / step_twin;
    cost.is_finite().then_some(cost)
}

/// callgrind's count of a scene's rolling steps: the difference of two
/// runs past the ramp, over the steps between.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Counted {
    /// Instructions per rolling step.
    pub instructions_per_step: f64,
    /// Located events per step over the same rolling steps.
    pub events_per_step: f64,
}

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
    /// The preset's smooth twin ([`smooth_twin`]).
    pub twin: ScalingRow,
    /// The preset's rolling steps counted by callgrind, where counted.
    pub preset_counted: Option<Counted>,
    /// The same of the twin.
    pub twin_counted: Option<Counted>,
    /// The duration (s) the preset was cut to before it was timed
    /// (`--quick`: its ramp and a few ms past it), `None` when timed whole.
    /// A cut run is mostly the ramp's landings: its real-time factor is not
    /// the preset's, and the real-time goal is not read from it.
    pub cut_to_s: Option<f64>,
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

    /// The preset's wall time per step over its smooth twin's.
    pub fn twin_ratio(&self) -> f64 {
        self.preset.step_s / self.twin.step_s
    }

    /// The same by instructions per rolling step, where both are counted.
    pub fn twin_ratio_instructions(&self) -> Option<f64> {
        Some(self.preset_counted?.instructions_per_step / self.twin_counted?.instructions_per_step)
    }

    /// What one located event costs in event-free steps, by wall time
    /// ([`event_cost_steps`]).
    pub fn event_cost_steps(&self) -> Option<f64> {
        event_cost_steps(
            self.preset.step_s,
            self.twin.step_s,
            self.preset.events_per_step,
            self.twin.events_per_step,
        )
    }

    /// The same by instructions per rolling step, over the events of the
    /// counted steps, where both are counted.
    pub fn event_cost_steps_instructions(&self) -> Option<f64> {
        let (preset, twin) = (self.preset_counted?, self.twin_counted?);
        event_cost_steps(
            preset.instructions_per_step,
            twin.instructions_per_step,
            preset.events_per_step,
            twin.events_per_step,
        )
    }
}

/// Measures `scene` (a patch: at least two rows across and two points
/// along), the study's patch of its size and the scene's smooth twin
/// ([`smooth_twin`]), the fastest of `timing.repeats` runs each.
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
        twin: measure_scene(&smooth_twin(scene), modes, Regime::Patch, timing)?,
        preset_counted: None,
        twin_counted: None,
        cut_to_s: None,
    })
}

/// `v` with `decimals`, or `-` where not measured.
fn or_dash(v: Option<f64>, decimals: usize) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{v:.decimals$}"))
}

/// `yes` or `no`.
fn met(ok: bool) -> &'static str {
    if ok { "yes" } else { "no" }
}

/// The markdown tables of measured presets: against the study's patch,
/// against the smooth twin, and the goals.
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
    s.push_str(&twin_markdown(rates));
    s.push_str(&goals_markdown(rates, timing));
    s
}

/// The table of each preset against its smooth twin.
fn twin_markdown(rates: &[PresetRate]) -> String {
    let counted = rates.iter().any(|r| r.preset_counted.is_some());
    let mut s = format!(
        "\n## Against the smooth twin: what the events cost\n\n\
         Each preset's smooth twin is the same scene (tyre, points, tread, speed, ramp, step and \
         duration) on a 0.1 mm sine road of 0.3 m wavelength, timed the same way. Columns: \
         *events/step*, located events (landings and releases) per step of the preset and of \
         the twin; *µs/step*, wall time per step (µs/step); *preset / twin*, the preset's \
         time per step over the twin's; *one event (event-free steps)*, what one located event \
         costs in steps of the twin, `(step − twin step) / (events/step − twin events/step) / \
         twin step` (`-` where both have the same events per step). The same by callgrind's \
         instructions per rolling step (M instructions/step: the count of a run to the ramp's \
         end + 0.02 s less that of a run to its end + 0.01 s, over the steps between), which \
         repeat exactly where wall times vary, with the events per step of those counted steps \
         (*counted events/step*, events/step); {}.\n\n\
         | preset | events/step | twin events/step | µs/step | twin (µs/step) | preset / twin | one event (event-free steps) | M instructions/step | counted events/step | twin (M instructions/step) | twin counted events/step | preset / twin, instructions | one event by instructions (event-free steps) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        if counted {
            "counted here"
        } else {
            "`-` here: not counted (valgrind not installed, or `--quick`)"
        }
    );
    for r in rates {
        s.push_str(&format!(
            "| {} | {:.3} | {:.3} | {:.1} | {:.1} | {:.2} | {} | {} | {} | {} | {} | {} | {} |\n",
            r.name,
            r.preset.events_per_step,
            r.twin.events_per_step,
            1e6 * r.preset.step_s,
            1e6 * r.twin.step_s,
            r.twin_ratio(),
            or_dash(r.event_cost_steps(), 2),
            or_dash(r.preset_counted.map(|c| c.instructions_per_step / 1e6), 3),
            or_dash(r.preset_counted.map(|c| c.events_per_step), 3),
            or_dash(r.twin_counted.map(|c| c.instructions_per_step / 1e6), 3),
            or_dash(r.twin_counted.map(|c| c.events_per_step), 3),
            or_dash(r.twin_ratio_instructions(), 2),
            or_dash(r.event_cost_steps_instructions(), 2),
        ));
    }
    s
}

/// The goals ([`GOALS`]) beside the measured numbers: by instructions
/// where counted, by wall time otherwise.
fn goals_markdown(rates: &[PresetRate], timing: Timing) -> String {
    let mut s = String::from(
        "\n## Goals\n\n\
         Each goal beside its number: the event cost and the ratio to the twin by instructions \
         where counted (else by wall time), the real-time factor by wall time (simulated s per \
         wall s).\n\n\
         | goal | preset | measured | met |\n|---|---|---|---|\n",
    );
    for r in rates {
        let (cost, by) = match r.event_cost_steps_instructions() {
            Some(c) => (Some(c), "instructions"),
            None => (r.event_cost_steps(), "wall time"),
        };
        s.push_str(&format!(
            "| {} | {} | {} event-free steps ({by}) | {} |\n",
            GOALS[0],
            r.name,
            or_dash(cost, 2),
            cost.map_or("-", |c| met(c <= GOAL_EVENT_STEPS)),
        ));
    }
    let chip: Vec<&PresetRate> = rates
        .iter()
        .filter(|r| r.name.to_lowercase().contains("chip seal"))
        .collect();
    if chip.is_empty() {
        s.push_str(&format!("| {} | (not measured) | - | - |\n", GOALS[1]));
    }
    for r in chip {
        let (ratio, by) = match r.twin_ratio_instructions() {
            Some(q) => (q, "instructions"),
            None => (r.twin_ratio(), "wall time"),
        };
        s.push_str(&format!(
            "| {} | {} | {ratio:.2}× ({by}) | {} |\n",
            GOALS[1],
            r.name,
            met(ratio <= GOAL_CHIP_SEAL_RATIO),
        ));
    }
    for r in rates {
        let comparable = r.dt_s == GOAL_DT_S && timing.threads == 1;
        s.push_str(&format!(
            "| {} | {} | {:.3}× | {} |\n",
            GOALS[2],
            r.name,
            r.real_time(),
            match r.cut_to_s {
                Some(cut_s) => format!(
                    "- (timed to {cut_s:.3} s only, mostly the ramp's landings: the goal is read on \
                     the whole preset, without --quick)"
                ),
                None if comparable => met(r.real_time() >= GOAL_REAL_TIME).to_string(),
                None => format!("- (dt = {:e} s on {} thread(s))", r.dt_s, timing.threads),
            },
        ));
    }
    s
}

/// A small preset's cost per step.
#[derive(Debug, Clone, PartialEq)]
pub struct PresetSteps {
    pub name: String,
    pub points: usize,
    pub modes: usize,
    pub dt_s: f64,
    pub steps: u64,
    /// Wall time per step (s), the fastest run.
    pub step_s: f64,
    /// Located events per step.
    pub events_per_step: f64,
    /// Instructions per rolling step (callgrind), where counted.
    pub instructions_per_step: Option<f64>,
}

impl PresetSteps {
    /// Simulated time per wall time.
    pub fn real_time(&self) -> f64 {
        self.dt_s / self.step_s
    }
}

/// Times `scene` as given (its duration), the fastest of `timing.repeats`
/// runs, set-up excluded.
pub fn measure_steps(scene: &Scene, timing: Timing) -> Result<PresetSteps, BenchError> {
    let (wall_s, sim) = fastest_run(scene, timing)?;
    let st = sim.stats();
    let steps = st.steps.max(1);
    Ok(PresetSteps {
        name: scene.name.clone(),
        points: sim.num_points(),
        modes: sim.problem().modes.len(),
        dt_s: scene.dt_s,
        steps,
        step_s: wall_s / steps as f64,
        events_per_step: st.events as f64 / steps as f64,
        instructions_per_step: None,
    })
}

/// The markdown table of [`measure_steps`]' rows.
pub fn steps_markdown(rows: &[PresetSteps], timing: Timing) -> String {
    let mut s = format!(
        "## Small shipped presets: cost per step\n\n\
         Each preset as shipped, the fastest of {} runs on {} thread(s), set-up excluded. \
         Columns: *steps*, steps of the timed run; *µs/step*, wall time per step (µs/step); \
         *events/step*, located events per step; *real time*, simulated s per wall s; \
         *instructions/step*, callgrind's instructions per rolling step (the count \
         of a run to the ramp's end + 0.21 s less that of a run to its end + 0.01 s, over the \
         steps between; `-` where not counted: valgrind not installed, or `--quick`).\n\n\
         | preset | points | modes | dt (s) | steps | µs/step | events/step | real time | instructions/step |\n\
         |---|---|---|---|---|---|---|---|---|\n",
        timing.repeats, timing.threads,
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {} | {} | {:e} | {} | {:.3} | {:.4} | {:.2}× | {} |\n",
            r.name,
            r.points,
            r.modes,
            r.dt_s,
            r.steps,
            1e6 * r.step_s,
            r.events_per_step,
            r.real_time(),
            or_dash(r.instructions_per_step, 0),
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

    /// The smooth twin keeps the grid, step and duration and takes the
    /// sine road; the ratio and the cost of an event follow from the
    /// measured rows, by wall time and by instructions, and a cost over
    /// no difference in events is `-`.
    #[test]
    fn a_preset_is_priced_against_its_smooth_twin() {
        let mut scene = patch_scene(4, 3, 12, Regime::Tread);
        scene.name = "small".into();
        scene.duration_s = 0.004;
        let twin = smooth_twin(&scene);
        assert_eq!(twin.points, scene.points);
        assert_eq!(
            (twin.dt_s, twin.duration_s, twin.ramp_s),
            (scene.dt_s, scene.duration_s, scene.ramp_s)
        );
        assert_eq!(twin.contact, scene.contact);
        assert_eq!(
            twin.road,
            Road::Sine {
                amplitude_m: 0.0001,
                wavelength_m: 0.3
            }
        );
        let one = Timing {
            repeats: 1,
            threads: 1,
        };
        let mut r = measure_preset(&scene, one).unwrap();
        assert_eq!(r.twin.steps, r.preset.steps);
        assert_eq!((r.twin.points, r.twin.modes), (12, 12));
        assert!(r.twin.step_s > 0.0);
        // by hand from the rows
        r.preset.step_s = 30e-6;
        r.twin.step_s = 10e-6;
        r.preset.events_per_step = 1.5;
        r.twin.events_per_step = 0.5;
        r.preset_counted = Some(Counted {
            instructions_per_step: 4e6,
            events_per_step: 1.25,
        });
        r.twin_counted = Some(Counted {
            instructions_per_step: 1e6,
            events_per_step: 0.25,
        });
        assert!((r.twin_ratio() - 3.0).abs() < 1e-12);
        // (30 − 10) µs / (1.5 − 0.5) events / 10 µs = 2 steps an event
        assert!((r.event_cost_steps().unwrap() - 2.0).abs() < 1e-12);
        assert_eq!(r.twin_ratio_instructions(), Some(4.0));
        // (4 − 1) M / (1.25 − 0.25) counted events / 1 M = 3 steps an event
        assert_eq!(r.event_cost_steps_instructions(), Some(3.0));
        let md = markdown(std::slice::from_ref(&r), one);
        let row = |md: &str| {
            md.lines()
                .find(|l| l.starts_with("| small | 1.500 |"))
                .unwrap_or_else(|| panic!("{md}"))
                .to_string()
        };
        assert_eq!(
            row(&md),
            "| small | 1.500 | 0.500 | 30.0 | 10.0 | 3.00 | 2.00 | 4.000 | 1.250 | 1.000 | 0.250 | 4.00 | 3.00 |"
        );
        assert!(md.contains(GOALS[0]) && md.contains(GOALS[1]) && md.contains(GOALS[2]));
        assert!(
            md.contains(&format!(
                "| {} | small | 3.00 event-free steps (instructions) | no |",
                GOALS[0]
            )),
            "{md}"
        );
        // the same events per step: no cost to divide
        r.twin.events_per_step = 1.5;
        r.twin_counted = None;
        assert_eq!(r.event_cost_steps(), None);
        assert_eq!(r.event_cost_steps_instructions(), None);
        assert_eq!(event_cost_steps(2.0, 1.0, 0.25, 0.25), None);
        r.twin_counted = Some(Counted {
            instructions_per_step: 1e6,
            events_per_step: 1.25,
        });
        assert_eq!(r.event_cost_steps_instructions(), None);
        r.twin_counted = None;
        let md = markdown(std::slice::from_ref(&r), one);
        assert_eq!(
            row(&md),
            "| small | 1.500 | 1.500 | 30.0 | 10.0 | 3.00 | - | 4.000 | 1.250 | - | - | - | - |"
        );
        // the real-time goal: read at dt = 1e-5 s on one thread (30 µs a
        // step: 0.333×), never from a run cut short
        r.dt_s = GOAL_DT_S;
        let goal = |md: &str| {
            md.lines()
                .find(|l| l.starts_with(&format!("| {} | small |", GOALS[2])))
                .unwrap_or_else(|| panic!("{md}"))
                .to_string()
        };
        let whole = markdown(std::slice::from_ref(&r), one);
        assert_eq!(
            goal(&whole),
            format!("| {} | small | 0.333× | no |", GOALS[2])
        );
        r.cut_to_s = Some(0.06);
        let cut = goal(&markdown(std::slice::from_ref(&r), one));
        assert!(cut.contains("0.333× | - (timed to 0.060 s only"), "{cut}");
    }

    /// A small scene's steps are timed and tabled, instructions `-` where
    /// not counted.
    #[test]
    fn a_small_preset_is_timed_per_step() {
        let mut scene = crate::analysis::bench::scenes::many_points(3, 4);
        scene.name = "line".into();
        scene.duration_s = 0.002;
        let one = Timing {
            repeats: 1,
            threads: 1,
        };
        let mut r = measure_steps(&scene, one).unwrap();
        assert_eq!((r.points, r.modes), (3, 4));
        assert!(r.steps >= 199 && r.step_s > 0.0, "{r:?}");
        let md = steps_markdown(std::slice::from_ref(&r), one);
        let row = md
            .lines()
            .find(|l| l.starts_with("| line |"))
            .unwrap_or_else(|| panic!("{md}"));
        assert!(row.ends_with("| - |"), "{row}");
        r.instructions_per_step = Some(12_345.0);
        let md = steps_markdown(&[r], one);
        assert!(md.contains("| 12345 |"), "{md}");
    }
}
