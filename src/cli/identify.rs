//! `tirecontact identify PRESET [-o modal.ron] [--diagram stab.png]
//! [--responses irf.csv] [--figures DIR]`: identifies the modal model of a
//! ring-tyre or measured-tyre scene by LSCE (method §5-6) and writes what
//! was asked; `tirecontact identify --data FILE --points N` identifies a
//! data file (UFF 58 or CSV) without a preset.

use super::{CliResult, load_scene};

mod frf;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tirecontact::SceneSimulation;
use tirecontact::fsio::write_atomic;
use tirecontact::identify::{TyreIdentification, driving, identify_tyre};
use tirecontact::model::lsce::Identification;
use tirecontact::output::figures::{Figure, Panel, Series, render_png};
use tirecontact::output::paper_figures::paper_figures;
use tirecontact::output::record::{PLOT_SAMPLES, Recording};
use tirecontact::output::stabilisation::{self, Method};
use tirecontact::output::summary::short_num;
use tirecontact::readers::measured::impulse_csv;
use tirecontact::scene::Tyre;
use tirecontact::{Scene, Simulation};

#[derive(Debug, clap::Args)]
// (a negative value reaches validation, which names the field, not clap's "unexpected argument")
#[command(allow_negative_numbers = true)]
pub struct IdentifyArgs {
    /// Scene preset (RON) with `tyre: Ring(...)` or `tyre: Measured(...)`.
    #[arg(required_unless_present = "data", conflicts_with = "data")]
    pub preset: Option<PathBuf>,
    /// A data file of tyre responses to identify without a preset (UFF 58,
    /// CSV impulse responses or CSV FRFs; see docs/presets.md), with
    /// --points (a UFF file's nodes, in increasing order, when omitted);
    /// the default identification options but --band-hz.
    #[arg(long)]
    pub data: Option<PathBuf>,
    /// Number of points in --data's file (required for CSV).
    #[arg(long, requires = "data")]
    pub points: Option<usize>,
    /// Identification band of --data (Hz): `LO HI` (default 0 500).
    #[arg(long, requires = "data", num_args = 2, value_names = ["LO", "HI"])]
    pub band_hz: Option<Vec<f64>>,
    /// Write the identified modal scene (`tyre: Modal(...)`, loadable by `run`).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Write the stabilisation diagram (PNG).
    #[arg(long)]
    pub diagram: Option<PathBuf>,
    /// Write the sampled impulse responses (CSV: `t_s`, `g{i}_{j}` in m/(N·s)).
    #[arg(long)]
    pub responses: Option<PathBuf>,
    /// Also run the identified scene and write `{stem}_fig1_displacement.png`
    /// and `{stem}_fig2_force.png` (the paper's Fig. 1 and 2) into this folder (created when missing)
    /// (Fig. 2 clips impact spikes as `run --plot` does; see
    /// --figures-unclipped).
    #[arg(long)]
    pub figures: Option<PathBuf>,
    /// Draw the impact spikes of --figures' Fig. 2 whole (impulse / dt:
    /// tens of kN, which squash the rolling force to a line).
    #[arg(long, requires = "figures")]
    pub figures_unclipped: bool,
    /// The nodes of --data's FRFs to use (all when omitted): the model's
    /// points, in increasing node number.
    #[arg(long, requires = "data", num_args = 1.., value_name = "NODE")]
    pub nodes: Option<Vec<i64>>,
    /// The polynomial order of the frequency-domain fit up to which modes
    /// are kept, 1 to 200 (default: the highest of the stabilisation
    /// diagram, 40). A mode is a pole stable against the order below at 5
    /// consecutive orders, the last of them this order or one of the 5
    /// below it; damping ratio below 0.2, inside the band, its term
    /// standing at least 3 times above the fit's residual around it.
    /// Every order up to it is fitted for the diagram (order 200 on three
    /// FRFs of 1000 lines: about 3 s).
    #[arg(long, requires = "data", value_name = "1-200")]
    pub order: Option<usize>,
    /// Write the frequency-domain fit into this folder (created when
    /// missing): modes.csv, fit.csv (data and fit per pair, in the file's
    /// ordinate, SI) and fit.png; written even when the fit is poor.
    #[arg(long, requires = "data")]
    pub fit: Option<PathBuf>,
    /// Keep a poor fit for -o (with a warning).
    #[arg(long, requires = "data")]
    pub accept: bool,
    /// Reverse the response direction at NODE (a sensor mounted the other
    /// way): every FRF whose response is at NODE is negated. Repeatable.
    #[arg(long, requires = "data", value_name = "NODE")]
    pub flip_direction: Vec<i64>,
}

