//! `bench --scaling --quick`: every size measured in its own process, the
//! table, the fitted exponents and the figure written.

use crate::support::{bin, temp_dir};

#[test]
fn the_scaling_study_writes_its_table_and_figure() {
    let tmp = temp_dir();
    let out = tmp.path().join("scaling");
    let o = bin()
        .args(["bench", "--scaling", "--quick", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("scaling.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    // four sizes, each with rigid contact and with tread springs, and two
    // of the contact patch
    assert_eq!(rows.len(), 10, "{csv}");
    assert_eq!(rows.iter().filter(|r| r[0] == "patch").count(), 2, "{csv}");
    for r in &rows {
        let step_s: f64 = r[4].parse().unwrap();
        let free_s: f64 = r[5].parse().unwrap();
        assert!(step_s > 0.0 && free_s > 0.0, "{r:?}");
        // each child reports its own peak memory (Linux)
        if cfg!(target_os = "linux") {
            let kb: f64 = r[13].parse().unwrap();
            assert!(kb > 1000.0, "{r:?}");
        }
        // 20 points: the tread holds the pressed third (6) on the road,
        // rigid contact about one point
        if r[1] == "20" {
            let on: f64 = r[7].parse::<f64>().unwrap() * 20.0;
            match r[0] {
                "tread" => assert!((5.5..=7.0).contains(&on), "{r:?}"),
                "rigid" => assert!(on < 3.0, "{r:?}"),
                other => panic!("contact `{other}`"),
            }
        }
        // the patch (20 points across): its pressed third on the road
        if r[0] == "patch" {
            let share: f64 = r[7].parse().unwrap();
            assert!((0.25..=0.42).contains(&share), "{r:?}");
        }
    }
    let md = std::fs::read_to_string(out.join("scaling.md")).unwrap();
    assert!(md.contains("Fitted exponents"), "{md}");
    assert!(out.join("scaling.png").metadata().unwrap().len() > 10_000);
    // a bad size is refused with what was expected
    let o = bin()
        .args(["bench", "--scaling-one", "5"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("expected P,K,CONTACT"));
}

/// `bench --patch-presets` on a small patch written here (2 threads): the
/// table names it with its grid and modes beside the study's patch, then
/// beside its smooth twin and the goals (no callgrind with `--quick`); a
/// preset without a patch is refused, named.
#[test]
fn patch_presets_are_timed_beside_the_study_patch() {
    let tmp = temp_dir();
    let preset = tmp.path().join("small_patch.ron");
    std::fs::write(
        &preset,
        r#"Scene(
    name: "Small patch",
    tyre: Plate(plate: (max_freq_hz: 600.0)),
    points: Grid(along: 4, across: 3, spacing_m: (0.006, 0.02), preload: Flat(depth_m: 0.0005)),
    road: Sine(amplitude_m: 0.0001, wavelength_m: 0.05),
    speed_mps: 10.0,
    ramp_s: 0.002,
    dt_s: 1e-5,
    duration_s: 0.004,
    contact: Compliant(stiffness_n_m: [75000.0]),
)"#,
    )
    .unwrap();
    let out = tmp.path().join("out");
    let o = bin()
        .args([
            "bench",
            "--patch-presets",
            "--quick",
            "--threads",
            "2",
            "-o",
        ])
        .arg(&out)
        .arg(&preset)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(out.join("patch_presets.md")).unwrap();
    let row = md
        .lines()
        .find(|l| l.starts_with("| Small patch |"))
        .unwrap_or_else(|| panic!("{md}"));
    assert!(row.contains("| 4 × 3 |"), "{row}");
    assert!(md.contains("on 2 thread(s)"), "{md}");
    assert!(md.contains("## Against the smooth twin"), "{md}");
    assert!(
        md.contains(
            "| preset | events/step | twin events/step | µs/step | twin (µs/step) | preset / twin | one event (event-free steps) | M instructions/step | counted events/step | twin (M instructions/step) | twin counted events/step | preset / twin, instructions | one event by instructions (event-free steps) |"
        ),
        "{md}"
    );
    let twin_row = md
        .lines()
        .filter(|l| l.starts_with("| Small patch |"))
        .nth(1)
        .unwrap_or_else(|| panic!("{md}"));
    // not counted with --quick
    assert!(
        twin_row.ends_with("| - | - | - | - | - | - |"),
        "{twin_row}"
    );
    assert!(md.contains("## Goals\n"), "{md}");
    for goal in [
        "| one located event ≤ 1 event-free step | Small patch |",
        "| chip seal ≤ 2.5× its smooth twin per step | (not measured) |",
        "| every shipped patch ≥ 0.4× real time at dt = 1e-5 s on one core | Small patch |",
    ] {
        assert!(md.contains(goal), "{goal}: {md}");
    }
    let line = tmp.path().join("line.ron");
    std::fs::copy("presets/three_points.ron", &line).unwrap();
    let o = bin()
        .args(["bench", "--patch-presets", "--quick", "-o"])
        .arg(&out)
        .arg(&line)
        .output()
        .unwrap();
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("line.ron") && e.contains("2 rows across"), "{e}");
}

/// `bench --presets-steps` on two small presets: the table of µs per step
/// (instructions `-` with `--quick`); the child run of a callgrind count
/// prints its events only, and a bad one is refused with what was expected.
#[test]
fn small_presets_are_timed_per_step() {
    let tmp = temp_dir();
    let out = tmp.path().join("steps");
    let o = bin()
        .args(["bench", "--presets-steps", "--quick", "-o"])
        .arg(&out)
        .args(["presets/single_mode.ron", "presets/three_points.ron"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(out.join("preset_steps.md")).unwrap();
    assert!(
        md.contains(
            "| preset | points | modes | dt (s) | steps | µs/step | events/step | real time | instructions/step |"
        ),
        "{md}"
    );
    let rows: Vec<&str> = md
        .lines()
        .filter(|l| l.starts_with("| Single mode") || l.starts_with("| Three coupled"))
        .collect();
    assert_eq!(rows.len(), 2, "{md}");
    assert!(rows.iter().all(|r| r.ends_with("| - |")), "{md}");
    let o = bin()
        .args([
            "bench",
            "--preset-one",
            "presets/three_points.ron,0.001,smooth",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let events = String::from_utf8_lossy(&o.stdout);
    assert!(events.trim().parse::<u64>().is_ok(), "{events}");
    for bad in ["presets/three_points.ron", "presets/three_points.ron,-1"] {
        let o = bin().args(["bench", "--preset-one", bad]).output().unwrap();
        assert!(!o.status.success());
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.contains("expected PATH,SECONDS[,smooth]"), "{e}");
    }
}
