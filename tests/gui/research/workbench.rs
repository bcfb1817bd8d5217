//! The identification workbench driven by the pointer: a measured tyre's
//! stabilisation diagram with the automatic choice picked, a click on a
//! picked pole drops its mode and a click picks it back, "Use these modes"
//! makes them the scene's modal tyre, and they save as a modal preset.

use crate::harness::{harness_sized, settle};
use crate::support::temp_dir;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use egui_plot::{PlotMemory, PlotPoint};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::ResearchCommand;
use tirecontact::gui::views::workbench_view::{DIAGRAM_PLOT_ID, FRF_SECTION};
use tirecontact::gui::{App, Command, View};
use tirecontact::model::lsce::IdentifyOptions;
use tirecontact::scene::Tyre;

/// The three-point scene with the pyuff fixture's exact impulse responses
/// as its measured tyre (three modes: 52, 131 and 247 Hz).
fn measured_scene() -> Scene {
    let mut s = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    s.tyre = Tyre::Measured {
        file: std::fs::canonicalize("tests/data/uff/time3.uff").unwrap(),
        identification: IdentifyOptions {
            band_hz: (0.0, 450.0),
            duration_s: 0.5,
            ..IdentifyOptions::default()
        },
        nodes: Vec::new(),
    };
    s
}

/// Frames until the workbench has its identification.
fn until_identified(h: &mut Harness<'_, App>) {
    for _ in 0..20_000 {
        if h.state().research().workbench().is_some() && !h.state().research().workbench_computing()
        {
            h.run_steps(2);
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
        h.run_steps(1);
    }
    panic!("the workbench never identified");
}

/// Clicks at the diagram's point `(freq_hz, order)`.
fn click_pole(h: &mut Harness<'_, App>, freq_hz: f64, order: f64) {
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(DIAGRAM_PLOT_ID)).expect("the diagram");
    let pos = mem
        .transform()
        .position_from_point(&PlotPoint::new(freq_hz, order));
    h.hover_at(pos);
    h.run_steps(1);
    h.drag_at(pos);
    h.run_steps(1);
    h.drop_at(pos);
    h.run_steps(2);
}

fn picked_freqs(h: &Harness<'_, App>) -> Vec<f64> {
    match h.state().research().workbench() {
        Some(Ok(w)) => w.modes.iter().map(|m| m.freq_hz).collect(),
        other => panic!("no workbench: {other:?}"),
    }
}

#[test]
fn the_diagram_legend_covers_no_pole() {
    let mut h = harness_sized(App::new(measured_scene(), None).unwrap(), [1280.0, 720.0]);
    settle(&mut h);
    h.state_mut().apply(Command::ShowView(View::Workbench));
    h.run_steps(1);
    until_identified(&mut h);
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(DIAGRAM_PLOT_ID)).expect("the diagram");
    let frame = *mem.transform().frame();
    for name in [
        "stable in f, ξ and shape",
        "stable in f and ξ",
        "stable in f",
        "new or unstable",
    ] {
        let entries: Vec<_> = h.query_all_by_label(name).collect();
        assert!(!entries.is_empty(), "no legend entry {name:?}");
        for e in entries {
            let r = e.rect();
            assert!(
                !frame.intersects(r),
                "the legend entry {name:?} at {r:?} is inside the diagram {frame:?}"
            );
        }
    }
}

