//! Bad presets, table-driven: every case is a small edit of a valid scene (or
//! a broken measured road file beside it) and states the error it must give:
//! `file:line:col` and the parser's complaint for syntax (the line under the
//! caret shows the field and the value), or the field, the value and what was
//! expected for values, or the road file and what is wrong with it. Each case
//! is checked through the library (`Scene::load` + `Simulation::new`, what
//! `check` does) and through the command line (`check` and `run`: exit code 1,
//! the message on stderr, no panic).
//!
//! The valid base scene runs cleanly through both (first test), so every
//! failure below is caused by the case's edit alone.

use crate::support::{bin, temp_dir};
use std::path::{Path, PathBuf};
use tirecontact::SceneSimulation;
use tirecontact::base::error::FieldError;
use tirecontact::readers::road::{MAX_PROFILE_BYTES, read_profile_csv_limited};
use tirecontact::{Scene, SceneError, Simulation};

/// Two points, one mode by shape and one by residue, a sine road: valid.
const BASE: &str = r#"// base scene of the bad-preset table
Scene(
    name: "base",
    tyre: Modal(modes: [
        Mode(freq_hz: 100.0, damping_ratio: 0.05, shape: [0.3, 0.3]),
        Mode(freq_hz: 200.0, damping_ratio: 0.04, residue: [[0.09, -0.09], [-0.09, 0.09]]),
    ]),
    points: [
        Point(x_m: 0.0, h_m: -0.001),
        Point(x_m: 0.05, h_m: -0.001),
    ],
    road: Sine(amplitude_m: 0.001, wavelength_m: 0.5),
    speed_mps: 10.0,
    ramp_s: 0.01,
    dt_s: 1e-4,
    duration_s: 0.01,
)
"#;

const SINE: &str = "road: Sine(amplitude_m: 0.001, wavelength_m: 0.5)";
const MEASURED: &str = r#"road: Measured(file: "road.csv")"#;
const RING: &str = "tyre: Ring(ring: (radius_m: 0.31, damping_ratio: 0.05, max_order: 20), identification: (band_hz: (0.0, 500.0))),";
const GOOD_ROAD: &str = "x_m,z_m\n-1.0,0.0\n0.5,0.001\n2.0,0.0\n";

/// The error a case must give.
enum Expect {
    /// A syntax (or type) error located at the first character of `at` in
    /// the case's text (`None`: at the end of the text); the message contains
    /// every one of `words`.
    Syntax {
        at: Option<&'static str>,
        words: &'static [&'static str],
    },
    /// A validation error on `field` with this `value`, whose expectation
    /// contains `expected`.
    Field {
        field: &'static str,
        value: &'static str,
        expected: &'static str,
    },
    /// The measured road file is refused: `road.file = <path>: ...` with `words`.
    Road { words: &'static [&'static str] },
}

struct Case {
    name: &'static str,
    text: String,
    /// Files written beside the preset (name, contents).
    files: Vec<(&'static str, Vec<u8>)>,
    expect: Expect,
}

/// BASE with each `(from, to)` applied; `from` must occur exactly once.
fn edit(pairs: &[(&str, &str)]) -> String {
    let mut s = BASE.to_string();
    for (a, b) in pairs {
        assert_eq!(s.matches(a).count(), 1, "`{a}` must occur once in the text");
        s = s.replacen(a, b, 1);
    }
    s
}

fn syntax(
    name: &'static str,
    text: String,
    at: Option<&'static str>,
    words: &'static [&'static str],
) -> Case {
    Case {
        name,
        text,
        files: vec![],
        expect: Expect::Syntax { at, words },
    }
}

fn field(
    name: &'static str,
    pairs: &[(&str, &str)],
    field: &'static str,
    value: &'static str,
    expected: &'static str,
) -> Case {
    Case {
        name,
        text: edit(pairs),
        files: vec![],
        expect: Expect::Field {
            field,
            value,
            expected,
        },
    }
}

