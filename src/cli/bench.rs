//! `tirecontact bench [-o DIR] [--quick] [PRESET...]`: the work-precision
//! study and the measured effect of each piece of skipped work.

mod presets;
mod scaling;

use super::{CliResult, load_scene};
use indicatif::{ProgressBar, ProgressStyle};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Duration;
use tirecontact::analysis::bench::work_precision::{self, Config};
use tirecontact::output::figures::render_png;
use tirecontact::{PreparedModel, Scene, SolverOptions};

#[derive(Debug, clap::Args)]
// (a negative value reaches validation, which names the field, not clap's "unexpected argument")
#[command(allow_negative_numbers = true)]
pub struct BenchArgs {
    /// Output folder for work_precision.csv, work_precision.md and the diagrams.
    #[arg(short, long, default_value = "bench-out")]
    pub output: PathBuf,
    /// A small study (under a second instead of about 2 min), without the
    /// large synthetic scene.
    #[arg(long)]
    pub quick: bool,
    /// Scenes to study (default: the shipped single-mode, three-point and
    /// paper presets, found from the repository's folder, a synthetic
    /// scene of 50 points on 200 modes, and the chip-seal patch cut to
    /// 6 × 2 points and 0.025 s with its tread springs, against BDF on the
    /// same springs).
    pub presets: Vec<PathBuf>,
    /// The default study's patch row at the chip-seal preset's full size
    /// (16 × 6 points, its 0.05 s ramp, 0.2 s) instead of its cut: the
    /// full patch's figure; 8 times the points and the run length of the
    /// cut, BDF's runs far longer.
    #[arg(long)]
    pub patch_full: bool,
    /// Instead of the work-precision study: the cost of a step against the
    /// number of points (5 to 400) and of modes (10 to 400), with rigid
    /// contact and with tread springs, and on a contact patch 20 points
    /// across (200 to 1000 points), each size timed in its own process
    /// (scaling.csv, .md, .png).
    #[arg(long)]
    pub scaling: bool,
    /// Instead of the work-precision study: each contact-patch preset
    /// (default: the shipped `presets/patch_*.ron`; or the presets given)
    /// timed as shipped and off the road, beside the scaling study's patch
    /// of the same grid and number of modes and beside its smooth twin (the
    /// same scene on a 0.1 mm sine road): the cost of one event in
    /// event-free steps, against the speed goals, by callgrind's
    /// instructions too where valgrind is installed (patch_presets.md).
    #[arg(long, conflicts_with = "scaling")]
    pub patch_presets: bool,
    /// Instead of the work-precision study: the small shipped presets
    /// (single mode, three points, paper, random road; or the presets
    /// given) timed per step, with callgrind's instructions per rolling
    /// step where valgrind is installed (preset_steps.md).
    #[arg(long, conflicts_with_all = ["scaling", "patch_presets"])]
    pub presets_steps: bool,
    /// Solver threads of each timed run of `--scaling`, `--patch-presets`
    /// and `--presets-steps` (results do not depend on them).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..=256))]
    pub threads: u16,
    /// One size of the scaling study, `P,K,CONTACT` with CONTACT `rigid`,
    /// `tread` or `patch` (the child process's job: its timed runs), or
    /// `P,K,CONTACT,SECONDS[,lifted]`: one run of that length, off the road
    /// with `lifted`, then the process's peak memory (what callgrind counts).
    #[arg(long, hide = true)]
    pub scaling_one: Option<String>,
    /// One run of a preset, `PATH,SECONDS[,smooth]`: loaded, on its smooth
    /// twin's road with `smooth`, run to SECONDS, its located events printed (what
    /// callgrind counts for `--patch-presets` and `--presets-steps`).
    #[arg(long, hide = true, conflicts_with = "scaling_one")]
    pub preset_one: Option<String>,
}

/// The scenes studied without preset arguments, relative to the working
/// folder.
const DEFAULT_PRESETS: [&str; 3] = [
    "presets/single_mode.ron",
    "presets/three_points.ron",
    "presets/paper.ron",
];

/// The patch preset of the default study's tread-spring row.
const DEFAULT_PATCH: &str = "presets/patch_chip_seal.ron";