#[test]
fn poles_are_picked_and_dropped_by_clicks_and_the_modes_used_and_saved() {
    let mut h = harness_sized(App::new(measured_scene(), None).unwrap(), [1600.0, 1000.0]);
    settle(&mut h);
    h.state_mut().apply(Command::ShowView(View::Workbench));
    h.run_steps(1);
    until_identified(&mut h);
    // the automatic choice: the three modes
    let auto = picked_freqs(&h);
    assert_eq!(auto.len(), 3, "{auto:?}");
    for (f, want) in auto.iter().zip([52.0, 131.0, 247.0]) {
        assert!((f - want).abs() < 1e-3 * want, "{auto:?}");
    }
    assert!(h.query_by_label_contains("3 modes picked;").is_some());
    // the picked 131 Hz pole, clicked: dropped
    let (order, f131) = {
        let Some(Ok(w)) = h.state().research().workbench() else {
            unreachable!()
        };
        let at = w.picked[1];
        (
            w.identification.diagram[at.0].order as f64,
            w.pole(at).unwrap().0,
        )
    };
    click_pole(&mut h, f131, order);
    let now = picked_freqs(&h);
    assert_eq!(now.len(), 2, "{now:?}");
    assert!(now.iter().all(|f| (f - 131.0).abs() > 1.0));
    assert!(h.query_by_label_contains("2 modes picked;").is_some());
    // errors as percentages, as in the fidelity view
    assert!(
        h.query_by_label_contains(" % (relative L2)").is_some(),
        "the fit's time error without its unit"
    );
    // clicked again: picked back
    click_pole(&mut h, f131, order);
    assert_eq!(picked_freqs(&h).len(), 3);
    // drop it once more, then use the two modes left
    click_pole(&mut h, f131, order);
    let two = match h.state().research().workbench() {
        Some(Ok(w)) => w.modes.clone(),
        _ => unreachable!(),
    };
    h.get_by_label("Use these modes").click();
    settle(&mut h);
    match &h.state().scene().tyre {
        Tyre::Modal { modes } => assert_eq!(modes, &two),
        t => panic!("not a modal tyre: {t:?}"),
    }
    assert_eq!(h.state().simulation().steps(), 0, "the run restarted");
    // the diagram and the picks stay, to refine the choice: the 131 Hz
    // pole picked again and used again
    h.run_steps(2);
    assert!(h.state().research().workbench_in_use());
    assert!(
        h.query_by_label_contains("open a ring or measured preset")
            .is_none()
    );
    assert!(h.query_by_label_contains("2 modes picked;").is_some());
    assert!(
        h.query_by_label_contains("again to refine the choice")
            .is_some()
    );
    click_pole(&mut h, f131, order);
    assert_eq!(picked_freqs(&h).len(), 3);
    h.get_by_label("Use these modes").click();
    settle(&mut h);
    match &h.state().scene().tyre {
        Tyre::Modal { modes } => assert_eq!(modes.len(), 3),
        t => panic!("not a modal tyre: {t:?}"),
    }
    h.run_steps(2);
    assert!(h.state().research().workbench_in_use());
    // another modal tyre (a mode edited away from the workbench's): the
    // view says there is nothing to identify
    let mut other = h.state().scene().clone();
    if let Tyre::Modal { modes } = &mut other.tyre {
        modes.pop();
    }
    h.state_mut().apply(Command::EditScene(Box::new(other)));
    settle(&mut h);
    h.run_steps(2);
    assert!(!h.state().research().workbench_in_use());
    assert!(
        h.query_by_label_contains("open a ring or measured preset")
            .is_some()
    );

    // saved as a modal preset, from a measured scene's workbench
    let mut h = harness_sized(App::new(measured_scene(), None).unwrap(), [1600.0, 1000.0]);
    settle(&mut h);
    h.state_mut().apply(Command::ShowView(View::Workbench));
    h.run_steps(1);
    until_identified(&mut h);
    let tmp = temp_dir();
    let path = tmp.path().join("picked.ron");
    h.state_mut()
        .apply(Command::Research(ResearchCommand::WorkbenchSave(
            path.clone(),
        )));
    h.run_steps(1);
    let saved = Scene::load(&path).unwrap();
    match saved.tyre {
        Tyre::Modal { modes } => assert_eq!(modes.len(), 3),
        t => panic!("not a modal tyre: {t:?}"),
    }
}

/// A measured tyre whose file holds FRFs (`tests/data/uff/frf3.uff`:
/// MODEL3's receptances, every pair): the workbench shows their
/// frequency-domain fit below the LSCE diagram — its three modes, every
/// driving point's check, the residual terms, data against fit.
#[test]
fn a_file_of_frfs_shows_its_frequency_domain_fit() {
    let mut s = measured_scene();
    s.tyre = Tyre::Measured {
        file: std::fs::canonicalize("tests/data/uff/frf3.uff").unwrap(),
        identification: IdentifyOptions {
            band_hz: (0.0, 450.0),
            duration_s: 0.5,
            ..IdentifyOptions::default()
        },
        nodes: Vec::new(),
    };
    let mut h = harness_sized(App::new(s, None).unwrap(), [1600.0, 1000.0]);
    settle(&mut h);
    h.state_mut().apply(Command::ShowView(View::Workbench));
    h.run_steps(1);
    until_identified(&mut h);
    let Some(Ok(fit)) = h.state().research().frf_fit() else {
        panic!(
            "no FRF fit: {:?}",
            h.state().research().frf_fit().map(|r| r.as_ref().err())
        )
    };
    let f: Vec<f64> = fit.poles.iter().map(|p| p.freq_hz).collect();
    assert_eq!(f.len(), 3, "{f:?}");
    for (a, b) in f.iter().zip([52.0, 131.0, 247.0]) {
        assert!((a - b).abs() < 1e-6 * b, "{a} vs {b}");
    }
    assert!(fit.complex.error < 1e-9, "{}", fit.complex.error);
    assert!(matches!(h.state().research().workbench(), Some(Ok(_))));
    // the fit follows the diagram, folded: scrolled to and opened
    h.get_by_label(FRF_SECTION).scroll_to_me();
    h.run_steps(3);
    h.get_by_label(FRF_SECTION).click();
    h.run_steps(3);
    for text in [
        "Frequency-domain fit of the FRFs",
        "driving point node 102 +Z: every stable mode's residue positive",
        "node 101 +Z / node 103 +Z",
        "residual terms of the 9 pairs",
        "contact model (real modes",
    ] {
        assert!(
            h.query_all_by_label_contains(text).next().is_some(),
            "{text}"
        );
    }
}

/// A plate tyre (as an FE-modes or modal one) has nothing to identify: the
/// view says what its tyre is, not an error.
#[test]
fn a_plate_tyre_has_nothing_to_identify_and_no_error() {
    let scene = Scene::load(Path::new("presets/patch_texture.ron")).unwrap();
    let mut h = harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
    settle(&mut h);
    h.state_mut().apply(Command::ShowView(View::Workbench));
    for _ in 0..5 {
        h.run_steps(2);
    }
    assert!(
        h.query_by_label_contains("an orthotropic plate").is_some(),
        "the view does not name the plate"
    );
    assert!(h.query_by_label_contains("No identification").is_none());
}
