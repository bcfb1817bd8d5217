//! method §2-§3: the exact step of one mode — the
//! propagator `Φ(τ)` and the weights of a force constant over the step,
//! linear through the step ends and linear through the two Gauss points —
//! against closed forms written here from the pole form of method §2
//! (`h = (e^{l₊t} - e^{l₋t}) / (l₊ - l₋)`), not from the crate's series.
//!
//! The existing checks compare the Gauss weights with a 400-panel quadrature
//! at 1e-9 (one underdamped mode) and `Φ`/`w_const` with `h` closed forms;
//! here every weight of every damping regime is compared with its exact
//! integral, to round-off.

use std::f64::consts::TAU;
use tirecontact::model::convolution::mode_step;

use crate::oscillator::{integrals, linear_response};

fn rel(got: f64, want: f64, scale: f64) -> f64 {
    (got - want).abs() / scale
}

#[test]
fn step_weights_match_pole_form_closed_forms_in_every_regime() {
    let g1 = 0.5 * (1.0 - 1.0 / 3f64.sqrt());
    let g2 = 0.5 * (1.0 + 1.0 / 3f64.sqrt());
    let mut worst = 0.0f64;
    let mut worst_at = (0.0, 0.0, "");
    for &xi in &[0.0, 0.02, 0.05, 0.3, 0.9, 1.0, 1.5, 4.0] {
        for &wt in &[0.1, 0.5, 2.0, 8.0, 30.0] {
            let omega = TAU * 250.0;
            let tau = wt / omega;
            let m = mode_step(omega, xi, tau);
            let ints = integrals(omega, xi, tau);
            let (h, hd, _, _) = ints;
            // Φ from the free response u(τ) = u0 (h' + 2ξωh) + v0 h, v(τ) = -ω² u0 h + v0 h'
            let phi = [hd + 2.0 * xi * omega * h, h, -omega * omega * h, hd];
            // scales: x entries ~ min(τ, 1/ω)·(1/ω or τ), v entries ~ that times ω
            let sx = tau.min(1.0 / omega);
            let checks: Vec<(&str, f64, f64, f64)> = {
                let mut c = Vec::new();
                let names = ["phi_xx", "phi_xv", "phi_vx", "phi_vv"];
                let scales = [1.0, sx, omega * omega * sx, 1.0];
                for k in 0..4 {
                    c.push((names[k], m.phi[k], phi[k], scales[k]));
                }
                c.push(("h", m.h[0], h, sx));
                c.push(("h'", m.h[1], hd, 1.0));
                let wc = linear_response(ints, tau, 1.0, 0.0);
                c.push(("w_const.x", m.w_const[0], wc[0], sx * sx));
                c.push(("w_const.v", m.w_const[1], wc[1], sx));
                // ends: q = qs (1 - σ/τ) + qe σ/τ
                let ws = linear_response(ints, tau, 1.0, -1.0 / tau);
                let we = linear_response(ints, tau, 0.0, 1.0 / tau);
                c.push(("w_ends[0].x", m.w_ends[0][0], ws[0], sx * sx));
                c.push(("w_ends[0].v", m.w_ends[0][1], ws[1], sx));
                c.push(("w_ends[1].x", m.w_ends[1][0], we[0], sx * sx));
                c.push(("w_ends[1].v", m.w_ends[1][1], we[1], sx));
                // Gauss points σ1 = g1 τ, σ2 = g2 τ (method §4 step 3)
                let (s1, s2) = (g1 * tau, g2 * tau);
                let d = s2 - s1;
                let wq1 = linear_response(ints, tau, s2 / d, -1.0 / d);
                let wq2 = linear_response(ints, tau, -s1 / d, 1.0 / d);
                c.push(("w_gauss[0].x", m.w_gauss[0][0], wq1[0], sx * sx));
                c.push(("w_gauss[0].v", m.w_gauss[0][1], wq1[1], sx));
                c.push(("w_gauss[1].x", m.w_gauss[1][0], wq2[0], sx * sx));
                c.push(("w_gauss[1].v", m.w_gauss[1][1], wq2[1], sx));
                c
            };
            for (name, got, want, scale) in checks {
                let e = rel(got, want, scale);
                assert!(
                    e < 1e-11,
                    "xi {xi}, omega tau {wt}: {name} = {got:e}, closed form {want:e} (error {e:.1e} of its scale {scale:e})"
                );
                if e > worst {
                    worst = e;
                    worst_at = (xi, wt, name);
                }
            }
        }
    }
    println!(
        "worst weight error {worst:.2e} of its scale at (xi, omega tau, entry) = {worst_at:?}"
    );
}