/// The default study's patch row (`work_precision::patch_study`) of
/// [`DEFAULT_PATCH`]: its scene and configuration; `None` when the preset
/// is not found from the working folder.
fn default_patch(full: bool) -> Result<Option<(Scene, Config)>, Box<dyn std::error::Error>> {
    let path = Path::new(DEFAULT_PATCH);
    if !path.exists() {
        eprintln!(
            "bench: {DEFAULT_PATCH} not found from here: the study runs without its patch row"
        );
        return Ok(None);
    }
    let preset = load_scene(Some(path))?;
    Ok(Some(
        work_precision::patch_study(&preset, full).ok_or_else(|| {
            format!("{DEFAULT_PATCH}: its points are not a grid as large as the study's cut")
        })?,
    ))
}

/// The large scene of the default study: 50 points on 200 rank-1 modes
/// (40 Hz to 25 kHz).
fn large_scene() -> Scene {
    tirecontact::analysis::bench::scenes::many_points(50, 200)
}

fn default_presets() -> Vec<PathBuf> {
    DEFAULT_PRESETS
        .iter()
        .map(PathBuf::from)
        .filter(|p| p.exists())
        .collect()
}

pub fn bench(args: &BenchArgs) -> CliResult {
    if let Some(pk) = &args.scaling_one {
        return scaling::scaling_one(pk, args.quick, args.threads.into());
    }
    if args.scaling {
        return scaling::scaling(args);
    }
    if let Some(spec) = &args.preset_one {
        return presets::preset_one(spec, args.threads.into());
    }
    if args.patch_presets {
        return presets::patch_presets(args);
    }
    if args.presets_steps {
        return presets::presets_steps(args);
    }
    let presets = if args.presets.is_empty() {
        let found = default_presets();
        if found.len() < DEFAULT_PRESETS.len() {
            // run outside the repository: say what is studied instead
            eprintln!(
                "bench: {} of the shipped presets ({}) found from {}: {}; pass preset files, or run from the repository's folder",
                found.len(),
                DEFAULT_PRESETS.join(", "),
                std::env::current_dir().map_or("here".into(), |d| d.display().to_string()),
                if found.is_empty() {
                    "studying the embedded default preset (the paper's) only".to_string()
                } else {
                    format!(
                        "studying {}",
                        found
                            .iter()
                            .map(|p| p.display().to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                }
            );
        }
        found
    } else {
        args.presets.clone()
    };
    let scenes: Vec<Scene> = if presets.is_empty() {
        vec![load_scene(None)?]
    } else {
        presets
            .iter()
            .map(|p| load_scene(Some(p)))
            .collect::<Result<_, _>>()?
    };
    super::paths::ensure_output_dir("-o", &args.output)?;
    let cfg = if args.quick {
        Config::quick()
    } else {
        Config::standard()
    };
    let bar = ProgressBar::new_spinner();
    bar.set_style(
        ProgressStyle::with_template("{spinner} {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    bar.enable_steady_tick(Duration::from_millis(200));
    let mut rows = Vec::new();
    for scene in &scenes {
        rows.extend(work_precision::study(scene, &cfg, |m| {
            bar.set_message(m.to_string())
        })?);
    }
    // the shipped presets have at most five points: the default study
    // adds a large synthetic scene, on its own thinned sweep
    let large = (!args.quick && args.presets.is_empty()).then(large_scene);
    if let Some(scene) = &large {
        rows.extend(work_precision::study(scene, &Config::large(), |m| {
            bar.set_message(m.to_string())
        })?);
    }
    // a shipped patch with its tread springs, against BDF on the same springs
    let patch = if !args.quick && args.presets.is_empty() {
        default_patch(args.patch_full)?
    } else {
        None
    };
    if let Some((scene, cfg)) = &patch {
        rows.extend(work_precision::study(scene, cfg, |m| {
            bar.set_message(m.to_string())
        })?);
    }
    bar.set_message("skipped work, before/after");
    let skip = tirecontact::analysis::bench::skipped::skipped_work(
        &scenes,
        if args.quick { 1 } else { SKIP_REPEATS },
        if args.quick { 0.05 } else { 0.5 },
    )?;
    bar.set_message("residual flexibility");
    let residual = residual_flexibility(&scenes, args.quick)?;
    bar.finish_and_clear();
    let csv = work_precision::to_csv(&rows)?;
    write(&args.output.join("work_precision.csv"), &csv)?;
    let mut md = String::from("# Work-precision study\n\n");
    md.push_str(&work_precision::to_markdown(&rows));
    md.push('\n');
    md.push_str(&skip);
    md.push('\n');
    md.push_str(&residual);
    md.push('\n');
    md.push_str(&alpha_beta_overflow()?);
    md.push('\n');
    md.push_str(&speed(&scenes, args.quick)?);
    write(&args.output.join("work_precision.md"), &md)?;
    for scene in scenes
        .iter()
        .chain(&large)
        .chain(patch.as_ref().map(|(s, _)| s))
    {
        let name = file_stem(&scene.name);
        let fig = work_precision::figure(&rows, &scene.name);
        render_png(
            &fig,
            &args.output.join(format!("work_precision_{name}.png")),
            1200,
            1000,
        )?;
    }
    println!("{md}");
    println!(
        "wrote {}/work_precision.csv, work_precision.md and work_precision_*.png",
        args.output.display()
    );
    Ok(())
}

pub(super) fn write(path: &Path, text: &str) -> CliResult {
    tirecontact::fsio::write_atomic(path, text.as_bytes())
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(())
}

/// A file-name stem of a scene name: lower-case letters and digits, one `_`
/// for each run of anything else (`paper_ring_tyre_five_points_sine_road`,
/// was `paper__ring_tyre__…`).
fn file_stem(name: &str) -> String {
    let mut stem = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            stem.push(c.to_ascii_lowercase());
        } else if !stem.is_empty() && !stem.ends_with('_') {
            stem.push('_');
        }
    }
    stem.trim_end_matches('_').to_string()
}

/// Runs of each timed scene in the speed table (the median is reported).
const SPEED_REPEATS: usize = 9;

/// Runs of each side of a before/after timing of skipped work.
const SKIP_REPEATS: usize = 5;

/// Steps per second and real-time factor of each scene and of synthetic
/// larger ones (5 points x 20 modes, 50 points x 200 rank-1 modes).
fn speed(scenes: &[Scene], quick: bool) -> Result<String, Box<dyn std::error::Error>> {
    use tirecontact::analysis::bench::scenes::many_points;
    let mut list: Vec<Scene> = scenes.to_vec();
    list.push(many_points(5, 20));
    list.push(many_points(50, 200));
    let repeats = if quick { 3 } else { SPEED_REPEATS };
    let mut s = format!(
        "## Speed (release build, one core)\n\nEach scene run {repeats} times (`Simulation::new` not timed): the median run, and the slowest and fastest runs' real-time factors.\n\n| scene | points | modes | states | dt (s) | steps | wall, median (s) | steps/s | real-time factor, median | slowest – fastest | located events per step |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for mut sc in list {
        sc.duration_s = if quick { 0.02 } else { 0.2 };
        let model = PreparedModel::of(&sc)?;
        let (timing, sim) =
            work_precision::time_repeated(&model, SolverOptions::default(), repeats)?;
        let st = sim.stats();
        let wall = timing.median_s();
        writeln!(
            s,
            "| {} | {} | {} | {} | {:e} | {} | {wall:.4} | {:.3e} | {:.1} | {:.1} – {:.1} | {:.4} |",
            sc.name,
            sc.num_points(),
            model.modes().len(),
            sim.num_states(),
            sc.dt_s,
            st.steps,
            st.steps as f64 / wall,
            sim.time_s() / wall,
            sim.time_s() / timing.max_s(),
            sim.time_s() / timing.min_s(),
            st.events as f64 / st.steps.max(1) as f64
        )?;
    }
    Ok(s)
}

/// The α/β form against the stable form on a 4 kHz, ξ = 0.1 mode (method §3):
/// where the α/β form overflows, and the stable form's state there.
fn alpha_beta_overflow() -> Result<String, Box<dyn std::error::Error>> {
    use tirecontact::model::convolution::paper_alpha_beta::AlphaBeta;
    use tirecontact::model::convolution::{ModalBasis, ModalState, StepTable};
    let (f_hz, xi, dt) = (4000.0, 0.1, 1e-5);
    let omega = std::f64::consts::TAU * f_hz;
    let mut ab = AlphaBeta::new(omega, xi, dt);
    let mode = tirecontact::scene::Mode {
        freq_hz: f_hz,
        damping_ratio: xi,
        residue: vec![vec![1.0]],
        shape: vec![],
    };
    // a 1 x 1 residue: one state per source is its only rank term
    let basis = ModalBasis::per_source(&[mode], 1);
    let table = StepTable::new(&basis, dt);
    let (mut st, mut tmp) = (ModalState::zeros(&basis), ModalState::zeros(&basis));
    let n = 40_000; // 0.4 s
    let (mut first_bad, mut max_stable) = (None, 0.0f64);
    for k in 0..n {
        let q = (0.37 * k as f64).sin(); // a bounded force (N)
        let u = ab.step(q);
        if first_bad.is_none() && !u.is_finite() {
            first_bad = Some((k + 1) as f64 * dt);
        }
        st.predict_into(&table, &mut tmp);
        tmp.add_constant_forces(&basis, &table, &[q]);
        st.copy_from(&tmp);
        max_stable = max_stable.max(st.x[0].abs());
    }
    Ok(format!(
        "## Stability: 4 kHz mode, ξ = 0.1, dt = 1e-5 s, bounded force, 0.4 s\n\n| form | first non-finite displacement | largest |x| (m per N/kg) |\n|---|---|---|\n| paper α/β (predicted overflow at {:.3} s) | {} | - |\n| stable (this solver) | none | {max_stable:.3e} |\n",
        ab.overflow_time_s(),
        first_bad.map_or("none".to_string(), |t| format!("t = {t:.4} s"))
    ))
}

/// Residual flexibility, modes above f_c dropped: plain truncation and
/// truncation with the dropped modes' static compliance against the full
/// model, each scene at its own dt, plus the 5 x 20 synthetic scene.
fn residual_flexibility(
    scenes: &[Scene],
    quick: bool,
) -> Result<String, Box<dyn std::error::Error>> {
    use tirecontact::analysis::bench::residual;
    let mut list: Vec<Scene> = scenes.to_vec();
    list.push(tirecontact::analysis::bench::scenes::many_points(5, 20));
    // smooth: 25 Hz excitation below every mode, 400 N preload on a 0.1 mm
    // road, slow ramp; never leaves the road (tests/solver/residual_flexibility.rs)
    let smooth = tirecontact::analysis::bench::scenes::preloaded_three_points(
        0.05, 400.0, 1e-4, 5.0, 0.1, 1e-5, 0.2,
    );
    let duration_s = if quick { 0.05 } else { 0.2 };
    let mut rows = Vec::new();
    for sc in &list {
        let model = PreparedModel::of(sc)?;
        if let Some(fc) = residual::default_cutoff_hz(&model) {
            rows.extend(residual::residual_study(&model, fc, duration_s, 1e-3)?);
        }
    }
    // the smooth scene at the cut-off of its test (4 of 12 modes kept), its full run
    let smooth = PreparedModel::of(&smooth)?;
    rows.extend(residual::residual_study(&smooth, 150.0, 0.2, 1e-3)?);
    rows.extend(residual::residual_study(&smooth, 231.0, 0.2, 1e-3)?);
    let mut s = String::from(
        "## Residual flexibility, modes above f_c dropped\n\nThe upper half of the modes (above the median frequency f_c) dropped from the convolution: plain truncation, and truncation with the dropped modes' static compliance `Σ A_k / ω_k²` added to the contact (`SolverOptions::residual_above_hz`); errors against the full model at the same dt. With rigid contact the impact mass is `(Σ A_k)⁻¹` over the kept modes only, so impacts change in both variants: compare the located events. The static term has no mass: a landing on it takes no impulse (its velocity mismatch becomes the next sub-step's force rate), so both contact schemes agree; where points leave and land the model is softer than the full one. The last scene (always in contact) stays on the road with the full model (errors over its whole 0.2 s run, the 0.1 s ramp included); it is run at two cut-offs.\n\n",
    );
    s.push_str(&residual::to_markdown(&rows));
    Ok(s)
}

#[cfg(test)]
mod tests {
    #[test]
    fn file_stems_have_single_underscores() {
        assert_eq!(
            super::file_stem("Paper: ring tyre, five points, sine road"),
            "paper_ring_tyre_five_points_sine_road"
        );
        assert_eq!(
            super::file_stem("Single mode on a sine road"),
            "single_mode_on_a_sine_road"
        );
        assert_eq!(super::file_stem("  (x) 5 x 20!  "), "x_5_x_20");
    }
}
