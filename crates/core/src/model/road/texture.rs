//! A synthetic road texture: an isotropic random surface whose spectrum
//! extends the ISO 8608 classes to two dimensions (method §4.8).
//!
//! ISO 8608 gives a profile's one-sided displacement PSD
//! `Gd(n) = Gd(n0) (n / n0)^-2` (see [`random`](super::random)). The
//! isotropic surface whose every straight profile has that PSD has the
//! two-sided 2D PSD (in cycles/m, over the whole plane)
//!
//! ```text
//! S2(κ) = C κ^-3,   C = Gd(n0) n0² / 4,   κ = |(n_x, n_y)|,
//! ```
//!
//! since `∫ (n_x² + n_y²)^-3/2 dn_y = 2 / n_x²` makes the two-sided profile
//! PSD `S1(n_x) = 2 C n_x^-2 = Gd(n_x) / 2`. The surface is the real sum
//! over the wavenumbers of a grid `nx × ny` (periods `L` along and `W`
//! across) inside the band `κ_min <= κ <= κ_max`,
//!
//! ```text
//! z(x, y) = Σ c_pq e^{2πi (p x / L + q y / W)},   |c_pq| = sqrt(S2(κ_pq) / (L W)),
//! ```
//!
//! with Hermitian symmetry `c_-p-q = conj(c_pq)` and seeded random phases
//! (ChaCha8), evaluated by a 2D inverse FFT, with the exact slopes along `x`.

use super::random::{N0_CPM, RoadClass};
use super::surface::{MAX_SURFACE_NODES, SurfaceGrid};
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{RngCore, SeedableRng};
use rustfft::FftPlanner;
use rustfft::num_complex::Complex;
use std::f64::consts::TAU;

/// Grid nodes per shortest wavelength of a texture, along and across.
pub const NODES_PER_WAVELENGTH: f64 = 6.0;

/// `C` of `S2(κ) = C κ^-3` (m⁴ · (cycles/m)³ / (cycles/m)... in m for `z` in
/// m and `κ` in cycles/m): `Gd(n0) n0² / 4`.
pub fn s2_constant(class: RoadClass) -> f64 {
    class.gd_n0_m3() * N0_CPM * N0_CPM / 4.0
}

/// The texture's 2D PSD `S2(κ)` (m⁴) at radial wavenumber `κ` (cycles/m)
/// inside the band, 0 outside.
pub fn s2_m4(class: RoadClass, kappa_cpm: f64, band_cpm: (f64, f64)) -> f64 {
    if kappa_cpm < band_cpm.0 || kappa_cpm > band_cpm.1 || kappa_cpm <= 0.0 {
        0.0
    } else {
        s2_constant(class) * kappa_cpm.powi(-3)
    }
}

/// The two-sided PSD (m³) of a straight profile of the band-limited
/// texture at `n_x` (cycles/m): `∫ S2 dn_y` over the band, in closed form
/// (`∫ κ^-3 dn_y = n_y / (n_x² κ)`).
pub fn profile_psd_two_sided_m3(class: RoadClass, nx_cpm: f64, band_cpm: (f64, f64)) -> f64 {
    let nx = nx_cpm.abs();
    let (lo, hi) = band_cpm;
    if nx == 0.0 || nx > hi {
        return 0.0;
    }
    let f = |ny: f64| ny / (nx * nx * (nx * nx + ny * ny).sqrt());
    let top = (hi * hi - nx * nx).sqrt();
    let bottom = if nx < lo {
        (lo * lo - nx * nx).sqrt()
    } else {
        0.0
    };
    2.0 * s2_constant(class) * (f(top) - f(bottom))
}

/// Grid sizes `(nx, ny)` of a texture: at least [`NODES_PER_WAVELENGTH`]
/// nodes per shortest wavelength, even.
pub fn grid_size(length_m: f64, width_m: f64, max_cpm: f64) -> (f64, f64) {
    let n = |l: f64| (2.0 * (l * max_cpm * NODES_PER_WAVELENGTH / 2.0).ceil()).max(4.0);
    (n(length_m), n(width_m))
}

