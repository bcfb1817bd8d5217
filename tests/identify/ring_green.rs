//! method §5 (ring tyre) and §7 (the paper's preset): the ring's Green functions against closed forms that do not go through
//! a modal sum.
//!
//! * Radial-only tensioned beam closed on itself: with `n⁴ + p n² + q =
//!   (n² + α)(n² + β)` the order sum of method §5 becomes two lattice sums
//!   `Σ_{n∈Z} cos(nθ)/(n² + a²) = (π/a) cosh(a(π - θ)) / sinh(πa)` (and, for
//!   `a² = -b² < 0`, `-(π/b) cos(b(π - θ)) / sin(πb)`), so the static and the
//!   undamped harmonic Green functions have closed forms; the crate's modal
//!   sum (`A_k / (ω_k² - Ω²)` over orders `0..=N`) must meet them to within
//!   its truncation tail, bounded here.
//! * Coupled radial/tangential ring: per order the radial receptance is the
//!   `(0, 0)` entry of `(K(n) - mΩ² I)⁻¹`, solved here as a 2×2 linear system
//!   (no eigen-decomposition), against the crate's sum over modes.
//! * Its stiff-tangential limit (`EA = 0`, `k_t -> ∞`) is method §5's
//!   tensioned-beam formula.

use std::f64::consts::{PI, TAU};
use tirecontact::model::ring::{RingMotion, RingParams};

/// `Σ_{n∈Z} cos(nθ) / (n² + c)` for `c > 0` or `c < 0` (not `-k²`).
fn lattice(c: f64, theta: f64) -> f64 {
    let th = theta.abs() % TAU;
    if c > 0.0 {
        let a = c.sqrt();
        // cosh(a(π-θ))/sinh(πa) without overflow for large a
        let num = (-a * th).exp() + (-a * (TAU - th)).exp();
        let den = 1.0 - (-TAU * a).exp();
        PI / a * num / den
    } else {
        let b = (-c).sqrt();
        -PI / b * (b * (PI - th)).cos() / (PI * b).sin()
    }
}

/// Radial-only ring: `(1/(2πR)) Σ_{n∈Z} cos(nθ) / (EI n⁴/R⁴ + T n²/R² + s - mΩ²)`.
fn beam_receptance(r: &RingParams, theta: f64, omega: f64) -> f64 {
    let rr = r.radius_m;
    let ei = r.bending_stiffness_n_m2;
    let t = r.inflation_pa * r.belt_width_m * rr;
    let s = r.radial_stiffness_n_m2 - r.mass_per_length_kg_m * omega * omega;
    // EI/R⁴ (n⁴ + p n² + q)
    let p = t * rr * rr / ei;
    let q = s * rr.powi(4) / ei;
    let disc = (p * p - 4.0 * q).sqrt();
    assert!(
        disc.is_finite(),
        "complex roots: not covered by this closed form"
    );
    // n⁴ + p n² + q = (n² + α)(n² + β), α = (p - disc)/2, β = (p + disc)/2
    let beta = 0.5 * (p + disc);
    let alpha = q / beta;
    let sum = (lattice(alpha, theta) - lattice(beta, theta)) / (beta - alpha);
    rr.powi(3) / (TAU * ei) * sum
}

/// Bound of the orders past `N` left out of `Σ cos(nθ)/K_n` (both signs of n).
fn beam_tail(r: &RingParams, omega: f64) -> f64 {
    let rr = r.radius_m;
    let n = r.max_order as f64;
    let kmin =
        r.bending_stiffness_n_m2 * n.powi(4) / rr.powi(4) - r.mass_per_length_kg_m * omega * omega;
    assert!(kmin > 0.0);
    // Σ_{n>N} 2 / (EI n⁴/R⁴ - mΩ²) <= 2 (R⁴/EI) / (3 N³) · (EI N⁴/R⁴)/kmin
    let sum = 2.0 * rr.powi(4) / (r.bending_stiffness_n_m2 * 3.0 * n.powi(3))
        * (r.bending_stiffness_n_m2 * n.powi(4) / rr.powi(4))
        / kmin;
    sum / (TAU * rr)
}

fn beam(max_order: usize, damping_ratio: f64) -> RingParams {
    RingParams {
        motion: RingMotion::RadialOnly,
        max_order,
        damping_ratio,
        ..RingParams::default()
    }
}

