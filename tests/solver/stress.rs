//! Stress tests of numerical stability: extreme damping ratios,
//! time steps from 1e-7 s to 1e-2 s (ω·dt up to 250), grazing contact, roads
//! shorter than the point spacing, a road that drops away faster than the
//! tyre can follow. No NaN, no overflow, bounded energy, complementarity held:
//! every case prints its worst violation.

use crate::support::temp_dir;
use std::f64::consts::TAU;
use tirecontact::SceneSimulation;
use tirecontact::model::convolution::{ModalBasis, ModalState, StepTable};
use tirecontact::model::road::Road;
use tirecontact::scene::{ContactScheme, Mode, Point, Scene, Tyre};
use tirecontact::{Simulation, SolverError};

fn one_point(freq_hz: f64, xi: f64, dt_s: f64, steps: usize) -> Scene {
    Scene {
        name: format!("f={freq_hz} xi={xi} dt={dt_s}"),
        description: String::new(),
        tyre: Tyre::Modal {
            modes: vec![Mode {
                freq_hz,
                damping_ratio: xi,
                residue: vec![vec![0.1]],
                shape: vec![],
            }],
        },
        points: vec![Point {
            x_m: 0.0,
            y_m: 0.0,
            h_m: -0.001,
        }]
        .into(),
        road: Road::Sine {
            amplitude_m: 0.002,
            wavelength_m: 0.5,
        },
        speed_mps: 20.0,
        ramp_s: 20.0 * dt_s,
        dt_s,
        duration_s: steps as f64 * dt_s,
        contact_scheme: ContactScheme::Located,
        contact: Default::default(),
        base_dir: None,
    }
}

/// Runs to the end; returns (worst pulling force relative to the largest, worst penetration m, max |u| m).
fn stress(scene: &Scene) -> Result<(f64, f64, f64), SolverError> {
    let mut sim = Simulation::from_scene(scene).unwrap();
    let (mut min_q, mut max_q, mut max_u) = (0.0f64, 0.0f64, 0.0f64);
    while !sim.finished() {
        sim.step()?;
        for (&q, &u) in sim.force_n().iter().zip(sim.displacement_m()) {
            assert!(
                q.is_finite() && u.is_finite(),
                "{}: non-finite at t = {}",
                scene.name,
                sim.time_s()
            );
            min_q = min_q.min(q);
            max_q = max_q.max(q);
            max_u = max_u.max(u.abs());
        }
    }
    Ok((
        -min_q / max_q.max(1e-300),
        sim.stats().worst_penetration_m,
        max_u,
    ))
}

#[test]
fn every_damping_ratio_and_time_step() {
    let mut worst = (0.0f64, 0.0f64);
    for &xi in &[0.0, 1.0 - 1e-12, 1.0, 1.0 + 1e-12, 50.0] {
        for &(dt, f) in &[(1e-7, 100.0), (1e-5, 100.0), (1e-3, 400.0), (1e-2, 4000.0)] {
            let scene = one_point(f, xi, dt, 3000);
            let (pull, pen, max_u) = stress(&scene).unwrap();
            // the road moves 2 mm about a 1 mm preload: anything beyond 1 m is a blow-up
            assert!(max_u < 1.0, "{}: |u| = {max_u}", scene.name);
            assert!(
                pull < 1e-9,
                "{}: pulling force {pull:e} of the largest",
                scene.name
            );
            worst = (worst.0.max(pull), worst.1.max(pen));
            eprintln!(
                "{:40} ω·dt = {:8.2e}  worst pull {pull:.1e}  penetration {pen:.1e} m",
                scene.name,
                TAU * f * dt
            );
        }
    }
    eprintln!(
        "worst over all: pulling force {:.1e} of the largest, penetration {:.1e} m",
        worst.0, worst.1
    );
}

#[test]
fn undamped_free_vibration_keeps_its_energy() {
    // ξ = 0: the exact propagator is a rotation; energy drifts only by round-off
    let mode = Mode {
        freq_hz: 500.0,
        damping_ratio: 0.0,
        residue: vec![vec![1.0]],
        shape: vec![],
    };
    let omega = TAU * 500.0;
    let basis = ModalBasis::new(&[mode], 1).unwrap();
    let table = StepTable::new(&basis, 8e-5); // ω·dt = 0.25
    let (mut s, mut tmp) = (ModalState::zeros(&basis), ModalState::zeros(&basis));
    s.add_impulses(&basis, &[0], &[1.0]);
    let energy = |s: &ModalState| 0.5 * (s.v[0] * s.v[0] + omega * omega * s.x[0] * s.x[0]);
    let e0 = energy(&s);
    for _ in 0..1_000_000 {
        s.predict_into(&table, &mut tmp);
        std::mem::swap(&mut s, &mut tmp);
    }
    let drift = (energy(&s) / e0 - 1.0).abs();
    eprintln!("energy drift after 1e6 undamped steps: {drift:.2e}");
    assert!(drift < 1e-9, "{drift}");
}

