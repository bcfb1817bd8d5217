//! Tests of the modal convolution: the exact step against closed forms,
//! the basis's symmetry, set-up tables on any number of threads, the
//! batched mode steps and the weights' exactness.

use super::*;
use crate::base::modal::unit_impulse;

fn check_against_closed_form(omega: f64, xi: f64, tau: f64) {
    let m = mode_step(omega, xi, tau);
    let (h, hd) = unit_impulse(omega, xi, tau);
    let scale_h = tau.min(1.0 / omega);
    assert!(
        (m.h[0] - h).abs() <= 1e-12 * scale_h,
        "h: xi={xi} wt={}: {} vs {h}",
        omega * tau,
        m.h[0]
    );
    assert!(
        (m.h[1] - hd).abs() <= 1e-12,
        "h': xi={xi} wt={}: {} vs {hd}",
        omega * tau,
        m.h[1]
    );
    // constant-force weight: step response (1 - h' - 2ξωh)/ω², fine only where it does not cancel
    if omega * tau > 0.5 {
        let step = (1.0 - hd - 2.0 * xi * omega * h) / (omega * omega);
        // 16 doublings at ξ = 50, ωτ = 250 leave ~1e-12 relative (round-off growth of the doublings)
        assert!(
            (m.w_const[0] - step).abs() <= 1e-11 / (omega * omega),
            "I0 xi={xi} wt={}: {} vs {step}",
            omega * tau,
            m.w_const[0]
        );
    } else {
        // small ωτ: I0 ≈ τ²/2 (1 - (2ξω) τ/3 ...)
        let approx = tau * tau / 2.0;
        assert!(
            (m.w_const[0] / approx - 1.0).abs() < 2.0 * (omega + 2.0 * xi * omega) * tau + 1e-12
        );
    }
}

/// Modes given by shape make a symmetric basis (the plate's, and a
/// symmetric residue's eigendecomposition); a residue that is not
/// symmetric does not.
#[test]
fn shapes_make_a_symmetric_basis() {
    let plate = crate::model::plate::PlateParams::default();
    let xy: Vec<(f64, f64)> = (0..6)
        .map(|i| (0.01 * i as f64, 0.02 * (i % 3) as f64 - 0.02))
        .collect();
    let modes = plate.modes(&xy);
    assert!(ModalBasis::new(&modes, xy.len()).unwrap().symmetric());
    let skew = Mode {
        freq_hz: 100.0,
        damping_ratio: 0.02,
        residue: vec![vec![1.0, 0.5], vec![-0.2, 2.0]],
        shape: vec![],
    };
    assert!(!ModalBasis::new(&[skew], 2).unwrap().symmetric());
}

/// The set-up tables on 2 and 3 threads (every call split) equal, bit
/// for bit, those on one: a residue basis of 23 points (ranges of
/// uneven lengths) with zero entries (skipped terms).
#[test]
fn set_up_tables_are_the_same_on_any_number_of_threads() {
    let p = 23;
    let modes: Vec<Mode> = (0..9)
        .map(|k| {
            let shape: Vec<f64> = (0..p)
                .map(|i| {
                    let x = ((i * 7 + k * 3) as f64 * 0.37).sin();
                    if (i + k) % 5 == 0 { 0.0 } else { x }
                })
                .collect();
            let residue = (0..p)
                .map(|i| (0..p).map(|j| shape[i] * shape[j]).collect())
                .collect();
            Mode {
                freq_hz: 50.0 + 37.0 * k as f64,
                damping_ratio: 0.04,
                // (rank terms of a residue, or a shape as it is)
                residue: if k % 2 == 0 { vec![] } else { residue },
                shape: if k % 2 == 0 { shape } else { vec![] },
            }
        })
        .collect();
    let basis = ModalBasis::new(&modes, p).unwrap();
    let table = StepTable::new(&basis, 1e-4);
    let bits = |a: &[f64]| a.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let g1 = Influence::new(&basis, &table);
    let j1 = basis.velocity_jump();
    assert!(j1.iter().any(|&x| x != 0.0));
    for n in [2, 3] {
        let threads = Threads::new(n).with_parallel_from(1);
        let g = Influence::new_on(&basis, &table, &threads);
        for (a, b) in [
            (&g.gx1, &g1.gx1),
            (&g.gx2, &g1.gx2),
            (&g.gv1, &g1.gv1),
            (&g.gv2, &g1.gv2),
        ] {
            assert_eq!(bits(a), bits(b), "{n} threads");
        }
        assert_eq!(
            bits(&basis.velocity_jump_on(&threads)),
            bits(&j1),
            "{n} threads"
        );
        assert_eq!(threads.split_calls(), 2);
    }
}

