//! `tirecontact sweep PRESET --param PATH --from A --to B --steps N [-o sweep.csv] [--plot sweep.png]`.

use super::CliResult;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::time::Instant;
use tirecontact::studies::sweep::{
    MAX_SWEEP_VALUES, Sweep, get_param, linspace, report, run_sweep, set_param,
};
use tirecontact::{Scene, SceneError};

#[derive(Debug, clap::Args)]
// (a negative value reaches validation, which names the field, not clap's "unexpected argument")
#[command(allow_negative_numbers = true)]
pub struct SweepArgs {
    /// Scene preset (RON). Without it, the embedded default preset.
    pub preset: Option<PathBuf>,
    /// Path of the numeric scene field to sweep, e.g. `speed_mps`,
    /// `road.amplitude_m`, `points[2].h_m`, `points[*].h_m` (all points),
    /// `tyre.modes[0].freq_hz`, `tyre.ring.inflation_pa`; a grid's
    /// `points.along`, `points.across` (whole numbers), `points.spacing_m.0`,
    /// `points.preload.depth_m`.
    #[arg(long)]
    pub param: String,
    /// First value, in the unit the parameter's name carries (m/s for
    /// `speed_mps`, Hz for `freq_hz`, m for `h_m`).
    #[arg(long, allow_hyphen_values = true, value_parser = super::values::parse_value)]
    pub from: f64,
    /// Last value (may be below --from: the values then decrease).
    #[arg(long, allow_hyphen_values = true, value_parser = super::values::parse_value)]
    pub to: f64,
    /// Number of values, evenly spaced, both ends included.
    #[arg(long, default_value_t = 10, allow_hyphen_values = true, value_parser = super::values::parse_count_usize)]
    pub steps: usize,
    /// Write the table (one row per value) to this CSV.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Draw max force, force RMS, contact fraction and band levels to this PNG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Worker threads; default all cores.
    #[arg(long, allow_hyphen_values = true, value_parser = super::values::parse_count_usize)]
    pub threads: Option<usize>,
    /// Override the time step (s) of every run.
    #[arg(long, allow_hyphen_values = true, value_parser = super::values::parse_seconds)]
    pub dt: Option<f64>,
    /// Override the duration (s) of every run.
    #[arg(long, allow_hyphen_values = true, value_parser = super::values::parse_seconds)]
    pub duration: Option<f64>,
}

fn base_scene(args: &SweepArgs) -> Result<Scene, SceneError> {
    super::load_with_overrides(args.preset.as_deref(), args.dt, args.duration)
}

pub fn sweep(args: &SweepArgs) -> CliResult {
    let scene = base_scene(args)?;
    // `--param " speed_mps "` (a quoted path with spaces) names speed_mps
    let param = args.param.trim();
    // output folders before any run (a missing one failed after all of them)
    if let Some(path) = &args.output {
        super::paths::check_output_file("-o", path, "CSV")?;
    }
    if let Some(path) = &args.plot {
        super::paths::check_output_file("--plot", path, "PNG")?;
    }
    // check the path (and the range ends) before any run
    get_param(&scene, param)?;
    for v in [args.from, args.to] {
        set_param(&mut scene.clone(), param, v)?;
    }
    let threads = match args.threads {
        Some(0) => return Err("--threads = 0: expected at least 1 thread".into()),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    if args.steps > MAX_SWEEP_VALUES {
        return Err(format!(
            "--steps = {}: expected 1 to {MAX_SWEEP_VALUES} values (each value is one run of the scene)",
            args.steps
        )
        .into());
    }
    let sweep = Sweep {
        param: param.to_string(),
        values: linspace(args.from, args.to, args.steps)?,
        threads,
    };
    let bar = ProgressBar::with_draw_target(Some(1), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {percent}% {msg} (eta {eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(format!(
        "{} of {} on {}",
        tirecontact::output::count(sweep.values.len(), "run"),
        param,
        tirecontact::output::count(threads, "thread")
    ));
    let start = Instant::now();
    let cancel = AtomicBool::new(false);
    let progress = |done: u64, total: u64| {
        bar.set_length(total);
        bar.set_position(done);
    };
    let cache = tirecontact::ModeCache::new();
    let points = run_sweep(&scene, &sweep, &cache, &progress, &cancel)?;
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();
    let columns = report::Columns::of(&scene, &[param]);
    if let Some(path) = &args.output {
        let mut buf = Vec::new();
        report::write_csv(&mut buf, param, &points, &columns)?;
        tirecontact::fsio::write_atomic(path, &buf)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    if let Some(path) = &args.plot {
        let fig = report::figure(
            &format!(
                "{}: sweep of {}",
                scene.name,
                tirecontact::scene::fields::label(param)
            ),
            &format!(
                "base scene: {}",
                super::run::scene_summary(&scene, &cache.modes(&scene)?)
            ),
            param,
            &points,
            &columns,
        );
        let (w, h) = report::FIGURE_PX;
        tirecontact::output::figures::render_png(&fig, path, w, h)?;
        eprintln!("wrote {}", path.display());
    }
    let failed: Vec<String> = points
        .iter()
        .filter_map(|pt| {
            pt.result
                .as_ref()
                .err()
                .map(|e| format!("{param} = {}: {e}", pt.value))
        })
        .collect();
    for f in &failed {
        eprintln!("run failed: {f}");
    }
    println!(
        "{}: {} of {} from {} to {} on {} in {wall:.3} s wall ({} failed)",
        scene.name,
        tirecontact::output::count(points.len(), "run"),
        param,
        args.from,
        args.to,
        tirecontact::output::count(threads, "thread"),
        failed.len()
    );
    if failed.len() == points.len() {
        return Err("every run of the sweep failed".into());
    }
    Ok(())
}
