//! `tirecontact run PRESET [-o out.csv] [--dt S] [--duration S] [--every N]`.

use super::CliResult;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::time::{Duration, Instant};
use tirecontact::analysis::metrics::ContactMetrics;
use tirecontact::analysis::spectrum::Window;
use tirecontact::analysis::spectrum::run::{DEFAULT_BANDS_HZ, SteadyRecorder, scene_markers};
use tirecontact::output::animation::FramesError;
use tirecontact::output::csv::{self as csv_out, RunWriter};
use tirecontact::output::record::{FigureSpec, RunPanel};
use tirecontact::solver::drive::Watch;
use tirecontact::{PreparedModel, Scene, SceneError, Simulation};

#[derive(Debug, clap::Args)]
// (a negative value reaches validation, which names the field, not clap's "unexpected argument")
#[command(allow_negative_numbers = true)]
// options of an output given without it are refused, not silently ignored
#[command(group(clap::ArgGroup::new("spectra").args(["spectrum", "spectrum_plot"]).multiple(true)))]
pub struct RunArgs {
    /// Scene preset (RON). Without it, the embedded default preset.
    pub preset: Option<PathBuf>,
    /// Write the time histories to this CSV.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Override the time step (s).
    #[arg(long, allow_hyphen_values = true, value_parser = super::values::parse_seconds)]
    pub dt: Option<f64>,
    /// Override the duration (s).
    #[arg(long, allow_hyphen_values = true, value_parser = super::values::parse_seconds)]
    pub duration: Option<f64>,
    /// Write one CSV row every N steps (forces averaged over them).
    #[arg(long, default_value_t = 1, allow_hyphen_values = true, value_parser = super::values::parse_count, requires = "output")]
    pub every: u64,
    /// Also draw displacements and forces of every point to this PNG (impact
    /// spikes clipped a margin above the force without impacts and marked by
    /// dots; see --plot-unclipped).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Draw the impact spikes of the --plot force panel whole (impulse / dt:
    /// tens of kN, which squash the rolling force to a line).
    #[arg(long, requires = "plot")]
    pub plot_unclipped: bool,
    /// Refuse up front a run whose CSV (`-o`) would be larger than this
    /// (decimal GB; estimated as rows × columns × 17 bytes).
    #[arg(long, default_value_t = DEFAULT_MAX_OUTPUT_GB, allow_hyphen_values = true, value_parser = super::values::parse_gb)]
    pub max_output_gb: f64,
    /// Size of the --plot PNG, WIDTHxHEIGHT in pixels (also of the
    /// --spectrum-plot PNG, which is at least 1200 px high).
    #[arg(long, default_value = "1400x900", allow_hyphen_values = true, value_parser = parse_size)]
    pub plot_size: (u32, u32),
    /// Write force and displacement spectra of the steady part (from
    /// `ramp_s`, Hann window, dB re 1 N / 1 m) to this CSV, and their
    /// third-octave band levels to `<stem>_bands.csv` beside it.
    #[arg(long)]
    pub spectrum: Option<PathBuf>,
    /// Also draw the spectra, with the road excitation and modal frequencies
    /// marked, to this PNG.
    #[arg(long)]
    pub spectrum_plot: Option<PathBuf>,
    /// Start of the analysed steady part (s); default the ramp time `ramp_s`.
    #[arg(long, requires = "spectra", allow_hyphen_values = true, value_parser = super::values::parse_seconds)]
    pub spectrum_from: Option<f64>,
    /// Highest frequency of the spectrum CSV and figure (Hz).
    #[arg(long, default_value_t = 5000.0, requires = "spectra", allow_hyphen_values = true, value_parser = super::values::parse_hz)]
    pub spectrum_max_hz: f64,
    /// Write animation frames of the scene (frame_00000.png, …) into this folder.
    #[arg(long)]
    pub frames: Option<PathBuf>,
    /// Frames per second of the animation (Hz).
    #[arg(long, default_value_t = 25.0, requires = "frames", allow_hyphen_values = true, value_parser = super::values::parse_frame_rate)]
    pub fps: f64,
    /// Video seconds per simulated second (20 = 0.05x real time).
    #[arg(long, default_value_t = 20.0, requires = "frames", allow_hyphen_values = true, value_parser = super::values::parse_factor)]
    pub slow_motion: f64,
    /// First animated time (s).
    #[arg(long, default_value_t = 0.0, requires = "frames", allow_hyphen_values = true, value_parser = super::values::parse_seconds)]
    pub frames_from: f64,
    /// End of the animated interval (s); default the scene's duration.
    #[arg(long, requires = "frames", allow_hyphen_values = true, value_parser = super::values::parse_seconds)]
    pub frames_to: Option<f64>,
    /// Remove the frames of an earlier export from the --frames folder
    /// (without it, a folder holding frame_*.png is refused: old and new
    /// frames would mix).
    #[arg(long, requires = "frames")]
    pub frames_clear: bool,
    /// Size of the frames, WIDTHxHEIGHT in pixels.
    #[arg(long, default_value = "1280x720", allow_hyphen_values = true, value_parser = parse_size, requires = "frames")]
    pub frame_size: (u32, u32),
    /// Keep every rank term of an identified (ring tyre) model's residues
    /// (exact rank), instead of dropping those below 1e-5 of the largest
    /// (identification noise; results move by ~1e-6 of their size, 2.5x
    /// fewer states on the paper preset). Modes given in the scene are
    /// always used exactly.
    #[arg(long)]
    pub exact_rank: bool,
    /// Threads of the solver's large kernels (the projection of the
    /// points' values, the forces into the modal states, the set-up
    /// tables): they pay from about 6x10^4 points x modal states
    /// (1.4-1.7x on 2 threads from 10^5); smaller scenes run on one
    /// thread whatever the count. Results are bit-identical for any count.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true, value_parser = super::values::parse_count_usize)]
    pub threads: usize,
    /// Write the contact patch over time to this CSV: total contact force,
    /// contact area (points on the road × the cell Δx Δy) and force per row
    /// along the rolling direction; and the spectrum of the total force
    /// after the ramp (Hann window) to `<stem>_spectrum.csv` beside it.
    /// The points must make a patch (at least 2 rows across).
    #[arg(long)]
    pub patch_summary: Option<PathBuf>,
    /// Write one --patch-summary row every N steps (the spectrum's sample
    /// rate is 1 / (N dt)).
    #[arg(long, default_value_t = 1, allow_hyphen_values = true, value_parser = super::values::parse_count, requires = "patch_summary")]
    pub patch_every: u64,
    /// Write heat maps of the contact force over the patch (colour bar in
    /// N, axes in mm) into this folder, `patch_0000.png`, … evenly over the
    /// run.
    #[arg(long)]
    pub patch_frames: Option<PathBuf>,
    /// Number of --patch-frames heat maps.
    #[arg(long, default_value_t = 40, allow_hyphen_values = true, value_parser = super::values::parse_count_usize, requires = "patch_frames")]
    pub patch_frame_count: usize,
}