#[test]
fn step_matches_closed_form_every_regime() {
    for &xi in &[0.0, 0.05, 0.7, 1.0 - 1e-12, 1.0, 1.0 + 1e-12, 1.5, 50.0] {
        for &wt in &[1e-6, 1e-3, 0.3, 1.0, 7.0, 250.0] {
            let omega = TAU * 400.0;
            check_against_closed_form(omega, xi, wt / omega);
        }
    }
}

/// Every number of a mode step, as bits.
fn bits(m: &ModeStep) -> Vec<u64> {
    [
        m.phi.to_vec(),
        m.w_const.to_vec(),
        m.w_gauss.concat(),
        m.h.to_vec(),
    ]
    .concat()
    .iter()
    .map(|x| x.to_bits())
    .collect()
}

/// As below over many modes and steps (403 modes, the last three in
/// padded lanes; log-spread frequencies 1 Hz to 100 kHz, damping ratios
/// of every regime, steps 1e-7 to 1e-2 s): the
/// four-lane series (AVX where the CPU has it) rounds as the one-mode
/// code in every lane. Reordering one product of the series fails it.
#[test]
fn batched_mode_steps_round_as_single_ones_over_many_modes() {
    let xis = [0.0, 0.01, 0.05, 0.3, 1.0, 1.0 + 1e-12, 2.0, 50.0];
    let modes: Vec<(f64, f64)> = (0..403)
        .map(|k| {
            let f = 10f64.powf(5.0 * ((k as f64 * 0.618_033_988_7) % 1.0));
            (TAU * f, xis[k % xis.len()])
        })
        .collect();
    let mut batch = Vec::new();
    for j in 0..25 {
        let tau = 10f64.powf(-7.0 + 5.0 * ((j as f64 * 0.414_213_562_4) % 1.0));
        mode_steps_into(&modes, tau, &mut batch);
        for (b, &(w, xi)) in batch.iter().zip(&modes) {
            let one = mode_step(w, xi, tau);
            assert_eq!(bits(b), bits(&one), "omega {w}, xi {xi}, tau {tau}");
        }
    }
}

#[test]
fn batched_mode_steps_equal_single_ones_bit_for_bit() {
    // lanes converging after different numbers of terms and doublings
    let modes: Vec<(f64, f64)> = [1.0, 40.0, 700.0, 3e3, 2e4, 9e4, 5.0, 1e5, 250.0]
        .iter()
        .zip([0.0, 0.05, 1.0, 0.7, 50.0, 0.1, 1.0 + 1e-12, 0.02, 0.3])
        .map(|(&f, xi)| (TAU * f, xi))
        .collect();
    for tau in [1e-7, 1e-5, 3.3e-4, 1e-2] {
        let mut batch = Vec::new();
        mode_steps_into(&modes, tau, &mut batch);
        assert_eq!(batch.len(), modes.len());
        for (b, &(w, xi)) in batch.iter().zip(&modes) {
            let one = mode_step(w, xi, tau);
            assert_eq!(bits(b), bits(&one), "omega {w}, xi {xi}, tau {tau}");
        }
    }
}

#[test]
fn weights_integrate_polynomials_exactly() {
    // ∫_0^τ h(τ-s) q(s) ds by 40-point composite Gauss-Legendre against the weights
    let (omega, xi, tau) = (TAU * 300.0, 0.08, 7e-4);
    let m = mode_step(omega, xi, tau);
    let quad = |f: &dyn Fn(f64) -> f64| {
        let n = 400;
        let g = [
            (-1.0 / 3f64.sqrt() + 1.0) / 2.0,
            (1.0 / 3f64.sqrt() + 1.0) / 2.0,
        ];
        let hs = tau / n as f64;
        (0..n)
            .map(|k| {
                g.iter()
                    .map(|&x| f((k as f64 + x) * hs) * hs / 2.0)
                    .sum::<f64>()
            })
            .sum::<f64>()
    };
    // linear force through the ends: q(s) = 2 + 3 s/τ
    let q = |s: f64| 2.0 + 3.0 * s / tau;
    let exact = quad(&|s| unit_impulse(omega, xi, tau - s).0 * q(s));
    let w = 2.0 * m.w_ends[0][0] + 5.0 * m.w_ends[1][0];
    assert!((w - exact).abs() < 1e-9 * exact.abs(), "{w} vs {exact}");
    // same force through the Gauss points
    let (s1, s2) = (
        tau * (1.0 - 1.0 / 3f64.sqrt()) / 2.0,
        tau * (1.0 + 1.0 / 3f64.sqrt()) / 2.0,
    );
    let wg = q(s1) * m.w_gauss[0][0] + q(s2) * m.w_gauss[1][0];
    assert!((wg - exact).abs() < 1e-9 * exact.abs(), "{wg} vs {exact}");
    let exact_v = quad(&|s| unit_impulse(omega, xi, tau - s).1 * q(s));
    let wv = q(s1) * m.w_gauss[0][1] + q(s2) * m.w_gauss[1][1];
    assert!((wv - exact_v).abs() < 1e-9 * exact_v.abs());
}
