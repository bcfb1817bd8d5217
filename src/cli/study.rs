//! `tirecontact study plan|run|merge`: parameter studies (see
//! `tirecontact::studies::study`), run on local cores, in shards on other machines
//! (GNU parallel, Slurm job arrays), and merged.

use super::CliResult;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::AtomicBool;
use std::time::Instant;
use tirecontact::ModeCache;
use tirecontact::studies::study::{
    Loaded, Row, header, load, record, run_row, run_rows, shard, table,
};

#[derive(Debug, clap::Args)]
pub struct StudyArgs {
    #[command(subcommand)]
    pub command: StudyCommand,
}

#[derive(Debug, clap::Subcommand)]
pub enum StudyCommand {
    /// Write the design's rows (row id and factor values) and estimate the
    /// wall time from a short timing run.
    Plan {
        /// Study file (RON).
        study: PathBuf,
        /// Write the rows (CSV).
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Run rows of a study on local threads into a part (CSV).
    Run {
        /// Study file (RON).
        study: PathBuf,
        /// Run shard K of N (1-based K): rows K-1, K-1+N, … (a Slurm array
        /// task's `$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT`).
        #[arg(long, conflicts_with = "rows")]
        shard: Option<String>,
        /// Run rows A..B (B excluded).
        #[arg(long)]
        rows: Option<String>,
        /// Worker threads (default: every core).
        #[arg(long)]
        threads: Option<usize>,
        /// Skip the rows already in the output (a killed run loses nothing
        /// finished).
        #[arg(long)]
        resume: bool,
        /// The part (CSV).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Per factor, the main effects of a table (mean and spread of each
    /// summary metric at each level), a figure and a markdown summary.
    Report {
        /// A table written by `study run` or `study merge`.
        table: PathBuf,
        /// The folder of `summary.md`, `main_effects.csv` and one PNG per
        /// factor (created when missing).
        #[arg(short, long)]
        output: PathBuf,
        /// The title of the summary and the figures (default: the table's
        /// file name without its extension).
        #[arg(long)]
        title: Option<String>,
    },
    /// Merge parts into one table: every row once, all of one study.
    Merge {
        /// Parts written by `study run`.
        #[arg(required = true)]
        parts: Vec<PathBuf>,
        #[arg(short, long)]
        output: PathBuf,
    },
}

pub fn study(args: &StudyArgs) -> CliResult {
    match &args.command {
        StudyCommand::Plan { study, output } => plan(study, output.as_deref()),
        StudyCommand::Run {
            study,
            shard,
            rows,
            threads,
            resume,
            output,
        } => run(
            study,
            shard.as_deref(),
            rows.as_deref(),
            *threads,
            *resume,
            output,
        ),
        StudyCommand::Merge { parts, output } => merge(parts, output),
        StudyCommand::Report {
            table,
            output,
            title,
        } => report(table, output, title.as_deref()),
    }
}

fn report(path: &Path, dir: &Path, title: Option<&str>) -> CliResult {
    use tirecontact::studies::study::report;
    super::paths::ensure_output_dir("-o", dir)?;
    let table::StudyTable { header, rows } = table::read_table(path)?;
    let records: Vec<Vec<String>> = rows.into_values().collect();
    let t = report::table(&header, &records).map_err(|e| format!("{}: {e}", path.display()))?;
    if t.rows.is_empty() {
        return Err(format!("{}: no row succeeded: nothing to report", path.display()).into());
    }
    let effects = report::main_effects(&t);
    let title = match title.map(str::trim) {
        Some("") => return Err("--title is empty: expected a title for the summary and the figures, e.g. --title \"Speed and road amplitude\"".into()),
        Some(t) => t.to_string(),
        None => path
            .file_stem()
            .map_or("study".into(), |s| s.to_string_lossy().into_owned()),
    };
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record(["factor", "level", "rows", "metric", "mean", "std"])?;
    let mut figures = Vec::new();
    for e in &effects {
        let file: String = e
            .factor
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect();
        let png = format!("main_effect_{file}.png");
        tirecontact::output::figures::render_png(
            &report::figure(e, &title),
            &dir.join(&png),
            report::figure_px(e.metrics.len()).0,
            report::figure_px(e.metrics.len()).1,
        )?;
        figures.push(png);
        for l in &e.levels {
            for (m, report::Metric { name, unit, .. }) in e.metrics.iter().enumerate() {
                csv.write_record([
                    e.factor.clone(),
                    format!("{}", l.value),
                    l.rows.to_string(),
                    format!("{name} ({unit})"),
                    format!("{}", l.mean[m]),
                    format!("{}", l.std[m]),
                ])?;
            }
        }
    }
    let bytes = csv.into_inner().map_err(|e| e.to_string())?;
    let out = dir.join("main_effects.csv");
    tirecontact::fsio::write_atomic(&out, &bytes).map_err(|e| format!("{}: {e}", out.display()))?;
    let md = dir.join("summary.md");
    tirecontact::fsio::write_atomic(
        &md,
        report::markdown(&title, &t, &effects, &figures).as_bytes(),
    )
    .map_err(|e| format!("{}: {e}", md.display()))?;
    eprintln!(
        "wrote {} (summary.md, main_effects.csv, {})",
        dir.display(),
        tirecontact::output::count(figures.len(), "figure")
    );
    Ok(())
}

fn plan(path: &Path, output: Option<&Path>) -> CliResult {
    let loaded = load(path)?;
    if let Some(out) = output {
        super::paths::check_output_file("-o", out, "CSV")?;
        let mut w = csv::Writer::from_writer(Vec::new());
        let mut h = vec!["row".to_string()];
        h.extend(loaded.study.factors.iter().map(|f| f.path.clone()));
        h.push("replicate".into());
        w.write_record(&h)?;
        for r in &loaded.rows {
            let mut rec = vec![r.id.to_string()];
            rec.extend(r.values.iter().map(|v| format!("{v}")));
            rec.push(r.replicate.to_string());
            w.write_record(&rec)?;
        }
        let bytes = w.into_inner().map_err(|e| e.to_string())?;
        tirecontact::fsio::write_atomic(out, &bytes)
            .map_err(|e| format!("{}: {e}", out.display()))?;
        println!("wrote {}", out.display());
    }
    // a timing run: the first row's scene prepared (a ring identified:
    // once per geometry and process, not timed), stepped through its ramp
    // (points mostly off the road: cheaper), then a tenth of its steps (at
    // least 2000) timed
    let cache = ModeCache::new();
    let scene = tirecontact::studies::study::scene_of(&loaded, &loaded.rows[0])?;
    let prepared = Instant::now();
    let model = tirecontact::PreparedModel::new(&scene, &cache)?;
    let prepare_s = prepared.elapsed().as_secs_f64();
    let mut sim = model.simulation(tirecontact::SolverOptions::default())?;
    let total = scene.num_steps();
    let ramp = ((scene.ramp_s / scene.dt_s).round() as u64).min(total);
    tirecontact::solver::drive::run(
        &mut sim,
        ramp,
        &mut (),
        tirecontact::solver::drive::Watch::none(),
    )?;
    let n = (total - ramp).min((total / 10).max(2000));
    let start = Instant::now();
    tirecontact::solver::drive::run(
        &mut sim,
        n,
        &mut (),
        tirecontact::solver::drive::Watch::none(),
    )?;
    let mut per_run = start.elapsed().as_secs_f64() * total as f64 / n.max(1) as f64;
    // short runs: the first, middle and last rows run in full (summary
    // included), the mean of the three
    let sample: Vec<&Row> = {
        let r = &loaded.rows;
        let mut s = vec![&r[0], &r[r.len() / 2], &r[r.len() - 1]];
        s.dedup_by_key(|row| row.id);
        s
    };
    if per_run * (sample.len() as f64) < 1.0 {
        let cancel = AtomicBool::new(false);
        let start = Instant::now();
        for row in &sample {
            // a failing row is timed too: `study run` records it and goes on
            let _ = run_row(&loaded, row, &cache, &cancel);
        }
        per_run = start.elapsed().as_secs_f64() / sample.len() as f64;
    }
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "{}: {} ({} factors, {} per row); about {} per run, {} on {} threads of this machine, after {:.2} s of preparation (a ring or measured tyre identified: once per process and geometry)",
        path.display(),
        tirecontact::output::count(loaded.rows.len(), "run"),
        loaded.study.factors.len(),
        tirecontact::output::count(loaded.study.replicates, "replicate"),
        if per_run < 0.1 {
            format!("{:.1} ms", per_run * 1e3)
        } else {
            format!("{per_run:.2} s")
        },
        human_s(per_run * loaded.rows.len() as f64 / threads as f64),
        threads,
        prepare_s
    );
    Ok(())
}

fn human_s(s: f64) -> String {
    if s < 0.1 {
        "under 0.1 s".into()
    } else if s < 10.0 {
        format!("{s:.1} s")
    } else if s < 120.0 {
        format!("{s:.0} s")
    } else if s < 7200.0 {
        format!("{:.0} min", s / 60.0)
    } else {
        format!("{:.1} h", s / 3600.0)
    }
}

/// `K/N` (1-based K) or `A..B`: the rows chosen.
fn chosen(
    loaded: &Loaded,
    shard_arg: Option<&str>,
    rows_arg: Option<&str>,
) -> Result<Vec<Row>, String> {
    if let Some(s) = shard_arg {
        let err = || format!("--shard {s}: expected K/N with 1 <= K <= N, e.g. 2/8");
        let (k, n) = s.split_once('/').ok_or_else(err)?;
        let (k, n): (usize, usize) = (
            k.trim().parse().map_err(|_| err())?,
            n.trim().parse().map_err(|_| err())?,
        );
        if k == 0 || k > n {
            return Err(err());
        }
        return Ok(shard(&loaded.rows, k - 1, n));
    }
    if let Some(r) = rows_arg {
        let n = loaded.rows.len();
        let err = || format!("--rows {r}: expected A..B with 0 <= A < B <= {n}");
        let (a, b) = r.split_once("..").ok_or_else(err)?;
        let (a, b): (usize, usize) = (
            a.trim().parse().map_err(|_| err())?,
            b.trim().parse().map_err(|_| err())?,
        );
        if a >= b || b > n {
            return Err(err());
        }
        return Ok(loaded.rows[a..b].to_vec());
    }
    Ok(loaded.rows.clone())
}

fn run(
    path: &Path,
    shard_arg: Option<&str>,
    rows_arg: Option<&str>,
    threads: Option<usize>,
    resume: bool,
    output: &Path,
) -> CliResult {
    let begun = Instant::now();
    let loaded = load(path)?;
    super::paths::check_output_file("-o", output, "CSV")?;
    let header = header(&loaded);
    let mut done: BTreeMap<usize, Vec<String>> = BTreeMap::new();
    if resume && output.exists() {
        let table::StudyTable { header: h, rows } = table::read_table(output)?;
        if h != header {
            return Err(format!(
                "{}: --resume: a table of another study (its columns differ)",
                output.display()
            )
            .into());
        }
        for (id, r) in rows {
            if r.get(2) != Some(&loaded.hash) {
                return Err(format!(
                    "{}: --resume: row {id} is of another study (hash {}, this one {})",
                    output.display(),
                    r.get(2).cloned().unwrap_or_default(),
                    loaded.hash
                )
                .into());
            }
            done.insert(id, r);
        }
    }
    let todo: Vec<Row> = chosen(&loaded, shard_arg, rows_arg)?
        .into_iter()
        .filter(|r| !done.contains_key(&r.id))
        .collect();
    let threads = match threads {
        Some(0) => return Err("--threads = 0: expected at least 1 thread".into()),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    // rows are appended as they finish (a killed run keeps them), then the
    // table is written sorted
    let mut journal = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(output)
        .map_err(|e| format!("{}: {e}", output.display()))?;
    if done.is_empty() {
        journal
            .set_len(0)
            .map_err(|e| format!("{}: {e}", output.display()))?;
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(&header)?;
        journal.write_all(&w.into_inner().map_err(|e| e.to_string())?)?;
    }
    let journal = Mutex::new(journal);
    let bar = ProgressBar::with_draw_target(Some(todo.len() as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} rows (eta {eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let cache = ModeCache::new();
    // a ring or measured tyre identified once up front, not by every
    // thread at once (rows that change its geometry identify their own)
    if let Some(first) = todo.first()
        && let Ok(scene) = tirecontact::studies::study::scene_of(&loaded, first)
    {
        let _ = cache.modes(&scene);
    }
    let cancel = AtomicBool::new(false);
    let results: Mutex<BTreeMap<usize, Vec<String>>> = Mutex::new(BTreeMap::new());
    let start = Instant::now();
    let timing = run_rows(&loaded, &todo, threads, &cache, &cancel, &|row, r| {
        let rec = record(&loaded, row, &r);
        let mut w = csv::Writer::from_writer(Vec::new());
        if w.write_record(&rec).is_ok()
            && let Ok(bytes) = w.into_inner()
        {
            let mut j = journal.lock().unwrap_or_else(|e| e.into_inner());
            let _ = j.write_all(&bytes).and_then(|()| j.flush());
        }
        results
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .insert(row.id, rec);
        bar.inc(1);
    });
    let rows_s = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let results = results.into_inner().unwrap_or_else(|e| e.into_inner());
    let failed = results
        .values()
        .filter(|r| r.last().is_some_and(|e| !e.is_empty()))
        .count();
    done.extend(results);
    table::write_table(output, &header, &done)?;
    eprintln!(
        "wrote {} ({} run in {:.1} s on {}, {failed} failed; {} in the table)",
        output.display(),
        tirecontact::output::count(todo.len(), "row"),
        rows_s,
        tirecontact::output::count(threads, "thread"),
        tirecontact::output::count(done.len(), "row"),
    );
    if !todo.is_empty() {
        let (t, busy_s) = (timing.runs, timing.busy_s);
        let n = todo.len() as f64;
        let ms = |s: f64| format!("{:.2} ms", 1e3 * s / n);
        let writing_s = (busy_s - t.total_s()).max(0.0);
        eprintln!(
            "per row, of its thread's time: {} = set-up {} + stepping {} + spectrum and metrics {} + writing {}; before the rows: {:.2} s (study, preset, identification){}",
            ms(busy_s),
            ms(t.setup_s),
            ms(t.stepping_s),
            ms(t.summary_s),
            ms(writing_s),
            start.duration_since(begun).as_secs_f64(),
            format_args!(
                "; overhead {:.1} % of stepping",
                100.0 * (busy_s - t.stepping_s - t.summary_s) / t.stepping_s.max(1e-12)
            )
        );
    }
    Ok(())
}

fn merge(parts: &[PathBuf], output: &Path) -> CliResult {
    super::paths::check_output_file("-o", output, "CSV")?;
    let merged = table::merge(parts)?;
    table::write_table(output, &merged.header, &merged.rows)?;
    eprintln!(
        "wrote {} ({} rows from {} parts)",
        output.display(),
        merged.rows.len(),
        parts.len()
    );
    Ok(())
}
