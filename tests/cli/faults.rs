//! Faults are harmless: solver failures are typed errors with their time and
//! points (the command line exits 1 with them), an output too large for the
//! budget is refused before anything runs, and a failed or interrupted save
//! leaves the old file intact with no temporary left behind.

use crate::support::{bin, temp_dir};
use std::path::Path;
use std::process::Output;
use tirecontact::SceneSimulation;
use tirecontact::output::csv::{estimated_bytes, human_bytes};
use tirecontact::output::{write_atomic, write_atomic_with};
use tirecontact::{Scene, Simulation, SolverError};

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit code 1 (an error, not a panic's 101), `error: ` on stderr, no panic.
fn assert_clean_failure(o: &Output, what: &str) -> String {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(1), "{what}: {err}");
    assert!(err.starts_with("error: "), "{what}: {err}");
    assert!(!err.contains("panicked"), "{what}: {err}");
    err
}

/// Three points on a single mode (the same shape everywhere), all preloaded
/// on a flat road: the paper's scheme puts all three in contact in the same
/// step and the rank-1 model cannot hold them independently.
const ONE_MODE_THREE_POINTS: &str = r#"Scene(
    name: "three points, one mode",
    tyre: Modal(modes: [Mode(freq_hz: 100.0, damping_ratio: 0.05, shape: [0.3, 0.3, 0.3])]),
    points: [Point(x_m: -0.05, h_m: -0.001), Point(x_m: 0.0, h_m: -0.001), Point(x_m: 0.05, h_m: -0.001)],
    road: Sine(amplitude_m: 0.0, wavelength_m: 0.5),
    speed_mps: 10.0,
    ramp_s: 0.01,
    dt_s: 1e-4,
    duration_s: 0.05,
    contact_scheme: Paper,
)
"#;

#[test]
fn singular_contact_system_is_a_typed_error_with_time_and_points() {
    let scene = Scene::parse(ONE_MODE_THREE_POINTS, "singular.ron").unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let mut fault = None;
    for _ in 0..500 {
        let t_before = sim.time_s();
        match sim.step() {
            Ok(_) => {}
            Err(e) => {
                fault = Some((e, t_before));
                break;
            }
        }
    }
    let (e, t_before) = fault.expect("the rank-1 model cannot hold three points");
    match &e {
        SolverError::SingularContactSystem { t_s, points, pivot } => {
            assert_eq!(points, &[0, 1, 2]);
            assert!(*t_s > t_before && *t_s <= t_before + scene.dt_s + 1e-15);
            assert!(pivot.abs() < 1e-11, "{pivot}");
        }
        other => panic!("expected a singular contact system, got {other:?}"),
    }
    // the failed step did not advance the clock; stepping again fails again, cleanly
    assert_eq!(sim.time_s(), t_before);
    assert!(sim.step().is_err());
    assert!(sim.displacement_m().iter().all(|u| u.is_finite()));

    let tmp = temp_dir();
    let dir = tmp.path();
    let p = dir.join("singular.ron");
    std::fs::write(&p, ONE_MODE_THREE_POINTS).unwrap();
    // `check` validates (the scene is well-formed); `run` meets the fault
    assert!(
        bin()
            .arg("check")
            .arg(&p)
            .output()
            .unwrap()
            .status
            .success()
    );
    let out = dir.join("out.csv");
    let o = bin()
        .arg("run")
        .arg(&p)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    let err = assert_clean_failure(&o, "run");
    assert!(
        err.contains("singular contact system at t = 1.000000e-4 s for points [0, 1, 2]"),
        "{err}"
    );
}

/// A measured road of ±1e308 (finite, so it passes the file checks) makes
/// the forces overflow: a `NonFinite` error naming the quantity, time and
/// point, and exit code 1 from `run`.
#[test]
fn non_finite_values_in_the_solver_are_a_typed_error() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let rows: String = (-100..400)
        .map(|i| {
            format!(
                "{},{}\n",
                i as f64 * 1e-3,
                if i % 2 == 0 { -1e308 } else { 1e308 }
            )
        })
        .collect();
    std::fs::write(dir.join("huge.csv"), format!("x_m,z_m\n{rows}")).unwrap();
    let text = ONE_MODE_THREE_POINTS
        .replace(
            "road: Sine(amplitude_m: 0.0, wavelength_m: 0.5)",
            r#"road: Measured(file: "huge.csv")"#,
        )
        .replace("shape: [0.3, 0.3, 0.3]", "shape: [0.3, 0.2, 0.1]")
        .replace("contact_scheme: Paper", "contact_scheme: Located");
    let p = dir.join("huge.ron");
    std::fs::write(&p, &text).unwrap();
    let scene = Scene::load(&p).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let e = (0..500)
        .find_map(|_| sim.step().err())
        .expect("overflowing forces must be reported");
    match &e {
        SolverError::NonFinite { t_s, point, .. } => {
            assert!(t_s.is_finite() && *t_s > 0.0 && *point < 3, "{e:?}");
        }
        other => panic!("expected a non-finite error, got {other:?}"),
    }
    let o = bin().arg("run").arg(&p).output().unwrap();
    let err = assert_clean_failure(&o, "run");
    assert!(
        err.contains("non-finite ") && err.contains(" at t = ") && err.contains(", point "),
        "{err}"
    );
}

