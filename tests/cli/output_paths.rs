//! A first-time user's mistakes with output paths and short runs: refused
//! before any work (nothing printed on stdout, no file written), naming the
//! option, the path and what to do; output folders of `identify --figures`
//! are created like those of `run --frames` and `bench -o`.

use crate::support::{bin, temp_dir};
use std::path::{Path, PathBuf};
use std::process::Output;

/// Every file under `dir`, recursively.
fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(files_under(&p));
        } else {
            out.push(p);
        }
    }
    out
}

/// Exit code 1, no panic, nothing on stdout (no run, no identification
/// printed), and every one of `words` in the message.
fn refused(o: &Output, words: &[&str], what: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{what}: {err}");
    assert!(!err.contains("panicked"), "{what}: {err}");
    assert!(
        o.stdout.is_empty(),
        "{what}: ran before refusing: {}",
        String::from_utf8_lossy(&o.stdout)
    );
    for w in words {
        assert!(err.contains(w), "{what}: `{w}` missing in: {err}");
    }
}

#[test]
fn outputs_in_missing_folders_are_refused_before_any_work() {
    let tmp = temp_dir();
    let d = tmp.path();
    let missing = d.join("no_such_folder");
    let m = |f: &str| missing.join(f).display().to_string();
    let folder = missing.display().to_string();
    let run = |extra: &[&str]| {
        bin()
            .args(["run", "presets/single_mode.ron", "--duration", "0.2"])
            .args(extra)
            .output()
            .unwrap()
    };
    for (opt, file, kind) in [
        ("-o", "out.csv", "CSV"),
        ("--spectrum", "s.csv", "CSV"),
        ("--spectrum-plot", "s.png", "PNG"),
        ("--plot", "fig.png", "PNG"),
    ] {
        let o = run(&[opt, &m(file)]);
        let head = format!("{opt} {}", m(file));
        let expected = format!("expected a {kind} path in an existing folder");
        refused(
            &o,
            &[&head, &format!("no folder {folder}"), &expected, "mkdir -p"],
            &format!("run {opt}"),
        );
    }
    // the spectrum CSV and a plot beside it: the later one's folder is
    // missing, the earlier one is not written either
    let ok_csv = d.join("s.csv");
    let o = run(&[
        "--spectrum",
        &ok_csv.display().to_string(),
        "--spectrum-plot",
        &m("s.png"),
    ]);
    refused(&o, &["--spectrum-plot"], "run --spectrum + --spectrum-plot");
    for (opt, file, kind) in [("-o", "sweep.csv", "CSV"), ("--plot", "sweep.png", "PNG")] {
        let o = bin()
            .args([
                "sweep",
                "presets/single_mode.ron",
                "--param",
                "speed_mps",
                "--from",
                "10",
                "--to",
                "20",
                "--steps",
                "2",
                "--duration",
                "0.2",
                opt,
                &m(file),
            ])
            .output()
            .unwrap();
        let expected = format!("expected a {kind} path in an existing folder");
        refused(
            &o,
            &[&format!("{opt} {}", m(file)), &expected],
            &format!("sweep {opt}"),
        );
    }
    // identify: the diagram written, then -o failing, used to leave one of
    // two outputs behind
    let diagram = d.join("d.png");
    for (opt, file, kind) in [
        ("-o", "modal.ron", "RON"),
        ("--diagram", "d.png", "PNG"),
        ("--responses", "irf.csv", "CSV"),
    ] {
        let mut cmd = bin();
        cmd.args(["identify", "presets/paper.ron", opt, &m(file)]);
        if opt != "--diagram" {
            cmd.arg("--diagram").arg(&diagram);
        }
        let o = cmd.output().unwrap();
        let expected = format!("expected a {kind} path in an existing folder");
        refused(
            &o,
            &[&format!("{opt} {}", m(file)), &expected],
            &format!("identify {opt}"),
        );
    }
    assert!(!missing.exists(), "a refused output created its folder");
    assert_eq!(files_under(d), Vec::<PathBuf>::new(), "files left behind");
}

