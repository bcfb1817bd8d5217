//! Tests of the kept inverse: updates against inverses formed afresh, the
//! kept system's residuals, refused updates and the lanes of the products.

use super::*;

/// A deterministic pseudo-random generator (xorshift) for test matrices.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// A non-symmetric matrix over `p` points with rows of very different
/// scales (end values ~1e-6, slopes ~1, as the contact system's), made
/// diagonally heavy so that every principal block system is regular.
fn system(p: usize, rng: &mut Rng) -> Vec<f64> {
    let n = 2 * p;
    let mut m = vec![0.0; n * n];
    for e in 0..n {
        let scale = if e % 2 == 0 { 1e-6 } else { 1.0 };
        for u in 0..n {
            m[e * n + u] = scale * (rng.next() + if e == u { 3.0 * n as f64 } else { 0.0 });
        }
        // the unknown pairs couple inside a point
        if e % 2 == 0 {
            m[e * n + e + 1] += scale * 2.0;
        }
    }
    m
}

/// The entries of the full system `m` (`2p` wide) by point and kind.
fn point_entry(m: &[f64], p: usize) -> impl Fn(usize, usize, usize, usize) -> f64 + '_ {
    move |i, r, j, c| m[(2 * i + r) * 2 * p + 2 * j + c]
}

/// The inverse by Gauss–Jordan with partial pivoting (the reference).
fn gauss_jordan(a: &[f64], n: usize) -> Vec<f64> {
    let mut a = a.to_vec();
    let mut inv = vec![0.0; n * n];
    for i in 0..n {
        inv[i * n + i] = 1.0;
    }
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| a[i * n + k].abs().total_cmp(&a[j * n + k].abs()))
            .unwrap();
        for c in 0..n {
            a.swap(k * n + c, p * n + c);
            inv.swap(k * n + c, p * n + c);
        }
        let piv = a[k * n + k];
        for c in 0..n {
            a[k * n + c] /= piv;
            inv[k * n + c] /= piv;
        }
        for r in 0..n {
            if r != k {
                let f = a[r * n + k];
                for c in 0..n {
                    a[r * n + c] -= f * a[k * n + c];
                    inv[r * n + c] -= f * inv[k * n + c];
                }
            }
        }
    }
    inv
}

/// The inverse's product takes rows four at a time; each row's value
/// must be bit for bit that of [`dot_lanes`] on the row alone, in the
/// dispatched build and the portable one, for every remainder of the
/// four rows and the eight lanes (a sum order changed by the blocking
/// fails it).
#[test]
fn rows_four_at_a_time_equal_each_row_alone_bit_for_bit() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for n in [1usize, 2, 7, 8, 9, 15, 16, 17, 31, 64, 67] {
        for rows in [1usize, 3, 4, 5, 8, 11] {
            // mixed scales: cancellation makes any reordering visible
            let a: Vec<f64> = (0..rows * n)
                .map(|k| rng.next() * 10f64.powi((k % 9) as i32 - 4))
                .collect();
            let b: Vec<f64> = (0..n)
                .map(|k| rng.next() * 10f64.powi((k % 5) as i32 - 2))
                .collect();
            let alone: Vec<u64> = a
                .chunks_exact(n)
                .map(|row| dot_lanes(row, &b).to_bits())
                .collect();
            let (mut x1, mut x2) = (vec![0.0; rows], vec![0.0; rows]);
            rows_times_dispatch(&a, &b, &mut x1);
            rows_times(&a, &b, &mut x2);
            let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&x1), alone, "dispatched, n {n}, rows {rows}");
            assert_eq!(bits(&x2), alone, "portable, n {n}, rows {rows}");
        }
    }
}

/// A join's `Y = r B`, four rows of `B` per pass, must be bit for bit
/// the sum one row at a time (each entry over the rows in order), for
/// every remainder of the four rows.
#[test]
fn join_rows_four_at_a_time_equal_one_row_at_a_time_bit_for_bit() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for n in [0usize, 1, 2, 3, 4, 5, 6, 7, 8, 9, 13, 30, 67] {
        let inv: Vec<f64> = (0..n * n)
            .map(|k| rng.next() * 10f64.powi((k % 9) as i32 - 4))
            .collect();
        let rb: Vec<f64> = (0..2 * n)
            .map(|k| rng.next() * 10f64.powi((k % 5) as i32 - 2))
            .collect();
        let (mut e0, mut e1) = (vec![0.0; n], vec![0.0; n]);
        for k in 0..n {
            for j in 0..n {
                e0[j] += rb[k] * inv[k * n + j];
                e1[j] += rb[n + k] * inv[k * n + j];
            }
        }
        let (mut y0, mut y1) = (vec![0.0; n], vec![0.0; n]);
        accumulate_rows(&inv, n, &rb, &mut y0, &mut y1);
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&y0), bits(&e0), "first row of Y, n {n}");
        assert_eq!(bits(&y1), bits(&e1), "second row of Y, n {n}");
    }
}