fn road(name: &'static str, csv: &[u8], words: &'static [&'static str]) -> Case {
    Case {
        name,
        text: edit(&[(SINE, MEASURED)]),
        files: vec![("road.csv", csv.to_vec())],
        expect: Expect::Road { words },
    }
}

fn cases() -> Vec<Case> {
    let mut v = vec![
        // --- syntax: file:line:col, the parser's complaint, the line shown ---
        syntax(
            "missing comma",
            edit(&[("speed_mps: 10.0,", "speed_mps: 10.0")]),
            Some("ramp_s"),
            &["Expected comma", "ramp_s: 0.01"],
        ),
        syntax(
            "missing closing paren of a variant",
            edit(&[("wavelength_m: 0.5),", "wavelength_m: 0.5,")]),
            Some("speed_mps"),
            &["Unexpected field named `speed_mps` in `Sine`"],
        ),
        syntax(
            "missing closing paren at the end",
            edit(&[("duration_s: 0.01,\n)", "duration_s: 0.01,\n")]),
            None,
            &["Unexpected end of RON"],
        ),
        syntax(
            "bad token",
            edit(&[("speed_mps: 10.0", "speed_mps: 10.0.5")]),
            Some("10.0.5"),
            &["Expected float", "speed_mps: 10.0.5"],
        ),
        syntax(
            "bad character",
            edit(&[("speed_mps: 10.0", "speed_mps: @10")]),
            Some("@10"),
            &["Expected float", "speed_mps: @10"],
        ),
        syntax(
            "unterminated string",
            edit(&[(r#"name: "base","#, r#"name: "base,"#)]),
            Some(r#""base,"#),
            &["Expected end of string", r#"name: "base,"#],
        ),
        syntax(
            "empty file",
            String::new(),
            None,
            &["Expected opening `(` for struct `Scene`"],
        ),
        syntax(
            "trailing characters",
            format!("{BASE}Scene()"),
            Some("Scene()"),
            &["Non-whitespace trailing characters"],
        ),
        syntax(
            "not RON at all",
            "\u{1}\u{2}PNG binary junk".to_string(),
            None,
            &["Expected"],
        ),
        syntax(
            "unknown field in the scene",
            edit(&[("speed_mps: 10.0", "speed: 10.0")]),
            Some("speed:"),
            &["Unexpected field named `speed` in `Scene`", "`speed_mps`"],
        ),
        syntax(
            "unknown field in a mode",
            edit(&[("Mode(freq_hz: 100.0", "Mode(frequency_hz: 100.0")]),
            Some("frequency_hz"),
            &[
                "Unexpected field named `frequency_hz` in `Mode`",
                "`freq_hz`",
            ],
        ),
        syntax(
            "unknown road variant",
            edit(&[("Sine(", "Sinus(")]),
            Some("Sinus"),
            &["Unexpected variant named `Sinus`", "`Sine`", "`Measured`"],
        ),
        syntax(
            "missing required field",
            edit(&[("    dt_s: 1e-4,\n", "")]),
            Some(")\n"),
            &["missing field named `dt_s` in `Scene`"],
        ),
        syntax(
            "string for a number",
            edit(&[("speed_mps: 10.0", r#"speed_mps: "fast""#)]),
            Some(r#""fast""#),
            &["Expected float", r#"speed_mps: "fast""#],
        ),
        syntax(
            "boolean for a number",
            edit(&[("damping_ratio: 0.05", "damping_ratio: true")]),
            Some("true"),
            &["Expected float", "damping_ratio: true"],
        ),
        syntax(
            "one point instead of a list",
            edit(&[(
                "points: [\n        Point(x_m: 0.0, h_m: -0.001),\n        Point(x_m: 0.05, h_m: -0.001),\n    ],",
                "points: Point(x_m: 0.0, h_m: -0.001),",
            )]),
            // (read as a whole, then told apart from a Grid(...))
            Some("Point(x_m: 0.0, h_m: -0.001),"),
            &["Expected opening `[`", "points: Point("],
        ),
        syntax(
            "negative integer for a count",
            edit(&[(
                "tyre: Modal(modes: [\n        Mode(freq_hz: 100.0, damping_ratio: 0.05, shape: [0.3, 0.3]),\n        Mode(freq_hz: 200.0, damping_ratio: 0.04, residue: [[0.09, -0.09], [-0.09, 0.09]]),\n    ]),",
                RING.replace("max_order: 20", "max_order: -3").as_str(),
            )]),
            Some("-3"),
            &["max_order: -3"],
        ),
        syntax(
            "number for a boolean",
            edit(&[(SINE, r#"road: Measured(file: "road.csv", looped: 1)"#)]),
            Some("1),\n    speed"),
            &["Expected boolean", "looped: 1"],
        ),
        // --- values: field, value, expectation ---
        field(
            "speed NaN",
            &[("speed_mps: 10.0", "speed_mps: NaN")],
            "speed_mps",
            "NaN",
            "a finite speed >= 0 m/s",
        ),
        field(
            "speed negative",
            &[("speed_mps: 10.0", "speed_mps: -5.0")],
            "speed_mps",
            "-5",
            "a finite speed >= 0 m/s",
        ),
        field(
            "speed infinite",
            &[("speed_mps: 10.0", "speed_mps: inf")],
            "speed_mps",
            "inf",
            "a finite speed >= 0 m/s",
        ),
        field(
            "speed too large",
            &[("speed_mps: 10.0", "speed_mps: 1e4")],
            "speed_mps",
            "10000",
            "a speed <= 1000 m/s",
        ),
        field(
            "time step zero",
            &[("dt_s: 1e-4", "dt_s: 0.0")],
            "dt_s",
            "0",
            "a finite time step > 0 s",
        ),
        field(
            "time step infinite",
            &[("dt_s: 1e-4", "dt_s: inf")],
            "dt_s",
            "inf",
            "a finite time step > 0 s",
        ),
        field(
            "time step NaN",
            &[("dt_s: 1e-4", "dt_s: NaN")],
            "dt_s",
            "NaN",
            "a finite time step > 0 s",
        ),
        field(
            "duration negative",
            &[("duration_s: 0.01", "duration_s: -1.0")],
            "duration_s",
            "-1",
            "a finite duration > 0 s",
        ),
        field(
            "time step longer than the duration",
            &[("dt_s: 1e-4", "dt_s: 0.05")],
            "dt_s",
            "0.05",
            "a time step <= duration_s = 0.01 s",
        ),
        field(
            "too many steps",
            &[
                ("dt_s: 1e-4", "dt_s: 1e-6"),
                ("duration_s: 0.01", "duration_s: 1e5"),
            ],
            "duration_s",
            "100000",
            "at most 1e10 steps",
        ),
        field(
            "frequency zero",
            &[("freq_hz: 100.0", "freq_hz: 0.0")],
            "tyre.modes[0].freq_hz",
            "0",
            "a finite frequency > 0 Hz",
        ),
        field(
            "frequency minus infinity",
            &[("freq_hz: 200.0", "freq_hz: -inf")],
            "tyre.modes[1].freq_hz",
            "-inf",
            "a finite frequency > 0 Hz",
        ),
        field(
            "frequency too high",
            &[("freq_hz: 200.0", "freq_hz: 1e7")],
            "tyre.modes[1].freq_hz",
            "1e7",
            "a frequency <= 1e6 Hz",
        ),
        field(
            "negative damping ratio",
            &[("damping_ratio: 0.05", "damping_ratio: -0.01")],
            "tyre.modes[0].damping_ratio",
            "-0.01",
            "a finite damping ratio >= 0",
        ),
        field(
            "damping ratio NaN",
            &[("damping_ratio: 0.04", "damping_ratio: NaN")],
            "tyre.modes[1].damping_ratio",
            "NaN",
            "a finite damping ratio >= 0",
        ),
        field(
            "residue of the wrong size",
            &[(
                "residue: [[0.09, -0.09], [-0.09, 0.09]]",
                "residue: [[0.09]]",
            )],
            "tyre.modes[1].residue",
            "1 rows of lengths [1]",
            "a 2x2 matrix",
        ),
        field(
            "residue not square",
            &[(
                "residue: [[0.09, -0.09], [-0.09, 0.09]]",
                "residue: [[0.09, -0.09], [-0.09]]",
            )],
            "tyre.modes[1].residue",
            "2 rows of lengths [2, 1]",
            "a 2x2 matrix",
        ),
        field(
            "residue entry NaN",
            &[(
                "residue: [[0.09, -0.09], [-0.09, 0.09]]",
                "residue: [[0.09, -0.09], [NaN, 0.09]]",
            )],
            "tyre.modes[1].residue[1][0]",
            "NaN",
            "a finite residue in 1/kg",
        ),
        field(
            "shape of the wrong length",
            &[("shape: [0.3, 0.3]", "shape: [0.3, 0.3, 0.3]")],
            "tyre.modes[0].shape",
            "3 values",
            "2 values (one per contact point)",
        ),
        field(
            "shape entry infinite",
            &[("shape: [0.3, 0.3]", "shape: [0.3, inf]")],
            "tyre.modes[0].shape[1]",
            "inf",
            "a finite value",
        ),
        field(
            "both residue and shape",
            &[(
                "shape: [0.3, 0.3]",
                "shape: [0.3, 0.3], residue: [[0.09, 0.09], [0.09, 0.09]]",
            )],
            "tyre.modes[0].shape",
            "[0.3, 0.3]",
            "either `residue` or `shape`, not both",
        ),
        field(
            "neither residue nor shape",
            &[(", shape: [0.3, 0.3]", "")],
            "tyre.modes[0].residue",
            "(missing)",
            "a 2x2 residue matrix or a shape of 2 values",
        ),
        field(
            "no modes",
            &[(
                "tyre: Modal(modes: [\n        Mode(freq_hz: 100.0, damping_ratio: 0.05, shape: [0.3, 0.3]),\n        Mode(freq_hz: 200.0, damping_ratio: 0.04, residue: [[0.09, -0.09], [-0.09, 0.09]]),\n    ]),",
                "tyre: Modal(modes: []),",
            )],
            "tyre.modes",
            "[]",
            "at least one mode",
        ),
        field(
            "coincident points",
            &[("x_m: 0.05", "x_m: 0.0")],
            "points[1].x_m",
            "0",
            "a place different from points[0]'s: both are at x_m = 0 m, y_m = 0 m (coincident points make the contact system singular)",
        ),
        field(
            "coincident points across the tread",
            &[
                ("x_m: 0.0, h_m", "x_m: 0.0, y_m: 0.04, h_m"),
                ("x_m: 0.05, h_m", "x_m: 0.0, y_m: 0.04, h_m"),
            ],
            "points[1].x_m",
            "0",
            "a place different from points[0]'s: both are at x_m = 0 m, y_m = 0.04 m",
        ),
        field(
            "position across the tread NaN",
            &[("x_m: 0.05, h_m", "x_m: 0.05, y_m: NaN, h_m")],
            "points[1].y_m",
            "NaN",
            "a finite position across the tread in m",
        ),
        field(
            "no points",
            &[(
                "points: [\n        Point(x_m: 0.0, h_m: -0.001),\n        Point(x_m: 0.05, h_m: -0.001),\n    ],",
                "points: [],",
            )],
            "points",
            "[]",
            "at least one contact point",
        ),
        field(
            "position NaN",
            &[("x_m: 0.05", "x_m: NaN")],
            "points[1].x_m",
            "NaN",
            "a finite position in m",
        ),
        field(
            "height of metres",
            &[("x_m: 0.05, h_m: -0.001", "x_m: 0.05, h_m: -2.0")],
            "points[1].h_m",
            "-2",
            "|h| <= 1 m",
        ),
        field(
            "no ramp with preload",
            &[("ramp_s: 0.01", "ramp_s: 0.0")],
            "ramp_s",
            "0",
            "a ramp time > 0 s: point 0 starts 1.000e-3 m below the road",
        ),
        field(
            "negative ramp",
            &[("ramp_s: 0.01", "ramp_s: -0.01")],
            "ramp_s",
            "-0.01",
            "a ramp time >= 0 s",
        ),
        field(
            "negative road amplitude",
            &[("amplitude_m: 0.001", "amplitude_m: -0.001")],
            "road.amplitude_m",
            "-0.001",
            "an amplitude >= 0 m",
        ),
        field(
            "zero wavelength",
            &[("wavelength_m: 0.5", "wavelength_m: 0.0")],
            "road.wavelength_m",
            "0",
            "a wavelength > 0 m",
        ),
        field(
            "no harmonics",
            &[(SINE, "road: Harmonics(components: [])")],
            "road.components",
            "[]",
            "at least one harmonic",
        ),
        field(
            "harmonic wavelength infinite",
            &[(
                SINE,
                "road: Harmonics(components: [Harmonic(amplitude_m: 0.001, wavelength_m: inf)])",
            )],
            "road.components[0].wavelength_m",
            "inf",
            "a wavelength > 0 m",
        ),
        field(
            "empty road file name",
            &[(SINE, r#"road: Measured(file: "")"#)],
            "road.file",
            "\"\"",
            "the path of a CSV",
        ),
    ];
    // more contact points than the solver's memory bound
    let many: String = (0..2001)
        .map(|i| format!("Point(x_m: {}, h_m: 0.0), ", i as f64 * 1e-3))
        .collect();
    let text = edit(&[(
        "points: [\n        Point(x_m: 0.0, h_m: -0.001),\n        Point(x_m: 0.05, h_m: -0.001),\n    ],",
        &format!("points: [{many}],"),
    )]);
    v.push(Case {
        name: "too many points",
        text,
        files: vec![],
        expect: Expect::Field {
            field: "points",
            value: "2001 points",
            expected: "at most 2000 contact points",
        },
    });
    // ring parameters out of range (the identification is never reached)
    let modal = "tyre: Modal(modes: [\n        Mode(freq_hz: 100.0, damping_ratio: 0.05, shape: [0.3, 0.3]),\n        Mode(freq_hz: 200.0, damping_ratio: 0.04, residue: [[0.09, -0.09], [-0.09, 0.09]]),\n    ]),";
    for (name, from, to, f, val, exp) in [
        (
            "ring radius negative",
            "radius_m: 0.31",
            "radius_m: -0.31",
            "tyre.ring.radius_m",
            "-0.31",
            "a ring radius > 0 m",
        ),
        (
            "ring damping ratio over 1",
            "damping_ratio: 0.05",
            "damping_ratio: 1.5",
            "tyre.ring.damping_ratio",
            "1.5",
            "a modal damping ratio in [0, 1)",
        ),
        (
            "ring order zero",
            "max_order: 20",
            "max_order: 0",
            "tyre.ring.max_order",
            "0",
            "a highest circumferential order in 1..=2000",
        ),
        (
            "identification band above Nyquist",
            "band_hz: (0.0, 500.0)",
            "band_hz: (600.0, 500.0)",
            "tyre.identification.band_hz",
            "(600, 500)",
            "0 <= f_lo < f_hi < fs/2",
        ),
    ] {
        let ring = RING.replace(from, to);
        v.push(field(name, &[(modal, ring.as_str())], f, val, exp));
    }
    // a ring tyre at one x across the tread with rigid contact: identical
    // rows (refused before any identification)
    v.push(field(
        "ring points at one x across the tread, rigid contact",
        &[
            (modal, RING),
            ("x_m: 0.05, h_m", "x_m: 0.0, y_m: 0.04, h_m"),
        ],
        "points[1].x_m",
        "0",
        "a position different from points[0].x_m: points[0] and points[1] share x_m = 0 m at different y_m (0 m and 0.04 m), but a Ring tyre's response does not depend on y, so with rigid contact their rows of the contact system are identical (singular); use contact: Compliant(...) or a Modal tyre whose residues depend on y",
    ));
    // measured road files
    v.extend([
        Case {
            name: "road file missing",
            text: edit(&[(SINE, MEASURED)]),
            files: vec![],
            expect: Expect::Road {
                words: &["road.csv", "cannot open"],
            },
        },
        road(
            "road file empty",
            b"",
            &["0 data row(s)", "expected at least two"],
        ),
        road(
            "road file header only",
            b"x_m,z_m\n",
            &["0 data row(s)", "expected at least two"],
        ),
        road(
            "road file one row",
            b"x_m,z_m\n0.0,0.001\n",
            &["1 data row(s)", "expected at least two"],
        ),
        road(
            "road file not monotonic",
            b"x_m,z_m\n-1.0,0.0\n0.5,0.001\n0.2,0.0\n",
            &["line 4", "x = 0.2 m after x = 0.5 m", "strictly increasing"],
        ),
        road(
            "road file repeated x",
            b"-1.0,0.0\n0.5,0.001\n0.5,0.0\n2,0\n",
            &["line 3", "x = 0.5 m after x = 0.5 m", "strictly increasing"],
        ),
        road(
            "road file NaN",
            b"x_m,z_m\n-1.0,0.0\n0.5,NaN\n2.0,0.0\n",
            &["line 3", "z = NaN", "expected finite numbers"],
        ),
        road(
            "road file infinite",
            b"x_m,z_m\n-1.0,0.0\n# a comment line\n0.5,0.0\ninf,0.0\n",
            &["line 5", "x = inf", "expected finite numbers"],
        ),
        road(
            "road file text",
            b"x_m,z_m\n-1.0,0.0\n0.5,high\n2.0,0.0\n",
            &["line 3", "expected two numbers", "`0.5, high`"],
        ),
        road(
            "road file one column",
            b"-1.0\n0.5\n",
            &["line 1", "expected two columns `x_m, z_m`, found 1"],
        ),
        road(
            "road file not UTF-8",
            b"x_m,z_m\n-1.0,0.0\n0.5,\xff\xfe\n2.0,0.0\n",
            &["record 3", "UTF-8"],
        ),
        Case {
            name: "road file is a folder",
            text: edit(&[(SINE, MEASURED)]),
            files: vec![("road.csv/keep", b"".to_vec())],
            expect: Expect::Road {
                words: &["is a folder"],
            },
        },
    ]);
    v
}

/// Writes the case into `dir` and returns the preset path.
fn write_case(dir: &Path, text: &str, files: &[(&str, Vec<u8>)]) -> PathBuf {
    for (name, bytes) in files {
        let p = dir.join(name);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, bytes).unwrap();
    }
    let p = dir.join("c.ron");
    std::fs::write(&p, text).unwrap();
    p
}

/// What `check` does: load, validate, read the road, build the solver.
fn load(path: &Path) -> Result<(), SceneError> {
    let scene = Scene::load(path)?;
    Simulation::from_scene(&scene).map(drop)
}

/// 1-based line and column (in characters, as RON counts) of byte `at`.
fn line_col(text: &str, at: usize) -> (usize, usize) {
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Checks one case; returns what is wrong with its error, if anything.
fn check_case(case: &Case, dir: &Path) -> Vec<String> {
    let mut bad = Vec::new();
    let path = write_case(dir, &case.text, &case.files);
    let file = path.display().to_string();
    // what the error message must contain (library and CLI alike)
    let mut must: Vec<String> = Vec::new();
    let result = load(&path);
    let msg = match &result {
        Ok(()) => {
            bad.push("accepted".to_string());
            return bad;
        }
        Err(e) => e.to_string(),
    };
    match (&case.expect, &result) {
        (Expect::Syntax { at, words }, Err(SceneError::Syntax { line, col, .. })) => {
            let byte = match at {
                Some(needle) => match case.text.find(needle) {
                    Some(b) => b,
                    None => panic!("{}: `{needle}` not in the text", case.name),
                },
                None => case.text.len(),
            };
            let (l, c) = line_col(&case.text, byte);
            // the position is on the offending token (an error at the end of
            // the text may sit anywhere after the last token)
            let len = at.map_or(0, |a| a.chars().count());
            if at.is_some() && !(*line == l && (c..c + len).contains(col)) {
                bad.push(format!("at {line}:{col}, expected {l}:{c} (+{len})"));
            }
            must.push(format!("{file}:{line}:{col}: "));
            must.extend(words.iter().map(|w| w.to_string()));
        }
        (Expect::Field { .. }, Err(SceneError::Invalid { errors, .. })) => {
            let Expect::Field {
                field,
                value,
                expected,
            } = case.expect
            else {
                unreachable!()
            };
            let hit = errors.iter().find(|e: &&FieldError| e.field == field);
            match hit {
                None => bad.push(format!("no error on `{field}` in {errors:?}")),
                Some(e) => {
                    if e.value != value {
                        bad.push(format!("value `{}`, expected `{value}`", e.value));
                    }
                    if !e.expected.contains(expected) {
                        bad.push(format!("expectation `{}` lacks `{expected}`", e.expected));
                    }
                }
            }
            must.push(format!("{field} = {value}: expected "));
            must.push(expected.to_string());
        }
        (Expect::Road { words }, Err(SceneError::RoadFile { path: p, .. })) => {
            if !p.ends_with("road.csv") {
                bad.push(format!("names {}, not road.csv", p.display()));
            }
            must.push("road.file = ".to_string());
            must.push("road.csv: ".to_string());
            must.extend(words.iter().map(|w| w.to_string()));
        }
        (_, Err(e)) => bad.push(format!("wrong kind of error: {e:?}")),
        (_, Ok(())) => unreachable!(),
    }
    for m in &must {
        if !msg.contains(m.as_str()) {
            bad.push(format!("library message lacks `{m}`:\n{msg}"));
        }
    }
    // the command line says the same (when built)
    for cmd in ["check", "run"]
        .into_iter()
        .filter(|_| cfg!(feature = "cli"))
    {
        let o = bin().arg(cmd).arg(&path).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        if o.status.code() != Some(1) {
            bad.push(format!("`{cmd}` exit {:?}", o.status.code()));
        }
        if err.contains("panicked") {
            bad.push(format!("`{cmd}` panicked: {err}"));
        }
        if !err.starts_with("error: ") {
            bad.push(format!(
                "`{cmd}` stderr does not start with `error: `: {err}"
            ));
        }
        for m in &must {
            if !err.contains(m.as_str()) {
                bad.push(format!("`{cmd}` stderr lacks `{m}`:\n{err}"));
            }
        }
    }
    bad
}

#[test]
fn base_scene_is_valid_through_library_and_cli() {
    let tmp = temp_dir();
    let dir = tmp.path();
    for (text, files) in [
        (BASE.to_string(), vec![]),
        (
            edit(&[(SINE, MEASURED)]),
            vec![("road.csv", GOOD_ROAD.as_bytes().to_vec())],
        ),
    ] {
        let path = write_case(dir, &text, &files);
        load(&path).unwrap();
        for cmd in ["check", "run"]
            .into_iter()
            .filter(|_| cfg!(feature = "cli"))
        {
            let o = bin().arg(cmd).arg(&path).output().unwrap();
            assert!(
                o.status.success(),
                "{cmd}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
        }
    }
    // the ring variant validates too (its identification is not run here)
    let ring = edit(&[(
        "tyre: Modal(modes: [\n        Mode(freq_hz: 100.0, damping_ratio: 0.05, shape: [0.3, 0.3]),\n        Mode(freq_hz: 200.0, damping_ratio: 0.04, residue: [[0.09, -0.09], [-0.09, 0.09]]),\n    ]),",
        RING,
    )]);
    Scene::from_ron_str(&ring, "ring.ron")
        .unwrap()
        .validate()
        .unwrap();
}

#[test]
fn every_bad_preset_names_the_problem() {
    let cases = cases();
    assert!(cases.len() >= 30, "{} cases", cases.len());
    let mut failures = Vec::new();
    for (k, case) in cases.iter().enumerate() {
        let dir = temp_dir();
        let bad = check_case(case, dir.path());
        if !bad.is_empty() {
            failures.push(format!("[{k}] {}:\n  {}", case.name, bad.join("\n  ")));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases fail:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// A road file over the size limit is refused from its size, before reading:
/// a sparse file of `MAX_PROFILE_BYTES + 1` bytes costs no disk and no time.
#[test]
fn huge_road_file_is_refused_before_reading() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let path = write_case(dir, &edit(&[(SINE, MEASURED)]), &[]);
    let f = std::fs::File::create(dir.join("road.csv")).unwrap();
    f.set_len(MAX_PROFILE_BYTES + 1).unwrap();
    drop(f);
    // the size refusal names the file's size: it was not read (a read would
    // stop at the row or the number check, with another message)
    let e = load(&path).unwrap_err().to_string();
    let want = format!(
        "{} bytes: expected at most {MAX_PROFILE_BYTES} bytes",
        MAX_PROFILE_BYTES + 1
    );
    assert!(e.contains("road.file = ") && e.contains(&want), "{e}");
    if cfg!(feature = "cli") {
        let o = bin().arg("check").arg(&path).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(err.contains(&want) && !err.contains("panicked"), "{err}");
    }
}

/// The row limit, on a small file through the same reader with lower limits.
#[test]
fn road_row_limit_is_enforced() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let p = dir.join("r.csv");
    let rows: String = (0..11).map(|i| format!("{i},0\n")).collect();
    std::fs::write(&p, format!("x_m,z_m\n{rows}")).unwrap();
    assert_eq!(
        read_profile_csv_limited(&p, 11, u64::MAX).unwrap().0.len(),
        11
    );
    let e = read_profile_csv_limited(&p, 10, u64::MAX)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("line 12: more than 10 rows: expected at most 10 rows"),
        "{e}"
    );
    let len = std::fs::metadata(&p).unwrap().len();
    assert!(read_profile_csv_limited(&p, 100, len).is_ok());
    let e = read_profile_csv_limited(&p, 100, len - 1)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(&format!("{len} bytes: expected at most {}", len - 1)),
        "{e}"
    );
}

/// Command-line overrides are validated like the preset, before anything
/// is built: the preset's measured road file is missing, which only
/// building the simulation finds, so each refusal must come first (this
/// replaces a wall-clock bound, which a loaded machine could break).
#[test]
#[cfg(feature = "cli")]
fn bad_command_line_values_are_refused() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let preset = dir.join("missing_road.ron");
    std::fs::write(
        &preset,
        std::fs::read_to_string("presets/single_mode.ron")
            .unwrap()
            .replace(
                "road: Sine(amplitude_m: 0.002, wavelength_m: 0.5)",
                "road: Measured(file: \"no_such_road.csv\")",
            ),
    )
    .unwrap();
    // the preset itself is refused only when the simulation is built
    let o = bin().arg("run").arg(&preset).output().unwrap();
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("road.file = "),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for (args, want) in [
        (
            &["--dt", "0"][..],
            "dt_s = 0: expected a finite time step > 0 s",
        ),
        (
            &["--dt", "NaN"][..],
            "dt_s = NaN: expected a finite time step > 0 s",
        ),
        (
            &["--duration=-1"][..],
            "duration_s = -1: expected a finite duration > 0 s",
        ),
        (
            &["--duration", "inf"][..],
            "duration_s = inf: expected a finite duration > 0 s",
        ),
        (
            &["--every", "0", "-o", "no/such/folder/x.csv"][..],
            "--every = 0: expected a number of steps >= 1",
        ),
        (
            &["--max-output-gb", "0"][..],
            "--max-output-gb = 0: expected a finite size > 0 GB",
        ),
        // refused before the run (1e7 steps), not after it
        (
            &["--duration", "100", "--plot", "x.png", "--plot-size", "0x0"][..],
            "--plot-size 0x0: expected 200..=8000 px per side",
        ),
        (
            &["--duration", "100", "--plot", "no/such/folder/x.png"][..],
            "--plot no/such/folder/x.png: no folder no/such/folder",
        ),
        (
            &["--duration", "100", "-o", "no/such/folder/x.csv"][..],
            "-o no/such/folder/x.csv: no folder no/such/folder",
        ),
    ] {
        let o = bin().arg("run").arg(&preset).args(args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            !err.contains("road.file"),
            "{args:?} built the simulation: {err}"
        );
        assert!(o.stdout.is_empty(), "{args:?} ran");
        assert!(
            err.contains(want) && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
}

/// Files that are not regular files, or have no line ends, are refused at
/// once with the file named, never read without bound or waited on: a
/// device (`/dev/zero` grew `check` to 7.5 GB in 20 s), a named pipe (the
/// open blocked forever), a folder, and a road file of one 100 MB line;
/// as presets and as road files.
#[test]
#[cfg(feature = "cli")]
fn hostile_files_are_refused_at_once() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let fifo = dir.join("pipe");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path; mkfifo only creates the node
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let long = dir.join("long.csv");
    std::fs::write(&long, vec![b'7'; 100 << 20]).unwrap();
    let base = include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/presets/three_points.ron"
    ));
    let with_road = |name: &str, file: &Path| {
        let text = base.replace(
            "road: Sine(amplitude_m: 0.0005, wavelength_m: 0.12)",
            &format!("road: Measured(file: {:?})", file.display().to_string()),
        );
        assert_ne!(text, base);
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let zero = Path::new("/dev/zero");
    let cases: Vec<(PathBuf, &str)> = vec![
        (zero.to_path_buf(), "is not a regular file"),
        (fifo.clone(), "is not a regular file"),
        (dir.to_path_buf(), "is a folder"),
        (with_road("zero.ron", zero), "is not a regular file"),
        (with_road("fifo.ron", &fifo), "is not a regular file"),
        (with_road("dir.ron", dir), "is a folder"),
        (
            with_road("long.ron", &long),
            "line 1 is longer than 4096 bytes",
        ),
    ];
    for (preset, want) in cases {
        let start = std::time::Instant::now();
        let mut child = bin()
            .arg("check")
            .arg(&preset)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        // a hang is a failure, not a stuck test run
        while child.try_wait().unwrap().is_none() {
            if start.elapsed() > std::time::Duration::from_secs(60) {
                child.kill().unwrap();
                panic!("check {} did not end in 60 s", preset.display());
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        let o = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{}: {err}", preset.display());
        assert!(
            err.contains(want) && !err.contains("panicked"),
            "{}: {err}",
            preset.display()
        );
    }
}