fn three(road: Road, h: f64, speed: f64) -> Scene {
    let text = std::fs::read_to_string("presets/three_points.ron").unwrap();
    let mut s = Scene::parse(&text, "three").unwrap();
    s.road = road;
    for p in &mut s.points {
        p.h_m = h;
    }
    s.speed_mps = speed;
    s.duration_s = 0.2;
    s
}

#[test]
fn grazing_short_and_falling_roads() {
    let tmp = temp_dir();
    let cases = [
        // crests just touch the undeformed tyre: grazing contact
        (
            "grazing",
            three(
                Road::Sine {
                    amplitude_m: 0.001,
                    wavelength_m: 0.12,
                },
                0.001,
                12.0,
            ),
        ),
        // wavelength shorter than the 5 cm point spacing
        (
            "wavelength < spacing",
            three(
                Road::Sine {
                    amplitude_m: 0.0005,
                    wavelength_m: 0.013,
                },
                -0.0015,
                12.0,
            ),
        ),
        // a road dropping away faster than the tyre can follow: a 5 mm step
        // down over 1 mm, met at 20 m/s (the road falls at 100 m/s)
        ("falling road", {
            let dir = tmp.path();
            std::fs::write(
                dir.join("cliff.csv"),
                "x_m,z_m\n-1,0\n0.2,0\n0.201,-0.005\n10,-0.005\n",
            )
            .unwrap();
            let mut s = three(
                Road::Measured {
                    file: "cliff.csv".into(),
                    looped: false,
                },
                -0.0015,
                20.0,
            );
            s.base_dir = Some(dir.to_path_buf());
            s
        }),
    ];
    for (name, scene) in cases {
        for scheme in [ContactScheme::Located, ContactScheme::Paper] {
            let mut s = scene.clone();
            s.contact_scheme = scheme;
            let (pull, pen, max_u) = stress(&s).unwrap();
            eprintln!(
                "{name:22} {scheme:?}: worst pull {pull:.1e}, penetration {pen:.1e} m, max |u| {max_u:.2e} m"
            );
            assert!(max_u < 0.05, "{name}: {max_u}");
            assert!(pull < 1e-9, "{name}: {pull}");
            if scheme == ContactScheme::Located {
                assert!(pen < 1e-9, "{name}: penetration {pen}");
            }
        }
    }
}

#[test]
fn measured_road_kinks_converge() {
    // a 5 mm step down over 1 mm: the road velocity jumps at two breakpoints;
    // located sub-steps end at breakpoints, so the error keeps second order
    let tmp = temp_dir();
    let dir = tmp.path();
    std::fs::write(
        dir.join("cliff.csv"),
        "x_m,z_m\n-1,0\n0.2,0\n0.201,-0.005\n10,-0.005\n",
    )
    .unwrap();
    let mut base = three(
        Road::Measured {
            file: "cliff.csv".into(),
            looped: false,
        },
        -0.0015,
        20.0,
    );
    base.base_dir = Some(dir.to_path_buf());
    base.duration_s = 0.03;
    let run = |dt: f64, scheme: ContactScheme| {
        let mut s = base.clone();
        s.dt_s = dt;
        s.contact_scheme = scheme;
        let mut sim = Simulation::from_scene(&s).unwrap();
        let every = (4e-5 / dt).round() as u64;
        let mut out = Vec::new();
        while !sim.finished() {
            sim.step().unwrap();
            if sim.steps().is_multiple_of(every) {
                out.extend_from_slice(sim.displacement_m());
            }
        }
        out
    };
    let reference = run(1.25e-6, ContactScheme::Located);
    let err = |u: &[f64]| {
        let num: f64 = u.iter().zip(&reference).map(|(a, b)| (a - b).powi(2)).sum();
        let den: f64 = reference.iter().map(|b| b * b).sum();
        (num / den).sqrt()
    };
    let (l4, l2, p2) = (
        err(&run(4e-5, ContactScheme::Located)),
        err(&run(2e-5, ContactScheme::Located)),
        err(&run(2e-5, ContactScheme::Paper)),
    );
    eprintln!("cliff road: located {l4:.2e} (4e-5 s), {l2:.2e} (2e-5 s); paper {p2:.2e} (2e-5 s)");
    assert!(l2 < 1e-8, "{l2}");
    assert!(l2 * 100.0 < p2, "{l2} vs {p2}");
}
