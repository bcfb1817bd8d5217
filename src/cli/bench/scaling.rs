//! `tirecontact bench --scaling`: the cost of a step against the numbers
//! of points and modes ([`tirecontact::analysis::bench::scaling`]) for both contact
//! laws, each size timed in a child process of its own
//! (`--scaling-one P,K,CONTACT`), its peak memory from one run in another
//! (`P,K,CONTACT,SECONDS`), and callgrind's instruction counts, with
//! contact and lifted off the road, where valgrind is installed.

use super::BenchArgs;
use crate::cli::CliResult;
use indicatif::{ProgressBar, ProgressStyle};
use tirecontact::analysis::bench::scaling::report::{MeasuredSize, ScalingReport};
use tirecontact::analysis::bench::scaling::{Regime, ScalingRow, Timing};
use tirecontact::output::figures::render_png;
use tirecontact::{PreparedModel, SolverOptions};

/// (points, modes) of each measured size.
type Sizes = Vec<(usize, usize)>;

/// The sizes of the scaling study: points at 400 modes, modes at 60 points.
fn scaling_sizes(quick: bool) -> (Sizes, Sizes) {
    if quick {
        (vec![(5, 50), (20, 50)], vec![(20, 10), (20, 50)])
    } else {
        (
            [5, 10, 25, 50, 100, 200, 400]
                .iter()
                .map(|&p| (p, 400))
                .collect(),
            [10, 25, 50, 100, 200, 400]
                .iter()
                .map(|&k| (60, k))
                .collect(),
        )
    }
}

/// The sizes of the contact patch (20 points across the tread): 10, 20
/// and 50 along, 400 modes.
fn patch_sizes(quick: bool) -> Sizes {
    if quick {
        vec![(60, 50), (120, 50)]
    } else {
        vec![(200, 400), (400, 400), (1000, 400)]
    }
}

/// The peak memory (kB) of one 0.1 s run of a size in a process of its
/// own; a warning on the progress bar and `None` when it fails.
fn peak_memory_kb(
    exe: &std::path::Path,
    p: usize,
    k: usize,
    regime: Regime,
    threads: u16,
    bar: &ProgressBar,
) -> Option<u64> {
    let out = std::process::Command::new(exe)
        .args([
            "bench",
            "--scaling-one",
            &format!("{p},{k},{},0.1", regime.key()),
            "--threads",
            &threads.to_string(),
        ])
        .output();
    let failed = |why: String| {
        bar.println(format!(
            "warning: P = {p}, K = {k}, {}: peak memory not measured: {why}",
            regime.label()
        ));
        None
    };
    match out {
        Err(e) => failed(e.to_string()),
        Ok(o) if !o.status.success() => failed(format!(
            "{}: {}",
            o.status,
            String::from_utf8_lossy(&o.stderr).trim()
        )),
        // empty where the system has no /proc/self/status
        Ok(o) => String::from_utf8_lossy(&o.stdout).trim().parse().ok(),
    }
}

/// Length (s) and number of the timed runs of a size.
fn timed_runs(quick: bool) -> (f64, usize) {
    if quick { (0.02, 1) } else { (0.1, 5) }
}

/// This process's peak resident memory (kB, /proc/self/status' VmHWM;
/// `None` where unknown).
fn peak_rss_kb() -> Option<u64> {
    std::fs::read_to_string("/proc/self/status")
        .ok()?
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))?
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()
}

/// Runs one size and prints it as a CSV line (its timed runs), or with a
/// duration `P,K,CONTACT,SECS` runs it once and prints the process's peak
/// resident memory (kB; empty where unknown).
pub fn scaling_one(pk: &str, quick: bool, threads: usize) -> CliResult {
    let bad = || {
        format!(
            "--scaling-one {pk}: expected P,K,CONTACT (points, modes, `rigid`, `tread` or `patch`), e.g. 50,400,tread, then optionally a duration in s and `lifted`"
        )
    };
    let f: Vec<&str> = pk.split(',').map(str::trim).collect();
    let (p, k, regime) = match f.as_slice() {
        [p, k, r] | [p, k, r, _] | [p, k, r, _, "lifted"] => (
            p.parse::<usize>().map_err(|_| bad())?,
            k.parse::<usize>().map_err(|_| bad())?,
            Regime::from_key(r).ok_or_else(bad)?,
        ),
        _ => return Err(bad().into()),
    };
    if let Some(d) = f.get(3) {
        // one run of `d` s, then this process's peak memory (kB)
        let mut scene = tirecontact::analysis::bench::scaling::scaling_scene(p, k, regime);
        if f.get(4).is_some() {
            scene = tirecontact::analysis::bench::scaling::lifted(&scene);
        }
        scene.duration_s = d.parse().map_err(|_| bad())?;
        let model = PreparedModel::of(&scene)?;
        let options = SolverOptions {
            threads,
            ..SolverOptions::default()
        };
        let mut sim = model.simulation(options)?;
        tirecontact::solver::drive::run_to_end(
            &mut sim,
            &mut (),
            tirecontact::solver::drive::Watch::none(),
        )?;
        println!("{}", peak_rss_kb().unwrap_or_default());
        return Ok(());
    }
    let (duration, repeats) = timed_runs(quick);
    let timing = Timing { repeats, threads };
    let r = tirecontact::analysis::bench::scaling::measure(p, k, regime, duration, timing)?;
    println!("{}", r.to_line());
    Ok(())
}