#[test]
fn a_folder_given_for_an_output_file_is_refused() {
    let tmp = temp_dir();
    let d = tmp.path();
    let o = bin()
        .args(["run", "presets/single_mode.ron", "--duration", "0.2", "-o"])
        .arg(d)
        .output()
        .unwrap();
    refused(
        &o,
        &[&format!("-o {}: is a folder", d.display()), "out.csv"],
        "run -o DIR",
    );
    // a file where identify --figures wants a folder
    let f = d.join("file");
    std::fs::write(&f, "x").unwrap();
    let o = bin()
        .args(["identify", "presets/paper.ron", "--figures"])
        .arg(&f)
        .output()
        .unwrap();
    refused(
        &o,
        &[&format!("--figures {}: is a file", f.display())],
        "identify --figures FILE",
    );
}

#[test]
fn identify_figures_creates_its_folder() {
    let tmp = temp_dir();
    let d = tmp.path();
    let dir = d.join("new/figures");
    let o = bin()
        .args(["identify", "presets/paper.ron", "--figures"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in ["paper_fig1_displacement.png", "paper_fig2_force.png"] {
        assert_eq!(&std::fs::read(dir.join(f)).unwrap()[1..4], b"PNG", "{f}");
    }
}

#[test]
fn a_spectrum_of_a_run_without_steady_part_is_refused_before_the_run() {
    let tmp = temp_dir();
    let d = tmp.path();
    let s = d.join("s.csv");
    // single_mode.ron: ramp_s = 0.05 s; the steady part is empty
    let o = bin()
        .args([
            "run",
            "presets/single_mode.ron",
            "--duration",
            "0.05",
            "--spectrum",
        ])
        .arg(&s)
        .output()
        .unwrap();
    refused(
        &o,
        &[
            "spectrum of 0 samples: expected at least 8 samples of the steady part",
            "lengthen duration_s (--duration)",
        ],
        "run --spectrum, duration = ramp_s",
    );
    assert!(!s.exists());
}

#[test]
fn preset_errors_count_in_english_and_a_missing_road_file_says_where_it_was_looked_for() {
    let tmp = temp_dir();
    let d = tmp.path();
    let base = std::fs::read_to_string("presets/single_mode.ron").unwrap();
    let bad = d.join("negdamp.ron");
    std::fs::write(
        &bad,
        base.replace("damping_ratio: 0.05", "damping_ratio: -0.1"),
    )
    .unwrap();
    let o = bin().arg("check").arg(&bad).output().unwrap();
    refused(
        &o,
        &[
            &format!("{}: 1 invalid value\n", bad.display()),
            "tyre.modes[0].damping_ratio = -0.1: expected",
        ],
        "negative damping",
    );
    let road = d.join("road.ron");
    std::fs::write(
        &road,
        base.replace(
            "road: Sine(amplitude_m: 0.002, wavelength_m: 0.5)",
            "road: Measured(file: \"nosuch.csv\")",
        ),
    )
    .unwrap();
    let o = bin().arg("check").arg(&road).output().unwrap();
    refused(
        &o,
        &[
            &format!(
                "road.file = {}: cannot open",
                d.join("nosuch.csv").display()
            ),
            "relative path is taken from the preset's folder",
        ],
        "missing road file",
    );
}

#[test]
fn check_names_each_number_it_prints() {
    // presets/single_mode.ron: V = 20 m/s, dt_s = 1e-5, duration_s = 1.0
    let o = bin()
        .args(["check", "presets/single_mode.ron"])
        .output()
        .unwrap();
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    for want in [
        "1 point, 1 mode",
        "speed V = 20 m/s (72 km/h)",
        "dt = 1e-5 s",
        "duration 1 s (100000 steps)",
    ] {
        assert!(out.contains(want), "`{want}` missing in: {out}");
    }
}

/// `check` of an FE tyre lists the unit factors of its file (mm, N, t:
/// mass × 0.001), each mode read with its record and dataset, the node of
/// each point with its distance (the preset's points sit on nodes), and
/// the datasets read and skipped, by number and count; a node listed that
/// the file lacks is refused naming the record.
#[test]
fn check_lists_an_fe_tyres_modes_nodes_and_units() {
    let o = bin()
        .args(["check", "presets/fe_plate.ron"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    for want in [
        "15 points, 41 modes",
        "FE tyre: 41 modes from 123.321 Hz to 399.963 Hz; file units: length × 1000, force × 1, mass × 0.001 of SI",
        "(dataset 164, code 9 `mm N t`)",
        "       0       3     2414  123.321000  1.000000e3  0.050000  (mode 1000 of the file)",
        "        0   112  0.0000",
        "       14   136  0.0000",
        "    datasets read: 43\n           1 × dataset 164 (units)\n           1 × dataset 2411 (node coordinates)\n          41 × dataset 2414 (normal mode shapes)\n    datasets skipped: 0\n",
    ] {
        assert!(out.contains(want), "`{want}` missing in: {out}");
    }
    let tmp = temp_dir();
    let text = std::fs::read_to_string("presets/fe_plate.ron").unwrap();
    // datasets the reader does not use: skipped, grouped by number
    let mut uff = std::fs::read_to_string("presets/fe_plate.uff").unwrap();
    for d in ["151", "2412", "2412", "2400", "2412"] {
        uff.push_str(&format!("    -1\n{d:>6}\n         1         2\n    -1\n"));
    }
    std::fs::write(tmp.path().join("fe_plate.uff"), uff).unwrap();
    std::fs::write(tmp.path().join("fe.ron"), &text).unwrap();
    let o = bin()
        .arg("check")
        .arg(tmp.path().join("fe.ron"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    let want = "    datasets skipped: 5\n           1 × dataset 151\n           3 × dataset 2412\n           1 × dataset 2400\n";
    assert!(out.contains(want), "`{want}` missing in: {out}");
    let listed = text.replace(
        "nodes: Nearest",
        "nodes: [112, 113, 114, 115, 116, 122, 123, 124, 125, 126, 132, 133, 134, 135, 999]",
    );
    let preset = tmp.path().join("fe.ron");
    std::fs::write(&preset, listed).unwrap();
    let o = bin().arg("check").arg(&preset).output().unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("node 999 of points[14]: record 3 (mode 1000) has no value at node 999"),
        "{err}"
    );
}

#[test]
fn non_numeric_values_say_what_number_was_expected() {
    let sweep = |extra: &[&str]| {
        let mut a = vec![
            "sweep",
            "presets/single_mode.ron",
            "--param",
            "speed_mps",
            "--from",
            "10",
            "--to",
            "20",
        ];
        a.extend_from_slice(extra);
        a.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let run = |extra: &[&str]| {
        let mut a = vec!["run", "presets/single_mode.ron"];
        a.extend_from_slice(extra);
        a.into_iter().map(String::from).collect::<Vec<_>>()
    };
    for (args, want) in [
        (
            run(&["--every", "ten", "-o", "x.csv"]),
            "'ten' for '--every <EVERY>': expected a whole number >= 1",
        ),
        (
            run(&["--every", "-3", "-o", "x.csv"]),
            "'-3' for '--every <EVERY>': expected a whole number >= 1",
        ),
        (
            run(&["--dt", "abc"]),
            "'abc' for '--dt <DT>': expected a time in seconds",
        ),
        (
            run(&["--duration", "1s"]),
            "'1s' for '--duration <DURATION>': expected a time in seconds",
        ),
        (
            sweep(&["--steps", "many"]),
            "'many' for '--steps <STEPS>': expected a whole number >= 1",
        ),
        (
            sweep(&["--threads", "two"]),
            "'two' for '--threads <THREADS>': expected a whole number >= 1",
        ),
        (
            vec![
                "sweep",
                "--param",
                "speed_mps",
                "--from",
                "fast",
                "--to",
                "20",
            ]
            .into_iter()
            .map(String::from)
            .collect(),
            "'fast' for '--from <FROM>': expected a number in the unit of --param",
        ),
    ] {
        let o = bin().args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?} ran");
        assert!(
            err.contains(want) && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn bench_outside_the_repository_says_what_it_studies() {
    let tmp = temp_dir();
    let d = tmp.path();
    let o = bin()
        .current_dir(d)
        .args(["bench", "--quick", "-o", "out"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("0 of the shipped presets")
            && err.contains("embedded default preset (the paper's) only"),
        "{err}"
    );
    // one underscore between words
    assert!(
        d.join("out/work_precision_paper_ring_tyre_five_points_sine_road.png")
            .exists()
    );
}

/// Ctrl-C or `kill` during `run -o` leaves neither the output nor its
/// hidden temporary (it was left behind, up to the whole output's size).
#[cfg(unix)]
#[test]
fn an_interrupted_run_leaves_no_temporary_file() {
    use std::os::unix::process::ExitStatusExt;
    let tmp = temp_dir();
    let d = tmp.path();
    for (name, sig) in [("SIGINT", libc::SIGINT), ("SIGTERM", libc::SIGTERM)] {
        let mut child = bin()
            .args(["run", "presets/single_mode.ron", "--duration", "100", "-o"])
            .arg(d.join("big.csv"))
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        // wait until rows are being written into the temporary
        let written = || {
            files_under(d)
                .iter()
                .any(|p| std::fs::metadata(p).is_ok_and(|m| m.len() > 0))
        };
        while !written() {
            assert!(child.try_wait().unwrap().is_none(), "ended before writing");
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        // the signal sent as the `kill` program would (a minimal system has
        // no such program)
        let pid = libc::pid_t::try_from(child.id()).unwrap();
        // SAFETY: kill(2) takes plain integers; `pid` is our child, not
        // reaped before the `wait` below, so it names no other process
        let sent = unsafe { libc::kill(pid, sig) };
        assert_eq!(sent, 0, "{name}: {}", std::io::Error::last_os_error());
        let status = child.wait().unwrap();
        assert!(status.signal().is_some(), "{name}: {status:?}");
        assert_eq!(files_under(d), Vec::<PathBuf>::new(), "{name}: left behind");
    }
}

#[test]
fn options_of_an_output_not_asked_for_are_refused() {
    // each would have been ignored without a word
    for (args, needed) in [
        (&["run", "--every", "10"][..], "--output <OUTPUT>"),
        (&["run", "--plot-unclipped"][..], "--plot <PLOT>"),
        (
            &["run", "--spectrum-from", "0.2"][..],
            "<--spectrum <SPECTRUM>|--spectrum-plot <SPECTRUM_PLOT>>",
        ),
        (&["run", "--spectrum-max-hz", "1000"][..], "--spectrum"),
        (&["run", "--fps", "10"][..], "--frames <FRAMES>"),
        (&["run", "--slow-motion", "5"][..], "--frames <FRAMES>"),
        (&["run", "--frames-from", "0.1"][..], "--frames <FRAMES>"),
        (&["run", "--frames-to", "0.2"][..], "--frames <FRAMES>"),
        (&["run", "--frame-size", "640x480"][..], "--frames <FRAMES>"),
        (
            &["identify", "presets/paper.ron", "--figures-unclipped"][..],
            "--figures <FIGURES>",
        ),
    ] {
        let o = bin().args(args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?} ran");
        assert!(
            err.contains("required arguments were not provided") && err.contains(needed),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn a_missing_comma_says_where_to_look() {
    let tmp = temp_dir();
    let d = tmp.path();
    let p = d.join("comma.ron");
    // the comma after `speed_mps: 20.0` (line 11) is missing: RON points at line 12
    std::fs::write(
        &p,
        std::fs::read_to_string("presets/single_mode.ron")
            .unwrap()
            .replace("speed_mps: 20.0,", "speed_mps: 20.0"),
    )
    .unwrap();
    let o = bin().arg("check").arg(&p).output().unwrap();
    refused(
        &o,
        &[
            &format!(
                "{}:12:5: Expected comma: a `,` is missing after the previous value",
                p.display()
            ),
            "ramp_s: 0.05",
        ],
        "missing comma",
    );
}