/// Why a texture's fields cannot make a grid (the fields are finite and
/// positive): the field to name and what is expected.
pub fn grid_error(length_m: f64, width_m: f64, max_cpm: f64) -> Option<String> {
    let (nx, ny) = grid_size(length_m, width_m, max_cpm);
    (nx * ny > MAX_SURFACE_NODES as f64).then(|| {
        format!(
            "a texture grid of at most {MAX_SURFACE_NODES} nodes: {nx:.0} × {ny:.0} nodes ({NODES_PER_WAVELENGTH} per shortest wavelength; shorten length_m or width_m, or lower max_wavenumber_cpm)"
        )
    })
}

/// Generates the texture on its grid (looped along `x`, periodic across,
/// `y` from `-W/2`). The caller has checked the fields.
pub fn generate(
    class: RoadClass,
    seed: u64,
    (length_m, width_m): (f64, f64),
    band_cpm: (f64, f64),
) -> SurfaceGrid {
    let (nx, ny) = grid_size(length_m, width_m, band_cpm.1);
    let (nx, ny) = (nx as usize, ny as usize);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut c = vec![Complex::new(0.0, 0.0); nx * ny];
    let signed = |k: usize, n: usize| {
        if k <= n / 2 {
            k as f64
        } else {
            k as f64 - n as f64
        }
    };
    let cell = 1.0 / (length_m * width_m);
    // one phase per wavenumber of the half plane (q > 0, or q = 0 and p > 0),
    // drawn in index order; its mirror is the conjugate
    for q in 0..ny {
        for p in 0..nx {
            let (kp, kq) = (signed(p, nx) / length_m, signed(q, ny) / width_m);
            let upper = kq > 0.0 || (kq == 0.0 && kp > 0.0);
            let nyquist = (nx % 2 == 0 && p == nx / 2) || (ny % 2 == 0 && q == ny / 2);
            if !upper || nyquist {
                continue;
            }
            let phase = TAU * (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
            let a = (s2_m4(class, kp.hypot(kq), band_cpm) * cell).sqrt();
            let v = Complex::from_polar(a, phase);
            c[q * nx + p] = v;
            let (pm, qm) = ((nx - p) % nx, (ny - q) % ny);
            c[qm * nx + pm] = v.conj();
        }
    }
    // slopes: d/dx multiplies by 2πi p / L
    let mut s: Vec<Complex<f64>> = c
        .iter()
        .enumerate()
        .map(|(k, v)| v * Complex::new(0.0, TAU * signed(k % nx, nx) / length_m))
        .collect();
    let mut planner = FftPlanner::<f64>::new();
    inverse_2d(&mut planner, &mut c, nx, ny);
    inverse_2d(&mut planner, &mut s, nx, ny);
    SurfaceGrid {
        x0_m: 0.0,
        dx_m: length_m / nx as f64,
        nx,
        y0_m: -width_m / 2.0,
        dy_m: width_m / ny as f64,
        ny,
        looped: true,
        periodic_y: true,
        z_m: c.iter().map(|v| v.re).collect(),
        dzdx: s.iter().map(|v| v.re).collect(),
        rows_y_m: Vec::new(),
        datum_m: 0.0,
        file_origin_m: (0.0, 0.0),
    }
}

/// In-place unscaled inverse 2D DFT of a row-major `ny × nx` array.
fn inverse_2d(planner: &mut FftPlanner<f64>, a: &mut [Complex<f64>], nx: usize, ny: usize) {
    let fx = planner.plan_fft_inverse(nx);
    fx.process(a);
    let fy = planner.plan_fft_inverse(ny);
    let mut col = vec![Complex::new(0.0, 0.0); ny];
    for p in 0..nx {
        for q in 0..ny {
            col[q] = a[q * nx + p];
        }
        fy.process(&mut col);
        for q in 0..ny {
            a[q * nx + p] = col[q];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The profiles along `x`, averaged over the rows, have the closed-form
    /// profile PSD of the isotropic extension (Parseval across `y` makes the
    /// average deterministic: only the spectrum's discretisation remains).
    #[test]
    fn profiles_have_the_isotropic_extension_of_the_class_psd() {
        let (class, band) = (RoadClass::C, (8.0, 120.0));
        let (len, wid) = (1.0, 0.6);
        let g = generate(class, 7, (len, wid), band);
        let (nx, ny) = (g.nx, g.ny);
        let mut planner = FftPlanner::<f64>::new();
        let f = planner.plan_fft_forward(nx);
        let mut mean_power = vec![0.0; nx];
        for j in 0..ny {
            let mut row: Vec<Complex<f64>> = g.z_m[j * nx..(j + 1) * nx]
                .iter()
                .map(|&z| Complex::new(z, 0.0))
                .collect();
            f.process(&mut row);
            for (m, v) in mean_power.iter_mut().zip(&row) {
                *m += (v / nx as f64).norm_sqr() / ny as f64;
            }
        }
        let dn = 1.0 / len;
        let mut checked = 0;
        for p in 1..nx / 2 {
            let n = p as f64 * dn;
            if !(20.0..=90.0).contains(&n) {
                continue;
            }
            let want = profile_psd_two_sided_m3(class, n, band);
            let got = mean_power[p] / dn;
            assert!(
                (got / want - 1.0).abs() < 0.03,
                "n = {n} cycles/m: PSD {got:e} vs {want:e} m³"
            );
            checked += 1;
        }
        assert!(checked > 60);
        // real, with exact slopes: against a centred difference of the
        // cubic interpolation at mid-cell
        let (z1, _) = g.sample(0.3 + 1e-6, 0.01).unwrap();
        let (z0, _) = g.sample(0.3 - 1e-6, 0.01).unwrap();
        let (_, d) = g.sample(0.3, 0.01).unwrap();
        let fd = (z1 - z0) / 2e-6;
        assert!(
            (fd - d).abs() < 1e-4 * d.abs().max(1e-3),
            "slope {d} vs difference {fd}"
        );
    }

    /// Reproducible by seed, different across seeds; the variance follows
    /// the class (a step of one class is four times the PSD).
    #[test]
    fn seeded_and_scaled_by_class() {
        let a = generate(RoadClass::B, 3, (0.5, 0.2), (10.0, 100.0));
        let b = generate(RoadClass::B, 3, (0.5, 0.2), (10.0, 100.0));
        let c = generate(RoadClass::B, 4, (0.5, 0.2), (10.0, 100.0));
        let d = generate(RoadClass::C, 3, (0.5, 0.2), (10.0, 100.0));
        assert_eq!(a, b);
        assert_ne!(a.z_m, c.z_m);
        let var = |g: &SurfaceGrid| g.z_m.iter().map(|z| z * z).sum::<f64>() / g.z_m.len() as f64;
        assert!((var(&d) / var(&a) - 4.0).abs() < 1e-9);
        // zero mean
        assert!(a.z_m.iter().sum::<f64>().abs() < 1e-12 * a.z_m.len() as f64);
    }

    #[test]
    fn the_profile_psd_closed_form_integrates_the_2d_psd() {
        let (class, band) = (RoadClass::D, (5.0, 50.0));
        for nx in [1.0f64, 4.99, 5.0, 20.0, 49.0] {
            // midpoint rule over n_y
            let m = 200_000;
            let top = (band.1 * band.1 - nx * nx).sqrt();
            let h = 2.0 * top / m as f64;
            let num: f64 = (0..m)
                .map(|k| {
                    let ny: f64 = -top + (k as f64 + 0.5) * h;
                    s2_m4(class, (nx * nx + ny * ny).sqrt(), band) * h
                })
                .sum();
            let want = profile_psd_two_sided_m3(class, nx, band);
            assert!(
                (num / want - 1.0).abs() < 2e-3,
                "n_x {nx}: {num:e} vs {want:e}"
            );
        }
        // without the band, S1 = Gd / 2
        let wide = (1e-9, 1e9);
        let n = 3.0;
        let got = profile_psd_two_sided_m3(class, n, wide);
        assert!((got / (class.gd_m3(n) / 2.0) - 1.0).abs() < 1e-6);
    }
}
