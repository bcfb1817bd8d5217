//! The command line: `run` writes the documented CSV and a one-line summary;
//! errors exit non-zero with a message naming the problem.

use crate::support::{bin, temp_dir};

#[test]
fn run_writes_csv_and_summary() {
    let tmp = temp_dir();
    let d = tmp.path();
    let out = d.join("out.csv");
    let o = bin()
        .args([
            "run",
            "presets/three_points.ron",
            "--duration",
            "0.002",
            "--every",
            "10",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary = String::from_utf8_lossy(&o.stdout);
    assert!(
        summary.contains("200 steps") && summary.contains("contact fraction"),
        "{summary}"
    );
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "t_s");
    assert_eq!(&header[1..4], ["u0_m", "u1_m", "u2_m"]);
    assert_eq!(header[4], "v0_mps");
    assert_eq!(header[7], "q0_N");
    assert_eq!(header[10], "gap0_m");
    assert_eq!(&header[13..16], ["contact0", "contact1", "contact2"]);
    // initial row + 20 rows of 10 steps
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 21);
    assert!((rows[20][0] - 0.002).abs() < 1e-12);
}

#[test]
fn bad_preset_exits_nonzero_with_location() {
    let tmp = temp_dir();
    let d = tmp.path();
    let p = d.join("bad.ron");
    std::fs::write(&p, "Scene(\n  name: \"x\",\n  tyre: Modal(modes: [)\n)").unwrap();
    for cmd in ["check", "run"] {
        let o = bin().arg(cmd).arg(&p).output().unwrap();
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("bad.ron:3:"), "{cmd}: {err}");
    }
    let o = bin().args(["check", "no/such/file.ron"]).output().unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("no/such/file.ron"));
}

#[test]
fn negative_overrides_are_named_by_validation() {
    // clap would take "-1" for a flag; the scene's validation names the field
    for (flag, field) in [("--dt", "dt_s = -1"), ("--duration", "duration_s = -1")] {
        let o = bin().args(["run", flag, "-1"]).output().unwrap();
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains(field) && err.contains("> 0 s"),
            "{flag}: {err}"
        );
    }
}

#[test]
fn check_accepts_shipped_presets() {
    let o = bin()
        .args(["check", "presets/single_mode.ron"])
        .output()
        .unwrap();
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("ok"));
}

#[test]
fn run_spectrum_and_sweep_write_their_tables() {
    let tmp = temp_dir();
    let d = tmp.path();
    let spec = d.join("spectrum.csv");
    let o = bin()
        .args([
            "run",
            "presets/three_points.ron",
            "--duration",
            "0.08",
            "--spectrum",
        ])
        .arg(&spec)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&spec).unwrap();
    assert!(text.starts_with(
        "freq_hz,q0_db_re_1N,q1_db_re_1N,q2_db_re_1N,q_total_db_re_1N,u0_db_re_1m,u1_db_re_1m,u2_db_re_1m\n"
    ));
    let bands = std::fs::read_to_string(d.join("spectrum_bands.csv")).unwrap();
    assert!(bands.lines().any(|l| l.starts_with("315,")), "{bands}");

    let table = d.join("sweep.csv");
    let o = bin()
        .args([
            "sweep",
            "presets/three_points.ron",
            "--param",
            "points[*].h_m",
            "--from",
            "-0.001",
            "--to",
            "-0.002",
            "--steps",
            "3",
            "--duration",
            "0.05",
            "-o",
        ])
        .arg(&table)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&table).unwrap();
    assert_eq!(text.lines().count(), 4);
    assert!(text.starts_with("points[*].h_m,q0_smooth_max_N,"));
    let o = bin()
        .args([
            "sweep",
            "presets/three_points.ron",
            "--param",
            "speed_kmh",
            "--from",
            "1",
            "--to",
            "2",
        ])
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("speed_kmh") && err.contains("speed_mps"),
        "{err}"
    );
}

/// A run that fails half-way (a measured road shorter than the run) exits
/// non-zero and leaves an existing output file as it was, with no temporary.
#[test]
fn a_failed_run_keeps_the_old_output_file() {
    let tmp = temp_dir();
    let d = tmp.path();
    std::fs::write(
        d.join("road.csv"),
        "x_m,z_m\n0.0,0.0\n0.05,0.001\n0.1,0.0\n",
    )
    .unwrap();
    let preset = d.join("short.ron");
    std::fs::write(
        &preset,
        r#"Scene(
        name: "short road",
        tyre: Modal(modes: [Mode(freq_hz: 100.0, damping_ratio: 0.05, residue: [[0.1]])]),
        points: [Point(x_m: 0.0, h_m: -0.001)],
        road: Measured(file: "road.csv"),
        speed_mps: 10.0,
        ramp_s: 0.002,
        dt_s: 1e-5,
        duration_s: 0.05,
    )"#,
    )
    .unwrap();
    let out = d.join("out.csv");
    std::fs::write(&out, "old results\n").unwrap();
    let o = bin()
        .arg("run")
        .arg(&preset)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("outside its extent"), "{err}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "old results\n");
    let left: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp-"))
        .collect();
    assert!(left.is_empty(), "temporaries left: {left:?}");
    // the same run to a good end replaces the file
    let o = bin()
        .args([
            "run",
            "presets/single_mode.ron",
            "--duration",
            "0.001",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read_to_string(&out).unwrap().starts_with("t_s,"));
}