/// A measured road shorter than the run: `RoadOutOfRange` names x, t, the
/// point, the extent and the ways out.
#[test]
fn road_sampled_past_its_end_is_a_typed_error() {
    let tmp = temp_dir();
    let dir = tmp.path();
    std::fs::write(dir.join("short.csv"), "x_m,z_m\n-0.1,0\n0.1,0\n").unwrap();
    let text = ONE_MODE_THREE_POINTS
        .replace(
            "road: Sine(amplitude_m: 0.0, wavelength_m: 0.5)",
            r#"road: Measured(file: "short.csv")"#,
        )
        .replace("contact_scheme: Paper", "contact_scheme: Located");
    let p = dir.join("short.ron");
    std::fs::write(&p, &text).unwrap();
    let mut sim = Simulation::from_scene(&Scene::load(&p).unwrap()).unwrap();
    let e = (0..500).find_map(|_| sim.step().err()).unwrap();
    match &e {
        // point 2 starts at 0.05 m and leaves [-0.1, 0.1] m after 5 ms at 10 m/s
        SolverError::RoadOutOfRange {
            point, x_m, t_s, ..
        } => {
            assert_eq!(*point, 2);
            assert!(*x_m > 0.1 && (*t_s - 0.005).abs() < 2e-4, "{e:?}");
        }
        other => panic!("expected out of range, got {other:?}"),
    }
    let o = bin().arg("run").arg(&p).output().unwrap();
    let err = assert_clean_failure(&o, "run");
    assert!(
        err.contains("point 2) outside its extent [-0.1, 0.1] m") && err.contains("looped: true"),
        "{err}"
    );
}

/// A generated scene of 1e9 steps × 100 points: `check` accepts it at once
/// and states the CSV size; `run -o` refuses it before building anything,
/// naming the estimate and the `--every` that would fit.
#[test]
fn oversized_output_is_refused_up_front() {
    let p = 100;
    let shape: Vec<String> = (0..p)
        .map(|i| format!("{:.3}", 0.1 + 0.001 * i as f64))
        .collect();
    let points: Vec<String> = (0..p)
        .map(|i| format!("Point(x_m: {:.3}, h_m: 0.0)", 0.01 * i as f64))
        .collect();
    let text = format!(
        "Scene(name: \"huge run\", tyre: Modal(modes: [Mode(freq_hz: 100.0, damping_ratio: 0.05, shape: [{}])]), points: [{}], road: Sine(amplitude_m: 0.001, wavelength_m: 0.5), speed_mps: 10.0, ramp_s: 0.01, dt_s: 1e-6, duration_s: 1000.0)",
        shape.join(", "),
        points.join(", ")
    );
    let scene = Scene::parse(&text, "huge.ron").unwrap();
    assert_eq!(scene.num_steps(), 1_000_000_000);
    // (1e9 + 3) rows × 501 columns × 17 bytes
    let est = estimated_bytes(scene.num_steps(), 1, p);
    assert!((est / 8.517e12 - 1.0).abs() < 1e-6, "{est}");
    assert_eq!(human_bytes(est), "8.52 TB");
    // the suggested --every fits, one less does not
    assert!(estimated_bytes(scene.num_steps(), 426, p) <= 20e9);
    assert!(estimated_bytes(scene.num_steps(), 425, p) > 20e9);

    let tmp = temp_dir();
    let dir = tmp.path();
    let path = dir.join("huge.ron");
    std::fs::write(&path, &text).unwrap();
    let o = bin().arg("check").arg(&path).output().unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        out.contains("1000000000 steps") && out.contains("8.52 TB"),
        "{out}"
    );

    let csv = dir.join("out.csv");
    let o = bin()
        .arg("run")
        .arg(&path)
        .arg("-o")
        .arg(&csv)
        .output()
        .unwrap();
    let err = assert_clean_failure(&o, "run -o");
    for want in [
        "the CSV would be about 8.52 TB",
        "1000000000 rows × 501 columns",
        "over the output budget of 20.00 GB",
        "--every 426",
        "--duration",
    ] {
        assert!(err.contains(want), "lacks `{want}`: {err}");
    }
    assert!(!csv.exists(), "nothing written");
    // refused before the run, which would take hours (a refusal after it
    // would hold this test past CI's limit): no run summary on stdout
    assert!(
        o.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
}

