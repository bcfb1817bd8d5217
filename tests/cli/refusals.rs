//! Inputs that panicked, hung or gave an unclear error (found by the property
//! tests of cli/hostile_args.rs and scene/hostile.rs), kept as plain tests:
//! each is now refused with a message naming the option or field.

use crate::support::{bin, temp_dir};
use tirecontact::SceneSimulation;
use tirecontact::scene::{Point, Scene};
use tirecontact::{DEFAULT_PRESET, DEFAULT_PRESET_NAME};

fn paper() -> Scene {
    Scene::parse(DEFAULT_PRESET, DEFAULT_PRESET_NAME).unwrap()
}

/// A ring tyre at 1000 points passed validation; its identification then
/// sampled P(P+1)/2 = 500 500 responses of 1000 samples (4 GB) and ran for
/// an hour. It is refused, naming `points`, the count and the limit.
#[test]
fn ring_tyre_with_a_thousand_points_is_refused_up_front() {
    let mut s = paper();
    s.points = (0..1000)
        .map(|i| Point {
            x_m: -0.05 + 1e-4 * i as f64,
            y_m: 0.0,
            h_m: -0.003,
        })
        .collect();
    let errors = s.validate().unwrap_err();
    let e = errors
        .iter()
        .find(|e| e.field == "points")
        .unwrap_or_else(|| panic!("no error about points: {errors:?}"));
    assert!(e.value.contains("1000"), "{e}");
    assert!(e.expected.contains("at most"), "{e}");
    // the shipped ring scene (5 points) and 50 points stay accepted
    assert!(paper().validate().is_ok());
    s.points.truncate(50);
    assert!(s.validate().is_ok(), "{:?}", s.validate());
}

/// `max_model_order: 18446744073709551615` (usize::MAX) panicked the
/// validator ("attempt to multiply with overflow" in lsce/options.rs, debug
/// builds; release builds wrapped and asked for 4 samples). It is an error
/// naming the field, and the duration check stays sensible.
#[test]
fn huge_max_model_order_is_an_error_not_an_overflow() {
    let text = DEFAULT_PRESET.replace(
        "max_model_order: 40",
        "max_model_order: 18446744073709551615",
    );
    assert_ne!(text, DEFAULT_PRESET);
    let err = Scene::parse(&text, "huge.ron").unwrap_err().to_string();
    assert!(
        err.contains("tyre.identification.max_model_order = 18446744073709551615"),
        "{err}"
    );
    assert!(!err.contains("tyre.identification.duration_s"), "{err}");
}

/// A preset with a byte that is not UTF-8 (a Latin-1 `é` typed in an old
/// editor) gave "stream did not contain valid UTF-8", with no line or
/// column. It is a syntax error at the byte's line and column.
#[test]
fn invalid_utf8_in_a_preset_names_line_and_column() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let path = dir.join("latin1.ron");
    let mut bytes = b"Scene(\n    name: \"caf".to_vec();
    bytes.push(0xE9); // Latin-1 e-acute, not UTF-8
    bytes.extend_from_slice(b"\",\n)\n");
    std::fs::write(&path, &bytes).unwrap();
    let err = Scene::load(&path).unwrap_err();
    match &err {
        tirecontact::SceneError::Syntax {
            line, col, message, ..
        } => {
            assert_eq!((*line, *col), (2, 15), "{err}");
            assert!(message.contains("UTF-8"), "{err}");
        }
        other => panic!("expected a syntax error with line and column, got: {other}"),
    }
}

/// A folder given as the preset gave "Is a directory (os error 21)", a
/// missing one "No such file or directory (os error 2)": neither said what
/// was expected.
#[test]
fn a_folder_or_missing_file_as_preset_says_a_preset_file_is_expected() {
    let tmp = temp_dir();
    let d = tmp.path();
    let e = Scene::load(d).unwrap_err().to_string();
    assert!(
        e.contains("is a folder") && e.contains("expected a scene preset"),
        "{e}"
    );
    let e = Scene::load(&d.join("none.ron")).unwrap_err().to_string();
    assert!(
        e.contains("none.ron") && e.contains("expected an existing scene preset"),
        "{e}"
    );
}

/// `bench -o FILE` (an existing file as the output folder) gave "File
/// exists (os error 17)", without the option or what was expected.
#[test]
fn bench_output_that_is_a_file_names_the_option() {
    let tmp = temp_dir();
    let d = tmp.path();
    let f = d.join("a_file");
    std::fs::write(&f, "x").unwrap();
    let o = bin()
        .args(["bench", "--quick", "-o"])
        .arg(&f)
        .arg("presets/single_mode.ron")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        err.contains("-o ") && err.contains("is a file") && err.contains("expected a folder"),
        "{err}"
    );
}