/// Points along the contact line and far round the ring (θ up to 3.2 rad).
const XS: [f64; 5] = [0.0, 0.025, 0.1, 0.4, 1.0];

#[test]
fn radial_only_static_green_function_matches_lattice_sum() {
    let r = beam(2000, 0.05);
    let model = r.modal_model(&XS);
    let c = model.static_compliance();
    let p = XS.len();
    let tail = beam_tail(&r, 0.0);
    let mut worst = 0.0f64;
    for i in 0..p {
        for j in 0..p {
            let th = (XS[i] - XS[j]) / r.radius_m;
            let exact = beam_receptance(&r, th, 0.0);
            let got = c[i * p + j];
            let e = (got - exact).abs();
            assert!(
                e <= tail + 1e-12 * exact.abs(),
                "({i},{j}) Δθ {th:.4} rad: modal sum {got:e} m/N, closed form {exact:e} m/N, tail bound {tail:e}"
            );
            worst = worst.max(e / c[0]);
        }
    }
    println!(
        "static Green function (N = 2000): worst |Δ| {worst:.2e} of G(0) = {:.6e} m/N; tail bound {:.1e}",
        c[0],
        tail / c[0]
    );
    // method §1 sign: a unit upward force lifts the point (G(0) > 0)
    assert!(c[0] > 0.0);
}

#[test]
fn radial_only_undamped_receptance_matches_lattice_sum_between_resonances() {
    let r = beam(2000, 0.0);
    let model = r.modal_model(&XS);
    let p = XS.len();
    // 100 Hz lies between n = 3 (95.8 Hz) and n = 4 (122.7 Hz); 30 Hz below n = 0
    for f in [30.0, 100.0, 400.0] {
        let omega = TAU * f;
        let tail = beam_tail(&r, omega);
        for i in 0..p {
            for j in 0..p {
                let th = (XS[i] - XS[j]) / r.radius_m;
                let exact = beam_receptance(&r, th, omega);
                let got = model.frequency_response(i, j, f);
                assert!(
                    got.im.abs() < 1e-300 + 1e-15 * got.re.abs(),
                    "undamped: real"
                );
                let e = (got.re - exact).abs();
                assert!(
                    e <= tail + 1e-10 * exact.abs(),
                    "{f} Hz ({i},{j}): modal sum {} m/N, closed form {exact:e} m/N, tail {tail:e}",
                    got.re
                );
            }
        }
    }
}

/// `K(n)` of the coupled ring (per unit length of circumference), written
/// from the strain `ε = (w + v')/R`, curvature change `(v' - w'')/R²`, the
/// tension's second-order energy `T/(2R) ∮ (w'² + v'² + 2wv')` and the
/// foundation springs, for `w = W cos nθ`, `v = V sin nθ`.
fn coupled_k(r: &RingParams, n: usize) -> [[f64; 2]; 2] {
    let nf = n as f64;
    let rr = r.radius_m;
    let ea = r.extensional_stiffness_n / (rr * rr);
    let ei = r.bending_stiffness_n_m2 / rr.powi(4);
    let t = r.inflation_pa * r.belt_width_m * rr / (rr * rr);
    // membrane (W + nV)², bending (n²W + nV)², tension n²W² + n²V² + 2nWV
    let k00 = ea + ei * nf.powi(4) + t * nf * nf + r.radial_stiffness_n_m2;
    let k01 = ea * nf + ei * nf.powi(3) + t * nf;
    let k11 = ea * nf * nf + ei * nf * nf + t * nf * nf + r.tangential_stiffness_n_m2;
    [[k00, k01], [k01, k11]]
}

