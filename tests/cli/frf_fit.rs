//! `identify --data FILE.uff` of FRFs as a process: the fit's report and
//! files (`--fit DIR`), the contact model (`-o`), a reversed driving point
//! (refused, `--flip-direction` offered and fixing it), driving residues of
//! both signs (no model, the fit written), a poor fit (refused, kept with
//! `--accept`).

use crate::support::frf::write_uff;
use crate::support::{bin, temp_dir};
use std::path::Path;
use tirecontact::model::lscf::Ordinate;

fn identify(args: &[&str], extra: &[&Path]) -> (bool, String) {
    let o = bin()
        .arg("identify")
        .args(args)
        .args(extra)
        .output()
        .unwrap();
    (
        o.status.success(),
        format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        ),
    )
}

/// The binary row of `tests/data/uff/row3_58b.uff` (accelerance in g/N):
/// three modes, the fit's files, a scene that loads with the shapes.
#[test]
fn a_binary_row_of_accelerances_gives_a_fit_and_a_contact_model() {
    let tmp = temp_dir();
    let fit = tmp.path().join("fit");
    let model = tmp.path().join("model.ron");
    let (ok, out) = identify(
        &["--data", "tests/data/uff/row3_58b.uff", "--fit"],
        &[&fit, Path::new("-o"), &model],
    );
    assert!(ok, "{out}");
    for want in [
        "3 modes fitted in the frequency domain",
        "accelerance, m/(s²·N)",
        "52.000 Hz  xi 0.0300000",
        "driving point node 101 +Z: every stable mode's residue positive",
    ] {
        assert!(out.contains(want), "{want}: {out}");
    }
    assert_eq!(out.matches("row3_58b.uff").count(), 0, "{out}");
    let modes = std::fs::read_to_string(fit.join("modes.csv")).unwrap();
    assert!(
        modes.starts_with("freq_hz,damping_ratio,stable,note\n"),
        "{modes}"
    );
    assert_eq!(modes.matches(",true").count(), 3, "{modes}");
    let csv = std::fs::read_to_string(fit.join("fit.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("freq_hz,response_node,reference_node,data_re,data_im,fit_re,fit_im")
    );
    // 250 frequencies (2 to 500 Hz) of three pairs; data against fit
    assert_eq!(lines.clone().count(), 750);
    for l in lines {
        let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
        let scale = v[3].hypot(v[4]);
        assert!((v[3] - v[5]).abs() <= 1e-6 * scale + 1e-12, "{l}");
        assert_eq!(v[1], 101.0);
    }
    assert_eq!(&std::fs::read(fit.join("fit.png")).unwrap()[1..4], b"PNG");
    let scene = tirecontact::Scene::load(&model).unwrap();
    assert_eq!(scene.num_points(), 3);
    let tirecontact::scene::Tyre::Modal { modes } = &scene.tyre else {
        panic!("a modal tyre")
    };
    assert_eq!(modes.len(), 3);
    assert!((modes[1].shape[2] - -0.9).abs() < 1e-6, "{:?}", modes[1]);
}

#[test]
fn reversed_and_inconsistent_driving_points_write_the_fit_and_no_model() {
    let tmp = temp_dir();
    let d = tmp.path();
    let rev = write_uff(
        d,
        "reversed.uff",
        &[(0, 0), (0, 1), (0, 2)],
        Ordinate::Accelerance,
        0.0,
        |_, _, _| -1.0,
    );
    let model = d.join("m.ron");
    let (ok, out) = identify(&["--data"], &[&rev, Path::new("-o"), &model]);
    assert!(!ok, "{out}");
    assert!(
        out.contains("every mode's residue is negative") && out.contains("--flip-direction 1"),
        "{out}"
    );
    assert!(out.contains("mode  5:"), "the mode list: {out}");
    assert!(out.contains("--fit DIR"), "points to --fit: {out}");
    assert!(!model.exists());
    let (ok, out) = identify(
        &["--flip-direction", "1", "--data"],
        &[&rev, Path::new("-o"), &model],
    );
    assert!(ok, "{out}");
    assert!(model.exists());
    let mixed = write_uff(
        d,
        "mixed.uff",
        &[(0, 0), (0, 1), (0, 2)],
        Ordinate::Mobility,
        0.0,
        |i, j, m| {
            if i == j && m % 2 == 1 { -1.0 } else { 1.0 }
        },
    );
    let fit = d.join("fit");
    let model2 = d.join("m2.ron");
    let (ok, out) = identify(
        &["--data"],
        &[&mixed, Path::new("--fit"), &fit, Path::new("-o"), &model2],
    );
    assert!(!ok, "{out}");
    assert!(
        out.contains("no valid driving point") && out.contains("node 1 +Z"),
        "{out}"
    );
    assert!(fit.join("fit.csv").exists() && fit.join("fit.png").exists());
    assert!(!model2.exists());
    // without -o: the fit shown, no error
    let (ok, out) = identify(&["--data"], &[&mixed]);
    assert!(ok && out.contains("no contact model"), "{out}");
}

/// 30 % noise: a poor fit, refused for -o (its errors and
/// the way out said) unless --accept, then written with a warning.
#[test]
fn a_poor_fit_is_kept_only_when_accepted() {
    let tmp = temp_dir();
    let d = tmp.path();
    let row = write_uff(
        d,
        "row.uff",
        &[(0, 0), (0, 1), (0, 2)],
        Ordinate::Receptance,
        0.3,
        |_, _, _| 1.0,
    );
    let model = d.join("m.ron");
    let (ok, out) = identify(&["--data"], &[&row, Path::new("-o"), &model]);
    assert!(!ok, "{out}");
    assert!(
        out.contains("the fit is poor") && out.contains("--accept"),
        "{out}"
    );
    assert!(!model.exists());
    let (ok, out) = identify(&["--accept", "--data"], &[&row, Path::new("-o"), &model]);
    assert!(
        ok && out.contains("warning: a poor fit kept by --accept"),
        "{out}"
    );
    assert!(model.exists());
    // the flags of the frequency-domain fit need a file of FRFs
    let (ok, out) = identify(&["--data", "tests/data/uff/time3.uff", "--accept"], &[]);
    assert!(
        !ok && out.contains("--accept: for the frequency-domain fit"),
        "{out}"
    );
}
