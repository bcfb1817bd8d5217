//! Every shipped preset loads, validates and runs a few steps; broken presets
//! report file, line and column, or the field, value and expectation.

use std::path::Path;
use tirecontact::SceneSimulation;
use tirecontact::{Scene, SceneError, Simulation};

fn shipped() -> Vec<std::path::PathBuf> {
    let mut v: Vec<_> = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("presets"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    v.sort();
    v
}

#[test]
fn every_shipped_preset_loads_and_steps() {
    let presets = shipped();
    assert!(presets.len() >= 2, "{presets:?}");
    for p in presets {
        let scene = Scene::load(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        let mut short = scene.clone();
        short.duration_s = 200.0 * short.dt_s;
        let mut sim =
            Simulation::from_scene(&short).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        for _ in 0..200 {
            sim.step()
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        }
        // saving and re-reading gives the same scene
        let saved = scene.to_ron_string();
        let again = Scene::parse(&saved, "roundtrip").unwrap();
        assert_eq!(again.points, scene.points);
        assert_eq!(again.tyre, scene.tyre);
        assert_eq!(again.road, scene.road);
        // points on the centreline are saved without `y_m`: `x_m` then
        // `h_m`, nothing between, nothing else
        // (a grid's points are saved as the Grid(...) they were written as)
        if scene.points.grid().is_none() {
            assert!(
                scene.points.iter().all(|pt| pt.y_m == 0.0),
                "{}",
                p.display()
            );
        }
        assert!(!saved.contains("y_m"), "{}:\n{saved}", p.display());
        if scene.points.grid().is_none() {
            assert!(
                saved.contains(&saved_points(&scene.points)),
                "{}: points not saved as `x_m`, `h_m`:\n{saved}",
                p.display()
            );
        } else {
            assert!(saved.contains("points: Grid("), "{}:\n{saved}", p.display());
        }
    }
}

/// The `points` list of a saved scene whose points are all on the
/// centreline, as the save writes it (numbers as RON writes them).
fn saved_points(points: &[tirecontact::scene::Point]) -> String {
    let num = |x: f64| ron::to_string(&x).unwrap();
    let mut s = "    points: [\n".to_string();
    for pt in points {
        s.push_str(&format!(
            "        Point(\n            x_m: {},\n            h_m: {},\n        ),\n",
            num(pt.x_m),
            num(pt.h_m)
        ));
    }
    s.push_str("    ],\n");
    s
}

/// Two points at one `x` across the tread, residues that tell them apart.
const ACROSS: &str = r#"Scene(
    name: "across",
    tyre: Modal(modes: [
        Mode(freq_hz: 100.0, damping_ratio: 0.05, residue: [[0.1, 0.02], [0.02, 0.06]]),
    ]),
    points: [Point(x_m: 0.1, h_m: -0.001), Point(x_m: 0.1, y_m: -0.04, h_m: -0.001)],
    road: Sine(amplitude_m: 0.002, wavelength_m: 0.5),
    speed_mps: 20.0,
    ramp_s: 0.05,
    dt_s: 1e-5,
    duration_s: 1.0,
)"#;

/// `y_m` is optional (0), read when written, saved between `x_m` and `h_m`
/// when not 0 and left out when 0, and read back as saved.
#[test]
fn points_across_the_tread_round_trip() {
    let s = Scene::parse(ACROSS, "across.ron").unwrap();
    assert_eq!(
        s.points
            .iter()
            .map(|p| (p.x_m, p.y_m, p.h_m))
            .collect::<Vec<_>>(),
        [(0.1, 0.0, -0.001), (0.1, -0.04, -0.001)]
    );
    let saved = s.to_ron_string();
    assert_eq!(saved.matches("y_m").count(), 1, "{saved}");
    assert!(
        saved.contains("x_m: 0.1,\n            y_m: -0.04,\n            h_m: -0.001,"),
        "{saved}"
    );
    let back = Scene::parse(&saved, "saved.ron").unwrap();
    assert_eq!(back, s);
    // a 0 written is not saved
    let zero = ACROSS.replace("Point(x_m: 0.1, h_m", "Point(x_m: 0.1, y_m: 0.0, h_m");
    let z = Scene::parse(&zero, "zero.ron").unwrap();
    assert_eq!(z, s);
    assert_eq!(z.to_ron_string(), saved);
}

#[test]
fn embedded_default_preset_is_valid() {
    Scene::parse(tirecontact::DEFAULT_PRESET, "default").unwrap();
}

const GOOD: &str = r#"Scene(
    name: "t",
    tyre: Modal(modes: [
        Mode(freq_hz: 100.0, damping_ratio: 0.05, residue: [[0.1]]),
    ]),
    points: [Point(x_m: 0.0, h_m: -0.001)],
    road: Sine(amplitude_m: 0.002, wavelength_m: 0.5),
    speed_mps: 20.0,
    ramp_s: 0.05,
    dt_s: 1e-5,
    duration_s: 1.0,
)"#;

#[test]
fn syntax_error_reports_line_and_column() {
    // missing comma after the speed on line 8
    let bad = GOOD.replace("speed_mps: 20.0,", "speed_mps: 20.0");
    match Scene::parse(&bad, "bad.ron") {
        Err(SceneError::Syntax {
            file, line, col, ..
        }) => {
            assert_eq!(file, "bad.ron");
            assert_eq!(line, 9, "error is reported where the parser stopped");
            assert!(col >= 1);
        }
        other => panic!("expected a syntax error, got {other:?}"),
    }
    let unknown = GOOD.replace("speed_mps", "sped_mps");
    let e = Scene::parse(&unknown, "u.ron").unwrap_err().to_string();
    assert!(e.contains("u.ron:8:") && e.contains("sped_mps"), "{e}");
}