/// The scene to identify: the preset, or a scene of `--data`'s points
/// (25 mm apart, on the default preset's road).
fn scene_of(args: &IdentifyArgs) -> Result<(Scene, PathBuf), Box<dyn std::error::Error>> {
    if let Some(data) = &args.data {
        let p = match args.points {
            Some(p) => p,
            None => uff_nodes(data)?,
        };
        if !(1..=tirecontact::readers::measured::MAX_POINTS).contains(&p) {
            return Err(format!(
                "--points {p}: expected 1 to {} points",
                tirecontact::readers::measured::MAX_POINTS
            )
            .into());
        }
        let mut scene = Scene::parse(
            tirecontact::DEFAULT_PRESET,
            tirecontact::DEFAULT_PRESET_NAME,
        )?;
        scene.name = data
            .file_stem()
            .map_or("data".into(), |s| s.to_string_lossy().into_owned());
        scene.description = format!(
            "Modes identified from {} ({p} points, placed 25 mm apart: set their positions).",
            data.display()
        );
        scene.points = data_points(p);
        let mut identification = tirecontact::model::lsce::IdentifyOptions::default();
        if let Some(b) = &args.band_hz {
            identification.band_hz = (b[0], b[1]);
        }
        scene.tyre = Tyre::Measured {
            file: data.clone(),
            identification,
            nodes: Vec::new(),
        };
        scene.base_dir = None;
        return Ok((scene, data.clone()));
    }
    let preset = args.preset.clone().unwrap_or_default();
    Ok((load_scene(Some(&preset))?, preset))
}

/// `p` points 25 mm apart along the tyre, preloaded by 3 mm.
fn data_points(p: usize) -> tirecontact::scene::Points {
    (0..p)
        .map(|i| tirecontact::scene::Point {
            x_m: 0.025 * (i as f64 - 0.5 * (p as f64 - 1.0)),
            y_m: 0.0,
            h_m: -0.003,
        })
        .collect()
}

/// The number of distinct nodes of a UFF file's usable records (`--points`
/// when omitted); CSV files need `--points`.
fn uff_nodes(data: &Path) -> Result<usize, Box<dyn std::error::Error>> {
    let ext = data
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if ext != "uff" && ext != "unv" {
        return Err(format!(
            "--data {}: a CSV file: expected --points N (a UFF file names its nodes)",
            data.display()
        )
        .into());
    }
    let bytes = std::fs::read(data).map_err(|e| format!("{}: {e}", data.display()))?;
    let (series, _) = tirecontact::readers::measured::uff::parse(&bytes, None)
        .map_err(|(at, m)| format!("{}: {at}{m}", data.display()))?;
    Ok(series.keys().map(|&(i, j)| i.max(j) + 1).max().unwrap_or(0))
}

