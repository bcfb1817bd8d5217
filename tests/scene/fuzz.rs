//! Property tests: arbitrary bytes and mutated presets never panic the
//! parser or validator; arbitrary structured scenes either validate and run
//! a short bounded run with finite, non-negative outputs, or fail with field
//! errors; arbitrary road files never panic the reader or a run over them;
//! no step-mean contact force pulls, rigid or compliant.
//! (A longer fuzzing campaign runs the same properties with more cases:
//! `PROPTEST_CASES=100000 cargo test --release --test scene fuzz::`.)

use crate::support::{proptest_cases, temp_dir};
use proptest::prelude::*;
use tirecontact::SceneSimulation;
use tirecontact::model::road::Road;
use tirecontact::readers::road::read_profile_csv;
use tirecontact::scene::{Contact, ContactScheme, Mode, Point, Scene, Tyre};
use tirecontact::{SceneError, Simulation};

fn presets() -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir("presets")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    v.sort();
    v
}

/// Builds the simulation and runs at most 50 steps; errors are fine, panics are not.
fn short_run(scene: &Scene) {
    let mut s = scene.clone();
    s.duration_s = 50.0 * s.dt_s;
    if let Ok(mut sim) = Simulation::from_scene(&s) {
        for _ in 0..50 {
            if sim.step().is_err() {
                break;
            }
        }
    }
}

