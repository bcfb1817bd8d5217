//! The researcher tools of the visualiser driven headless with
//! egui_kittest: spectra, sweep, A/B compare, fidelity. Presets are loaded
//! explicitly from presets/.

use crate::support::temp_dir;
mod fidelity_fit;
mod legends;
mod marker_labels;
mod spectra_fit;
mod spectra_thread;
mod sweep_note;
mod sweep_view_fit;
mod workbench;
mod workbench_axis;
mod workbench_fold;

use crate::harness::{advance, harness, wait_fidelity};
use crate::support::preset;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::sync::atomic::AtomicBool;
use tirecontact::analysis::fidelity::{band_frequencies, relative_l2_error};
use tirecontact::base::modal::ModalModel;
use tirecontact::gui::ResearchCommand;
use tirecontact::gui::SweepState;
use tirecontact::gui::View;
use tirecontact::gui::research::fidelity::FIDELITY_FREQS;
use tirecontact::gui::{App, Command};
use tirecontact::model::road::Road;
use tirecontact::scene::Tyre;
use tirecontact::studies::sweep::{Sweep, linspace, run_sweep};

/// Opens a researcher view through the "Research" menu of the top bar.
fn show(h: &mut Harness<'_, App>, label: &str) {
    h.get_by_label_contains("Research").click();
    h.run_steps(2);
    h.get_by_label(label).click();
    h.run_steps(2);
}