/// `--frames DIR`: the animation frames, before the run proper.
fn write_frames(model: &PreparedModel, args: &RunArgs) -> CliResult {
    let scene = model.scene();
    use std::sync::atomic::{AtomicBool, AtomicU64};
    use tirecontact::output::animation::{FrameSettings, export_frames};
    let Some(dir) = &args.frames else {
        return Ok(());
    };
    let settings = FrameSettings {
        t0_s: args.frames_from,
        t1_s: args.frames_to.unwrap_or(scene.duration_s),
        fps: args.fps,
        slow_motion: args.slow_motion,
        width: args.frame_size.0,
        height: args.frame_size.1,
    };
    settings.check(scene.duration_s).map_err(frames_error)?;
    let n = export_frames(
        model.simulation(tirecontact::SolverOptions::default())?,
        &scene.road,
        dir,
        &settings,
        args.frames_clear,
        &AtomicU64::new(0),
        &AtomicBool::new(false),
    )?;
    eprintln!(
        "wrote {n} frames ({}x{} px, {} fps, {}x slow motion) into {}",
        settings.width,
        settings.height,
        settings.fps,
        settings.slow_motion,
        dir.display()
    );
    Ok(())
}

/// A refusal of the frame settings, its field named as the option typed
/// (`fps = 0` -> `--fps = 0`).
fn frames_error(e: FramesError) -> String {
    const OPTIONS: [(&str, &str); 6] = [
        ("fps", "--fps"),
        ("slow_motion", "--slow-motion"),
        ("t0_s", "--frames-from"),
        ("t1_s", "--frames-to"),
        ("width", "--frame-size width"),
        ("height", "--frame-size height"),
    ];
    if let FramesError::Setting {
        field,
        value,
        expected,
    } = &e
        && let Some((_, option)) = OPTIONS.iter().find(|(f, _)| f == field)
    {
        return format!("--frames: {option} = {value}: expected {expected}");
    }
    format!("--frames: {e}")
}

