//! Tyre responses from a file (`tyre: Measured`): the ring's sampled
//! responses written by `identify --responses` and read back identify to
//! the ring's modes; receptances of a known modal model (CSV FRFs and UFF
//! 58 FRFs) identify to its modes; a measured scene runs like the others.

use std::path::Path;
use tirecontact::identify::{identify_measured, identify_ring};
use tirecontact::lsce::IdentifyOptions;
use tirecontact::measured::impulse_csv;
use tirecontact::modal::{ModalModel, Mode};
use tirecontact::scene::Tyre;
use tirecontact::{ModeCache, Scene, Simulation};

/// The paper's ring, its responses written as `identify --responses`
/// writes them, read back as a measured tyre: the same modes, to 1e-6 in
/// frequency and damping, residues to 1e-6 of the largest.
#[test]
fn ring_responses_read_back_identify_to_the_rings_modes() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let Tyre::Ring {
        ring,
        identification,
    } = &scene.tyre
    else {
        panic!("the paper preset is a ring")
    };
    let x: Vec<f64> = scene.points.iter().map(|p| p.x_m).collect();
    let direct = identify_ring(ring, &x, identification).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("paper_irf.csv");
    std::fs::write(&file, impulse_csv(&direct.responses)).unwrap();
    let read = identify_measured(&file, None, x.len(), identification).unwrap();
    assert_eq!(
        read.responses, direct.responses,
        "the CSV reads back exactly"
    );
    let (a, b) = (&direct.identification.modes, &read.identification.modes);
    assert_eq!(a.len(), b.len());
    for (m, n) in a.iter().zip(b) {
        assert!(
            (m.freq_hz - n.freq_hz).abs() <= 1e-6 * m.freq_hz,
            "{} vs {}",
            m.freq_hz,
            n.freq_hz
        );
        assert!((m.damping_ratio - n.damping_ratio).abs() <= 1e-6 * m.damping_ratio);
    }
    // as a scene: `tyre: Measured(file: …)` relative to the preset's folder
    let mut measured = scene.clone();
    measured.tyre = Tyre::Measured {
        file: "paper_irf.csv".into(),
        identification: identification.clone(),
        nodes: None,
    };
    measured.base_dir = Some(dir.path().to_path_buf());
    measured.validate().unwrap();
    let cache = ModeCache::new();
    let modes = cache.modes(&measured).unwrap();
    assert_eq!(modes.as_slice(), b.as_slice());
    assert!(cache.has_modes(&measured));
    // and it runs
    measured.duration_s = 0.01;
    let model = tirecontact::PreparedModel::new(&measured, &cache).unwrap();
    let mut sim = Simulation::new(&model, tirecontact::SolverOptions::default()).unwrap();
    while !sim.finished() {
        sim.step().unwrap();
    }
    assert!(sim.force_n().iter().all(|q| q.is_finite()));
}

/// A three-point, three-mode model with exact receptances.
fn model() -> (Vec<Mode>, ModalModel) {
    let modes = vec![
        Mode {
            freq_hz: 52.0,
            damping_ratio: 0.03,
            residue: vec![],
            shape: vec![1.0, 0.6, 0.2],
        },
        Mode {
            freq_hz: 131.0,
            damping_ratio: 0.02,
            residue: vec![],
            shape: vec![0.5, -0.4, -0.9],
        },
        Mode {
            freq_hz: 247.0,
            damping_ratio: 0.04,
            residue: vec![],
            shape: vec![0.3, -0.8, 0.7],
        },
    ];
    let m = ModalModel::from_modes(&modes, 3);
    (modes, m)
}

/// Receptances of a known model, written as a CSV of FRFs (only `i >= j`:
/// the others from reciprocity), identify to its modes.
#[test]
fn receptances_of_a_known_model_identify_to_its_modes() {
    let (modes, m) = model();
    let (df, k) = (0.25, 8000); // to 2 kHz, impulse responses 2 s long
    let dir = tempfile::tempdir().unwrap();
    let mut csv = String::from("freq_hz");
    // the lower triangle only: the pairs i < j from reciprocity
    let pairs: Vec<(usize, usize)> = (0..3).flat_map(|i| (0..=i).map(move |j| (i, j))).collect();
    for (i, j) in &pairs {
        csv.push_str(&format!(",h{i}_{j}_re,h{i}_{j}_im"));
    }
    csv.push('\n');
    for n in 0..=k {
        let f = n as f64 * df;
        csv.push_str(&format!("{f:e}"));
        for &(i, j) in &pairs {
            let h = m.frequency_response(i, j, f);
            csv.push_str(&format!(",{:e},{:e}", h.re, h.im));
        }
        csv.push('\n');
    }
    let file = dir.path().join("frf.csv");
    std::fs::write(&file, csv).unwrap();
    let opts = IdentifyOptions {
        band_hz: (0.0, 500.0),
        duration_s: 0.5,
        ..IdentifyOptions::default()
    };
    let id = identify_measured(&file, None, 3, &opts).unwrap();
    assert!(
        id.notes.iter().any(|n| n.contains("reciprocity")),
        "{:?}",
        id.notes
    );
    assert!(
        id.notes.iter().any(|n| n.contains("inverse FFT")),
        "{:?}",
        id.notes
    );
    let got = &id.identification.modes;
    assert_eq!(got.len(), modes.len(), "{got:?}");
    for (a, b) in modes.iter().zip(got) {
        assert!(
            (a.freq_hz - b.freq_hz).abs() <= 1e-3 * a.freq_hz,
            "{} vs {}",
            a.freq_hz,
            b.freq_hz
        );
        assert!(
            (a.damping_ratio - b.damping_ratio).abs() <= 2e-2 * a.damping_ratio,
            "{} vs {}",
            a.damping_ratio,
            b.damping_ratio
        );
    }
}