/// A time step too coarse for the scene leaves penetration at step ends:
/// `run` still finishes but warns and suggests a smaller step; a resolved
/// run does not warn.
#[test]
fn run_warns_when_the_time_step_leaves_penetration() {
    let run = |dt: &str| {
        bin()
            .args([
                "run",
                "presets/three_points.ron",
                "--duration",
                "0.2",
                "--dt",
                dt,
            ])
            .output()
            .unwrap()
    };
    // 2e-3 s: 3.3e-4 m left behind (at 1e-3 s impacts solved jointly over
    // the points at the road leave none, where one point at a time left
    // 4e-6 m)
    let coarse = run("2e-3");
    assert!(coarse.status.success());
    let err = String::from_utf8_lossy(&coarse.stderr);
    assert!(
        err.contains("warning: a point was left") && err.contains("--dt"),
        "{err}"
    );
    let fine = run("1e-5");
    assert!(fine.status.success());
    let err = String::from_utf8_lossy(&fine.stderr);
    assert!(!err.contains("warning"), "{err}");
}

/// `run --threads N`: the same CSV, byte for byte, as on one thread;
/// `--threads 0` is refused, naming the option.
#[test]
fn threads_option_keeps_the_results_and_refuses_zero() {
    let tmp = temp_dir();
    let d = tmp.path();
    let csv = |threads: &str| -> String {
        let out = d.join(format!("threads_{threads}.csv"));
        let o = bin()
            .args(["run", "presets/paper.ron", "--duration", "0.05"])
            .args(["--threads", threads, "-o"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read_to_string(&out).unwrap()
    };
    let one = csv("1");
    assert!(one.lines().count() > 100);
    assert_eq!(csv("2"), one);
    let o = bin()
        .args(["run", "presets/paper.ron", "--threads", "0"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--threads = 0: expected"), "{err}");
}

/// `run --exact-rank` keeps every residue term: the paper preset's results
/// move, by about 1e-6 of the displacements, against the default rank cut.
#[test]
fn exact_rank_flag_keeps_every_residue_term() {
    let tmp = temp_dir();
    let d = tmp.path();
    let displacements = |extra: &[&str], name: &str| -> Vec<f64> {
        let out = d.join(name);
        let o = bin()
            .args([
                "run",
                "presets/paper.ron",
                "--duration",
                "0.1",
                "--every",
                "100",
            ])
            .args(extra)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = std::fs::read_to_string(&out).unwrap();
        text.lines()
            .skip(1)
            .flat_map(|l| {
                l.split(',')
                    .skip(1)
                    .take(5)
                    .map(|x| x.parse::<f64>().unwrap())
                    .collect::<Vec<_>>()
            })
            .collect()
    };
    let (cut, exact) = (
        displacements(&[], "cut.csv"),
        displacements(&["--exact-rank"], "exact.csv"),
    );
    let peak = exact.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = cut
        .iter()
        .zip(&exact)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(peak > 1e-4, "peak displacement {peak} m");
    assert!(
        diff > 0.0 && diff < 1e-5 * peak,
        "moved {diff:e} m of {peak:e} m"
    );
}

#[test]
fn bench_quick_writes_its_tables_and_diagram() {
    let tmp = temp_dir();
    let d = tmp.path();
    let o = bin()
        .args(["bench", "--quick", "presets/single_mode.ron", "-o"])
        .arg(d)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(d.join("work_precision.md")).unwrap();
    for section in [
        "# Work-precision study",
        "## Speed",
        "## Work skipped",
        "## Residual flexibility",
    ] {
        assert!(md.contains(section), "no {section:?} in:\n{md}");
    }
    // the speed table: the preset and both synthetic scenes, medians of repeated runs
    assert!(md.contains("run 3 times"), "{md}");
    for scene in ["Single mode", "5 points x 20", "50 points x 200"] {
        assert!(
            md.lines().any(|l| l.starts_with(&format!("| {scene}"))),
            "no speed row for {scene}"
        );
    }
    let csv = std::fs::read_to_string(d.join("work_precision.csv")).unwrap();
    assert!(csv.lines().count() > 5, "{csv}");
    // one diagram per scene, named after it
    let png = std::fs::read(d.join("work_precision_single_mode_on_a_sine_road.png")).unwrap();
    assert_eq!(&png[..4], b"\x89PNG");
}

#[test]
fn run_plots_clipped_by_default_and_whole_on_request() {
    let tmp = temp_dir();
    let d = tmp.path();
    for (name, extra) in [
        ("clipped.png", None),
        ("whole.png", Some("--plot-unclipped")),
    ] {
        let png = d.join(name);
        let o = bin()
            .args(["run", "presets/three_points.ron", "--duration", "0.03"])
            .arg("--plot")
            .arg(&png)
            .args(extra)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(&std::fs::read(&png).unwrap()[1..4], b"PNG");
    }
    // the two figures differ (the spikes are cut in one)
    assert_ne!(
        std::fs::read(d.join("clipped.png")).unwrap(),
        std::fs::read(d.join("whole.png")).unwrap()
    );
}

/// The OpenCRG preset: `check` prints the file's `u` range, where the
/// patch starts and the height taken off (the road's mean height); `run`
/// steps it; a duration past the file's end is refused naming the last
/// time that fits.
#[test]
fn check_and_run_the_opencrg_preset() {
    let o = bin()
        .args(["check", "presets/patch_belgian_block.ron"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    for want in [
        "road OpenCRG",
        "1001 × 341 nodes",
        "the file covers u 730.000 m to 740.000 m; x = 0 at u = 731.000 m",
        "2.1135 m (the absolute height offset)",
    ] {
        assert!(out.contains(want), "`{want}` missing in: {out}");
    }
    let o = bin()
        .args([
            "run",
            "presets/patch_belgian_block.ron",
            "--duration",
            "0.0005",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("50 steps"));
    let o = bin()
        .args(["run", "presets/patch_belgian_block.ron", "--duration", "5"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("duration_s") && err.contains("a duration <= 1.119375 s"),
        "{err}"
    );
}