/// `spectrum.csv` -> `spectrum_bands.csv` beside it.
pub fn bands_path(path: &std::path::Path) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or("spectrum".into(), |s| s.to_string_lossy().into_owned());
    path.with_file_name(format!("{stem}_bands.csv"))
}

/// Default budget of the CSV written by `run -o` (decimal GB): a larger
/// output is refused before anything is computed or written, naming the
/// estimate and the `--every` that fits. Runs without `-o` stream and keep
/// no history, whatever their length.
pub const DEFAULT_MAX_OUTPUT_GB: f64 = 20.0;

/// Refuses an output larger than the budget, with the estimate and a way out.
pub fn check_output_budget(scene: &Scene, args: &RunArgs) -> Result<(), String> {
    let budget_gb = args.max_output_gb;
    if !(budget_gb.is_finite() && budget_gb > 0.0) {
        return Err(format!(
            "--max-output-gb = {}: expected a finite size > 0 GB",
            tirecontact::base::error::fmt_num(budget_gb)
        ));
    }
    let Some(path) = &args.output else {
        return Ok(());
    };
    let (n, p) = (scene.num_steps(), scene.num_points());
    let est = csv_out::estimated_bytes(n, args.every, p);
    let budget = budget_gb * 1e9;
    if est > budget {
        let rows = n.div_ceil(args.every.max(1));
        let fit = (args.every as f64 * est / budget).ceil();
        // the smallest output (one row every n steps) may already be over it
        let how = if csv_out::estimated_bytes(n, n, p) > budget {
            format!(
                "a larger budget: the smallest output (--every {n}) is {}: raise --max-output-gb",
                csv_out::human_bytes(csv_out::estimated_bytes(n, n, p))
            )
        } else {
            format!(
                "a smaller output: write one row every N steps with --every {fit:.0} or more, shorten it with --duration, or raise --max-output-gb"
            )
        };
        return Err(format!(
            "-o {}: the CSV would be about {} ({rows} rows × {} columns × ~{} bytes: {n} steps of {:e} s, --every {}), over the output budget of {} (--max-output-gb {}): expected {how}",
            path.display(),
            csv_out::human_bytes(est),
            1 + 5 * p,
            csv_out::BYTES_PER_VALUE,
            scene.dt_s,
            args.every,
            csv_out::human_bytes(budget),
            tirecontact::base::error::fmt_num(budget_gb),
        ));
    }
    Ok(())
}

