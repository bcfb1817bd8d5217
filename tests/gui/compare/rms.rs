//! The RMS of the force difference in the A/B compare view: without
//! impacts it is that of the difference of the forces plotted (so never
//! more than their largest magnitudes summed); with impacts, where the
//! runs' impulse / dt spikes fall at different steps and set it, the line
//! also gives the RMS without impacts and says why the two differ.

use crate::harness::{advance, harness, settle, texts};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::analysis::compare::PinnedRun;
use tirecontact::gui::research::compare::recording_without_impacts;
use tirecontact::gui::views::compare_view::IMPACT_RMS_NOTE;
use tirecontact::gui::{App, Command, ResearchCommand, View};
use tirecontact::output::record::Recording;
use tirecontact::scene::Tyre;

/// The force RMS of each point in the compare view's RMS line (N), and the
/// line.
fn rms_line(h: &Harness<'_, App>, points: usize) -> (String, Vec<f64>) {
    let text = texts(h)
        .into_iter()
        .map(|(t, _)| t)
        .find(|t| t.contains("RMS of current − reference"))
        .expect("an RMS line");
    let values = (0..points)
        .map(|i| {
            text.split(&format!("p{i}: "))
                .nth(1)
                .and_then(|rest| rest.split(" N").next())
                .and_then(|v| v.parse::<f64>().ok())
                .unwrap_or_else(|| panic!("no force RMS of p{i} in {text}"))
        })
        .collect();
    (text, values)
}

fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

#[test]
fn the_force_difference_rms_is_that_of_the_forces_plotted() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let p = scene.num_points();
    let mut h = harness(App::new(scene, None).unwrap());
    settle(&mut h);
    advance(&mut h, 20_000);
    h.state_mut().apply(Command::ShowView(View::Compare));
    h.run_steps(2);
    h.state_mut()
        .apply(Command::Research(ResearchCommand::PinReference));
    h.run_steps(2);
    let pinned = recording_without_impacts(h.state().history());
    // one mode's damping tripled
    let mut modes = h.state().modes().to_vec();
    modes[2].damping_ratio *= 3.0;
    let mut edited = h.state().scene().clone();
    edited.tyre = Tyre::Modal { modes };
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    h.run_steps(1);
    advance(&mut h, 20_000);
    h.run_steps(4);
    let current = recording_without_impacts(h.state().history());

    let (text, smooth) = rms_line(&h, p);
    assert!(text.contains("force without impacts"), "{text}");
    for (i, rms) in smooth.iter().enumerate() {
        let bound = max_abs(&pinned.q_n[i]) + max_abs(&current.q_n[i]);
        assert!(
            *rms > 0.0 && *rms <= bound,
            "p{i}: RMS {rms} N of the difference of forces within {bound} N: {text}"
        );
    }
    assert!(h.query_by_label(IMPACT_RMS_NOTE).is_none());

    // with impacts: the spikes set the RMS, far above the forces plotted
    // without them, and the line gives the RMS without impacts beside it
    h.get_by_label("clip impact spikes").click();
    h.run_steps(4);
    let (text, raw) = rms_line(&h, p);
    assert!(text.contains("force with impacts"), "{text}");
    for i in 0..p {
        let bound = max_abs(&pinned.q_n[i]) + max_abs(&current.q_n[i]);
        eprintln!(
            "p{i}: {} N with impacts, {} N without (forces within {bound} N)",
            raw[i], smooth[i]
        );
        let without = text
            .split(&format!("p{i}: "))
            .nth(1)
            .and_then(|rest| rest.split(" N without impacts").next())
            .and_then(|rest| rest.rsplit('(').next())
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or_else(|| panic!("no RMS without impacts of p{i} in {text}"));
        assert_eq!(without, smooth[i], "{text}");
    }
    assert!(
        (0..p).any(|i| raw[i] > max_abs(&current.q_n[i])),
        "the impacts make the RMS larger than the forces without them: {text}"
    );
    assert!(h.query_by_label(IMPACT_RMS_NOTE).is_some());
}

/// Two runs of constant forces differ by their difference: its RMS is it.
#[test]
fn constant_forces_differ_by_their_difference_rms() {
    let scene = Scene::load(Path::new("presets/single_mode.ron")).unwrap();
    let run = |q: f64| {
        let t: Vec<f64> = (0..50).map(|k| k as f64 * 1e-3).collect();
        let n = t.len();
        Recording::from_samples(
            1,
            t,
            vec![vec![0.0; n]],
            vec![vec![q; n]],
            vec![vec![0.0; n]],
            vec![vec![0.0; n]],
            vec![vec![true; n]],
        )
    };
    let pin = PinnedRun::new("A", &scene, 1, &run(312.5));
    let d = pin.difference(&scene.points[..1], &run(200.0));
    assert_eq!(d.t_s.len(), 50);
    assert_eq!(d.rms_dq_n, vec![112.5]);
    let d = pin.difference(&scene.points[..1], &run(400.0));
    assert_eq!(d.rms_dq_n, vec![87.5]);
}