/// The backward error's row sums: the AVX build gives the plain lanes'
/// values bit for bit, and both are the left-to-right sum and
/// magnitude to round-off, for every remainder of the eight lanes.
#[test]
fn row_sums_and_magnitudes_in_lanes() {
    let mut rng = Rng(0x51_7cc1_b727_220a);
    for n in [0usize, 1, 3, 7, 8, 9, 15, 16, 17, 40, 67] {
        let a: Vec<f64> = (0..n)
            .map(|k| rng.next() * 10f64.powi((k % 9) as i32 - 4))
            .collect();
        let x: Vec<f64> = (0..n).map(|_| rng.next()).collect();
        let (s1, m1) = sum_and_magnitude(&a, &x);
        let (s2, m2) = sum_and_magnitude_lanes(&a, &x);
        assert_eq!(
            (s1.to_bits(), m1.to_bits()),
            (s2.to_bits(), m2.to_bits()),
            "n {n}"
        );
        let m: f64 = a.iter().zip(&x).map(|(p, q)| (p * q).abs()).sum();
        let s: f64 = a.iter().zip(&x).map(|(p, q)| p * q).sum();
        let tol = 2.0 * n as f64 * f64::EPSILON * m;
        assert!(
            (s1 - s).abs() <= tol && (m1 - m).abs() <= tol,
            "n {n}: {s1} {s}, {m1} {m}"
        );
    }
}

/// Joins and leaves in a random order over many sets: each updated
/// inverse solves its system with a backward error near round-off and
/// agrees with an inverse formed from scratch.
#[test]
fn updates_follow_joins_and_leaves() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for p in [1usize, 3, 8, 17] {
        let m = system(p, &mut rng);
        let mut inv = BorderedInverse::new(p);
        let mut set: Vec<usize> = Vec::new();
        for round in 0..6 * p {
            let out: Vec<usize> = (0..p).filter(|i| !set.contains(i)).collect();
            let join = set.is_empty() || (!out.is_empty() && rng.next() > -0.2);
            if join {
                let pt = out[((rng.next() + 1.0) * 0.5 * out.len() as f64) as usize % out.len()];
                assert!(inv.join(pt, point_entry(&m, p)), "p {p} round {round}");
                set.push(pt);
            } else {
                let k = ((rng.next() + 1.0) * 0.5 * set.len() as f64) as usize % set.len();
                assert!(inv.leave(k), "p {p} round {round}");
                set.remove(k);
            }
            assert_eq!(inv.points(), &set[..]);
            let n = 2 * set.len();
            if n == 0 {
                continue;
            }
            let b: Vec<f64> = (0..n).map(|_| rng.next()).collect();
            let mut x = vec![0.0; n];
            inv.solve(&b, &mut x);
            let be = inv.backward_error(&b, &x);
            let entry =
                |e: usize, u: usize| point_entry(&m, p)(set[e / 2], e % 2, set[u / 2], u % 2);
            assert!(be < 1e-12, "p {p}, round {round}: backward error {be:e}");
            let dense: Vec<f64> = (0..n * n).map(|k| entry(k / n, k % n)).collect();
            let reference = gauss_jordan(&dense, n);
            for (k, (a, r)) in inv.inv[..n * n].iter().zip(&reference).enumerate() {
                let scale = reference[(k / n) * n..(k / n + 1) * n]
                    .iter()
                    .fold(0.0f64, |s, v| s.max(v.abs()));
                assert!(
                    (a - r).abs() <= 1e-10 * scale,
                    "p {p}, round {round}, entry {k}: {a} vs {r}"
                );
            }
        }
    }
}

/// A leaving point whose block of the inverse is singular (the points
/// left would make a singular system: `det (M⁻¹)_kk = det M_rest /
/// det M`) is refused, and the inverse and the kept system left as
/// they were.
#[test]
fn a_singular_leave_is_refused() {
    // two points coupled only across: each one's own block is zero,
    // the system a permutation, its own inverse
    let m = [
        0.0, 0.0, 1.0, 0.0, //
        0.0, 0.0, 0.0, 1.0, //
        1.0, 0.0, 0.0, 0.0, //
        0.0, 1.0, 0.0, 0.0,
    ];
    let entry = point_entry(&m, 2);
    let mut inv = BorderedInverse::new(2);
    inv.set(&[0, 1], &m, &entry);
    assert!(!inv.leave(1));
    assert!(!inv.leave(0));
    assert_eq!(inv.points(), &[0, 1]);
    assert_eq!(inv.updates, 0);
    let b = [1.0, 2.0, 3.0, 4.0];
    let mut x = [0.0; 4];
    inv.solve(&b, &mut x);
    assert_eq!(x, [3.0, 4.0, 1.0, 2.0]);
    assert_eq!(inv.backward_error(&b, &x), 0.0);
    // (a wrong solution shows its residual: the kept system is whole)
    assert!(inv.backward_error(&b, &[3.0, 4.0, 1.0, 3.0]) > 0.1);
}

/// A joining point whose block makes the system singular is refused
/// and the inverse left as it was.
#[test]
fn a_singular_border_is_refused() {
    // two identical points: the second's rows and columns repeat the first's
    let m1 = [2.0, 1.0, 0.5, 3.0];
    let entry = |_: usize, r: usize, _: usize, c: usize| m1[r * 2 + c];
    let mut inv = BorderedInverse::new(2);
    assert!(inv.join(7, entry));
    assert!(!inv.join(8, entry));
    assert_eq!(inv.points(), &[7]);
    let mut x = [0.0; 2];
    inv.solve(&[2.0, 0.5], &mut x);
    assert!((x[0] - 1.0).abs() < 1e-15 && x[1].abs() < 1e-15, "{x:?}");
    // the kept system is still the one point's: the exact solution
    // has no residual, a wrong one the residual it should
    assert_eq!(inv.backward_error(&[2.0, 0.5], &[1.0, 0.0]), 0.0);
    let be = inv.backward_error(&[2.0, 0.5], &[1.0, 1.0]);
    // residuals (1, 3) against magnitudes (2 + 1 + 2, 0.5 + 3 + 0.5)
    assert!((be - 0.75).abs() < 1e-15, "{be}");
}
