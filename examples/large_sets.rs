//! A scene of the scaling study run with the direct contact solves and
//! with the methods of large active sets, one after the other in one
//! process (with rigid contact, also with impacts one point at a time,
//! `SolverOptions::joint_impacts` off): wall time and events per step over
//! windows of steps, and the counts of events, factorisations, updates and
//! GMRES products (docs/performance.md, "Large active sets" and "Rigid
//! contact at 400 points").
//!
//! ```sh
//! cargo run --release --example large_sets -- patch 1000 400 0.014 200
//! ```
//!
//! Arguments: the setting (`rigid`, `tread` or `patch`), points, modes,
//! duration (s) and the window (steps).

use std::time::Instant;
use tirecontact::analysis::bench::scaling::{Regime, scaling_scene};
use tirecontact::{PreparedModel, SolverOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: large_sets SETTING POINTS MODES DURATION_S WINDOW_STEPS (SETTING: rigid, tread or patch)";
    let [setting, p, k, d, w] = &args[..] else {
        return Err(usage.into());
    };
    let regime = Regime::from_key(setting).ok_or(usage)?;
    let (p, k, w): (usize, usize, u64) = (p.parse()?, k.parse()?, w.parse()?);
    let mut scene = scaling_scene(p, k, regime);
    scene.duration_s = d.parse()?;
    let model = PreparedModel::of(&scene)?;
    let mut runs = vec![
        ("direct solves", usize::MAX, true),
        ("large-set methods", 24, true),
    ];
    if regime == Regime::Rigid {
        // (the impacts of method §4.4 before "Several events at one instant")
        runs.push(("large-set methods, impacts one point at a time", 24, false));
    }
    for (name, from, joint_impacts) in runs {
        let options = SolverOptions {
            large_set_from: from,
            compliant_large_set_from: from,
            iterative_sub_from: from,
            joint_impacts,
            ..SolverOptions::default()
        };
        let mut sim = model.simulation(options)?;
        println!("{} — {name}", scene.name);
        let (start, mut window) = (Instant::now(), Instant::now());
        let mut events_before = 0;
        while !sim.finished() {
            sim.step()?;
            if sim.steps() % w == 0 {
                let on = sim.force_n().iter().filter(|f| **f > 0.0).count();
                let events = sim.stats().events;
                println!(
                    "  steps {:>6} to {:>6}: {:8.1} µs per step, {:7.2} events per step, {on} points on the road",
                    sim.steps() - w + 1,
                    sim.steps(),
                    window.elapsed().as_secs_f64() / w as f64 * 1e6,
                    (events - events_before) as f64 / w as f64
                );
                events_before = events;
                window = Instant::now();
            }
        }
        let st = sim.stats();
        println!(
            "  whole run: {:.1} µs per step; {} events, {} factorisations, {} updates ({} refused), {} GMRES products ({} fallbacks)",
            start.elapsed().as_secs_f64() / st.steps.max(1) as f64 * 1e6,
            st.events,
            st.factorisations,
            st.contact_updates,
            st.update_refusals,
            st.krylov_applications,
            st.krylov_fallbacks
        );
    }
    Ok(())
}