fn invalid(text: &str) -> Vec<tirecontact::base::error::FieldError> {
    match Scene::parse(text, "x.ron") {
        Err(SceneError::Invalid { errors, .. }) => errors,
        other => panic!("expected invalid, got {other:?}"),
    }
}

#[test]
fn validation_names_field_value_and_expectation() {
    let e = invalid(&GOOD.replace("damping_ratio: 0.05", "damping_ratio: -0.1"));
    assert_eq!(e[0].field, "tyre.modes[0].damping_ratio");
    assert_eq!(e[0].value, "-0.1");
    assert!(e[0].expected.contains(">= 0"));

    let e = invalid(&GOOD.replace("residue: [[0.1]]", "residue: [[0.1, 0.2]]"));
    assert_eq!(e[0].field, "tyre.modes[0].residue");

    let e = invalid(
        &GOOD
            .replace("dt_s: 1e-5", "dt_s: 2.0")
            .replace("duration_s: 1.0", "duration_s: 0.5"),
    );
    assert!(e.iter().any(|e| e.field == "dt_s"), "{e:?}");

    let e = invalid(&GOOD.replace("ramp_s: 0.05", "ramp_s: 0.0"));
    assert_eq!(e[0].field, "ramp_s");

    let e = invalid(&GOOD.replace("wavelength_m: 0.5", "wavelength_m: 0.0"));
    assert_eq!(e[0].field, "road.wavelength_m");

    let e = invalid(&GOOD.replace("speed_mps: 20.0", "speed_mps: inf"));
    assert_eq!(
        (e[0].field.as_str(), e[0].value.as_str()),
        ("speed_mps", "inf")
    );

    let two = GOOD.replace(
        "points: [Point(x_m: 0.0, h_m: -0.001)]",
        "points: [Point(x_m: 0.0, h_m: -0.001), Point(x_m: 0.0, h_m: -0.001)]",
    );
    let e = invalid(&two);
    assert!(
        e.iter().any(|e| e.field == "points[1].x_m"
            && e.value == "0"
            && e.expected.contains("points[0]")),
        "{e:?}"
    );
}

/// Contact fraction per point over a whole run of a shipped preset.
fn contact_fraction(name: &str) -> Vec<f64> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets")
        .join(name);
    let scene = Scene::load(&p).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    while !sim.finished() {
        sim.step().unwrap();
    }
    sim.stats().contact_fraction()
}

/// What the guided-tour descriptions tell the class to watch holds: the
/// first preset of each pair and the second differ as described.
#[test]
fn guided_tour_descriptions_match_the_runs() {
    let soft = contact_fraction("guided_1a_soft_tyre.ron")[0];
    let stiff = contact_fraction("guided_1b_stiff_tyre.ron")[0];
    assert!(soft < 0.6 && stiff > 0.99, "soft {soft}, stiff {stiff}");
    let low = contact_fraction("guided_2a_low_damping.ron")[0];
    let high = contact_fraction("guided_2b_high_damping.ron")[0];
    assert!(high > low && low < 0.6, "low {low}, high {high}");
    let slow = contact_fraction("guided_3a_slow.ron")[0];
    let fast = contact_fraction("guided_3b_fast.ron")[0];
    assert!(slow > 0.99 && fast < 0.5, "slow {slow}, fast {fast}");
    let long = contact_fraction("guided_4a_long_wavelength.ron");
    let short = contact_fraction("guided_4b_short_wavelength.ron");
    assert!(
        long[0] > 0.99 && long[2] > 0.99 && long[1] < 0.1,
        "{long:?}"
    );
    assert!(short.iter().all(|c| (0.2..0.6).contains(c)), "{short:?}");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
    /// Numbers written to a preset read back bit for bit (serde's and ron's
    /// float formatting and parsing): any finite value, tiny, huge, negative
    /// zero, 17 significant digits.
    #[test]
    fn preset_numbers_round_trip_bit_for_bit(
        v in proptest::collection::vec(proptest::num::f64::NORMAL | proptest::num::f64::SUBNORMAL | proptest::num::f64::ZERO, 8)
    ) {
        let mut s = Scene::parse(tirecontact::DEFAULT_PRESET, "paper").unwrap();
        s.speed_mps = v[0];
        s.dt_s = v[1];
        s.duration_s = v[2];
        s.ramp_s = v[3];
        s.points[0].x_m = v[4];
        s.points[1].h_m = v[5];
        s.tyre = tirecontact::scene::Tyre::Modal {
            modes: vec![tirecontact::scene::Mode {
                freq_hz: v[6],
                damping_ratio: v[7],
                residue: Vec::new(),
                shape: v[..5].to_vec(),
            }],
        };
        let text = s.to_ron_string();
        // parse only: the values need not be valid, only read back
        let back: Scene = ron::from_str(&text).unwrap();
        let bits = |s: &Scene| -> Vec<u64> {
            let tirecontact::scene::Tyre::Modal { modes } = &s.tyre else { return vec![] };
            [s.speed_mps, s.dt_s, s.duration_s, s.ramp_s, s.points[0].x_m, s.points[1].h_m,
             modes[0].freq_hz, modes[0].damping_ratio]
                .iter()
                .chain(&modes[0].shape)
                .map(|x| x.to_bits())
                .collect()
        };
        proptest::prop_assert_eq!(bits(&back), bits(&s), "{}", text);
    }
}
