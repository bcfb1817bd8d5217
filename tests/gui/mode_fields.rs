//! The modes table shows each value whole: a field narrower than its text
//! showed the start of it ("0.0497" for a damping ratio of 0.0497672, "0.13"
//! for a residue of 0.138186), a wrong number with nothing to say so.

use crate::harness::{harness_sized, texts};
use egui_kittest::kittest::Queryable;
use tirecontact::Scene;
use tirecontact::gui::App;
use tirecontact::gui::widgets::number::format_number;
use tirecontact::scene::{Mode, Tyre};

/// Identified-looking modes (many digits) on the single-mode preset's point.
fn scene(modes: Vec<Mode>) -> Scene {
    let mut s = Scene::load(std::path::Path::new("presets/single_mode.ron")).unwrap();
    s.tyre = Tyre::Modal { modes };
    s.validate().unwrap();
    s
}

/// The painted text `text` lies inside the field named `name`.
fn whole_in_field(h: &egui_kittest::Harness<'_, App>, name: &str, text: &str) {
    let field = h.get_by_label(name).rect();
    let painted: Vec<egui::Rect> = texts(h)
        .into_iter()
        .filter(|(t, r)| t == text && field.intersects(*r))
        .map(|(_, r)| r)
        .collect();
    assert!(
        !painted.is_empty(),
        "{name}: no text {text:?} painted in the field {field:?}"
    );
    for r in painted {
        assert!(
            r.left() >= field.left() - 0.5 && r.right() <= field.right() + 0.5,
            "{name}: {text:?} painted over x {:.1}..{:.1}, the field spans {:.1}..{:.1}: \
             the end of the number is cut off",
            r.left(),
            r.right(),
            field.left(),
            field.right()
        );
    }
}

#[test]
fn mode_fields_show_their_whole_value() {
    let modes = vec![
        Mode {
            freq_hz: 40.90838025659372,
            damping_ratio: 0.049767248095479076,
            residue: vec![vec![0.1381860985635578]],
            shape: Vec::new(),
        },
        Mode {
            freq_hz: 1234.5678901,
            damping_ratio: 0.00123456789,
            residue: vec![vec![-0.000123456789]],
            shape: Vec::new(),
        },
    ];
    // tall enough for both residue matrices open without scrolling
    for size in [[1280.0, 1000.0], [1600.0, 1000.0]] {
        let mut h = harness_sized(App::new(scene(modes.clone()), None).unwrap(), size);
        h.run_steps(3);
        for k in 0..modes.len() {
            h.get_by_label(&format!("mode {k}: residue matrix A (1/kg), 1x1"))
                .click();
            h.run_steps(3);
        }
        for (k, m) in modes.iter().enumerate() {
            for (name, v) in [
                (format!("tyre.modes[{k}].freq_hz"), m.freq_hz),
                (format!("tyre.modes[{k}].damping_ratio"), m.damping_ratio),
                (format!("tyre.modes[{k}].residue[0][0]"), m.residue[0][0]),
            ] {
                whole_in_field(&h, &name, &format_number(v));
            }
        }
    }
}

/// A ring tyre's identified modes say where their residues are, and "Edit as
/// a modal model" puts them in the modes table.
#[test]
fn the_ring_modes_say_where_their_residues_are() {
    use tirecontact::gui::panels::modes_table::RING_RESIDUES_NOTE;
    // tall enough for the whole panel, the identified modes open
    let mut h = harness_sized(App::with_default_preset(), [1280.0, 1600.0]);
    h.run_steps(3);
    let n = h.state().modes().len();
    h.get_by_label(&format!("{n} identified modes, used by the run"))
        .click();
    h.run_steps(3);
    assert!(h.query_by_label(RING_RESIDUES_NOTE).is_some());
    h.get_by_label("Edit as a modal model").click();
    h.run_steps(3);
    let p = h.state().scene().num_points();
    assert!(
        h.query_by_label(&format!("mode 0: residue matrix A (1/kg), {p}x{p}"))
            .is_some()
    );
}

