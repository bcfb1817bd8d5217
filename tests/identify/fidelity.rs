//! Fidelity error of a modal model against a reference G(ω): zero against
//! itself, the closed form when a mode is removed, growth on the ring tyre.

use std::f64::consts::TAU;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::analysis::fidelity::{
    GreenMatrix, SampledGreen, band_frequencies, detuned, relative_l2_error, removal_costs,
    without_mode,
};
use tirecontact::base::modal::ModalModel;
use tirecontact::identify::identify_ring;
use tirecontact::model::lsce::IdentifyOptions;
use tirecontact::model::ring::RingParams;

fn three_point_modes() -> Vec<tirecontact::scene::Mode> {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    tirecontact::ModeCache::new()
        .modes(&scene)
        .unwrap()
        .to_vec()
}

/// `1 / (ω² - Ω² + 2iξωΩ)` written out here.
fn receptance(f_mode: f64, xi: f64, f: f64) -> (f64, f64) {
    let (w, o) = (TAU * f_mode, TAU * f);
    let (re, im) = (w * w - o * o, 2.0 * xi * w * o);
    let d = re * re + im * im;
    (re / d, -im / d)
}

#[test]
fn zero_against_itself_and_closed_form_when_a_mode_is_removed() {
    let modes = three_point_modes();
    let p = 3;
    let model = ModalModel::from_modes(&modes, p);
    let freqs = band_frequencies(0.0, 500.0, 400).unwrap();
    let same = relative_l2_error(&model, &model, &freqs).unwrap();
    assert_eq!(same.relative_l2, 0.0);
    assert!(same.per_pair.iter().all(|&e| e == 0.0));
    for k in 0..modes.len() {
        let cut = ModalModel::from_modes(&without_mode(&modes, k).unwrap(), p);
        let e = relative_l2_error(&model, &cut, &freqs).unwrap().relative_l2;
        // G - Ĝ = A_k r_k(Ω) exactly; the norms summed here independently
        let a = modes[k].residue_matrix();
        let (mut num, mut den) = (0.0, 0.0);
        for &f in &freqs {
            let rk = receptance(modes[k].freq_hz, modes[k].damping_ratio, f);
            for i in 0..p {
                for j in 0..p {
                    num += a[i][j] * a[i][j] * (rk.0 * rk.0 + rk.1 * rk.1);
                    let (mut gr, mut gi) = (0.0, 0.0);
                    for m in &modes {
                        let r = receptance(m.freq_hz, m.damping_ratio, f);
                        let am = m.residue_matrix()[i][j];
                        gr += am * r.0;
                        gi += am * r.1;
                    }
                    den += gr * gr + gi * gi;
                }
            }
        }
        let expect = (num / den).sqrt();
        assert!(
            (e - expect).abs() < 1e-12 * expect,
            "mode {k}: {e} vs {expect}"
        );
        assert!(e > 0.05, "removing mode {k} costs only {e}");
    }
    // detuning grows with the detuning
    let e = |factor: f64| {
        let m = ModalModel::from_modes(&detuned(&modes, 1, factor, None).unwrap(), p);
        relative_l2_error(&model, &m, &freqs).unwrap().relative_l2
    };
    assert_eq!(e(1.0), 0.0);
    assert!(0.0 < e(1.01) && e(1.01) < e(1.03) && e(1.03) < e(1.1));
    assert!(without_mode(&modes, 3).is_err());
    assert!(relative_l2_error(&model, &ModalModel::from_modes(&modes, 2), &freqs).is_err());
    assert!(band_frequencies(500.0, 100.0, 10).is_err());
}

#[test]
fn sampled_reference_matches_its_source_on_its_grid() {
    let modes = three_point_modes();
    let model = ModalModel::from_modes(&modes, 3);
    let freqs = band_frequencies(10.0, 600.0, 300).unwrap();
    let sampled = SampledGreen::sample(&model, &freqs);
    assert_eq!(
        relative_l2_error(&sampled, &model, &freqs)
            .unwrap()
            .relative_l2,
        0.0
    );
    // midway between two grid points: the mean of the two
    let (f0, f1) = (freqs[10], freqs[11]);
    let g = sampled.receptance(0, 2, 0.5 * (f0 + f1));
    let (a, b) = (
        model.frequency_response(0, 2, f0),
        model.frequency_response(0, 2, f1),
    );
    assert!(
        (g.re - 0.5 * (a.re + b.re)).abs() < 1e-15 && (g.im - 0.5 * (a.im + b.im)).abs() < 1e-15
    );
}

#[test]
fn ring_source_against_its_identified_model() {
    let ring = RingParams::default();
    let x = [-0.025, 0.0, 0.025];
    let opts = IdentifyOptions::default();
    let id = identify_ring(&ring, &x, &opts).unwrap();
    let modes = id.identification.modes;
    let identified = ModalModel::from_modes(&modes, x.len());
    let source = ring.modal_model(&x);
    let freqs = band_frequencies(opts.band_hz.0, opts.band_hz.1, 500).unwrap();
    assert_eq!(
        relative_l2_error(&identified, &identified, &freqs)
            .unwrap()
            .relative_l2,
        0.0
    );
    let e0 = relative_l2_error(&source, &identified, &freqs)
        .unwrap()
        .relative_l2;
    let costs = removal_costs(&source, &modes, &freqs).unwrap();
    eprintln!(
        "ring vs identified ({} modes): {e0:.3e}; without each mode: {:?}",
        modes.len(),
        costs.iter().map(|c| format!("{c:.3}")).collect::<Vec<_>>()
    );
    assert!(e0 < 0.05, "identified model off by {e0}");
    assert!(costs.iter().all(|&c| c > e0), "{costs:?} vs {e0}");
    let worst = costs.iter().cloned().fold(0.0, f64::max);
    assert!(worst > 5.0 * e0 && worst > 0.1, "{worst} vs {e0}");
}