/// A generated scene: modes given by their shapes at the points (one mode
/// per `(f_hz, damping_ratio, shape)`), points 3 cm apart at heights `h_m`,
/// a sine road `(amplitude_m, wavelength_m)`, rigid located contact.
fn sine_scene(
    name: &str,
    modes: &[(f64, f64, Vec<f64>)],
    h_m: &[f64],
    (amplitude_m, wavelength_m): (f64, f64),
    speed_mps: f64,
    ramp_s: f64,
    dt_s: f64,
) -> Scene {
    let p = h_m.len();
    Scene {
        name: name.into(),
        description: String::new(),
        tyre: Tyre::Modal {
            modes: modes
                .iter()
                .map(|(f, xi, shape)| Mode {
                    freq_hz: *f,
                    damping_ratio: *xi,
                    residue: vec![],
                    shape: shape[..p].to_vec(),
                })
                .collect(),
        },
        points: (0..p)
            .map(|i| Point {
                x_m: 0.03 * i as f64,
                y_m: 0.0,
                h_m: h_m[i],
            })
            .collect(),
        road: Road::Sine {
            amplitude_m,
            wavelength_m,
        },
        speed_mps,
        ramp_s,
        dt_s,
        duration_s: 200.0 * dt_s,
        contact_scheme: ContactScheme::Located,
        contact: Contact::Rigid,
        base_dir: None,
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: proptest_cases(400), ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        let text = String::from_utf8_lossy(&bytes);
        match Scene::parse(&text, "fuzz.ron") {
            Ok(scene) => short_run(&scene),
            Err(SceneError::Syntax { line, col, message, .. }) => {
                prop_assert!(line >= 1 && col >= 1 && !message.is_empty());
            }
            Err(_) => {}
        }
    }

    /// Road files: arbitrary bytes, or text made of what CSV numbers are made
    /// of, never panic the reader; what it accepts is strictly increasing
    /// and finite, and a short run over it (looped or not) never panics.
    #[test]
    fn road_files_never_panic(
        bytes in prop_oneof![
            proptest::collection::vec(any::<u8>(), 0..300),
            "[-+0-9.eE,\n #a-zN]{0,200}".prop_map(String::into_bytes),
            proptest::collection::vec((-1e3f64..1e3, prop_oneof![-1e3f64..1e3, Just(1e308), Just(-1e308)]), 0..8)
                // sorted, so that most are accepted and run over
                .prop_map(|mut rows| {
                    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
                    rows.iter().map(|(x, z)| format!("{x},{z}\n")).collect::<String>().into_bytes()
                }),
        ],
        looped in any::<bool>(),
        speed in 0.0f64..100.0,
    ) {
        let tmp = temp_dir();
        let dir = tmp.path();
        let path = dir.join("r.csv");
        std::fs::write(&path, &bytes).unwrap();
        match read_profile_csv(&path) {
            Ok((x, z)) => {
                prop_assert!(x.len() >= 2 && x.len() == z.len());
                prop_assert!(x.windows(2).all(|w| w[0] < w[1]));
                prop_assert!(x.iter().chain(&z).all(|v| v.is_finite()));
                let scene = Scene {
                    name: "road".into(),
                    description: String::new(),
                    tyre: Tyre::Modal { modes: vec![Mode { freq_hz: 100.0, damping_ratio: 0.05, residue: vec![], shape: vec![0.3, 0.2] }] },
                    points: vec![Point { x_m: x[0], y_m: 0.0, h_m: 0.0 }, Point { x_m: x[0] + 0.5 * (x[1] - x[0]), y_m: 0.0, h_m: -0.001 }].into(),
                    road: Road::Measured { file: path.clone(), looped },
                    speed_mps: speed,
                    ramp_s: 0.001,
                    dt_s: 1e-4,
                    duration_s: 5e-3,
                    contact_scheme: ContactScheme::Located,
                    contact: Default::default(),
                    base_dir: None,
                };
                short_run(&scene);
            }
            Err(e) => prop_assert!(!e.message.is_empty() && e.path == path),
        }
    }

    #[test]
    fn mutated_presets_never_panic(which in 0usize..8, pos in 0usize..4000, len in 0usize..20, junk in "[ -~]{0,12}") {
        let all = presets();
        let text = &all[which % all.len()];
        let mut b = text.clone().into_bytes();
        let p = pos % (b.len() + 1);
        let end = (p + len).min(b.len());
        b.splice(p..end, junk.bytes());
        let text = String::from_utf8_lossy(&b);
        match Scene::parse(&text, "m.ron") {
            Ok(scene) => short_run(&scene),
            Err(SceneError::Syntax { line, col, .. }) => prop_assert!(line >= 1 && col >= 1),
            Err(SceneError::Invalid { errors, .. }) => prop_assert!(!errors.is_empty()),
            Err(_) => {}
        }
    }

    #[test]
    fn structured_scenes_run_or_fail_cleanly(
        p in 1usize..5,
        modes in proptest::collection::vec((1.0f64..5000.0, 0.0f64..3.0, proptest::collection::vec(-1.0f64..1.0, 5)), 1..6),
        h in proptest::collection::vec(-0.003f64..0.001, 5),
        amp in 0.0f64..0.004,
        wl in 0.01f64..2.0,
        speed in 0.0f64..60.0,
        ramp in 0.0f64..0.02,
        dt_exp in -6.5f64..-3.0,
        paper in any::<bool>(),
    ) {
        let mut scene = sine_scene("prop", &modes, &h[..p], (amp, wl), speed, ramp, 10f64.powf(dt_exp));
        scene.duration_s = 200.0 * scene.dt_s;
        scene.contact_scheme = if paper { ContactScheme::Paper } else { ContactScheme::Located };
        let f_max = modes.iter().map(|m| m.0).fold(0.0, f64::max);
        let resolved = speed * scene.dt_s * 20.0 <= wl && f_max * scene.dt_s * 20.0 <= 1.0;
        match Simulation::from_scene(&scene) {
            Err(SceneError::Invalid { errors, .. }) => {
                prop_assert!(errors.iter().all(|e| !e.field.is_empty() && !e.expected.is_empty()));
            }
            Err(e) => prop_assert!(false, "unexpected error {e}"),
            Ok(mut sim) => {
                for _ in 0..200 {
                    match sim.step() {
                        Ok(_) => {
                            prop_assert!(sim.displacement_m().iter().all(|u| u.is_finite()));
                            // forces are step means of non-negative impulses (round-off
                            // aside) wherever the steps resolve the road and the fastest
                            // mode (>= 20 steps per period); on coarser steps only
                            // finiteness is promised
                            if resolved {
                                let scale = sim.force_n().iter().fold(1.0f64, |m, q| m.max(q.abs()));
                                prop_assert!(sim.force_n().iter().all(|&q| q >= -1e-6 * scale), "{:?}", sim.force_n());
                            } else {
                                prop_assert!(sim.force_n().iter().all(|q| q.is_finite()));
                            }
                        }
                        // too few modes for the points in contact is a typed error, not a panic
                        Err(_) => break,
                    }
                }
            }
        }
    }
}