/// `x` to 6 significant digits in fixed notation (ξ of lightly damped
/// tests: 0.000212345).
fn sig6(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let decimals = (5 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

pub fn identify(args: &IdentifyArgs) -> CliResult {
    if let Some(data) = &args.data
        && frf::is_uff(data)
        && tirecontact::readers::measured::frf::holds_frfs(data)?
    {
        return frf::identify_frfs(args, data);
    }
    for (given, flag) in [
        (args.nodes.is_some(), "--nodes"),
        (args.order.is_some(), "--order"),
        (args.fit.is_some(), "--fit"),
        (args.accept, "--accept"),
        (!args.flip_direction.is_empty(), "--flip-direction"),
    ] {
        if given {
            return Err(format!(
                "{flag}: for the frequency-domain fit of a UFF file of FRFs (dataset 58, function type 4): expected --data FILE.uff holding FRFs"
            )
            .into());
        }
    }
    let (scene, source) = scene_of(args)?;
    // every output's folder, before the identification and any file written
    use super::paths::{check_output_file, ensure_output_dir};
    if let Some(path) = &args.output {
        check_output_file("-o", path, "RON")?;
    }
    if let Some(path) = &args.diagram {
        check_output_file("--diagram", path, "PNG")?;
    }
    if let Some(path) = &args.responses {
        check_output_file("--responses", path, "CSV")?;
    }
    if let Some(dir) = &args.figures {
        // a folder, like `run --frames` and `bench -o`: created when missing
        ensure_output_dir("--figures", dir)?;
    }
    let id = match identify_tyre(&scene) {
        Some(r) => r.map_err(|e| match e {
            // a file's error names the file
            tirecontact::identify::IdentifyError::Data(d) => d.to_string(),
            e => format!("{}: {e}", source.display()),
        })?,
        None => {
            return Err(format!(
                "{}: tyre is `Modal(...)`: nothing to identify (expected `Ring(...)` or `Measured(...)`)",
                source.display()
            )
            .into());
        }
    };
    print!("{}", summary(&scene, &id));
    // the driving-point check (measured tyres): a model only from data
    // whose driving-point residues are all positive
    let mut refused = None;
    if let Tyre::Measured { .. } = &scene.tyre {
        let names = point_names(&scene);
        for (i, (name, node)) in names.iter().enumerate() {
            let d = driving::check(&id.identification.modes, &id.identification.stable, i);
            let line = driving::describe(&d, name, *node);
            println!("  {line}");
            if d != driving::DrivingPoint::Positive && refused.is_none() {
                refused = Some(line);
            }
        }
    }
    let mut modal = scene.clone();
    modal.tyre = Tyre::Modal {
        modes: id.identification.modes.clone(),
    };
    modal.name = format!("{} (identified)", scene.name);
    let mut deferred = None;
    if let Some(out) = &args.output {
        if let Some(why) = &refused {
            deferred = Some(format!("-o {}: not written: {why}", out.display()));
        } else {
            modal.save(out)?;
            println!("wrote {}", out.display());
        }
    }
    if let Some(path) = &args.diagram {
        render_png(&diagram_figure(&scene, &id.identification), path, 1200, 900)?;
        println!("wrote {}", path.display());
    }
    if let Some(path) = &args.responses {
        write_atomic(path, impulse_csv(&id.responses).as_bytes())
            .map_err(|e| format!("{}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    if let Some(dir) = &args.figures {
        let stem = source
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
        run_figures(&modal, dir, &stem, !args.figures_unclipped)?;
    }
    match deferred {
        Some(e) => Err(e.into()),
        None => Ok(()),
    }
}

/// The measured scene's points as messages name them, `point 0 (node
/// 101 +Z)`, with their node numbers (the point's index when the file does
/// not name nodes).
fn point_names(scene: &Scene) -> Vec<(String, i64)> {
    let p = scene.num_points();
    let plain = || (0..p).map(|i| (format!("point {i}"), i as i64)).collect();
    let Tyre::Measured { file, nodes, .. } = &scene.tyre else {
        return plain();
    };
    let path = scene
        .base_dir
        .as_ref()
        .map_or(file.clone(), |b| b.join(file));
    let Some(recs) = std::fs::read(&path)
        .ok()
        .and_then(|b| tirecontact::readers::measured::uff::records(&b).ok())
    else {
        return plain();
    };
    let mut all: Vec<i64> = recs
        .iter()
        .filter(|r| matches!(r.function_type, 1 | 4))
        .flat_map(|r| [r.response_node, r.reference_node])
        .collect();
    all.sort_unstable();
    all.dedup();
    let map = if nodes.is_empty() { all } else { nodes.clone() };
    if map.len() != p {
        return plain();
    }
    map.iter()
        .enumerate()
        .map(|(i, &n)| {
            let dir = recs
                .iter()
                .find(|r| r.response_node == n && r.reference_node == n)
                .map_or(0, |r| r.response_direction);
            (
                format!(
                    "point {i} ({})",
                    tirecontact::readers::measured::uff::dof(n, dir)
                ),
                n,
            )
        })
        .collect()
}

fn summary(scene: &Scene, id: &TyreIdentification) -> String {
    let ident = &id.identification;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{}: {} identified at model order {} in {:.3} s; fit error: time {:.3e} (kept modes), {:.3e} (all poles), |G| (sampled) {:.3e}",
        scene.name,
        tirecontact::output::count(ident.modes.len(), "mode"),
        ident.model_order,
        id.elapsed_s,
        ident.report.time_error,
        ident.report.time_error_all_poles,
        ident.report.magnitude_error,
    );
    for n in &id.notes {
        let _ = writeln!(s, "  {n}");
    }
    let ls = ident.report.least_squares;
    let _ = writeln!(
        s,
        "  least-squares residuals (relative): linear prediction {:.3e}, real residues {:.3e}, complex residues {:.3e}",
        ls.prediction, ls.residues, ls.complex_residues
    );
    for (k, m) in ident.modes.iter().enumerate() {
        let _ = writeln!(
            s,
            "  mode {k:2}: {:8.2} Hz  xi {}  {}  discarded cos part {:.2e}",
            m.freq_hz,
            sig6(m.damping_ratio),
            if ident.stable[k] {
                "stable  "
            } else {
                "unstable"
            },
            ident.discarded_ratio[k]
        );
    }
    s
}

fn diagram_figure(scene: &Scene, id: &Identification) -> Figure {
    let chosen: Vec<f64> = id.modes.iter().map(|m| m.freq_hz).collect();
    let mut panels = vec![stabilisation::panel(
        &id.diagram,
        Method::Lsce,
        id.model_order,
        &chosen,
    )];
    panels.push(Panel {
        title: "relative L2 fit error in time vs model order".into(),
        x_label: "model order M (pole pairs)".into(),
        y_label: "log10 of the fit error (-)".into(),
        series: vec![
            Series::line(
                "log10 time-domain error, all responses",
                id.order_errors
                    .iter()
                    .filter(|d| d.time_error > 0.0)
                    .map(|d| (d.order as f64, d.time_error.log10()))
                    .collect(),
            ),
            Series::line(
                "log10 time-domain error of the in-band poles only",
                id.order_errors
                    .iter()
                    .filter(|d| d.band_time_error > 0.0)
                    .map(|d| (d.order as f64, d.band_time_error.log10()))
                    .collect(),
            ),
        ],
        ..Panel::default()
    });
    Figure {
        title: format!("{}: LSCE identification", scene.name),
        subtitle: format!(
            "{}; {} at order {}; time error {:.2e}, |G| error {:.2e}",
            tirecontact::output::count(scene.num_points(), "point"),
            tirecontact::output::count(id.modes.len(), "mode"),
            id.model_order,
            id.report.time_error,
            id.report.magnitude_error
        ),
        panels,
    }
}

/// Runs `scene` and draws displacements (mm) and forces (N) of every point,
/// recorded and clipped (`clip_impacts`) as `run --plot` does.
fn run_figures(scene: &Scene, dir: &Path, stem: &str, clip_impacts: bool) -> CliResult {
    let start = Instant::now();
    let mut sim = Simulation::from_scene(scene)?;
    let n = scene.num_steps();
    let mut rec = Recording::new(scene.num_points(), n, PLOT_SAMPLES);
    tirecontact::solver::drive::run_to_end(
        &mut sim,
        &mut rec,
        tirecontact::solver::drive::Watch::none(),
    )?;
    let wall = start.elapsed().as_secs_f64();
    let sub = format!(
        "{}: V = {} m/s, road {}, dt = {} s ({} steps in {:.1} ms wall)",
        scene.name,
        short_num(scene.speed_mps, 4),
        scene.road.kind(),
        short_num(scene.dt_s, 4),
        n,
        wall * 1e3
    );
    for (file, fig) in paper_figures(&rec, scene, &sub, clip_impacts) {
        let path = dir.join(format!("{stem}_{file}.png"));
        render_png(&fig, &path, 1200, 700)?;
        println!("wrote {}", path.display());
    }
    println!(
        "run: {n} steps of {:e} s in {:.1} ms wall",
        scene.dt_s,
        wall * 1e3
    );
    Ok(())
}
