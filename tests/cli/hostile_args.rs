//! Hostile command lines: random option values and paths for `run`, `check`,
//! `identify`, `sweep` and `bench`. Every launch either succeeds or exits
//! non-zero with an `error` message on stderr; none panics (exit code 101,
//! "panicked at") or dies on a signal, and a failed launch leaves no output
//! file and no temporary behind.
//!
//! Launches: `PROPTEST_CASES`, else 200 (3.5 s in a debug build with the
//! GUI feature; most are refused before any work).

use crate::support::{bin, proptest_cases, temp_dir};
use proptest::prelude::*;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// Number-like strings a user (or a script with an unset variable) may type.
const NUMBERS: [&str; 30] = [
    "0",
    "-0",
    "-1",
    "1e-300",
    "1e300",
    "1.7976931348623157e308",
    "2.2250738585072014e-308",
    "5e-324",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "infinity",
    "18446744073709551615",
    "18446744073709551616",
    "99999999999999999999999999999",
    "",
    "  ",
    "abc",
    "1e",
    "0x10",
    "1_000",
    "\u{ff11}", // fullwidth 1
    "1e-5s",
    "+1",
    "-",
    "\u{663}", // Arabic-Indic 3
    "2.5",
    "1,5",
    "-1e-300",
];

const SIZES: [&str; 14] = [
    "0x0",
    "1x1",
    "199x200",
    "8001x900",
    "4294967295x4294967295",
    "4294967296x1",
    "x",
    "1400x",
    "x900",
    "-1x5",
    "1400X900",
    "1400x900x3",
    "\u{ff11}400x900",
    "",
];

const PARAMS: [&str; 16] = [
    "",
    " ",
    "speed_mps",
    "points[999].h_m",
    "points[-1].h_m",
    "points[*].x_m",
    "points[18446744073709551616].h_m",
    "tyre.modes[0].freq_hz",
    "tyre.modes[99].freq_hz",
    "tyre.ring.inflation_pa",
    "\u{fc}n\u{ef}c\u{f6}d\u{e9}",
    "road..amplitude_m",
    "[",
    "points[",
    "dt_s",
    "name",
];

/// Where an output goes.
#[derive(Debug, Clone, Copy)]
enum OutPath {
    Plain,
    UnicodeSpaces,
    MissingDir,
    IsDir,
    Empty,
    TrailingSlash,
    ExistingFileAsDir,
}

const OUT_PATHS: [OutPath; 7] = [
    OutPath::Plain,
    OutPath::UnicodeSpaces,
    OutPath::MissingDir,
    OutPath::IsDir,
    OutPath::Empty,
    OutPath::TrailingSlash,
    OutPath::ExistingFileAsDir,
];

fn out_path(dir: &Path, kind: OutPath, ext: &str) -> PathBuf {
    match kind {
        OutPath::Plain => dir.join(format!("out.{ext}")),
        OutPath::UnicodeSpaces => {
            let d = dir.join("\u{fc} \u{f1} \u{7a7a} dir");
            std::fs::create_dir_all(&d).unwrap();
            d.join(format!("o u t \u{e9}.{ext}"))
        }
        OutPath::MissingDir => dir.join("no such dir").join(format!("out.{ext}")),
        OutPath::IsDir => dir.to_path_buf(),
        OutPath::Empty => PathBuf::new(),
        OutPath::TrailingSlash => PathBuf::from(format!("{}/", dir.join("slash").display())),
        OutPath::ExistingFileAsDir => {
            let f = dir.join("a_file");
            std::fs::write(&f, "x").unwrap();
            f.join(format!("out.{ext}"))
        }
    }
}

/// Which preset a command is given.
fn preset_path(dir: &Path, kind: usize, base: &str) -> PathBuf {
    match kind % 8 {
        0..=2 => PathBuf::from(base),
        3 => {
            let d = dir.join("pr\u{e9}sets \u{2603}");
            std::fs::create_dir_all(&d).unwrap();
            let p = d.join("sc\u{e8}ne one.ron");
            std::fs::copy(base, &p).unwrap();
            p
        }
        4 => dir.join("missing dir").join("none.ron"),
        5 => dir.to_path_buf(),
        6 => {
            let p = dir.join("empty.ron");
            std::fs::write(&p, "").unwrap();
            p
        }
        _ => {
            let p = dir.join("latin1.ron");
            std::fs::write(&p, b"Scene(name: \"caf\xe9\")").unwrap();
            p
        }
    }
}