#[test]
fn coupled_ring_receptance_is_the_radial_entry_of_the_order_inverse() {
    let r = RingParams {
        max_order: 60,
        damping_ratio: 0.0,
        ..RingParams::default()
    };
    let model = r.modal_model(&XS);
    let p = XS.len();
    let m = r.mass_per_length_kg_m;
    for f in [0.0, 55.0, 170.0] {
        let w2 = (TAU * f).powi(2);
        for i in 0..p {
            for j in 0..p {
                let th = (XS[i] - XS[j]) / r.radius_m;
                let mut exact = 0.0;
                for n in 0..=r.max_order {
                    let k = coupled_k(&r, n);
                    let (a, b, d) = (k[0][0] - m * w2, k[0][1], k[1][1] - m * w2);
                    // n = 0: v = V sin 0 = 0, the radial equation alone
                    let radial = if n == 0 { 1.0 / a } else { d / (a * d - b * b) };
                    let c = if n == 0 { 1.0 } else { 2.0 };
                    exact += c * (n as f64 * th).cos() * radial;
                }
                exact /= TAU * r.radius_m;
                let got = if f == 0.0 {
                    model.static_compliance()[i * p + j]
                } else {
                    model.frequency_response(i, j, f).re
                };
                let scale = exact.abs().max(1e-3 * model.static_compliance()[0]);
                assert!(
                    (got - exact).abs() < 1e-10 * scale,
                    "{f} Hz ({i},{j}): modes {got:e}, 2x2 solves {exact:e}"
                );
            }
        }
    }
}

#[test]
fn coupled_ring_with_locked_tangential_motion_is_the_tensioned_beam() {
    // EA = 0 and k_t -> ∞ force V -> 0: the lower branch of each order tends
    // to method §5's ω_n² = (EI (n/R)⁴ + T (n/R)² + s) / m
    let r = RingParams {
        extensional_stiffness_n: 0.0,
        tangential_stiffness_n_m2: 1e13,
        max_order: 12,
        ..RingParams::default()
    };
    let (rr, m, t, s, ei) = (0.31, 3.70, 2.0e5 * 0.165 * 0.31, 3.3e5, 6.0);
    for n in 0..=12 {
        let k = n as f64 / rr;
        let closed = ((ei * k.powi(4) + t * k * k + s) / m).sqrt() / TAU;
        let got = r.order_frequencies_hz(n)[0];
        assert!(
            (got - closed).abs() < 1e-6 * closed,
            "n = {n}: coupled {got} Hz, tensioned beam {closed} Hz"
        );
    }
}

/// method §5 lists the radial-only frequencies of its passenger tyre and says
/// the coupled ring "shifts these somewhat". The preset's (paper.ron) ring
/// uses the coupled model with an assumed EA = 5e6 N: its breathing order
/// n = 0 is then a membrane mode at `sqrt((EA/R² + k_r)/m)` (closed form:
/// order 0 is uncoupled), far above the 0-500 Hz band. The frequencies are
/// printed beside the method's list; the closed forms are asserted.
#[test]
fn preset_ring_frequencies_against_spec_list() {
    let scene = tirecontact::Scene::from_ron_str(
        tirecontact::DEFAULT_PRESET,
        tirecontact::DEFAULT_PRESET_NAME,
    )
    .expect("default preset parses");
    let tirecontact::scene::Tyre::Ring { ring, .. } = &scene.tyre else {
        panic!("the paper preset uses the ring tyre (method §7)");
    };
    assert_eq!(scene.points.len(), 5, "method §7: five contact points");
    let spec = [47.6, 54.7, 72.5, 95.9, 122.8, 152.6, 185.2];
    let radial_only = RingParams {
        motion: RingMotion::RadialOnly,
        ..ring.clone()
    };
    println!("n  reference radial-only  crate radial-only  coupled (lower / upper branch) Hz");
    for (n, f_spec) in spec.iter().enumerate() {
        let ro = radial_only.order_frequencies_hz(n)[0];
        let co = ring.order_frequencies_hz(n);
        println!("{n}  {f_spec:>6.1}  {ro:>8.2}  {co:>8.2?}");
        assert!(
            (ro - f_spec).abs() < 0.15,
            "n = {n}: {ro} vs reference {f_spec}"
        );
    }
    let n0 = ((ring.extensional_stiffness_n / ring.radius_m.powi(2) + ring.radial_stiffness_n_m2)
        / ring.mass_per_length_kg_m)
        .sqrt()
        / TAU;
    let radial_n0: Vec<f64> = ring
        .order_modes(0)
        .iter()
        .filter(|m| m.radial != 0.0)
        .map(|m| m.freq_hz())
        .collect();
    assert_eq!(radial_n0.len(), 1);
    assert!(
        (radial_n0[0] - n0).abs() < 1e-9 * n0,
        "{radial_n0:?} vs {n0}"
    );
    println!(
        "order 0 radial (breathing) mode of the preset: {n0:.1} Hz (radial-only: {:.1} Hz)",
        spec[0]
    );
}
