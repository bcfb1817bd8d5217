//! A known six-mode model (52 to 959 Hz, three nodes) and its FRFs written
//! as UFF 58 files: the frequency-domain fit's tests (`identify
//! frf_fit`, `cli frf_fit`).

use faer::c64;
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use tirecontact::model::lscf::Ordinate;

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

/// An ASCII dataset 58 of an FRF (complex double), response and
/// reference `(node, direction)`, numerator specific data type `num`
/// (8, 11, 12) in SI, values at `f0 + k df`.
pub fn uff58(
    resp: (i64, i64),
    refn: (i64, i64),
    num: i64,
    f0: f64,
    df: f64,
    vals: &[c64],
) -> String {
    let units = match num {
        8 => "m",
        11 => "m/s",
        _ => "m/s^2",
    };
    let mut s = String::from("    -1\n    58\n");
    for k in 1..=5 {
        s.push_str(&format!("ID line {k}\n"));
    }
    s.push_str(&format!(
        "{:>5}{:>10}{:>5}{:>10} {:<10}{:>10}{:>4} {:<10}{:>10}{:>4}\n",
        4, 1, 0, 0, "TYRE", resp.0, resp.1, "TYRE", refn.0, refn.1
    ));
    s.push_str(&format!(
        "{:>10}{:>10}{:>10}{:>13.5E}{:>13.5E}{:>13.5E}\n",
        6,
        vals.len(),
        1,
        f0,
        df,
        0.0
    ));
    for (t, label) in [(18, "Hz"), (num, units), (13, "N"), (0, "NONE")] {
        s.push_str(&format!(
            "{t:>10}{:>5}{:>5}{:>5} {:<20} {label:<20}\n",
            0, 0, 0, "NONE"
        ));
    }
    for chunk in vals.chunks(2) {
        for v in chunk {
            s.push_str(&format!("{:>20.12E}{:>20.12E}", v.re, v.im));
        }
        s.push('\n');
    }
    s.push_str("    -1\n");
    s
}

/// Writes a UFF file of `pairs` (points 0, 1, 2 = nodes 1, 2, 3 +Z) of
/// SIX over 0–1000 Hz every 1 Hz, each mode's share of a pair times
/// `sign(i, j, mode)`, each value times `1 + noise·(n₁ + j n₂)` (`n` of a
/// seeded generator, uniform in `[−√3, √3]`).
pub fn write_uff(
    dir: &Path,
    name: &str,
    pairs: &[(usize, usize)],
    q: Ordinate,
    noise: f64,
    sign: impl Fn(usize, usize, usize) -> f64,
) -> PathBuf {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut n = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        noise * 3f64.sqrt() * (2.0 * (state >> 11) as f64 / (1u64 << 53) as f64 - 1.0)
    };
    let num = [8, 11, 12][q.power() as usize];
    let mut text = String::new();
    for &(i, j) in pairs {
        let vals: Vec<c64> = (0..=1000)
            .map(|k| {
                let f = k as f64;
                if k == 0 {
                    return c64::new(0.0, 0.0);
                }
                SIX.iter()
                    .enumerate()
                    .map(|(m, mode)| frf(std::slice::from_ref(mode), i, j, f, q) * sign(i, j, m))
                    .sum::<c64>()
                    * c64::new(1.0 + n(), n())
            })
            .collect();
        text.push_str(&uff58(
            (i as i64 + 1, 3),
            (j as i64 + 1, 3),
            num,
            0.0,
            1.0,
            &vals,
        ));
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}