/// One generated command line: its arguments and the outputs it names.
#[derive(Debug)]
struct Launch {
    args: Vec<OsString>,
    outputs: Vec<PathBuf>,
}

fn s(x: &str) -> OsString {
    x.into()
}

fn launch(cmd: usize, opt: usize, v: usize, out: usize, preset: usize, dir: &Path) -> Launch {
    let num = NUMBERS[v % NUMBERS.len()];
    let size = SIZES[v % SIZES.len()];
    let okind = OUT_PATHS[out % OUT_PATHS.len()];
    let mut outputs = Vec::new();
    let mut a: Vec<OsString> = Vec::new();
    match cmd % 5 {
        // run: one hostile option on a short run of a small scene
        0 => {
            let p = preset_path(dir, preset, "presets/three_points.ron");
            let opt = opt % 13;
            a.push(s("run"));
            a.push(p.into());
            if opt != 1 {
                a.push(s("--duration"));
                a.push(s("0.001"));
            }
            let o = out_path(dir, okind, "csv");
            match opt {
                0 => {
                    a.push(s("--dt"));
                    a.push(s(num));
                }
                1 => {
                    a.push(s("--duration"));
                    a.push(s(num));
                }
                2 => {
                    a.push(s("--every"));
                    a.push(s(num));
                    a.push(s("-o"));
                    a.push(o.clone().into());
                    outputs.push(o);
                }
                3 => {
                    a.push(s("--max-output-gb"));
                    a.push(s(num));
                    a.push(s("-o"));
                    a.push(o.clone().into());
                    outputs.push(o);
                }
                4 => {
                    let png = out_path(dir, okind, "png");
                    a.push(s("--plot-size"));
                    a.push(s(size));
                    a.push(s("--plot"));
                    a.push(png.clone().into());
                    outputs.push(png);
                }
                5 => {
                    a.push(s("--spectrum-max-hz"));
                    a.push(s(num));
                    a.push(s("--spectrum"));
                    a.push(o.clone().into());
                    outputs.push(o);
                }
                6 => {
                    a.push(s("--spectrum-from"));
                    a.push(s(num));
                    a.push(s("--spectrum"));
                    a.push(o.clone().into());
                    outputs.push(o);
                }
                7..=10 => {
                    let flag = ["--fps", "--slow-motion", "--frames-from", "--frames-to"][opt - 7];
                    a.push(s(flag));
                    a.push(s(num));
                    a.push(s("--frames"));
                    // frames go into a folder; a plain path is a new folder
                    let d = out_path(dir, okind, "d");
                    a.push(d.into());
                }
                11 => {
                    a.push(s("--frame-size"));
                    a.push(s(size));
                    a.push(s("--frames"));
                    a.push(out_path(dir, okind, "d").into());
                }
                _ => {
                    // an output of each kind at once
                    a.push(s("-o"));
                    a.push(o.clone().into());
                    outputs.push(o);
                    let png = out_path(dir, okind, "png");
                    a.push(s("--plot"));
                    a.push(png.clone().into());
                    outputs.push(png);
                }
            }
        }
        // check: only the preset varies
        1 => {
            a.push(s("check"));
            a.push(preset_path(dir, preset + opt, "presets/single_mode.ron").into());
        }
        // identify: hostile preset and output paths
        2 => {
            let p = preset_path(dir, preset, "presets/paper.ron");
            a.push(s("identify"));
            a.push(p.into());
            let (flag, ext) = [
                ("-o", "ron"),
                ("--diagram", "png"),
                ("--responses", "csv"),
                ("--figures", "d"),
            ][opt % 4];
            // (a valid --figures runs the scene: only its refusals here)
            let okind = if flag == "--figures" {
                [OutPath::Empty, OutPath::ExistingFileAsDir][out % 2]
            } else {
                okind
            };
            let o = out_path(dir, okind, ext);
            a.push(flag.into());
            a.push(o.clone().into());
            if flag != "--figures" {
                outputs.push(o);
            }
        }
        // sweep: hostile parameter path, range, counts and outputs
        3 => {
            let p = preset_path(dir, preset, "presets/single_mode.ron");
            let opt = opt % 8;
            a.push(s("sweep"));
            a.push(p.into());
            let param = if opt == 0 {
                PARAMS[v % PARAMS.len()]
            } else {
                "speed_mps"
            };
            a.push(s("--param"));
            a.push(s(param));
            a.push(s("--from"));
            a.push(s(if opt == 1 { num } else { "1" }));
            a.push(s("--to"));
            a.push(s(if opt == 2 { num } else { "2" }));
            // --steps and --threads: small or refused values only (a huge
            // --steps allocates before any check: see refusals.rs)
            let counts = ["0", "1", "2", "-1", "abc", "1.5", "", "3"];
            a.push(s("--steps"));
            a.push(s(if opt == 3 {
                counts[v % counts.len()]
            } else {
                "2"
            }));
            if opt == 4 {
                a.push(s("--threads"));
                a.push(s(counts[v % counts.len()]));
            }
            a.push(s("--dt"));
            a.push(s(if opt == 5 { num } else { "1e-4" }));
            a.push(s("--duration"));
            a.push(s(if opt == 6 { num } else { "0.06" }));
            let o = out_path(dir, okind, "csv");
            a.push(s("-o"));
            a.push(o.clone().into());
            outputs.push(o);
            if opt == 7 {
                let png = out_path(dir, okind, "png");
                a.push("--plot".into());
                a.push(png.clone().into());
                outputs.push(png);
            }
        }
        // bench: only refusals (a valid study takes minutes in a debug build)
        _ => {
            a.push(s("bench"));
            a.push(s("--quick"));
            a.push(s("-o"));
            if opt.is_multiple_of(2) {
                // an existing file as the output folder, a valid preset
                a.push(
                    out_path(dir, OutPath::ExistingFileAsDir, "d")
                        .parent()
                        .unwrap()
                        .into(),
                );
                a.push("presets/single_mode.ron".into());
            } else {
                a.push(dir.join("bench out").into());
                // a preset that cannot be read or parsed
                a.push(preset_path(dir, 4 + preset % 4, "presets/single_mode.ron").into());
            }
        }
    }
    Launch { args: a, outputs }
}