/// `run -o DIR/new/` (a path ending in `/`, a folder that does not exist)
/// passed the up-front check, ran, then failed with "Not a directory (os
/// error 20)". It is refused before the run, naming the option.
#[test]
fn output_path_ending_in_a_slash_is_refused_up_front() {
    let tmp = temp_dir();
    let d = tmp.path();
    let out = format!("{}/", d.join("new").display());
    let o = bin()
        .args([
            "run",
            "presets/single_mode.ron",
            "--duration",
            "0.001",
            "-o",
            &out,
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        err.contains("-o ") && err.contains("expected a CSV file name"),
        "{err}"
    );
    assert!(!d.join("new").exists());
}

fn run_err(args: &[&str]) -> String {
    let o = bin().arg("run").args(args).output().unwrap();
    assert!(!o.status.success(), "{args:?} succeeded");
    assert_ne!(o.status.code(), Some(101));
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `--dt -inf`, `--duration -1e-300`, `--max-output-gb -1e-300` were
/// "unexpected argument '-i' found" (clap took the value for a flag);
/// `--fps abc` said "invalid float literal"; `--frames-to 1` was refused as
/// "t1_s = 1", a name the command line does not have.
#[test]
fn run_option_values_are_named_as_typed() {
    let e = run_err(&["presets/single_mode.ron", "--dt", "-inf"]);
    assert!(e.contains("dt_s = -inf"), "{e}");
    let e = run_err(&["presets/single_mode.ron", "--duration", "-1e-300"]);
    assert!(e.contains("duration_s = -1e-300"), "{e}");
    let tmp = temp_dir();
    let d = tmp.path();
    let frames = d.join("frames");
    let f = frames.to_str().unwrap();
    let e = run_err(&[
        "presets/single_mode.ron",
        "--duration",
        "0.01",
        "--frames",
        f,
        "--fps",
        "abc",
    ]);
    assert!(
        e.contains("--fps") && e.contains("expected a frame rate in Hz"),
        "{e}"
    );
    let e = run_err(&[
        "presets/single_mode.ron",
        "--duration",
        "0.01",
        "--frames",
        f,
        "--frames-to",
        "1",
    ]);
    assert!(e.contains("--frames-to = 1: expected"), "{e}");
    let e = run_err(&[
        "presets/single_mode.ron",
        "--duration",
        "0.01",
        "--frames",
        f,
        "--frame-size",
        "-1x5",
    ]);
    assert!(
        e.contains("--frame-size") && e.contains("WIDTHxHEIGHT"),
        "{e}"
    );
}

/// Hostile numbers were shown with every digit: `duration_s = 1e300` as 301
/// characters, `5e-324` as 324 zeros, in the value and in what was
/// expected. They are shown in exponent form, the way they can be typed.
#[test]
fn huge_and_tiny_values_are_shown_short() {
    let mut s = Scene::parse(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/single_mode.ron"
        )),
        "single_mode.ron",
    )
    .unwrap();
    s.duration_s = 5e-324;
    s.speed_mps = 1e300;
    s.points[0].h_m = -1e300;
    let shown: Vec<String> = s
        .validate()
        .unwrap_err()
        .iter()
        .map(|e| e.to_string())
        .collect();
    let all = shown.join("\n");
    assert!(all.contains("speed_mps = 1e300"), "{all}");
    assert!(all.contains("points[0].h_m = -1e300"), "{all}");
    assert!(all.contains("duration_s = 5e-324"), "{all}");
    assert!(shown.iter().all(|e| e.len() < 200), "{all}");
    s.duration_s = 1.0;
    s.speed_mps = 10.0;
    s.points[0].h_m = -0.001;
    s.dt_s = 2.5e-310;
    let all: String = s
        .validate()
        .unwrap_err()
        .iter()
        .map(|e| e.to_string())
        .collect();
    assert!(all.contains("dt_s = 2.5e-310"), "{all}");
    assert!(all.len() < 300, "{all}");
}

/// `sweep --steps 18446744073709551615` panicked with "capacity overflow"
/// (exit 101) and `--steps 100000000000` aborted on an 800 GB allocation
/// (exit 134), both in `linspace` before any check: both are refused
/// naming `--steps`.
#[test]
fn sweep_with_a_huge_step_count_is_refused() {
    for steps in ["18446744073709551615", "100000000000"] {
        let o = bin()
            .args(["sweep", "presets/single_mode.ron", "--param", "speed_mps"])
            .args([
                "--from",
                "1",
                "--to",
                "2",
                "--steps",
                steps,
                "--duration",
                "0.06",
            ])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "--steps {steps}: {err}");
        assert!(
            err.contains("--steps") && !err.contains("panicked"),
            "{err}"
        );
    }
}

