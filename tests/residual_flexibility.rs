//! Residual flexibility (`SolverOptions::residual_above_hz`): modes above
//! `f_c` replaced by their static compliance `Σ A_k / ω_k²`.

use tirecontact::{Scene, Simulation, SolverOptions};

use tirecontact::bench::scenes::preloaded_three_points as scene;

fn options(fc: Option<f64>) -> SolverOptions {
    SolverOptions {
        residual_above_hz: fc,
        ..SolverOptions::default()
    }
}

fn settled_forces(s: &Scene, fc: Option<f64>) -> Vec<f64> {
    let mut sim = Simulation::with_options(s, options(fc)).unwrap();
    while !sim.finished() {
        sim.step().unwrap();
    }
    sim.force_n().to_vec()
}

#[test]
fn residual_flexibility_reproduces_the_static_preload_exactly() {
    // flat road, strong damping: the run settles to the static preload
    let (force_n, fc) = (100.0, 150.0);
    let s = scene(0.3, force_n, 0.0, 20.0, 0.02, 1e-4, 0.6);
    let p = s.num_points();
    // closed form: the points were preloaded by C (force_n, ...) with the
    // full static compliance C, so the settled force is force_n everywhere
    let exact = nalgebra::DVector::from_element(p, force_n);
    let rel = |q: &[f64], r: &nalgebra::DVector<f64>| {
        (0..p)
            .map(|i| ((q[i] - r[i]) / r[i]).abs())
            .fold(0.0, f64::max)
    };
    let full = settled_forces(&s, None);
    let residual = settled_forces(&s, Some(fc));
    let truncated = {
        // plain truncation: the dropped modes deleted from the scene
        let mut t = s.clone();
        if let tirecontact::scene::Tyre::Modal { modes } = &mut t.tyre {
            modes.retain(|m| m.freq_hz <= fc);
        }
        settled_forces(&t, None)
    };
    assert!(rel(&full, &exact) < 1e-9, "full model: {full:?} vs {exact}");
    assert!(
        rel(&residual, &exact) < 1e-9,
        "residual flexibility: {residual:?} vs {exact}"
    );
    // plain truncation is stiffer: it settles to another static force
    assert!(
        rel(&truncated, &exact) > 1e-2,
        "truncation should miss the dropped modes' compliance: {truncated:?} vs {exact}"
    );
}

#[test]
fn residual_flexibility_beats_plain_truncation_on_a_smooth_scene() {
    // 25 Hz excitation (5 m/s over 0.2 m), below every mode; a 400 N
    // preload against a 0.1 mm road: always in contact after the landing.
    // The ramp is slow: its acceleration jumps at its ends (6 / T² times
    // the preload), and a massless residual spring between the road and
    // the kept modes' mass rings after each jump (the caveat of residual
    // flexibility with rigid contact: the impact mass is that of the kept
    // modes only).
    let fc = 150.0;
    let (ramp_s, from_s) = (0.1, 0.12);
    let s = scene(0.05, 400.0, 0.1e-3, 5.0, ramp_s, 1e-5, 0.2);
    let run = |s: &Scene, fc: Option<f64>| {
        let mut sim = Simulation::with_options(s, options(fc)).unwrap();
        let mut q = Vec::new();
        let mut events_at_start = 0;
        while !sim.finished() {
            sim.step().unwrap();
            if sim.time_s() <= from_s {
                events_at_start = sim.stats().events;
            } else {
                q.extend_from_slice(sim.force_n());
            }
        }
        assert_eq!(
            sim.stats().events,
            events_at_start,
            "no impact or release ({fc:?}, {} points)",
            s.num_points()
        );
        assert!(sim.in_contact().iter().all(|&c| c));
        q
    };
    let mut t = s.clone();
    if let tirecontact::scene::Tyre::Modal { modes } = &mut t.tyre {
        modes.retain(|m| m.freq_hz <= fc);
    }
    let truncated = run(&t, None);
    let full = run(&s, None);
    let residual = run(&s, Some(fc));
    let err = |q: &[f64]| {
        let num: f64 = q.iter().zip(&full).map(|(a, b)| (a - b).powi(2)).sum();
        let den: f64 = full.iter().map(|b| b * b).sum();
        (num / den).sqrt()
    };
    let (e_res, e_trunc) = (err(&residual), err(&truncated));
    println!(
        "RMS relative force error against the full model: residual {e_res:.3e}, truncated {e_trunc:.3e}"
    );
    assert!(
        e_res < 0.5 * e_trunc,
        "RMS relative force error: residual {e_res:.3e}, truncated {e_trunc:.3e}"
    );
}

#[test]
fn bad_cutoff_names_the_option_value_and_expectation() {
    let s = scene(0.05, 100.0, 0.0, 20.0, 0.02, 1e-4, 0.01);
    for (fc, want) in [
        (f64::NAN, "finite"),
        (-5.0, "> 0"),
        (1.0, "at least one mode"),
    ] {
        let msg = match Simulation::with_options(&s, options(Some(fc))) {
            Ok(_) => panic!("{fc} accepted"),
            Err(e) => e.to_string(),
        };
        assert!(
            msg.contains("residual_above_hz") && msg.contains(want),
            "{fc}: {msg}"
        );
    }
}
