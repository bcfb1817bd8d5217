//! Residual flexibility (`SolverOptions::residual_above_hz`): modes above
//! `f_c` replaced by their static compliance `Σ A_k / ω_k²`.

use tirecontact::{Scene, Simulation, SolverOptions};

use tirecontact::SceneSimulation;
use tirecontact::analysis::bench::scenes::preloaded_three_points as scene;

fn options(fc: Option<f64>) -> SolverOptions {
    SolverOptions {
        residual_above_hz: fc,
        ..SolverOptions::default()
    }
}

fn settled_forces(s: &Scene, fc: Option<f64>) -> Vec<f64> {
    let mut sim = Simulation::from_scene_with(s, options(fc)).unwrap();
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
    let exact = vec![force_n; p];
    let rel = |q: &[f64], r: &[f64]| {
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
    assert!(
        rel(&full, &exact) < 1e-9,
        "full model: {full:?} vs {exact:?}"
    );
    assert!(
        rel(&residual, &exact) < 1e-9,
        "residual flexibility: {residual:?} vs {exact:?}"
    );
    // plain truncation is stiffer: it settles to another static force
    assert!(
        rel(&truncated, &exact) > 1e-2,
        "truncation should miss the dropped modes' compliance: {truncated:?} vs {exact:?}"
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
        let mut sim = Simulation::from_scene_with(s, options(fc)).unwrap();
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
        let msg = match Simulation::from_scene_with(&s, options(Some(fc))) {
            Ok(_) => panic!("{fc} accepted"),
            Err(e) => e.to_string(),
        };
        assert!(
            msg.contains("residual_above_hz") && msg.contains(want),
            "{fc}: {msg}"
        );
    }
}

/// Window means (N) of each point's step-mean force over `window` steps,
/// the located events and the contact changes (a point's flag flipping
/// from one step to the next) of a run of `s` with cut-off `fc`; `None`
/// once the run passes `max_events` located events.
fn window_forces(
    s: &Scene,
    fc: Option<f64>,
    window: usize,
    max_events: u64,
) -> Option<(Vec<f64>, u64, u64)> {
    let mut sim = Simulation::from_scene_with(s, options(fc)).unwrap();
    let p = s.num_points();
    let (mut means, mut acc, mut n) = (Vec::new(), vec![0.0; p], 0);
    let mut flags = sim.in_contact().to_vec();
    let mut changes = 0;
    while !sim.finished() {
        sim.step().unwrap();
        if sim.stats().events > max_events {
            return None;
        }
        for (a, q) in acc.iter_mut().zip(sim.force_n()) {
            *a += q;
        }
        n += 1;
        if n == window {
            means.extend(acc.iter().map(|a| a / window as f64));
            acc.fill(0.0);
            n = 0;
        }
        for (f, &c) in flags.iter_mut().zip(sim.in_contact()) {
            changes += (*f != c) as u64;
            *f = c;
        }
    }
    Some((means, sim.stats().events, changes))
}

#[test]
fn located_landings_with_residual_flexibility_do_not_cascade() {
    // The smooth scene at f_c = 231 Hz (5 of 12 modes kept). In the first
    // step of the ramp the linear force that meets the road's t² rise in
    // position and velocity through the static term starts at about minus
    // its end value, and the middle point's step mean comes out negative
    // (-2.6e-6 N against ±5.8e-3 N): it is released at the step start and
    // lands at the next step's start. A kept-mode impulse there threw the
    // neighbours off, their static deflection C q vanished at once and
    // they landed again, every step at the event limit 4P + 16 (558 817
    // events in 20 000 steps). Landings take no impulse through the static
    // compliance: the model's own lift-offs (it is softer than the full
    // model early in the ramp) are all the events left, and the located
    // rule agrees with the paper's step-end rule on the same model.
    let s = scene(0.05, 400.0, 0.1e-3, 5.0, 0.1, 1e-5, 0.2);
    let fc = Some(231.0);
    let window = 100; // 1 ms
    let (full, full_events, _) = window_forces(&s, None, window, 1000).unwrap();
    let mut paper_scene = s.clone();
    paper_scene.contact_scheme = tirecontact::scene::ContactScheme::Paper;
    let (paper, _, paper_changes) = window_forces(&paper_scene, fc, window, 1000).unwrap();
    let located = window_forces(&s, fc, window, 10_000);
    let Some((located, events, _)) = located else {
        panic!("more than 10 000 located events in 20 000 steps: a cascade");
    };
    let err = |q: &[f64]| {
        let num: f64 = q.iter().zip(&full).map(|(a, b)| (a - b).powi(2)).sum();
        let den: f64 = full.iter().map(|b| b * b).sum();
        (num / den).sqrt()
    };
    let (e_loc, e_paper) = (err(&located), err(&paper));
    println!(
        "events: full {full_events}, located + residual {events}; paper rule contact changes \
         {paper_changes}; force error (1 ms means) located {e_loc:.3e}, paper rule {e_paper:.3e}"
    );
    // every located event is a landing or a release of the model's own
    // contact changes (3 landings at the start, then the paper rule's)
    assert!(
        events <= 3 + 2 * paper_changes,
        "{events} located events for {paper_changes} contact changes of the paper rule"
    );
    assert!(
        e_loc <= 1.5 * e_paper && e_loc < 5e-3,
        "force error located {e_loc:.3e}, paper rule {e_paper:.3e}"
    );
}