/// The budget applies to `-o` only (a run without it streams and keeps no
/// history) and follows `--max-output-gb`.
#[test]
fn output_budget_follows_the_flag_and_only_applies_to_files() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let csv = dir.join("out.csv");
    let base = ["run", "presets/single_mode.ron", "--duration", "0.001"];
    // 100 steps of 1 point: (100 + 3) rows × 6 columns × 17 bytes = 10506 bytes
    let o = bin()
        .args(base)
        .args(["--max-output-gb", "1e-5"])
        .arg("-o")
        .arg(&csv)
        .output()
        .unwrap();
    let err = assert_clean_failure(&o, "tiny budget");
    assert!(
        err.contains("about 10.51 kB") && err.contains("--every 2"),
        "{err}"
    );
    assert!(!csv.exists());
    // without -o nothing is kept: no budget
    let o = bin()
        .args(base)
        .args(["--max-output-gb", "1e-5"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    // the suggested --every fits: (50 + 3) rows × 6 × 17 = 5406 bytes
    let o = bin()
        .args(base)
        .args(["--max-output-gb", "1e-5", "--every", "2", "-o"])
        .arg(&csv)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(csv.exists());
}

fn names_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// A write that fails half-way (a writer error after N bytes, as from a full
/// disk or an interruption) leaves the old file byte for byte and no
/// temporary beside it; a write that succeeds replaces it whole.
#[test]
fn interrupted_atomic_write_keeps_the_old_file() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let path = dir.join("scene.ron");
    let old = b"old contents\n".repeat(100);
    std::fs::write(&path, &old).unwrap();
    let new: Vec<u8> = (0..100_000u32).map(|i| (i % 251) as u8).collect();
    // 0 bytes, a few, past the write buffer (8 KiB), all but one
    for n in [0, 10, 50_000, new.len() - 1] {
        let r = write_atomic_with(&path, |w| {
            w.write_all(&new[..n])?;
            w.flush()?; // the bytes reach the temporary file
            Err(std::io::Error::other(format!(
                "interrupted after {n} bytes"
            )))
        });
        let e = r.unwrap_err();
        assert!(e.to_string().contains("interrupted after"), "{e}");
        assert_eq!(std::fs::read(&path).unwrap(), old, "after {n} bytes");
        assert_eq!(names_in(dir), ["scene.ron"], "after {n} bytes");
    }
    write_atomic(&path, &new).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), new);
    assert_eq!(names_in(dir), ["scene.ron"]);
}

/// `Scene::save` where the temporary cannot be created (its name, longer
/// than the file's, exceeds the file system's name limit) or where the
/// rename fails (the target is a folder): an error naming the path, the old
/// contents intact, nothing left behind.
#[test]
fn failed_scene_save_keeps_the_old_file() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let scene = Scene::parse(tirecontact::DEFAULT_PRESET, "default").unwrap();
    // 250 characters: a valid name; its temporary `.NAME.tmp-PID-N` is not
    let long = dir.join(format!("{}.ron", "s".repeat(246)));
    std::fs::write(&long, "old").unwrap();
    let e = scene.save(&long).unwrap_err().to_string();
    assert!(e.contains(&"s".repeat(246)), "{e}");
    assert_eq!(std::fs::read_to_string(&long).unwrap(), "old");
    assert_eq!(names_in(dir).len(), 1);

    let folder = dir.join("folder.ron");
    std::fs::create_dir(&folder).unwrap();
    std::fs::write(folder.join("inside"), "kept").unwrap();
    assert!(scene.save(&folder).is_err());
    assert_eq!(
        std::fs::read_to_string(folder.join("inside")).unwrap(),
        "kept"
    );
    assert_eq!(names_in(dir).len(), 2, "{:?}", names_in(dir));

    // and a save that works round-trips
    let ok = dir.join("ok.ron");
    scene.save(&ok).unwrap();
    assert_eq!(Scene::load(&ok).unwrap().points, scene.points);
    assert_eq!(names_in(dir).len(), 3, "{:?}", names_in(dir));
}

/// Output piped into a reader that has stopped (`| head -1`) ends the
/// command quietly, as other tools do: no panic on the closed pipe. The
/// pipe is closed before the command prints (it identifies first).
#[cfg(unix)]
#[test]
fn a_closed_stdout_pipe_ends_the_command_without_a_panic() {
    use std::process::Stdio;
    let mut child = bin()
        .args([
            "identify",
            "--data",
            "tests/data/uff/time3.uff",
            "--points",
            "3",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = stderr(&out);
    assert!(!err.contains("panicked"), "{err}");
    assert_ne!(out.status.code(), Some(101), "{err}");
}