/// Files whose names mark a temporary of `write_atomic` (`.NAME.tmp-PID-N`).
fn temporaries(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(rd) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in rd.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p
                .file_name()
                .is_some_and(|n| n.to_string_lossy().contains(".tmp-"))
            {
                found.push(p);
            }
        }
    }
    found
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: proptest_cases(200),
        // a failing launch shrinks over a few more launches only
        max_shrink_iters: 64,
        ..ProptestConfig::default()
    })]

    #[test]
    fn hostile_command_lines_never_panic(
        cmd in 0usize..5,
        opt in 0usize..64,
        v in 0usize..1000,
        out in 0usize..7,
        preset in 0usize..8,
    ) {
        let scratch = temp_dir();
        let dir = scratch.path();
        let l = launch(cmd, opt, v, out, preset, dir);
        let existed: Vec<bool> = l.outputs.iter().map(|p| p.exists()).collect();
        let o = bin()
            .args(&l.args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        let shown = format!("{:?}\nexit {:?}\nstderr:\n{err}", l.args, o.status.code());
        if std::env::var_os("ROBUST_CLI_LOG").is_some() {
            eprintln!("---- {shown}");
        }
        prop_assert!(o.status.code().is_some(), "killed by a signal: {shown}");
        prop_assert_ne!(o.status.code(), Some(101), "{}", shown);
        prop_assert!(!err.contains("panicked at"), "{shown}");
        if !o.status.success() {
            prop_assert!(err.contains("error"), "a failure without an error message: {shown}");
            for (p, e) in l.outputs.iter().zip(existed) {
                prop_assert!(e || !p.is_file(), "a failed launch left {}: {shown}", p.display());
            }
        }
        let tmp = temporaries(dir);
        prop_assert!(tmp.is_empty(), "temporaries left: {tmp:?}: {shown}");
    }
}
