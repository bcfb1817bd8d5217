//! `tirecontact bench --patch-presets`: the shipped contact-patch presets
//! beside the scaling study's patch of their size and beside their smooth
//! twins, read against the speed goals; `bench --presets-steps`: the small
//! shipped presets' cost per step. Both time in this process and, where
//! valgrind is installed (not with `--quick`), count instructions per
//! rolling step with callgrind in child processes of this executable
//! (`--preset-one PATH,SECONDS[,smooth]`).

use super::BenchArgs;
use super::scaling::{callgrind_available, callgrind_count};
use crate::cli::CliResult;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};
use tirecontact::analysis::bench::scaling::Timing;
use tirecontact::analysis::bench::scaling::presets;
use tirecontact::{PreparedModel, Scene, SolverOptions};

/// The small shipped presets of `--presets-steps`, relative to the
/// working folder.
const STEPS_PRESETS: [&str; 4] = [
    "presets/single_mode.ron",
    "presets/three_points.ron",
    "presets/paper.ron",
    "presets/random_road.ron",
];

/// The two run lengths past the ramp (s) whose callgrind counts differ by
/// the rolling steps between them: 1000 steps of a patch.
const COUNTED_PAST_RAMP_S: (f64, f64) = (0.01, 0.02);

/// [`COUNTED_PAST_RAMP_S`] for the small presets: 20 000 steps. Their
/// steps cost a few thousand instructions, and the set-up's heap (its
/// buffers sized by the run's length) differs between the two runs by
/// about 10^5 instructions: over 1000 steps that moved a step's count by
/// up to 6 % from one build to the next.
const SMALL_COUNTED_PAST_RAMP_S: (f64, f64) = (0.01, 0.21);

/// How each preset is timed: the fastest of 3 runs, one with `--quick`.
fn timing(args: &BenchArgs) -> Timing {
    Timing {
        repeats: if args.quick { 1 } else { 3 },
        threads: args.threads.into(),
    }
}

/// A progress bar over `len` presets.
fn preset_bar(len: usize) -> ProgressBar {
    let bar = ProgressBar::new(len as u64);
    bar.set_style(
        ProgressStyle::with_template("{elapsed} [{bar:30}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar
}

/// Loads a preset to time: with `--quick`, cut to 10 ms past its ramp;
/// and whether it was cut.
fn load_timed(path: &Path, quick: bool) -> Result<(Scene, bool), Box<dyn std::error::Error>> {
    let mut scene = Scene::load(path)?;
    let shipped_s = scene.duration_s;
    if quick {
        scene.duration_s = scene.duration_s.min(scene.ramp_s + 0.01);
    }
    let cut = scene.duration_s < shipped_s;
    Ok((scene, cut))
}

/// callgrind's instructions per rolling step of the preset at `path` (its
/// smooth twin with `smooth`), and its located events per step over the
/// same steps: the count of a run to `ramp_s + window.1` s less that of a
/// run to `ramp_s + window.0` s (set-up and ramp cancel), over the steps
/// between. `None`, with a warning, where a run counted nothing.
fn counted(
    exe: &Path,
    path: &Path,
    scene: &Scene,
    smooth: bool,
    window: (f64, f64),
    threads: u16,
    bar: &ProgressBar,
) -> Option<presets::Counted> {
    let (short_s, long_s) = window;
    let kind = if smooth { "smooth twin" } else { "as shipped" };
    let count = |past_s: f64| {
        let to_s = scene.ramp_s + past_s;
        bar.set_message(format!(
            "callgrind: {}, {kind}, to {to_s:.3} s",
            path.display()
        ));
        let child = [
            "--preset-one".to_string(),
            format!(
                "{},{to_s}{}",
                path.display(),
                if smooth { ",smooth" } else { "" }
            ),
            "--threads".to_string(),
            threads.to_string(),
        ];
        let what = format!("{}, {kind}", path.display());
        let n = callgrind_count(exe, &child, &what, bar).and_then(|(n, printed)| {
            // the child prints its located events
            match printed.trim().parse::<f64>() {
                Ok(events) => Some((n, events)),
                Err(_) => {
                    bar.println(format!(
                        "warning: {what}: expected the run's events on stdout, got `{}`",
                        printed.trim()
                    ));
                    None
                }
            }
        });
        bar.inc(1);
        n
    };
    let steps = ((long_s - short_s) / scene.dt_s).round().max(1.0);
    let long = count(long_s);
    let short = count(short_s);
    let ((long_n, long_events), (short_n, short_events)) = (long?, short?);
    Some(presets::Counted {
        instructions_per_step: (long_n - short_n) / steps,
        events_per_step: (long_events - short_events) / steps,
    })
}

/// The child of a callgrind count: loads the preset `PATH`, on its smooth
/// twin's road with `smooth`, runs it to `SECONDS` and prints its number
/// of located events, nothing else.
pub fn preset_one(spec: &str, threads: usize) -> CliResult {
    let bad = |why: String| {
        format!(
            "--preset-one {spec}: {why}: expected PATH,SECONDS[,smooth], e.g. presets/patch_chip_seal.ron,0.07,smooth"
        )
    };
    let (rest, smooth) = match spec.rsplit_once(',') {
        Some((rest, last)) if last.trim() == "smooth" => (rest, true),
        _ => (spec, false),
    };
    let (path, seconds) = rest
        .rsplit_once(',')
        .ok_or_else(|| bad("no duration".into()))?;
    let duration_s = seconds
        .trim()
        .parse::<f64>()
        .ok()
        .filter(|d| d.is_finite() && *d > 0.0)
        .ok_or_else(|| {
            bad(format!(
                "duration `{seconds}` is not a positive number of seconds"
            ))
        })?;
    let mut scene = Scene::load(Path::new(path))?;
    if smooth {
        scene = presets::smooth_twin(&scene);
    }
    scene.duration_s = duration_s;
    let model = PreparedModel::of(&scene).map_err(|e| format!("{path}: {e}"))?;
    let mut sim = model.simulation(SolverOptions {
        threads,
        ..SolverOptions::default()
    })?;
    tirecontact::solver::drive::run_to_end(
        &mut sim,
        &mut (),
        tirecontact::solver::drive::Watch::none(),
    )?;
    println!("{}", sim.stats().events);
    Ok(())
}

/// The patch presets to measure: those given, or the shipped
/// `presets/patch_*.ron`.
fn patch_paths(args: &BenchArgs) -> Result<Vec<PathBuf>, Box<dyn std::error::Error>> {
    if !args.presets.is_empty() {
        return Ok(args.presets.clone());
    }
    let mut found: Vec<_> = std::fs::read_dir("presets")
        .map_err(|e| {
            format!("presets/: {e}: run from the repository's folder or name the presets")
        })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("patch_") && n.ends_with(".ron"))
        })
        .collect();
    found.sort();
    if found.is_empty() {
        return Err(
            "no patch preset found (presets/patch_*.ron): name the presets to measure".into(),
        );
    }
    Ok(found)
}