/// Cases of [`step_mean_forces_never_pull`]: 64, or `PROPTEST_CASES`.
fn contact_cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(64)
}

/// Runs `scene` to its end: the most negative step-mean force and the
/// largest magnitude of one, of any point in any step (N; NaN for a
/// non-finite force), or the typed error that stopped the run (too few
/// modes for the points on the road, say).
fn force_range(scene: &Scene) -> Result<(f64, f64), String> {
    let mut sim = Simulation::from_scene(scene).map_err(|e| e.to_string())?;
    let (mut lowest, mut largest) = (0.0f64, 0.0f64);
    while !sim.finished() {
        sim.step().map_err(|e| e.to_string())?;
        for &q in sim.force_n() {
            if !q.is_finite() {
                return Ok((f64::NAN, f64::NAN));
            }
            lowest = lowest.min(q);
            largest = largest.max(q.abs());
        }
    }
    Ok((lowest, largest))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: contact_cases(), ..ProptestConfig::default() })]

    /// The road only pushes (method §1, `q_i >= 0`): no step-mean force is
    /// negative beyond round-off (1e-9 of the run's largest force), at any
    /// point of any step, for compliant contact (tread springs: the spring
    /// law holds only over the part of a step in contact, its landing and
    /// release located inside the step) and for rigid contact under both
    /// schemes, on scenes where points land, bounce off and land again.
    #[test]
    fn step_mean_forces_never_pull(
        p in 1usize..=5,
        modes in proptest::collection::vec((20.0f64..1000.0, 0.0f64..0.3, proptest::collection::vec(-1.0f64..1.0, 5)), 1..=6),
        h in proptest::collection::vec(-0.002f64..0.0002, 5),
        stiffness_exp in proptest::collection::vec(5.0f64..9.0, 5),
        amp in 1e-4f64..0.003,
        wl in 0.05f64..1.0,
        speed in 1.0f64..40.0,
        ramp in 0.001f64..0.01,
        dt_exp in -5.5f64..-4.0,
    ) {
        let mut scene = sine_scene("pull", &modes, &h[..p], (amp, wl), speed, ramp, 10f64.powf(dt_exp));
        scene.duration_s = 0.02;
        scene.contact = Contact::Compliant { stiffness_n_m: stiffness_exp[..p].iter().map(|e| 10f64.powf(*e)).collect() };
        let compliant = scene.clone();
        scene.contact = Contact::Rigid;
        let located = scene.clone();
        scene.contact_scheme = ContactScheme::Paper;
        for (what, s) in [("compliant", &compliant), ("rigid, located", &located), ("rigid, paper", &scene)] {
            // a typed error (too few modes to hold the points on the road
            // rigidly) ends a rigid run; the springs' compliance leaves none
            let range = force_range(s);
            prop_assert!(range.is_ok() || what != "compliant", "{what}: {range:?}");
            if let Ok((lowest, largest)) = range {
                prop_assert!(lowest.is_finite(), "{what}: non-finite force");
                prop_assert!(
                    lowest >= -1e-9 * largest,
                    "{what}: step-mean force {lowest:.6e} N, largest {largest:.6e} N"
                );
            }
        }
    }
}
