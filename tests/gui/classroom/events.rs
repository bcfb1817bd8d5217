//! In classroom mode every impact and release the phase strip lists is also
//! written at its point in the scene view, at the run's most crowded moment
//! too (the plot once had room for one lane of labels below the points, and
//! the other events were left to the strip). Read from the painted text
//! shapes.

use crate::harness::{advance, shapes, texts};
use std::path::Path;
use tirecontact::SceneSimulation;
use tirecontact::gui::View;
use tirecontact::gui::classroom::{
    EVENT_COLOR, EVENT_HOLD_WALL_S, EVENT_RING_PX, SLOW_MOTION, phase_text,
};
use tirecontact::gui::{App, Command};
use tirecontact::solver::phase::PhaseTracker;
use tirecontact::{Scene, Simulation};

fn check(size: [f32; 2], steps: u64) -> usize {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), size);
    h.run();
    h.state_mut().apply(Command::ShowView(View::Scene));
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(2);
    advance(&mut h, steps);
    h.run_steps(2);
    let t = h.state().simulation().time_s();
    let events: Vec<String> = (0..h.state().simulation().num_points())
        .map(|i| (i, h.state().phases().phase(i, t)))
        .filter(|(_, p)| p.is_event())
        .map(|(i, p)| phase_text(i, p))
        .collect();
    let all = texts(&h);
    // the scene's plot: between its legend row and its x axis label
    let axis = all
        .iter()
        .find(|(t, _)| t == "position along the contact line x (m)")
        .expect("x axis label")
        .1;
    let strip_bottom = all
        .iter()
        .find(|(t, _)| t == "contact phase:")
        .expect("phase strip")
        .1
        .bottom();
    let panel_left = all
        .iter()
        .find(|(t, _)| t == "Mode contributions")
        .expect("mode bars")
        .1
        .left();
    let in_plot: Vec<&(String, egui::Rect)> = all
        .iter()
        .filter(|(_, r)| {
            r.top() > strip_bottom + 30.0 && r.bottom() < axis.top() && r.left() < panel_left
        })
        .collect();
    // a ring round every point at an event
    let rings: Vec<egui::Pos2> = shapes(&h)
        .into_iter()
        .filter_map(|s| match s {
            egui::Shape::Circle(c)
                if c.stroke.color == EVENT_COLOR && (c.radius - EVENT_RING_PX).abs() < 0.5 =>
            {
                Some(c.center)
            }
            _ => None,
        })
        .collect();
    assert_eq!(
        rings.len(),
        events.len(),
        "{size:?} t = {t} s: rings at {rings:?} for the events {events:?}"
    );
    // and its label, whole, above or below it, where the lanes have room
    let mut labelled = 0;
    for e in &events {
        let shown: Vec<_> = in_plot.iter().filter(|(t, _)| t == e).collect();
        assert!(
            shown.len() <= 1,
            "{size:?} t = {t} s: {e:?} drawn {} times",
            shown.len()
        );
        for (_, r) in shown {
            assert!(
                rings.iter().any(|c| (c.x - r.center().x).abs() < 1.0),
                "{size:?} t = {t} s: {e:?} at {r:?} is over no ringed point ({rings:?})"
            );
            labelled += 1;
        }
    }
    // an impact is written first when there is one (at the run's end the
    // lanes went to releases, from left to right, and p3's impact to none)
    if events.iter().any(|e| e.ends_with("IMPACT")) {
        assert!(
            in_plot
                .iter()
                .any(|(t, _)| t.ends_with("IMPACT") && events.contains(t)),
            "{size:?} t = {t} s: no impact written of {events:?}"
        );
    }
    // and the labels keep clear of each other and of the force values
    let labels: Vec<&&(String, egui::Rect)> = in_plot
        .iter()
        .filter(|(t, _)| events.contains(t) || t.ends_with(" N"))
        .collect();
    for (k, (a, ra)) in labels.iter().map(|x| (&x.0, x.1)).enumerate() {
        for (b, rb) in labels.iter().skip(k + 1).map(|x| (&x.0, x.1)) {
            assert!(
                !ra.intersects(rb),
                "{size:?} t = {t} s: {a:?} at {ra:?} over {b:?} at {rb:?}"
            );
            // two phase labels side by side keep a text height apart (6 px
            // apart, "p0: RELEASE p3: IMPACT" read as one label)
            let side_by_side = ra.top() < rb.bottom() && rb.top() < ra.bottom();
            if side_by_side && events.contains(a) && events.contains(b) {
                let apart = (rb.left() - ra.right()).max(ra.left() - rb.right());
                assert!(
                    apart >= 0.8 * ra.height(),
                    "{size:?} t = {t} s: {a:?} and {b:?} only {apart:.1} px apart"
                );
            }
        }
    }
    labelled
}

/// The step of the paper preset's run, from `from` on, at which the most
/// points show an event in classroom mode (its slow motion's hold), found
/// by a run of the library with the same tracker, and how many.
fn most_crowded_step(from: u64) -> (u64, usize) {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let p = scene.num_points();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let mut tr = PhaseTracker::new(p, EVENT_HOLD_WALL_S * SLOW_MOTION);
    let mut best = (from, 0);
    while !sim.finished() {
        sim.step().unwrap();
        tr.after_step(sim.time_s(), sim.in_contact(), sim.force_n());
        let n = (0..p)
            .filter(|&i| tr.phase(i, sim.time_s()).is_event())
            .count();
        if sim.steps() >= from && n > best.1 {
            best = (sim.steps(), n);
        }
    }
    best
}

#[test]
fn every_event_in_the_strip_is_written_in_the_scene() {
    // the moment of the run's second half with the most events at once
    // (an event stays up at most half the contact or flight it starts, so
    // events of the five points overlap less than they once did)
    let (step, most) = most_crowded_step(10_000);
    assert!(most >= 2, "at most {most} events at once");
    for size in [[1280.0, 720.0], [1500.0, 950.0], [1600.0, 1000.0]] {
        let n = check(size, step);
        // all of them where the plot is tall enough; three at least in
        // 1280 x 720's short plot (the others stay in the strip)
        let want = if size[1] < 900.0 { most.min(3) } else { most };
        assert!(
            n >= want,
            "{size:?}: {n} of {most} events written at step {step}"
        );
        // the run's end and a moment of the run: whatever is held, written
        check(size, 20_000);
        check(size, 16_575);
    }
}