/// The shipped patch presets (or those given) against the study's patch
/// of their size and against their smooth twins, in this process, one
/// after the other, then callgrind's counts where valgrind is installed
/// ([`tirecontact::analysis::bench::scaling::presets`]).
pub fn patch_presets(args: &BenchArgs) -> CliResult {
    crate::cli::paths::ensure_output_dir("-o", &args.output)?;
    let paths = patch_paths(args)?;
    let timing = timing(args);
    let bar = preset_bar(paths.len());
    let mut scenes = Vec::with_capacity(paths.len());
    let mut rates = Vec::with_capacity(paths.len());
    for path in &paths {
        bar.set_message(path.display().to_string());
        let (scene, cut) = load_timed(path, args.quick)?;
        let mut rate = presets::measure_preset(&scene, timing)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        rate.cut_to_s = cut.then_some(scene.duration_s);
        rates.push(rate);
        scenes.push(scene);
        bar.inc(1);
    }
    if callgrind_available(args.quick) {
        let exe = std::env::current_exe()?;
        // two runs each of the preset and of its twin
        bar.set_length(4 * paths.len() as u64);
        bar.set_position(0);
        for ((path, scene), rate) in paths.iter().zip(&scenes).zip(&mut rates) {
            let window = COUNTED_PAST_RAMP_S;
            rate.preset_counted = counted(&exe, path, scene, false, window, args.threads, &bar);
            rate.twin_counted = counted(&exe, path, scene, true, window, args.threads, &bar);
        }
    }
    bar.finish_and_clear();
    let md = presets::markdown(&rates, timing);
    super::write(&args.output.join("patch_presets.md"), &md)?;
    println!("{md}");
    println!("wrote {}/patch_presets.md", args.output.display());
    Ok(())
}

/// The small presets to time: those given, or the shipped ones
/// ([`STEPS_PRESETS`]), every one of which must be found.
fn steps_paths(args: &BenchArgs) -> Result<Vec<PathBuf>, Box<dyn std::error::Error>> {
    if !args.presets.is_empty() {
        return Ok(args.presets.clone());
    }
    let missing: Vec<&str> = STEPS_PRESETS
        .iter()
        .copied()
        .filter(|p| !Path::new(p).exists())
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "{} not found from {}: run from the repository's folder or name the presets",
            missing.join(", "),
            std::env::current_dir().map_or("here".into(), |d| d.display().to_string())
        )
        .into());
    }
    Ok(STEPS_PRESETS.iter().map(PathBuf::from).collect())
}

/// The small shipped presets (or those given): µs per step in this
/// process, then callgrind's instructions per rolling step where valgrind
/// is installed (preset_steps.md).
pub fn presets_steps(args: &BenchArgs) -> CliResult {
    crate::cli::paths::ensure_output_dir("-o", &args.output)?;
    let paths = steps_paths(args)?;
    let timing = timing(args);
    let bar = preset_bar(paths.len());
    let mut scenes = Vec::with_capacity(paths.len());
    let mut rows = Vec::with_capacity(paths.len());
    for path in &paths {
        bar.set_message(path.display().to_string());
        let (scene, _) = load_timed(path, args.quick)?;
        rows.push(
            presets::measure_steps(&scene, timing)
                .map_err(|e| format!("{}: {e}", path.display()))?,
        );
        scenes.push(scene);
        bar.inc(1);
    }
    if callgrind_available(args.quick) {
        let exe = std::env::current_exe()?;
        bar.set_length(2 * paths.len() as u64);
        bar.set_position(0);
        for ((path, scene), row) in paths.iter().zip(&scenes).zip(&mut rows) {
            let window = SMALL_COUNTED_PAST_RAMP_S;
            row.instructions_per_step =
                counted(&exe, path, scene, false, window, args.threads, &bar)
                    .map(|c| c.instructions_per_step);
        }
    }
    bar.finish_and_clear();
    let md = presets::steps_markdown(&rows, timing);
    super::write(&args.output.join("preset_steps.md"), &md)?;
    println!("{md}");
    println!("wrote {}/preset_steps.md", args.output.display());
    Ok(())
}