/// method §3's claim "exact for the assumed force shape": the recursion over
/// many steps with the Gauss weights reproduces the exact response to a
/// force that is piecewise linear (continuous at the step ends, so linear
/// through each step's Gauss points), computed here from `integrals`
/// on each piece and summed by superposition (no recursion).
#[test]
fn recursion_reproduces_superposed_exact_pieces() {
    use tirecontact::model::convolution::{ModalBasis, ModalState, StepTable};
    use tirecontact::scene::Mode;
    let (f, xi, dt) = (180.0, 0.07, 3e-4);
    let omega = TAU * f;
    let modes = [Mode {
        freq_hz: f,
        damping_ratio: xi,
        residue: vec![vec![2.5]],
        shape: vec![],
    }];
    let basis = ModalBasis::new(&modes, 1).unwrap();
    let table = StepTable::new(&basis, dt);
    let mut state = ModalState::zeros(&basis);
    // force values at step ends (N)
    let n = 200;
    let q_end: Vec<f64> = (0..=n)
        .map(|k| {
            let t = k as f64 * dt;
            100.0 * (1.0 + (90.0 * t).sin()) + 40.0 * (1500.0 * t).cos()
        })
        .collect();
    let g1 = 0.5 * (1.0 - 1.0 / 3f64.sqrt());
    let g2 = 0.5 * (1.0 + 1.0 / 3f64.sqrt());
    let (mut u, mut v) = ([0.0], [0.0]);
    let mut worst = 0.0f64;
    let (mut errs, mut umax, mut vmax) = (Vec::new(), 0.0f64, 0.0f64);
    for k in 0..n {
        let mut free = ModalState::zeros(&basis);
        state.predict_into(&table, &mut free);
        state = free;
        let (qa, qb) = (q_end[k], q_end[k + 1]);
        let q1 = qa + (qb - qa) * g1;
        let q2 = qa + (qb - qa) * g2;
        state.add_gauss_forces(&basis, &table, &[0], &[q1], &[q2]);
        state.project(&basis, &mut u, &mut v);
        // superposition: piece j contributes the response at t_{k+1} of its
        // linear force, i.e. from rest over [0, dt] then free for (k - j) dt
        let t_end = (k + 1) as f64 * dt;
        let (mut ur, mut vr) = (0.0, 0.0);
        for j in 0..=k {
            let ints = integrals(omega, xi, dt);
            let (qa, qb) = (q_end[j], q_end[j + 1]);
            let [x0, v0] = linear_response(ints, dt, qa, (qb - qa) / dt);
            let lag = t_end - (j + 1) as f64 * dt;
            let (h, hd, _, _) = integrals(omega, xi, lag.max(0.0));
            let (x, xv) = if lag > 0.0 {
                (
                    x0 * (hd + 2.0 * xi * omega * h) + v0 * h,
                    -omega * omega * x0 * h + v0 * hd,
                )
            } else {
                (x0, v0)
            };
            ur += 2.5 * x;
            vr += 2.5 * xv;
        }
        errs.push(((u[0] - ur).abs(), (v[0] - vr).abs()));
        (umax, vmax) = (umax.max(ur.abs()), vmax.max(vr.abs()));
    }
    for (eu, ev) in errs {
        worst = worst.max(eu / umax).max(ev / vmax);
    }
    println!("piecewise-linear force, 200 steps: worst error {worst:.2e} of the largest |u|, |v|");
    assert!(worst < 1e-11, "worst {worst:e}");
}