/// A ring of radius 1e-9 m (valid: > 0) has every mode far above the
/// sampling's Nyquist frequency; identification said only "LSCE: every
/// response is zero". It says why and which fields to change.
#[test]
fn ring_without_modes_below_nyquist_says_why() {
    let text = DEFAULT_PRESET.replace("radius_m: 0.31", "radius_m: 1e-9");
    assert_ne!(text, DEFAULT_PRESET);
    let s = Scene::parse(&text, "tiny.ron").unwrap();
    let e = tirecontact::Simulation::from_scene(&s)
        .err()
        .expect("an error")
        .to_string();
    assert!(
        e.contains("Nyquist") && e.contains("sample_rate_hz") && e.contains("radius_m"),
        "{e}"
    );
}

/// `--max-output-gb 1e-300` printed the budget with 300 zeros and advised
/// `--every 1050599…` (a 300-digit count, beyond any run): the budget is
/// shown short, and a budget below the smallest output says to raise it.
#[test]
fn a_budget_below_one_row_says_to_raise_it() {
    let tmp = temp_dir();
    let d = tmp.path();
    let csv = d.join("b.csv");
    let e = run_err(&[
        "presets/single_mode.ron",
        "--duration",
        "0.001",
        "--max-output-gb",
        "1e-300",
        "-o",
        csv.to_str().unwrap(),
    ]);
    assert!(e.contains("--max-output-gb 1e-300"), "{e}");
    assert!(
        e.contains("raise --max-output-gb") && !e.contains("--every 10505"),
        "{e}"
    );
    assert!(e.len() < 600, "{e}");
    assert!(!csv.exists());
}

/// A sweep whose runs end before their ramp does (no steady part to
/// summarise) ran every value and then failed each with "spectrum of 0
/// samples", after writing a table of failures. It is refused before any
/// run, naming the value and what to do, and writes nothing.
#[test]
fn sweep_shorter_than_its_ramp_is_refused_before_any_run() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let csv = dir.join("s.csv");
    let o = bin()
        .args(["sweep", "presets/single_mode.ron", "--param", "speed_mps"])
        .args([
            "--from",
            "5",
            "--to",
            "10",
            "--steps",
            "3",
            "--duration",
            "0.001",
        ])
        .arg("-o")
        .arg(&csv)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("speed_mps = 5") && err.contains("lengthen duration_s"),
        "{err}"
    );
    assert!(!csv.exists(), "a failed sweep wrote {}", csv.display());
}

/// `sweep --dt -inf` was clap's "unexpected argument '-i' found"; the
/// value reaches the parser or the scene's validation, which name the
/// option or the field it sets.
#[test]
fn sweep_numeric_options_take_values_starting_with_a_minus() {
    for (opt, v, named) in [
        ("--dt", "-inf", "dt_s = -inf"),
        ("--duration", "-1e-300", "duration_s = -1e-300"),
        ("--threads", "-1", "--threads"),
    ] {
        let o = bin()
            .args(["sweep", "presets/single_mode.ron", "--param", "speed_mps"])
            .args(["--from", "5", "--to", "10", opt, v])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_ne!(o.status.code(), Some(0), "{opt} {v}");
        assert!(
            err.contains(named) && !err.contains("unexpected argument"),
            "{opt} {v}: {err}"
        );
    }
}

/// A value refused by validation is placed like a syntax error, at the
/// file, line and column where the preset writes it (it was named by its
/// path only: in a long preset the user had to find it).
#[test]
fn a_refused_preset_value_is_reported_at_its_line_and_column() {
    let text = std::fs::read_to_string("presets/single_mode.ron").unwrap();
    let (line0, l) = text
        .lines()
        .enumerate()
        .find(|(_, l)| l.contains("damping_ratio: 0.05"))
        .unwrap();
    let col = l.find("damping_ratio").unwrap() + 1;
    let bad = text.replace("damping_ratio: 0.05", "damping_ratio: -0.05");
    let err = Scene::parse(&bad, "single_mode.ron")
        .unwrap_err()
        .to_string();
    let want = format!(
        "single_mode.ron:{}:{col}: tyre.modes[0].damping_ratio = -0.05",
        line0 + 1
    );
    assert!(err.contains(&want), "{err}\nwanted: {want}");
    // a scene built in code has no text: the path alone, as before
    let mut s = Scene::parse(&text, "x").unwrap();
    s.tyre = bad_tyre(&bad);
    let shown = format!("{:?}", s.validate().unwrap_err());
    assert!(shown.contains("tyre.modes[0].damping_ratio"), "{shown}");
}

fn bad_tyre(text: &str) -> tirecontact::scene::Tyre {
    tirecontact::Scene::from_ron_str(text, "t").unwrap().tyre
}