/// The scaling study: each size and contact regime in a child process,
/// callgrind's counts where valgrind is installed, then the report
/// ([`ScalingReport`]: table, fitted exponents, figure).
pub fn scaling(args: &BenchArgs) -> CliResult {
    crate::cli::paths::ensure_output_dir("-o", &args.output)?;
    let exe = std::env::current_exe()?;
    let (by_p, by_k) = scaling_sizes(args.quick);
    let repeats = timed_runs(args.quick).1;
    // every (size, regime) of the study, points first
    let mut jobs: Vec<(bool, usize, usize, Regime)> = [Regime::Rigid, Regime::Tread]
        .iter()
        .flat_map(|&r| {
            by_p.iter()
                .map(move |&(p, k)| (true, p, k, r))
                .chain(by_k.iter().map(move |&(p, k)| (false, p, k, r)))
        })
        .collect();
    // the contact patch, by points only
    jobs.extend(
        patch_sizes(args.quick)
            .into_iter()
            .map(|(p, k)| (true, p, k, Regime::Patch)),
    );
    let bar = ProgressBar::new(jobs.len() as u64);
    bar.set_style(
        ProgressStyle::with_template("{elapsed} [{bar:30}] {pos}/{len} sizes {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut sizes = Vec::with_capacity(jobs.len());
    for &(by_points, p, k, regime) in &jobs {
        bar.set_message(format!("P = {p}, K = {k}, {}", regime.label()));
        sizes.push(MeasuredSize {
            by_points,
            row: time_size(&exe, p, k, regime, args)?,
            peak_rss_kb: peak_memory_kb(&exe, p, k, regime, args.threads, &bar),
        });
        bar.inc(1);
    }
    // instructions per step: callgrind's count of 0.03 s less that of
    // 0.02 s (1000 rolling steps; the set-up and the ramp cancel)
    if callgrind_available(args.quick) {
        bar.set_position(0);
        for s in &mut sizes {
            let (p, k, regime) = (s.row.points, s.row.modes, s.row.regime);
            bar.set_message(format!("callgrind, P = {p}, K = {k}, {}", regime.label()));
            let per_step = |lifted: &str| {
                let n = |d: f64| {
                    let child = [
                        "--scaling-one".to_string(),
                        format!("{p},{k},{},{d}{lifted}", regime.key()),
                        "--threads".to_string(),
                        args.threads.to_string(),
                    ];
                    let what = format!("P = {p}, K = {k}, {}{lifted}", regime.label());
                    callgrind_count(&exe, &child, &what, &bar).map(|(n, _)| n)
                };
                Some((n(0.03)? - n(0.02)?) / 1000.0)
            };
            s.row.instructions_per_step = per_step("");
            s.row.free_instructions_per_step = per_step(",lifted");
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    let report = ScalingReport {
        sizes,
        repeats,
        threads: args.threads.into(),
    };
    let md = report.markdown();
    super::write(&args.output.join("scaling.csv"), &report.csv())?;
    super::write(&args.output.join("scaling.md"), &md)?;
    let fig = report.figure();
    let height = 500 * fig.panels.len() as u32;
    render_png(&fig, &args.output.join("scaling.png"), 1200, height)?;
    println!("{md}");
    println!(
        "wrote {}/scaling.csv, scaling.md and scaling.png",
        args.output.display()
    );
    Ok(())
}

/// Times one size in a child process (`--scaling-one P,K,CONTACT`).
fn time_size(
    exe: &std::path::Path,
    p: usize,
    k: usize,
    regime: Regime,
    args: &BenchArgs,
) -> Result<ScalingRow, Box<dyn std::error::Error>> {
    let mut cmd = std::process::Command::new(exe);
    cmd.args([
        "bench",
        "--scaling-one",
        &format!("{p},{k},{}", regime.key()),
        "--threads",
        &args.threads.to_string(),
    ]);
    if args.quick {
        cmd.arg("--quick");
    }
    let out = cmd.output()?;
    if !out.status.success() {
        return Err(format!(
            "P = {p}, K = {k}, {}: {}",
            regime.label(),
            String::from_utf8_lossy(&out.stderr).trim()
        )
        .into());
    }
    Ok(ScalingRow::from_line(
        p,
        k,
        regime,
        &String::from_utf8_lossy(&out.stdout),
    )?)
}

/// Whether callgrind can count: not with `--quick`, and only where
/// `valgrind` runs.
pub(super) fn callgrind_available(quick: bool) -> bool {
    !quick
        && std::process::Command::new("valgrind")
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
}

/// callgrind's instruction count of one child run of this executable,
/// `tirecontact bench CHILD_ARGS...` (a hidden one-run mode), its profile
/// discarded, and what the child printed; `what` names the run in a
/// warning on the progress bar, and `None` when it counted nothing.
pub(super) fn callgrind_count(
    exe: &std::path::Path,
    child_args: &[String],
    what: &str,
    bar: &ProgressBar,
) -> Option<(f64, String)> {
    let out = std::process::Command::new("valgrind")
        .args(["--tool=callgrind", "--callgrind-out-file=/dev/null"])
        .arg(exe)
        .arg("bench")
        .args(child_args)
        .output()
        .ok()?;
    let err = String::from_utf8_lossy(&out.stderr);
    let n = err
        .lines()
        .find_map(|l| l.split("Collected :").nth(1))
        .and_then(|n| n.trim().parse().ok());
    if n.is_none() || !out.status.success() {
        bar.println(format!(
            "warning: {what}: callgrind counted nothing ({}): {}",
            out.status,
            err.lines().last().unwrap_or("").trim()
        ));
        return None;
    }
    Some((n?, String::from_utf8_lossy(&out.stdout).into_owned()))
}
