//! `tirecontact bench --scaling`: the cost of a step against the numbers
//! of points and modes ([`tirecontact::bench::scaling`]) for both contact
//! laws, each size timed in a child process of its own
//! (`--scaling-one P,K,CONTACT`), its peak memory from one run in another
//! (`P,K,CONTACT,SECONDS`), and callgrind's instruction counts, with
//! contact and lifted off the road, where valgrind is installed.

use super::CliResult;
use super::bench::BenchArgs;
use indicatif::{ProgressBar, ProgressStyle};
use tirecontact::bench::scaling::{Regime, ScalingRow};
use tirecontact::output::figures::render_png;
use tirecontact::{PreparedModel, SolverOptions};

/// (points, modes) of each measured size.
type Sizes = Vec<(usize, usize)>;
/// A measured size and its process's peak memory (kB).
type Measured = Vec<(ScalingRow, Option<u64>)>;

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

/// The peak memory (kB) of one 0.1 s run of a size in a process of its
/// own; a warning on the progress bar and `None` when it fails.
fn peak_memory_kb(
    exe: &std::path::Path,
    p: usize,
    k: usize,
    regime: Regime,
    bar: &ProgressBar,
) -> Option<u64> {
    let out = std::process::Command::new(exe)
        .args([
            "bench",
            "--scaling-one",
            &format!("{p},{k},{},0.1", regime.key()),
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
pub fn scaling_one(pk: &str, quick: bool) -> CliResult {
    let bad = || {
        format!(
            "--scaling-one {pk}: expected P,K,CONTACT (points, modes, `rigid` or `tread`), e.g. 50,400,tread, then optionally a duration in s and `lifted`"
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
        let mut scene = tirecontact::bench::scaling::scaling_scene(p, k, regime);
        if f.get(4).is_some() {
            scene = tirecontact::bench::scaling::lifted(&scene);
        }
        scene.duration_s = d.parse().map_err(|_| bad())?;
        let model = PreparedModel::of(&scene)?;
        let mut sim = tirecontact::Simulation::new(&model, SolverOptions::default())?;
        tirecontact::drive::run_to_end(&mut sim, &mut (), tirecontact::drive::Watch::none())?;
        println!("{}", peak_rss_kb().unwrap_or_default());
        return Ok(());
    }
    let (duration, repeats) = timed_runs(quick);
    let r = tirecontact::bench::scaling::measure(p, k, regime, duration, repeats)?;
    println!(
        "{},{},{},{:e},{:e},{},{},{}",
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

/// The scaling study: each size and contact regime in a child process,
/// then the table, the fitted exponents and the figure.
pub fn scaling(args: &BenchArgs) -> CliResult {
    use tirecontact::bench::scaling::{figure, loglog_slope};
    super::paths::ensure_output_dir("-o", &args.output)?;
    let exe = std::env::current_exe()?;
    let (by_p, by_k) = scaling_sizes(args.quick);
    let repeats = timed_runs(args.quick).1;
    // every (size, regime) of the study, points first
    let jobs: Vec<(bool, usize, usize, Regime)> = Regime::ALL
        .iter()
        .flat_map(|&r| {
            by_p.iter()
                .map(move |&(p, k)| (true, p, k, r))
                .chain(by_k.iter().map(move |&(p, k)| (false, p, k, r)))
        })
        .collect();
    let bar = ProgressBar::new(jobs.len() as u64);
    bar.set_style(
        ProgressStyle::with_template("{elapsed} [{bar:30}] {pos}/{len} sizes {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut measured: Measured = Vec::new();
    for &(_, p, k, regime) in &jobs {
        bar.set_message(format!("P = {p}, K = {k}, {}", regime.label()));
        let mut cmd = std::process::Command::new(&exe);
        cmd.args([
            "bench",
            "--scaling-one",
            &format!("{p},{k},{}", regime.key()),
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
        let line = String::from_utf8_lossy(&out.stdout);
        let f: Vec<&str> = line.trim().split(',').collect();
        let num = |i: usize| -> Result<f64, String> {
            f.get(i)
                .and_then(|x| x.parse().ok())
                .ok_or_else(|| format!("P = {p}, K = {k}: unreadable line `{}`", line.trim()))
        };
        measured.push((
            ScalingRow {
                points: p,
                regime,
                modes: k,
                steps: num(2)? as u64,
                step_s: num(3)?,
                free_step_s: num(4)?,
                on_road: num(5)?,
                events_per_step: num(6)?,
                factorisations_per_step: num(7)?,
                instructions_per_step: None,
                free_instructions_per_step: None,
            },
            peak_memory_kb(&exe, p, k, regime, &bar),
        ));
        bar.inc(1);
    }
    // instructions per step: callgrind's count of 0.03 s less that of
    // 0.02 s (1000 rolling steps; the set-up and the ramp cancel)
    let valgrind = !args.quick
        && std::process::Command::new("valgrind")
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success());
    bar.set_position(0);
    let counted = if valgrind { measured.len() } else { 0 };
    for (&(_, p, k, regime), (row, _)) in jobs.iter().zip(&mut measured).take(counted) {
        bar.set_message(format!("callgrind, P = {p}, K = {k}, {}", regime.label()));
        let count = |d: f64, lifted: &str| -> Option<f64> {
            let out = std::process::Command::new("valgrind")
                .args(["--tool=callgrind", "--callgrind-out-file=/dev/null"])
                .arg(&exe)
                .args([
                    "bench",
                    "--scaling-one",
                    &format!("{p},{k},{},{d}{lifted}", regime.key()),
                ])
                .output()
                .ok()?;
            let err = String::from_utf8_lossy(&out.stderr);
            let n = err
                .lines()
                .find_map(|l| l.split("Collected :").nth(1))
                .and_then(|n| n.trim().parse().ok());
            if n.is_none() || !out.status.success() {
                bar.println(format!(
                    "warning: P = {p}, K = {k}, {}{lifted}: callgrind counted nothing ({}): {}",
                    regime.label(),
                    out.status,
                    err.lines().last().unwrap_or("").trim()
                ));
            }
            n
        };
        let per_step = |lifted: &str| Some((count(0.03, lifted)? - count(0.02, lifted)?) / 1000.0);
        row.instructions_per_step = per_step("");
        row.free_instructions_per_step = per_step(",lifted");
        bar.inc(1);
    }
    bar.finish_and_clear();
    let mut csv = String::from(
        "contact,points,modes,steps,step_s,free_step_s,contact_share,on_road,events_per_step,factorisations_per_step,instructions_per_step,free_instructions_per_step,contact_share_instructions,max_rss_kb\n",
    );
    let mut md = format!(
        "# Cost of a step against the problem's size\n\nRank-1 modes; the middle third of the points pressed by up to {} mm on a 0.1 mm sine road at 10 m/s; dt = 1e-5 s. Rigid contact holds about one point on the road (the smooth mode shapes lift the neighbours of a pressed point); a soft tread spring at each point (compliant contact, {:e} N/m shared by the points) holds the pressed third. Each size is timed in its own process, the fastest of {repeats} run(s); its peak resident memory is that of one 0.1 s run in a process of its own. The contact's share is 1 − (the same scene off the road) / (with contact), by wall time and by instructions. Instructions per step: callgrind's count over 1000 rolling steps (`-` without valgrind or with --quick); unlike wall times they repeat exactly.\n\n| contact | points P | modes K | µs per step | off the road | contact share | points on the road | events per step | factorisations per step | instructions per step | off the road | contact share by instructions | peak memory (MB) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        tirecontact::bench::scaling::PRELOAD_M * 1e3,
        tirecontact::bench::scaling::TREAD_TOTAL_N_M,
    );
    for (r, rss) in &measured {
        let fmt = |x: Option<f64>, f: &dyn Fn(f64) -> String| x.map_or(String::new(), f);
        let (with, free) = (r.instructions_per_step, r.free_instructions_per_step);
        let share = r.contact_share_instructions();
        csv.push_str(&format!(
            "{},{},{},{},{:e},{:e},{:.4},{:.4},{:.4},{:.4},{},{},{},{}\n",
            r.regime.key(),
            r.points,
            r.modes,
            r.steps,
            r.step_s,
            r.free_step_s,
            r.contact_share(),
            r.on_road,
            r.events_per_step,
            r.factorisations_per_step,
            fmt(with, &|n| format!("{n:.0}")),
            fmt(free, &|n| format!("{n:.0}")),
            fmt(share, &|x| format!("{x:.4}")),
            rss.map_or(String::new(), |v| v.to_string())
        ));
        let or_dash = |t: String| if t.is_empty() { "-".to_string() } else { t };
        md.push_str(&format!(
            "| {} | {} | {} | {:.2} | {:.2} | {:.0} % | {:.1} | {:.3} | {:.3} | {} | {} | {} | {} |\n",
            r.regime.key(),
            r.points,
            r.modes,
            r.step_s * 1e6,
            r.free_step_s * 1e6,
            100.0 * r.contact_share(),
            r.on_road * r.points as f64,
            r.events_per_step,
            r.factorisations_per_step,
            or_dash(fmt(with, &|n| format!("{n:.0}"))),
            or_dash(fmt(free, &|n| format!("{n:.0}"))),
            or_dash(fmt(share, &|x| format!("{:.0} %", 100.0 * x))),
            rss.map_or("-".into(), |v| format!("{:.1}", v as f64 / 1024.0))
        ));
    }
    // the rows of one scan (by P or by K) of a regime
    let scan = |by_points: bool, regime: Regime| -> Vec<&ScalingRow> {
        jobs.iter()
            .zip(&measured)
            .filter(|((b, _, _, r), _)| *b == by_points && *r == regime)
            .map(|(_, (row, _))| row)
            .collect()
    };
    let x = |r: &ScalingRow, by_points: bool| (if by_points { r.points } else { r.modes }) as f64;
    let slope = |by_points: bool, regime: Regime, free: bool| {
        let xy: Vec<(f64, f64)> = scan(by_points, regime)
            .iter()
            .map(|r| (x(r, by_points), if free { r.free_step_s } else { r.step_s }))
            .collect();
        loglog_slope(&xy)
    };
    // (x, instructions per step) of a scan, where every row was counted
    let ins_xy = |by_points: bool, regime: Regime| -> Option<Vec<(f64, f64)>> {
        let xy: Option<Vec<(f64, f64)>> = scan(by_points, regime)
            .iter()
            .map(|r| r.instructions_per_step.map(|n| (x(r, by_points), n)))
            .collect();
        xy.filter(|v| v.len() >= 2)
    };
    let ins_slope =
        |by_points: bool, regime: Regime| ins_xy(by_points, regime).map(|v| loglog_slope(&v));
    let (k_fixed, p_fixed) = (
        by_p.first().map_or(0, |s| s.1),
        by_k.first().map_or(0, |s| s.0),
    );
    md.push_str(&format!(
        "\nFitted exponents (least squares, log-log) of the time per step: off the road P^{:.2} (K = {k_fixed}) and K^{:.2} (P = {p_fixed}).\n",
        slope(true, Regime::Rigid, true),
        slope(false, Regime::Rigid, true),
    ));
    for regime in Regime::ALL {
        md.push_str(&format!(
            "- {}: P^{:.2}, K^{:.2}",
            regime.label(),
            slope(true, regime, false),
            slope(false, regime, false)
        ));
        if let (Some(a), Some(b)) = (ins_slope(true, regime), ins_slope(false, regime)) {
            md.push_str(&format!("; instructions per step P^{a:.2}, K^{b:.2}"));
        }
        md.push_str(".\n");
    }
    // the small active set's instructions against K and against P: affine
    let fit = |by_points: bool| {
        ins_xy(by_points, Regime::Rigid).map(|v| tirecontact::bench::scaling::line_fit(&v))
    };
    if let (Some((ak, bk)), Some((ap, bp))) = (fit(false), fit(true)) {
        md.push_str(&format!(
            "\nWith rigid contact (a small active set) the instructions per step are {ak:.0} + {bk:.1} K at P = {p_fixed} and {ap:.0} + {bp:.1} P at K = {k_fixed}: each mode adds {:.2} instructions per point and step, each point {:.2} per mode (the O(K·P) modal update), on top of parts in P or K alone.\n",
            bk / p_fixed.max(1) as f64,
            bp / k_fixed.max(1) as f64
        ));
    }
    // the contact's share, by instructions where counted
    let share = |r: &ScalingRow| {
        r.contact_share_instructions()
            .map_or((r.contact_share(), "wall time"), |s| (s, "instructions"))
    };
    let dominant = scan(true, Regime::Tread)
        .into_iter()
        .find(|r| share(r).0 > 0.5);
    md.push_str(&match dominant {
        Some(r) => format!(
            "\nWith the pressed third on the road the contact takes more than half of a step from P = {} ({:.1} points on the road, {:.0} % of the step by {}).\n",
            r.points,
            r.on_road * r.points as f64,
            100.0 * share(r).0,
            share(r).1
        ),
        None => "\nWith the pressed third on the road the contact stays below half of a step at every measured P.\n".to_string(),
    });
    super::bench::write(&args.output.join("scaling.csv"), &csv)?;
    super::bench::write(&args.output.join("scaling.md"), &md)?;
    let rows = |by_points: bool| -> Vec<ScalingRow> {
        Regime::ALL
            .iter()
            .flat_map(|&r| scan(by_points, r).into_iter().cloned())
            .collect()
    };
    let fig = figure(&rows(true), &rows(false));
    let height = 500 * fig.panels.len() as u32;
    render_png(&fig, &args.output.join("scaling.png"), 1200, height)?;
    println!("{md}");
    println!(
        "wrote {}/scaling.csv, scaling.md and scaling.png",
        args.output.display()
    );
    Ok(())
}
