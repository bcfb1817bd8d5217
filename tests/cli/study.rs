//! `tirecontact study`: a study's rows run in one process, on one or two
//! threads, or in shards merged afterwards give the same table byte for
//! byte; a killed run resumes without redoing its rows; merge refuses
//! missing, doubled and foreign rows by name; a bad study file is refused
//! with its line and column.

use crate::support::{bin, temp_dir};
use std::path::Path;

fn study_file(dir: &Path, extra: &str) -> std::path::PathBuf {
    let preset = std::fs::canonicalize("presets/single_mode.ron").unwrap();
    let text = format!(
        r#"Study(
    preset: "{}",
    factors: [
        Factor(path: "speed_mps", values: Range(from: 10.0, to: 20.0, steps: 3)),
        Factor(path: "road.amplitude_m", values: List([0.001, 0.002])),
    ],
    design: FullFactorial,
    duration_s: Some(0.1),{extra}
)"#,
        preset.display()
    );
    let p = dir.join("study.ron");
    std::fs::write(&p, text).unwrap();
    p
}

fn study(args: &[&str]) -> std::process::Output {
    let o = bin().arg("study").args(args).output().unwrap();
    assert!(
        !String::from_utf8_lossy(&o.stderr).contains("panicked"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn ok(args: &[&str]) {
    let o = study(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn err(args: &[&str]) -> String {
    let o = study(args);
    assert_eq!(o.status.code(), Some(1), "{args:?}");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn shards_threads_and_resumes_give_the_one_process_table_byte_for_byte() {
    let tmp = temp_dir();
    let d = tmp.path();
    let s = study_file(d, "");
    let s = s.to_str().unwrap();
    let path = |n: &str| d.join(n).to_str().unwrap().to_string();
    ok(&["run", s, "--threads", "1", "-o", &path("one.csv")]);
    ok(&["run", s, "--threads", "2", "-o", &path("two.csv")]);
    let one = std::fs::read(path("one.csv")).unwrap();
    assert_eq!(one, std::fs::read(path("two.csv")).unwrap(), "threads");
    let text = String::from_utf8(one.clone()).unwrap();
    assert_eq!(text.lines().count(), 1 + 6);
    assert!(
        text.lines().skip(1).all(|l| l.ends_with(',')),
        "no row failed:\n{text}"
    );
    for k in 1..=3 {
        ok(&[
            "run",
            s,
            "--shard",
            &format!("{k}/3"),
            "-o",
            &path(&format!("p{k}.csv")),
        ]);
    }
    ok(&[
        "merge",
        &path("p1.csv"),
        &path("p2.csv"),
        &path("p3.csv"),
        "-o",
        &path("merged.csv"),
    ]);
    assert_eq!(
        std::fs::read(path("merged.csv")).unwrap(),
        one,
        "shards merged"
    );
    // a run that stopped after two rows, resumed
    ok(&["run", s, "--rows", "0..2", "-o", &path("resumed.csv")]);
    ok(&["run", s, "--resume", "-o", &path("resumed.csv")]);
    assert_eq!(std::fs::read(path("resumed.csv")).unwrap(), one, "resumed");
    // the report: per factor, its levels' means (here 3 speeds, 2 rows
    // each), a figure and the summary
    ok(&["report", &path("one.csv"), "-o", &path("report")]);
    let md = std::fs::read_to_string(d.join("report/summary.md")).unwrap();
    assert!(
        md.contains("## speed_mps") && md.contains("## road.amplitude_m"),
        "{md}"
    );
    assert!(md.contains("| 15 | 2 |"), "{md}");
    for f in [
        "main_effect_speed_mps.png",
        "main_effect_road_amplitude_m.png",
        "main_effects.csv",
    ] {
        assert!(d.join("report").join(f).is_file(), "{f}");
    }
    // the title is the table's name unless given
    assert!(md.starts_with("# one\n"), "{md}");
    ok(&[
        "report",
        &path("one.csv"),
        "-o",
        &path("titled"),
        "--title",
        "Speed and road amplitude",
    ]);
    let md = std::fs::read_to_string(d.join("titled/summary.md")).unwrap();
    assert!(md.starts_with("# Speed and road amplitude\n"), "{md}");
    let e = err(&[
        "report",
        &path("one.csv"),
        "-o",
        &path("t2"),
        "--title",
        " ",
    ]);
    assert!(e.contains("--title is empty"), "{e}");
    // merge names what is wrong
    let e = err(&[
        "merge",
        &path("p1.csv"),
        &path("p2.csv"),
        "-o",
        &path("m.csv"),
    ]);
    assert!(e.contains("2 of 6 rows missing: 2, 5"), "{e}");
    let e = err(&[
        "merge",
        &path("p1.csv"),
        &path("p1.csv"),
        &path("p2.csv"),
        &path("p3.csv"),
        "-o",
        &path("m.csv"),
    ]);
    assert!(e.contains("row 0 is in two parts"), "{e}");
    // parts of another study (its duration differs: another hash)
    let other_dir = d.join("other");
    std::fs::create_dir(&other_dir).unwrap();
    let other = study_file(&other_dir, "\n    dt_s: Some(2e-5),");
    ok(&[
        "run",
        other.to_str().unwrap(),
        "--shard",
        "3/3",
        "-o",
        &path("q3.csv"),
    ]);
    let e = err(&[
        "merge",
        &path("p1.csv"),
        &path("p2.csv"),
        &path("q3.csv"),
        "-o",
        &path("m.csv"),
    ]);
    assert!(e.contains("expected parts of one study"), "{e}");
}

#[test]
fn bad_studies_and_arguments_are_refused_with_where_and_what() {
    let tmp = temp_dir();
    let d = tmp.path();
    let bad = d.join("bad.ron");
    std::fs::write(
        &bad,
        "Study(\n    preset: \"x.ron\",\n    factors: [],\n    design: Halton,\n)",
    )
    .unwrap();
    let e = err(&["plan", bad.to_str().unwrap()]);
    assert!(e.contains("bad.ron:4:"), "{e}");
    let s = study_file(d, "");
    let s = s.to_str().unwrap();
    let out = d.join("x.csv");
    let out = out.to_str().unwrap();
    assert!(err(&["run", s, "--shard", "4/3", "-o", out]).contains("--shard 4/3: expected K/N"));
    assert!(err(&["run", s, "--rows", "5..9", "-o", out]).contains("--rows 5..9: expected A..B"));
    let nope = d.join("nope.ron");
    std::fs::write(
        &nope,
        std::fs::read_to_string(s)
            .unwrap()
            .replace("road.amplitude_m", "road.nope_m"),
    )
    .unwrap();
    let e = err(&["plan", nope.to_str().unwrap()]);
    assert!(e.contains("factors[1].path"), "{e}");
}

/// Each field the study's checks refuse is named with its line and column
/// in the study file (`study_file`'s lines: 2 preset, 4 and 5 the factors,
/// 7 the design, 8 the duration, 9 the extra field).
#[test]
fn a_refused_study_field_is_named_at_its_line() {
    let tmp = temp_dir();
    let d = tmp.path();
    let base = std::fs::read_to_string(study_file(d, "\n    replicates: 1,")).unwrap();
    let cases: [(&str, &str, &str, &[&str]); 7] = [
        (
            "road.amplitude_m",
            "road.nope_m",
            ":5:",
            &["factors[1].path", "road.nope_m"],
        ),
        (
            "steps: 3",
            "steps: 0",
            ":4:",
            &["factors[0].values", "steps: 0", "steps >= 1"],
        ),
        (
            "List([0.001, 0.002])",
            "List([])",
            ":5:",
            &["factors[1].values", "at least one"],
        ),
        (
            "FullFactorial",
            "Sobol(samples: 0, seed: 1)",
            ":7:",
            &["design.samples = 0", "expected 1 to"],
        ),
        ("Some(0.1)", "Some(-1.0)", ":8:", &["duration_s", "-1"]),
        (
            "replicates: 1",
            "replicates: 2",
            ":9:",
            &["replicates = 2", "random road"],
        ),
        (
            "single_mode.ron",
            "no_such_preset.ron",
            ":2:",
            &["preset", "no_such_preset.ron"],
        ),
    ];
    for (from, to, line, want) in cases {
        assert!(base.contains(from), "{from}");
        let f = d.join("case.ron");
        std::fs::write(&f, base.replace(from, to)).unwrap();
        let e = err(&["plan", f.to_str().unwrap()]);
        assert!(e.contains(&format!("case.ron{line}")), "{to}: {e}");
        for w in want {
            assert!(e.contains(w), "{to}: `{w}` missing: {e}");
        }
    }
}