/// A figure that could not be drawn after the run, or an output file whose
/// folder does not exist, is refused before it.
fn check_plot_args(args: &RunArgs) -> Result<(), String> {
    use super::paths::check_output_file;
    if let Some(path) = &args.output {
        check_output_file("-o", path, "CSV")?;
    }
    if let Some(path) = &args.spectrum {
        check_output_file("--spectrum", path, "CSV")?;
    }
    if let Some(path) = &args.spectrum_plot {
        check_output_file("--spectrum-plot", path, "PNG")?;
    }
    if let Some(path) = &args.patch_summary {
        check_output_file("--patch-summary", path, "CSV")?;
    }
    let Some(path) = &args.plot else {
        return Ok(());
    };
    let (w, h) = args.plot_size;
    if !(200..=8000).contains(&w) || !(200..=8000).contains(&h) {
        return Err(format!(
            "--plot-size {w}x{h}: expected 200..=8000 px per side"
        ));
    }
    check_output_file("--plot", path, "PNG")
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let err = || format!("`{s}`: expected WIDTHxHEIGHT in pixels, e.g. 1400x900");
    let (w, h) = s.split_once('x').ok_or_else(err)?;
    Ok((
        w.trim().parse().map_err(|_| err())?,
        h.trim().parse().map_err(|_| err())?,
    ))
}

pub use tirecontact::output::summary::scene_summary;
use tirecontact::output::summary::short_num;

/// Applies command-line overrides and re-validates.
pub fn scene_with_overrides(args: &RunArgs) -> Result<Scene, SceneError> {
    super::load_with_overrides(args.preset.as_deref(), args.dt, args.duration)
}

/// Penetration left at a step end above which `run` warns (m): resolved
/// runs of the shipped presets leave at most about 1e-17 m.
pub const PENETRATION_WARNING_M: f64 = 1e-9;