/// Frames until the sweep is no longer running (bounded).
fn wait_sweep(h: &mut Harness<'_, App>) {
    for _ in 0..20_000 {
        if !h.state().research().sweep().is_running() {
            h.run_steps(1);
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.run_steps(1);
    }
    panic!("the sweep did not end");
}

#[test]
fn spectra_view_marks_the_road_excitation_of_the_scene() {
    let scene = preset("three_points");
    let Road::Sine { wavelength_m, .. } = scene.road else {
        panic!("three_points has a sine road")
    };
    let f0 = scene.speed_mps / wavelength_m;
    let mut h = harness(App::new(scene.clone(), None).unwrap());
    h.run();
    advance(&mut h, 12_000);
    h.run_steps(1);
    show(&mut h, "Spectra");
    assert_eq!(h.state().research().spectra_computations(), 1);
    let text = format!("V/λ = {f0:.2} Hz");
    assert!(
        h.query_by_label_contains(&text).is_some(),
        "no excitation marker text `{text}`"
    );
    assert!(h.query_by_label_contains("Hann window, t = ").is_some());
    let hs = h.state().research().spectra().unwrap().as_ref().unwrap();
    // the steady part only: the ramp is skipped
    assert!(hs.span.t0_s >= scene.ramp_s);
    // the displacement of point 0 has its largest tone at the excitation
    let s = &hs.spectra.displacement[0];
    let tone = s.tone(f0, 3.0 * s.df_hz).unwrap();
    assert!((tone.freq_hz - f0).abs() <= s.df_hz);
    // no recomputation on a frame where nothing moved; the button forces one
    h.run_steps(3);
    assert_eq!(h.state().research().spectra_computations(), 1);
    h.get_by_label("Recompute").click();
    h.run_steps(2);
    assert_eq!(h.state().research().spectra_computations(), 2);
    // a speed edit moves the marker
    let mut faster = h.state().scene().clone();
    faster.speed_mps = 15.0;
    h.state_mut().apply(Command::EditScene(Box::new(faster)));
    h.run_steps(2);
    let text = format!("V/λ = {:.2} Hz", 15.0 / wavelength_m);
    assert!(h.query_by_label_contains(&text).is_some(), "{text}");
}

#[test]
fn a_sweep_from_the_gui_equals_the_library_sweep() {
    let mut scene = preset("three_points");
    scene.duration_s = 0.05;
    let mut h = harness(App::new(scene.clone(), None).unwrap());
    h.run();
    show(&mut h, "Sweep");
    assert!(h.query_by_label_contains("No sweep yet").is_some());
    // the default form: speed_mps from 8 to 36 m/s in 8 steps
    h.get_by_label("Run sweep").click();
    h.run_steps(1);
    assert!(h.state().research().sweep().is_running());
    wait_sweep(&mut h);
    let SweepState::Finished(r) = h.state().research().sweep() else {
        panic!("sweep not finished: {:?}", h.state().message())
    };
    let lib = run_sweep(
        &scene,
        &Sweep {
            param: "speed_mps".into(),
            values: linspace(8.0, 36.0, 8).unwrap(),
            threads: 1,
        },
        &tirecontact::ModeCache::new(),
        &|_, _| {},
        &AtomicBool::new(false),
    )
    .unwrap();
    assert_eq!(r.points, lib);
    assert!(h.query_by_label_contains("8 runs of speed V").is_some());
    // exports: the CSV is the CLI's table
    let tmp = temp_dir();
    let dir = tmp.path();
    let csv = dir.join("sweep.csv");
    h.state_mut()
        .apply(Command::Research(ResearchCommand::ExportSweepCsv(
            csv.clone(),
        )));
    let mut expected = Vec::new();
    let columns = tirecontact::studies::sweep::report::Columns {
        points: Some(3),
        patch: false,
    };
    tirecontact::studies::sweep::report::write_csv(&mut expected, "speed_mps", &lib, &columns)
        .unwrap();
    assert_eq!(std::fs::read(&csv).unwrap(), expected);
    let png = dir.join("sweep.png");
    h.state_mut()
        .apply(Command::Research(ResearchCommand::ExportSweepPng(
            png.clone(),
        )));
    assert!(std::fs::metadata(&png).unwrap().len() > 10_000);
    // the CLI's figure, at the size where every y title fits its plot
    let bytes = std::fs::read(&png).unwrap();
    let be = |k: usize| u32::from_be_bytes(bytes[k..k + 4].try_into().unwrap());
    assert_eq!(
        (be(16), be(20)),
        tirecontact::studies::sweep::report::FIGURE_PX,
        "PNG width and height"
    );
}

#[test]
fn cancel_stops_a_sweep_and_leaves_the_app_usable() {
    let mut scene = preset("three_points");
    // 8 runs of 1e6 steps: far longer than the test takes to cancel
    scene.duration_s = 10.0;
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    show(&mut h, "Sweep");
    h.get_by_label("Run sweep").click();
    // one frame applies the click, the next draws Cancel enabled
    h.run_steps(2);
    assert!(h.state().research().sweep().is_running());
    assert!(h.query_by_label_contains("runs of speed V on").is_some());
    h.get_by_label("Cancel").click();
    wait_sweep(&mut h);
    assert!(
        matches!(h.state().research().sweep(), SweepState::Cancelled),
        "{:?} {:?}",
        h.state().research().sweep(),
        h.state().message()
    );
    assert!(
        h.query_by_label_contains("The sweep was cancelled")
            .is_some()
    );
    // still usable
    advance(&mut h, 100);
    h.run_steps(1);
    assert_eq!(h.state().simulation().steps(), 100);
}

#[test]
fn a_pinned_run_survives_a_restart_and_differs_from_itself_by_zero() {
    let scene = preset("three_points");
    let mut h = harness(App::new(scene.clone(), None).unwrap());
    h.run();
    advance(&mut h, 3000);
    h.run_steps(1);
    show(&mut h, "A/B compare");
    h.get_by_label("Pin as reference").click();
    h.run_steps(2);
    let pin = h.state().research().pinned().unwrap().clone();
    assert_eq!(pin.scene, scene);
    let d = h.state().research().difference().unwrap();
    assert_eq!(d.t_s.len(), h.state().history().len());
    assert!(d.rms_dq_n.iter().chain(&d.rms_du_m).all(|&x| x == 0.0));
    // an edit that restarts the run keeps the pin
    let mut edited = scene.clone();
    if let Tyre::Modal { modes } = &mut edited.tyre {
        modes[0].freq_hz *= 1.1;
    }
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    h.run_steps(1);
    assert_eq!(h.state().simulation().steps(), 0);
    assert_eq!(h.state().research().pinned().unwrap().scene, scene);
    advance(&mut h, 3000);
    h.run_steps(1);
    let d = pin.difference(
        &h.state().scene().points,
        &h.state().history().to_recording(),
    );
    assert!(d.rms_dq_n.iter().any(|&x| x > 0.0), "{:?}", d.rms_dq_n);
    assert!(h.query_by_label_contains("reference (dashed): ").is_some());
    // back to the pinned scene: the same run again, difference zero
    h.state_mut().apply(Command::EditScene(Box::new(scene)));
    h.run_steps(1);
    advance(&mut h, 3000);
    h.run_steps(1);
    let d = pin.difference(
        &h.state().scene().points,
        &h.state().history().to_recording(),
    );
    assert!(d.rms_dq_n.iter().chain(&d.rms_du_m).all(|&x| x == 0.0));
    h.get_by_label("Unpin").click();
    h.run_steps(1);
    assert!(h.state().research().pinned().is_none());
}

#[test]
fn fidelity_figure_equals_the_library_and_grows_when_a_mode_goes() {
    let ring_scene = preset("paper");
    let Tyre::Ring { ring, .. } = &ring_scene.tyre else {
        panic!("paper is a ring tyre")
    };
    let ring = ring.clone();
    let mut h = harness(App::new(ring_scene.clone(), None).unwrap());
    h.run();
    h.state_mut().apply(Command::ShowView(View::Fidelity));
    h.run_steps(1);
    // the figures are computed on a background thread: under way after the
    // first frame of the view (a job is polled from the next frame on), not
    // yet shown
    assert!(h.state().research().fidelity_computing().is_some());
    assert_eq!(h.state().research().fidelity_jobs(), 1);
    assert!(
        h.query_by_label_contains("computing the relative L2 error")
            .is_some()
    );
    wait_fidelity(&mut h);
    let x: Vec<f64> = ring_scene.points.iter().map(|p| p.x_m).collect();
    let freqs = band_frequencies(0.0, 500.0, FIDELITY_FREQS).unwrap();
    let source = ring.modal_model(&x);
    let expect = |modes: &[tirecontact::scene::Mode]| {
        relative_l2_error(&source, &ModalModel::from_modes(modes, 5), &freqs)
            .unwrap()
            .relative_l2
    };
    let shown = |h: &Harness<'_, App>| {
        h.state()
            .research()
            .fidelity()
            .unwrap()
            .as_ref()
            .unwrap()
            .fidelity
            .relative_l2
    };
    let modes = h.state().modes().to_vec();
    let e0 = shown(&h);
    assert_eq!(e0, expect(&modes));
    let text = format!("{:.3} % ({:.4e})", 100.0 * e0, e0);
    assert!(h.query_by_label_contains(&text).is_some(), "{text}");
    // converted to an editable modal model, the ring stays the reference
    h.get_by_label("Edit as a modal model").click();
    h.run_steps(2);
    wait_fidelity(&mut h);
    assert!(matches!(h.state().scene().tyre, Tyre::Modal { .. }));
    assert!(h.state().research().fidelity_reference().is_some());
    assert_eq!(shown(&h), e0);
    // removing the lowest mode costs accuracy
    let mut cut = h.state().scene().clone();
    if let Tyre::Modal { modes } = &mut cut.tyre {
        modes.remove(0);
    }
    h.state_mut().apply(Command::EditScene(Box::new(cut)));
    h.run_steps(2);
    wait_fidelity(&mut h);
    assert!(h.state().research().fidelity_jobs() >= 2);
    let e1 = shown(&h);
    assert_eq!(e1, expect(h.state().modes()));
    assert!(e1 > e0, "{e1} vs {e0}");
    let text = format!("{:.3} % ({:.4e})", 100.0 * e1, e1);
    assert!(h.query_by_label_contains(&text).is_some(), "{text}");
    // another scene without a ring: no reference, said so
    h.state_mut()
        .apply(Command::OpenPath("presets/three_points.ron".into()));
    h.run_steps(1);
    h.state_mut().apply(Command::ConfirmDiscard);
    crate::harness::settle(&mut h);
    assert_eq!(h.state().scene().num_points(), 3);
    assert!(h.state().research().fidelity_reference().is_none());
    assert!(
        h.query_by_label_contains("No source Green functions")
            .is_some()
    );
    let _ = View::Fidelity;
}
