//! The frequency-domain fit of measured FRFs (method §6.5): LSCF poles and
//! LSFD residues of a known six-mode model (52 to 959 Hz, three nodes,
//! 0–1000 Hz every 1 Hz, as a hammer test of a small structure) measured
//! as a row, a column or a full matrix, in receptance, mobility or
//! accelerance, with and without noise; the driving-point check and the
//! contact model; UFF files read in their own ordinate.

use faer::c64;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::f64::consts::TAU;
use tirecontact::model::lscf::{self, FitOptions, FrfSet, Ordinate};

/// Six modes: `(f_hz, ξ, shape at nodes 1, 2, 3)`.
pub const SIX: [(f64, f64, [f64; 3]); 6] = [
    (52.3, 0.012, [0.9, 0.5, 0.2]),
    (131.7, 0.008, [0.6, -0.4, -0.8]),
    (247.1, 0.006, [0.5, -0.7, 0.6]),
    (433.9, 0.005, [0.7, 0.3, -0.5]),
    (687.2, 0.004, [0.4, -0.6, 0.3]),
    (959.4, 0.003, [0.5, 0.45, 0.35]),
];

/// The model's receptance `Σ φ_i φ_j / (ω_k² − ω² + 2jξω_kω)` times
/// `(jω)^q`, `modes` given.
pub fn frf(modes: &[(f64, f64, [f64; 3])], i: usize, j: usize, f_hz: f64, q: Ordinate) -> c64 {
    let w = TAU * f_hz;
    modes
        .iter()
        .map(|&(f, xi, s)| {
            let wk = TAU * f;
            c64::new(s[i] * s[j], 0.0) / c64::new(wk * wk - w * w, 2.0 * xi * wk * w)
        })
        .sum::<c64>()
        * q.factor(w)
}

/// A set of `pairs` over 1..=1000 Hz, every 1 Hz, with relative noise
/// `noise` (each value times `1 + noise·(n₁ + j n₂)`, `n` uniform in
/// `[−√3, √3]`: unit variance).
fn set(pairs: &[(usize, usize)], q: Ordinate, noise: f64, seed: u64) -> FrfSet {
    let mut rng = StdRng::seed_from_u64(seed);
    let freq_hz: Vec<f64> = (1..=1000).map(f64::from).collect();
    let mut n = || noise * 3f64.sqrt() * (2.0 * rng.random::<f64>() - 1.0);
    let h = pairs
        .iter()
        .map(|&(i, j)| {
            freq_hz
                .iter()
                .map(|&f| frf(&SIX, i, j, f, q) * c64::new(1.0 + n(), n()))
                .collect()
        })
        .collect();
    FrfSet {
        freq_hz,
        ordinate: q,
        pairs: pairs.to_vec(),
        h,
    }
}

const ROW: [(usize, usize); 3] = [(0, 0), (0, 1), (0, 2)];
const COLUMN: [(usize, usize); 3] = [(0, 0), (1, 0), (2, 0)];

/// Poles and real modal constants of a set, with the worst relative
/// errors against SIX: frequency, damping, modal constant.
fn fit(s: &FrfSet) -> (Vec<lscf::Pole>, f64, f64, f64, f64, f64) {
    let opts = FitOptions::default();
    let diagram = lscf::stabilisation(s, (1.0, 1000.0), &opts).unwrap();
    let (_, selected) = lscf::select(&diagram, &opts);
    let (poles, complex) = lscf::refine(s, &selected, 20).unwrap();
    let real = lscf::real_modes(s, &poles).unwrap();
    assert_eq!(
        poles.len(),
        6,
        "{:?}",
        poles.iter().map(|p| p.freq_hz).collect::<Vec<_>>()
    );
    let (mut ef, mut ex, mut ea): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for (k, (p, &(f, xi, shape))) in poles.iter().zip(&SIX).enumerate() {
        ef = ef.max((p.freq_hz - f).abs());
        ex = ex.max((p.damping_ratio - xi).abs() / xi);
        for (pr, &(i, j)) in s.pairs.iter().enumerate() {
            let a = shape[i] * shape[j];
            ea = ea.max((real.constants[pr][k] - a).abs() / shape[0].abs().max(0.2).powi(2));
        }
    }
    (poles, ef, ex, ea, complex.error, real.error)
}

/// Noise-free rows and columns in every ordinate: frequencies, damping and
/// modal constants to 1e-6 relative; both errors below 1e-6.
#[test]
fn noise_free_rows_and_columns_fit_to_round_off_in_every_ordinate() {
    for q in [Ordinate::Receptance, Ordinate::Mobility, Ordinate::Accelerance] {
        for (name, pairs) in [("row", &ROW), ("column", &COLUMN)] {
            let (_, ef, ex, ea, ec, er) = fit(&set(pairs, q, 0.0, 1));
            eprintln!("{name} {q:?}: f {ef:.2e} Hz, xi {ex:.2e}, A {ea:.2e}, errors {ec:.2e} {er:.2e}");
            assert!(
                ef < 1e-6 * 52.0 && ex < 1e-6 && ea < 1e-6 && ec < 1e-6 && er < 1e-6,
                "{name} {q:?}: f {ef:e} Hz, xi {ex:e}, A {ea:e}, errors {ec:e} {er:e}"
            );
        }
    }
}

/// 1 % noise: frequencies within 0.05 Hz, damping within 10 %, modal
/// constants within 3 % of the largest, both errors within 1.5 times the
/// noise level (0.015).
#[test]
fn one_percent_noise_keeps_frequencies_within_five_hundredths_of_a_hertz() {
    for q in [Ordinate::Receptance, Ordinate::Mobility, Ordinate::Accelerance] {
        for (name, pairs) in [("row", &ROW), ("column", &COLUMN)] {
            let (_, ef, ex, ea, ec, er) = fit(&set(pairs, q, 0.01, 7));
            eprintln!("{name} {q:?}: f {ef:.2e} Hz, xi {ex:.2e}, A {ea:.2e}, errors {ec:.2e} {er:.2e}");
            assert!(
                ef < 0.05 && ex < 0.1 && ea < 0.03 && ec < 0.015 && er < 0.015,
                "{name} {q:?}: f {ef:e} Hz, xi {ex:e}, A {ea:e}, errors {ec:e} {er:e}"
            );
        }
    }
}
