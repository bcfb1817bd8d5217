//! The steady path (`SolverOptions::steady_path`): steps that keep the same
//! contact set and locate no event skip the event loop (rigid contact under
//! the `Located` scheme, and compliant contact). It must change no
//! result: every output of every step is compared bit for bit with the
//! event loop alone (the control), on scenes that land, release, ramp,
//! change speed and road live, and reset.

use crate::support::temp_dir;
use tirecontact::SceneSimulation;
use tirecontact::analysis::bench::scenes::many_points;
use tirecontact::model::road::Road;
use tirecontact::scene::ContactScheme;
use tirecontact::{Scene, Simulation, SolverOptions};

/// What a live session may do between steps.
#[derive(Clone, Copy)]
enum Live {
    Nothing,
    /// `set_speed` at a step, m/s.
    Speed(u64, f64),
    /// `set_road` to a sine of this wavelength (m) at a step.
    Road(u64, f64),
    /// `reset` at a step.
    Reset(u64),
}

fn preset(name: &str, duration_s: f64) -> Scene {
    let mut s = Scene::load(std::path::Path::new(&format!("presets/{name}.ron"))).unwrap();
    s.duration_s = duration_s;
    s
}

/// A preset on tread springs of `k_n_m` (N/m).
fn compliant(name: &str, duration_s: f64, k_n_m: f64) -> Scene {
    let mut s = preset(name, duration_s);
    s.contact = tirecontact::scene::Contact::Compliant {
        stiffness_n_m: vec![k_n_m],
    };
    s
}

/// Runs `scene` with and without the steady path, comparing displacement,
/// velocity, force, impulses and contact after every step; returns the
/// steady run's statistics.
fn compare(scene: &Scene, live: Live) -> tirecontact::solver::simulation::RunStats {
    // (the merged event step of tread springs starts from the steady
    // path's trial: without it, events take the sub-steps)
    let on = SolverOptions {
        merged_events: false,
        ..SolverOptions::default()
    };
    let off = SolverOptions {
        steady_path: false,
        ..on
    };
    let mut a = Simulation::from_scene_with(scene, on).unwrap();
    let mut b = Simulation::from_scene_with(scene, off).unwrap();
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    for step in 0..scene.num_steps() {
        match live {
            Live::Speed(at, v) if at == step => {
                a.set_speed(v);
                b.set_speed(v);
            }
            Live::Road(at, wavelength_m) if at == step => {
                let road = Road::Sine {
                    amplitude_m: 0.002,
                    wavelength_m,
                };
                let profile = tirecontact::scene::load_road(&road, None).unwrap();
                a.set_road(profile.clone());
                b.set_road(profile);
            }
            Live::Reset(at) if at == step => {
                a.reset();
                b.reset();
            }
            _ => {}
        }
        let (ra, rb) = (a.step().unwrap(), b.step().unwrap());
        assert_eq!(ra, rb, "{}: step report at step {step}", scene.name);
        for (what, x, y) in [
            ("displacement", a.displacement_m(), b.displacement_m()),
            ("velocity", a.velocity_mps(), b.velocity_mps()),
            ("force", a.force_n(), b.force_n()),
            (
                "impact impulse",
                a.impact_impulse_ns(),
                b.impact_impulse_ns(),
            ),
        ] {
            assert_eq!(bits(x), bits(y), "{}: {what} at step {step}", scene.name);
        }
        assert_eq!(a.in_contact(), b.in_contact(), "{}: contact", scene.name);
    }
    let (sa, sb) = (a.stats().clone(), b.stats().clone());
    assert_eq!(
        sb.steady_steps, 0,
        "the control never takes the steady path"
    );
    assert_eq!(
        RunStatsWithoutSteady::from(&sa),
        RunStatsWithoutSteady::from(&sb),
        "{}: statistics",
        scene.name
    );
    sa
}