pub fn run(args: &RunArgs) -> CliResult {
    if args.every == 0 {
        return Err("--every = 0: expected a number of steps >= 1".into());
    }
    if args.threads == 0 {
        return Err("--threads = 0: expected a number of threads >= 1".into());
    }
    let scene = scene_with_overrides(args)?;
    // before anything is built, computed or written
    check_output_budget(&scene, args)?;
    check_plot_args(args)?;
    check_spectrum_args(args, &scene)?;
    // identification, road file: once, for the frames and the run
    let model = PreparedModel::of(&scene)?;
    write_frames(&model, args)?;
    let options = tirecontact::SolverOptions {
        rank_tolerance: args
            .exact_rank
            .then_some(tirecontact::model::convolution::EXACT_RANK_TOLERANCE),
        threads: args.threads,
        ..tirecontact::SolverOptions::default()
    };
    let mut sim = model.simulation(options)?;
    let n = scene.num_steps();
    let mut writer = match &args.output {
        Some(path) => {
            // written beside `path` and renamed at the end: a failed run keeps the old file
            let f = tirecontact::fsio::AtomicFile::create(path)
                .map_err(|e| format!("{}: {e}", path.display()))?;
            Some(RunWriter::piped(f, scene.num_points(), args.every)?)
        }
        None => None,
    };
    let mut rec = args.plot.as_ref().map(|_| {
        use tirecontact::output::record::{PLOT_SAMPLES, Recording};
        Recording::new(scene.num_points(), n, PLOT_SAMPLES)
    });
    let want_spectrum = args.spectrum.is_some() || args.spectrum_plot.is_some();
    let mut steady = if want_spectrum {
        Some(SteadyRecorder::new(&scene, args.spectrum_from)?)
    } else {
        None
    };
    let mut patch = patch_recorder(args, &scene)?;
    // the one-line summary's forces, over the whole run
    let mut metrics = ContactMetrics::new(&scene, Some(0.0));
    let start = Instant::now();
    let bar = ProgressBar::with_draw_target(Some(n), indicatif::ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {percent}% {msg} (eta {eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut shown = false;
    let mut last_tick = Instant::now();
    let mut progress = |k: u64, sim: &Simulation| {
        if !shown && start.elapsed() > Duration::from_millis(800) && (k as f64) < 0.7 * n as f64 {
            shown = true;
            bar.reset_elapsed();
        }
        if shown && last_tick.elapsed() > Duration::from_millis(100) {
            bar.set_position(k);
            bar.set_message(format!("t = {:.4} s", sim.time_s()));
            last_tick = Instant::now();
        }
    };
    tirecontact::solver::drive::run_to_end(
        &mut sim,
        &mut (
            writer.as_mut(),
            rec.as_mut(),
            steady.as_mut(),
            &mut metrics,
            patch.as_mut(),
        ),
        Watch::none().with_progress(&mut progress),
    )?;
    bar.finish_and_clear();
    if let Some(w) = writer {
        w.finish()?.commit()?;
    }
    let wall = start.elapsed().as_secs_f64();
    if let (Some(r), Some(path)) = (rec, &args.plot) {
        let fig = r.figure(&FigureSpec {
            title: &scene.name,
            subtitle: &scene_summary(&scene, model.modes()),
            dt_s: scene.dt_s,
            clip_impacts: !args.plot_unclipped,
            points: None,
            panels: &RunPanel::RUN,
        });
        tirecontact::output::figures::render_png(&fig, path, args.plot_size.0, args.plot_size.1)?;
        eprintln!("wrote {}", path.display());
    }
    if let Some(r) = steady {
        write_spectra(args, &model, &r)?;
    }
    if let Some(p) = &patch {
        write_patch(args, &scene, p)?;
    }
    let st = sim.stats();
    if st.worst_penetration_m > PENETRATION_WARNING_M {
        eprintln!(
            "warning: a point was left {:.2e} m inside the road at a step end (corrected at the next step; well-resolved runs stay below {PENETRATION_WARNING_M:e} m): the time step dt_s = {:e} s may not resolve the fastest mode or the road; try a smaller --dt",
            st.worst_penetration_m, scene.dt_s
        );
    }
    println!("{}", summary_line(args, &scene, &sim, &metrics, wall));
    Ok(())
}

/// The spectrum options, checked before anything is built.
fn check_spectrum_args(args: &RunArgs, scene: &Scene) -> Result<(), String> {
    let want_spectrum = args.spectrum.is_some() || args.spectrum_plot.is_some();
    if want_spectrum && !(args.spectrum_max_hz.is_finite() && args.spectrum_max_hz > 0.0) {
        return Err(format!(
            "--spectrum-max-hz = {}: expected a frequency > 0 Hz",
            args.spectrum_max_hz
        ));
    }
    if let Some(from) = args.spectrum_from
        && !(from.is_finite() && from >= 0.0 && from < scene.duration_s)
    {
        return Err(format!(
            "--spectrum-from = {from}: expected a start time >= 0 s and < duration_s = {} s",
            scene.duration_s
        ));
    }
    Ok(())
}

/// The patch recorder of `--patch-summary` / `--patch-frames`, if asked.
fn patch_recorder(
    args: &RunArgs,
    scene: &Scene,
) -> Result<Option<tirecontact::output::patch::PatchRecorder>, String> {
    if args.patch_summary.is_none() && args.patch_frames.is_none() {
        return Ok(None);
    }
    let frames = if args.patch_frames.is_some() {
        args.patch_frame_count
    } else {
        0
    };
    tirecontact::output::patch::PatchRecorder::new(scene, args.patch_every, frames)
        .map(Some)
        .map_err(|e| format!("--patch-summary/--patch-frames: {e}"))
}

/// The one-line summary of a finished run: steps, wall time and real-time
/// factor, forces, impacts, contact, events and penetration.
fn summary_line(
    args: &RunArgs,
    scene: &Scene,
    sim: &Simulation,
    metrics: &ContactMetrics,
    wall: f64,
) -> String {
    let st = sim.stats();
    let fmt_list = |v: &[f64], f: &dyn Fn(f64) -> String| {
        v.iter().map(|&x| f(x)).collect::<Vec<_>>().join(" ")
    };
    let m = metrics.summary();
    let impacts: Vec<f64> = m
        .impacts_per_s
        .iter()
        .map(|&r| (r * m.steps as f64 * scene.dt_s).round())
        .collect();
    format!(
        "{}: {} steps of {:e} s to t = {:.4} s in {:.3} s wall ({:.2}x real time, {:.0} steps/s); max force without impacts [N]: {}; impacts: {}; largest impulse [N·s]: {}; contact fraction: {}; events {}; worst penetration {:.2e} m{}",
        scene.name,
        st.steps,
        scene.dt_s,
        sim.time_s(),
        wall,
        sim.time_s() / wall.max(1e-12),
        st.steps as f64 / wall.max(1e-12),
        fmt_list(&m.force_max_n, &|x| format!("{x:.1}")),
        fmt_list(&impacts, &|x| format!("{x}")),
        fmt_list(&m.impulse_max_ns, &|x| short_num(x, 3)),
        fmt_list(&m.contact_fraction, &|x| format!("{x:.3}")),
        st.events,
        st.worst_penetration_m,
        args.output
            .as_ref()
            .map_or(String::new(), |p| format!("; wrote {}", p.display()))
    )
}

/// Writes the patch summary, its total force's spectrum and the heat maps.
fn write_patch(
    args: &RunArgs,
    scene: &Scene,
    p: &tirecontact::output::patch::PatchRecorder,
) -> CliResult {
    if let Some(path) = &args.patch_summary {
        p.save_csv(path)?;
        let spectrum_path = {
            let stem = path
                .file_stem()
                .map_or("patch".into(), |s| s.to_string_lossy().into_owned());
            path.with_file_name(format!("{stem}_spectrum.csv"))
        };
        let from = p.t_s.partition_point(|&t| t < scene.ramp_s);
        let rate_hz = 1.0 / (scene.dt_s * args.patch_every as f64);
        match tirecontact::analysis::spectrum::spectrum(
            &p.total_n[from..],
            rate_hz,
            Window::Hann,
            true,
        ) {
            Ok(s) => {
                let mut buf =
                    b"freq_hz,total_force_psd_n2_per_hz,total_force_amplitude_n\n".to_vec();
                for k in 0..s.freq_hz.len() {
                    buf.extend(
                        format!("{:e},{:e},{:e}\n", s.freq_hz[k], s.psd[k], s.amplitude[k]).bytes(),
                    );
                }
                tirecontact::fsio::write_atomic(&spectrum_path, &buf)
                    .map_err(|e| format!("{}: {e}", spectrum_path.display()))?;
                eprintln!("wrote {} and {}", path.display(), spectrum_path.display());
            }
            Err(e) => eprintln!(
                "wrote {}; no spectrum of the total force: {e} (samples after the ramp, t >= {} s)",
                path.display(),
                scene.ramp_s
            ),
        }
    }
    if let Some(dir) = &args.patch_frames {
        let n = p.save_frames(dir, &scene.name, args.plot_size)?;
        eprintln!(
            "wrote {n} heat maps of the contact force into {}",
            dir.display()
        );
    }
    Ok(())
}

/// Writes the spectrum CSV, its band table and the spectrum figure.
fn write_spectra(args: &RunArgs, model: &PreparedModel, rec: &SteadyRecorder) -> CliResult {
    let scene = model.scene();
    let spectra = rec.spectra(Window::Hann)?;
    eprintln!("spectra: {}", spectra.describe());
    if let Some(path) = &args.spectrum {
        let mut buf = Vec::new();
        spectra.write_csv(&mut buf, args.spectrum_max_hz)?;
        tirecontact::fsio::write_atomic(path, &buf)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let bands = bands_path(path);
        let mut buf = Vec::new();
        spectra.write_bands_csv(&mut buf, DEFAULT_BANDS_HZ.0, DEFAULT_BANDS_HZ.1)?;
        tirecontact::fsio::write_atomic(&bands, &buf)
            .map_err(|e| format!("{}: {e}", bands.display()))?;
        eprintln!("wrote {} and {}", path.display(), bands.display());
    }
    if let Some(path) = &args.spectrum_plot {
        let marks = scene_markers(model, args.spectrum_max_hz);
        let fig = spectra.figure(
            &format!("{}: spectra", scene.name),
            &scene_summary(scene, model.modes()),
            &marks,
            args.spectrum_max_hz,
        );
        tirecontact::output::figures::render_png(
            &fig,
            path,
            args.plot_size.0,
            args.plot_size.1.max(1200),
        )?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
