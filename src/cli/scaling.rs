//! `tirecontact bench --scaling`: the cost of a step against the numbers
//! of points and modes ([`tirecontact::bench::scaling`]), each size in a
//! child process of its own (`--scaling-one P,K`) for its peak memory, and
//! callgrind's instruction counts where valgrind is installed.

use super::CliResult;
use super::bench::BenchArgs;
use indicatif::{ProgressBar, ProgressStyle};
use tirecontact::bench::scaling::ScalingRow;
use tirecontact::output::figures::render_png;
use tirecontact::{PreparedModel, SolverOptions};

/// (points, modes) of each measured size.
type Sizes = Vec<(usize, usize)>;
/// A measured size and its process's peak memory (kB).
type Measured = Vec<(ScalingRow, Option<u64>)>;

/// The sizes of the scaling study: points at 400 modes, modes at 24 points.
fn scaling_sizes(quick: bool) -> (Sizes, Sizes) {
    if quick {
        (vec![(5, 50), (20, 50)], vec![(10, 10), (10, 50)])
    } else {
        (
            [5, 10, 25, 50, 100, 200, 400]
                .iter()
                .map(|&p| (p, 400))
                .collect(),
            [10, 25, 50, 100, 200, 400]
                .iter()
                .map(|&k| (24, k))
                .collect(),
        )
    }
}

/// Runs one size and prints it as a CSV line with the process's peak
/// resident memory (kB, from /proc/self/status; empty where unknown).
pub fn scaling_one(pk: &str, quick: bool) -> CliResult {
    let bad = || format!("--scaling-one {pk}: expected P,K (points, modes), e.g. 50,400");
    let f: Vec<&str> = pk.split(',').map(str::trim).collect();
    let (p, k): (usize, usize) = match f.as_slice() {
        [p, k] | [p, k, _] => (p.parse().map_err(|_| bad())?, k.parse().map_err(|_| bad())?),
        _ => return Err(bad().into()),
    };
    if let Some(d) = f.get(2) {
        let mut scene = tirecontact::bench::scaling::scaling_scene(p, k);
        scene.duration_s = d.parse().map_err(|_| bad())?;
        let model = PreparedModel::of(&scene)?;
        let mut sim = tirecontact::Simulation::new(&model, SolverOptions::default())?;
        tirecontact::drive::run_to_end(&mut sim, &mut (), tirecontact::drive::Watch::none())?;
        return Ok(());
    }
    let (duration, repeats) = if quick { (0.02, 1) } else { (0.1, 3) };
    let r = tirecontact::bench::scaling::measure(p, k, duration, repeats)?;
    let rss = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|t| {
            t.lines()
                .find_map(|l| l.strip_prefix("VmHWM:"))
                .map(|v| v.trim().trim_end_matches("kB").trim().to_string())
        })
        .unwrap_or_default();
    println!(
        "{},{},{},{:e},{:e},{},{},{},{rss}",
        r.points,
        r.modes,
        r.steps,
        r.step_s,
        r.free_step_s,
        r.on_road,
        r.events_per_step,
        r.factorisations_per_step
    );
    Ok(())
}