/// The Green functions view names the modes with their damping to three
/// significant digits ("ξ=0.000" read as undamped for 0.0004) and one mode
/// as one mode ("1 modes").
#[test]
fn the_green_view_lists_light_damping_as_such() {
    use tirecontact::gui::Command;
    use tirecontact::gui::View;
    let modes = vec![Mode {
        freq_hz: 100.0,
        damping_ratio: 0.0004,
        residue: vec![vec![0.1]],
        shape: Vec::new(),
    }];
    let mut h = harness_sized(App::new(scene(modes), None).unwrap(), [1280.0, 720.0]);
    h.run();
    h.state_mut().apply(Command::ShowView(View::Green));
    h.run_steps(3);
    assert!(
        h.query_by_label("1 mode: 100.0 Hz ξ=0.000400").is_some(),
        "labels: {:?}",
        texts(&h)
            .into_iter()
            .map(|(t, _)| t)
            .filter(|t| t.contains('ξ'))
            .collect::<Vec<_>>()
    );
}

/// "Edit as a modal model" says what it did and where the modes are; a mute,
/// which also turns the ring into modes, does not.
#[test]
fn the_conversion_to_a_modal_model_says_what_it_did() {
    use tirecontact::gui::Command;
    let mut h = harness_sized(App::with_default_preset(), [1280.0, 1600.0]);
    h.run_steps(3);
    let n = h.state().modes().len();
    h.state_mut().apply(Command::ToggleMute(1));
    h.run_steps(2);
    let said = |h: &egui_kittest::Harness<'_, App>| {
        h.state()
            .message()
            .is_some_and(|m| !m.error && m.text.contains("replaced by its"))
    };
    assert!(!said(&h), "a mute: {:?}", h.state().message());
    h.state_mut().apply(Command::UnmuteAll);
    h.run_steps(2);
    h.get_by_label("Edit as a modal model").click();
    h.run_steps(3);
    assert!(
        matches!(h.state().scene().tyre, Tyre::Modal { .. }),
        "not converted"
    );
    let m = h.state().message().expect("a message after the conversion");
    assert!(
        !m.error
            && m.text
                .contains(&format!("replaced by its {n} identified modes")),
        "{m:?}"
    );
    assert!(h.query_by_label_contains("replaced by its").is_some());
}

/// A residue matrix names its points: column indices j above the fields,
/// row indices i on their left (nine bare fields of a 3 x 3 matrix said
/// nothing of which pair each was).
#[test]
fn a_residue_matrix_names_its_rows_and_columns() {
    // the three-point preset's modes as residue matrices A = φ φᵀ
    let mut s = Scene::load(std::path::Path::new("presets/three_points.ron")).unwrap();
    if let Tyre::Modal { modes } = &mut s.tyre {
        for m in modes.iter_mut() {
            let phi = std::mem::take(&mut m.shape);
            m.residue = phi
                .iter()
                .map(|a| phi.iter().map(|b| a * b).collect())
                .collect();
        }
    }
    s.validate().unwrap();
    let mut h = harness_sized(App::new(s, None).unwrap(), [1500.0, 1000.0]);
    h.run_steps(2);
    h.get_by_label("mode 0: residue matrix A (1/kg), 3x3")
        .click();
    h.run_steps(3);
    let painted = texts(&h);
    assert!(
        painted.iter().any(|(t, _)| t == "i \\ j"),
        "the corner label"
    );
    for k in 0..3 {
        let col = h
            .get_by_label(&format!("tyre.modes[0].residue[0][{k}]"))
            .rect();
        let row = h
            .get_by_label(&format!("tyre.modes[0].residue[{k}][0]"))
            .rect();
        let label = k.to_string();
        // column k's index above its first field, row k's on its left
        assert!(
            painted.iter().any(|(t, r)| *t == label
                && r.bottom() <= col.top() + 0.5
                && r.center().x >= col.left()
                && r.center().x <= col.right()),
            "no column index {k} above its field {col:?}"
        );
        assert!(
            painted.iter().any(|(t, r)| *t == label
                && r.right() <= row.left() + 0.5
                && r.center().y >= row.top()
                && r.center().y <= row.bottom()),
            "no row index {k} left of its field {row:?}"
        );
    }
}