/// [`tirecontact::solver::simulation::RunStats`] without the steady-step count.
#[derive(Debug, PartialEq)]
struct RunStatsWithoutSteady(Vec<u64>, Vec<u64>, u64);

impl From<&tirecontact::solver::simulation::RunStats> for RunStatsWithoutSteady {
    fn from(s: &tirecontact::solver::simulation::RunStats) -> Self {
        RunStatsWithoutSteady(
            vec![s.steps, s.events, s.solves, s.factorisations],
            s.max_force_n
                .iter()
                .chain([&s.worst_penetration_m])
                .map(|x| x.to_bits())
                .collect(),
            s.contact_steps.iter().sum(),
        )
    }
}

#[test]
fn rolling_presets_are_bit_identical_and_mostly_steady() {
    // ramp, landings and releases on every road period
    for (scene, live) in [
        (preset("paper", 0.08), Live::Nothing),
        (preset("three_points", 0.1), Live::Nothing),
        (preset("single_mode", 0.1), Live::Nothing),
        (many_points(5, 20), Live::Nothing),
        // tread springs: their own steady step, landings and releases
        // located by the event loop
        (compliant("three_points", 0.1, 5e7), Live::Nothing),
        (compliant("single_mode", 0.1, 5e7), Live::Nothing),
    ] {
        let mut scene = scene;
        scene.duration_s = scene.duration_s.min(0.1);
        let st = compare(&scene, live);
        let fraction = st.steady_steps as f64 / st.steps as f64;
        eprintln!(
            "{}: {} of {} steps steady ({:.1} %), {} events",
            scene.name,
            st.steady_steps,
            st.steps,
            100.0 * fraction,
            st.events
        );
        assert!(st.events > 0, "{}: the scene must have events", scene.name);
        // most steps hold their contact set: the path is taken
        assert!(fraction > 0.8, "{}: {fraction}", scene.name);
    }
}

#[test]
fn live_changes_and_reset_are_bit_identical() {
    for base in [
        preset("three_points", 0.06),
        compliant("three_points", 0.06, 2e5),
    ] {
        for live in [
            Live::Speed(2500, 25.0),
            Live::Speed(2500, 0.0),
            // a rougher road under the points at once: points end below it
            Live::Road(3000, 0.02),
            Live::Reset(2000),
        ] {
            let st = compare(&base, live);
            assert!(st.steady_steps > 0);
        }
    }
}

#[test]
fn other_schemes_and_measured_roads_never_take_it_wrongly() {
    // the paper's scheme has its own step
    let mut paper = preset("three_points", 0.05);
    paper.contact_scheme = ContactScheme::Paper;
    assert_eq!(compare(&paper, Live::Nothing).steady_steps, 0);
    // a measured road: breakpoints under points in contact end sub-steps
    let tmp = temp_dir();
    let dir = tmp.path();
    let rows: String = (0..=400)
        .map(|k| {
            let x = -1.0 + 0.01 * k as f64;
            format!("{x},{}\n", 0.001 * (7.0 * x).sin() * (k % 3) as f64 / 2.0)
        })
        .collect();
    std::fs::write(dir.join("bumps.csv"), format!("x_m,z_m\n{rows}")).unwrap();
    let mut measured = preset("three_points", 0.05);
    measured.road = Road::Measured {
        file: "bumps.csv".into(),
        looped: false,
    };
    measured.base_dir = Some(dir.to_path_buf());
    let st = compare(&measured, Live::Nothing);
    eprintln!("measured: {} of {} steps steady", st.steady_steps, st.steps);
    // (tread springs do not split their steps at the breakpoints)
    measured.contact = tirecontact::scene::Contact::Compliant {
        stiffness_n_m: vec![5e7],
    };
    let st = compare(&measured, Live::Nothing);
    eprintln!(
        "measured, compliant: {} of {} steps steady, {} events",
        st.steady_steps, st.steps, st.events
    );
}