/// The scaling study: each size in a child process, then the table, the
/// fitted exponents and the figure.
pub fn scaling(args: &BenchArgs) -> CliResult {
    use tirecontact::bench::scaling::{figure, loglog_slope};
    super::paths::ensure_output_dir("-o", &args.output)?;
    let exe = std::env::current_exe()?;
    let (by_p, by_k) = scaling_sizes(args.quick);
    let bar = ProgressBar::new((by_p.len() + by_k.len()) as u64);
    bar.set_style(
        ProgressStyle::with_template("{elapsed} [{bar:30}] {pos}/{len} sizes {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let run = |sizes: &[(usize, usize)]| -> Result<Measured, Box<dyn std::error::Error>> {
        let mut rows = Vec::new();
        for &(p, k) in sizes {
            bar.set_message(format!("P = {p}, K = {k}"));
            let mut cmd = std::process::Command::new(&exe);
            cmd.args(["bench", "--scaling-one", &format!("{p},{k}")]);
            if args.quick {
                cmd.arg("--quick");
            }
            let out = cmd.output()?;
            if !out.status.success() {
                return Err(format!(
                    "P = {p}, K = {k}: {}",
                    String::from_utf8_lossy(&out.stderr).trim()
                )
                .into());
            }
            let line = String::from_utf8_lossy(&out.stdout);
            let f: Vec<&str> = line.trim().split(',').collect();
            let num = |i: usize| -> Result<f64, String> {
                f.get(i)
                    .and_then(|x| x.parse().ok())
                    .ok_or_else(|| format!("P = {p}, K = {k}: unreadable line `{}`", line.trim()))
            };
            rows.push((
                ScalingRow {
                    points: p,
                    modes: k,
                    steps: num(2)? as u64,
                    step_s: num(3)?,
                    free_step_s: num(4)?,
                    on_road: num(5)?,
                    events_per_step: num(6)?,
                    factorisations_per_step: num(7)?,
                },
                f.get(8).and_then(|x| x.parse().ok()),
            ));
            bar.inc(1);
        }
        Ok(rows)
    };
    let rp = run(&by_p)?;
    let rk = run(&by_k)?;
    // instructions per step: callgrind's count of 0.03 s less that of
    // 0.02 s (1000 rolling steps; the set-up and the ramp cancel)
    let valgrind = std::process::Command::new("valgrind")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    let mut instructions: Vec<Option<f64>> = Vec::new();
    for &(p, k) in by_p.iter().chain(&by_k) {
        if !valgrind || args.quick {
            instructions.push(None);
            continue;
        }
        bar.set_message(format!("callgrind, P = {p}, K = {k}"));
        let count = |d: f64| -> Option<f64> {
            let out = std::process::Command::new("valgrind")
                .args(["--tool=callgrind", "--callgrind-out-file=/dev/null"])
                .arg(&exe)
                .args(["bench", "--scaling-one", &format!("{p},{k},{d}")])
                .output()
                .ok()?;
            let err = String::from_utf8_lossy(&out.stderr);
            err.lines()
                .find_map(|l| l.split("Collected :").nth(1))
                .and_then(|n| n.trim().parse().ok())
        };
        instructions.push(match (count(0.02), count(0.03)) {
            (Some(a), Some(b)) => Some((b - a) / 1000.0),
            _ => None,
        });
    }
    bar.finish_and_clear();
    let mut csv = String::from(
        "points,modes,steps,step_s,free_step_s,contact_share,on_road,events_per_step,factorisations_per_step,instructions_per_step,max_rss_kb\n",
    );
    let mut md = String::from(
        "# Cost of a step against the problem's size\n\nRank-1 modes; the middle third of the points pressed by up to 2 mm on a 0.1 mm sine road at 10 m/s; dt = 1e-5 s. Each size runs in its own process (its peak resident memory); the fastest of its runs. The contact's share is 1 − (the same scene off the road) / (with contact). Instructions per step: callgrind's count over 1000 rolling steps (`-` without valgrind or with --quick).\n\n| points P | modes K | µs per step | off the road | contact share | points on the road | events per step | factorisations per step | instructions per step | peak memory (MB) |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for ((r, rss), ins) in rp.iter().chain(&rk).zip(&instructions) {
        let ins_text = ins.map_or(String::new(), |n| format!("{n:.0}"));
        csv.push_str(&format!(
            "{},{},{},{:e},{:e},{:.4},{:.4},{:.4},{:.4},{ins_text},{}\n",
            r.points,
            r.modes,
            r.steps,
            r.step_s,
            r.free_step_s,
            r.contact_share(),
            r.on_road,
            r.events_per_step,
            r.factorisations_per_step,
            rss.map_or(String::new(), |v| v.to_string())
        ));
        md.push_str(&format!(
            "| {} | {} | {:.2} | {:.2} | {:.0} % | {:.2} | {:.3} | {:.3} | {} | {} |\n",
            r.points,
            r.modes,
            r.step_s * 1e6,
            r.free_step_s * 1e6,
            100.0 * r.contact_share(),
            r.on_road * r.points as f64,
            r.events_per_step,
            r.factorisations_per_step,
            if ins_text.is_empty() { "-" } else { &ins_text },
            rss.map_or("-".into(), |v| format!("{:.1}", v as f64 / 1024.0))
        ));
    }
    let slope = |rows: &[(ScalingRow, Option<u64>)], by_p: bool, free: bool| {
        loglog_slope(
            &rows
                .iter()
                .map(|(r, _)| {
                    (
                        (if by_p { r.points } else { r.modes }) as f64,
                        if free { r.free_step_s } else { r.step_s },
                    )
                })
                .collect::<Vec<_>>(),
        )
    };
    md.push_str(&format!(
        "\nFitted exponents (least squares, log-log): time per step ∝ P^{:.2} with contact, P^{:.2} off the road (K = {}); ∝ K^{:.2} with contact, K^{:.2} off the road (P = {}).\n",
        slope(&rp, true, false), slope(&rp, true, true), by_p.first().map_or(0, |s| s.1),
        slope(&rk, false, false), slope(&rk, false, true), by_k.first().map_or(0, |s| s.0),
    ));
    let (ip, ik) = instructions.split_at(by_p.len());
    let ins_slope = |sizes: &[(usize, usize)], ins: &[Option<f64>], by_p: bool| -> Option<f64> {
        let xy: Option<Vec<(f64, f64)>> = sizes
            .iter()
            .zip(ins)
            .map(|(&(p, k), n)| n.map(|n| ((if by_p { p } else { k }) as f64, n)))
            .collect();
        xy.filter(|v| v.len() >= 2).map(|v| loglog_slope(&v))
    };
    if let (Some(a), Some(b)) = (ins_slope(&by_p, ip, true), ins_slope(&by_k, ik, false)) {
        md.push_str(&format!(
            "Instructions per step ∝ P^{a:.2} (K = {}), ∝ K^{b:.2} (P = {}).\n",
            by_p.first().map_or(0, |s| s.1),
            by_k.first().map_or(0, |s| s.0)
        ));
    }
    super::bench::write(&args.output.join("scaling.csv"), &csv)?;
    super::bench::write(&args.output.join("scaling.md"), &md)?;
    let rows_p: Vec<ScalingRow> = rp.into_iter().map(|(r, _)| r).collect();
    let rows_k: Vec<ScalingRow> = rk.into_iter().map(|(r, _)| r).collect();
    render_png(
        &figure(&rows_p, &rows_k),
        &args.output.join("scaling.png"),
        1200,
        1000,
    )?;
    println!("{md}");
    println!(
        "wrote {}/scaling.csv, scaling.md and scaling.png",
        args.output.display()
    );
    Ok(())
}
