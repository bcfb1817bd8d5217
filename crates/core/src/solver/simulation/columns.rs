//! Every point's response to the full-step Gauss-point forces of a set of
//! points, down their influence columns (`full_inf_cols`, method §4.3
//! step 3): `u_i += Σ_j (Gx1_ij q1_j + Gx2_ij q2_j)`,
//! `v_i += Σ_j (Gv1_ij q1_j + Gv2_ij q2_j)`.
//!
//! Summed column by column, every point's value is loaded and stored once
//! per source point. Here the points are taken in blocks of rows whose
//! sums stay in registers while the set's columns stream past: one load
//! and one store per point. Each point still adds its terms one source at
//! a time, in the order of the set, with the same operations (no FMA): the
//! values are those of the column-by-column sums, to the bit.

/// Point `j`'s four influence columns (`x1, x2, v1, v2`, `p` values each)
/// in `cols`.
#[inline(always)]
fn columns(cols: &[f64], p: usize, j: usize) -> &[f64] {
    &cols[4 * p * j..4 * p * (j + 1)]
}

/// `u += G_x1 q1 + G_x2 q2`, `v += G_v1 q1 + G_v2 q2` down one point's
/// four contiguous influence columns `c` (`x1, x2, v1, v2`, `p` values
/// each), for the rows `rows`.
#[inline(always)]
pub(super) fn column_response(
    c: &[f64],
    p: usize,
    rows: std::ops::Range<usize>,
    q1: f64,
    q2: f64,
    u: &mut [f64],
    v: &mut [f64],
) {
    let (gx1, rest) = c.split_at(p);
    let (gx2, rest) = rest.split_at(p);
    let (gv1, gv2) = rest.split_at(p);
    let (u, v) = (&mut u[..p], &mut v[..p]);
    for i in rows {
        u[i] += gx1[i] * q1 + gx2[i] * q2;
        v[i] += gv1[i] * q1 + gv2[i] * q2;
    }
}

/// Adds to every point's end displacement `u` (m) and velocity `v` (m/s)
/// the response to the full-step forces `q1[j]`, `q2[j]` (N, indexed by
/// point) of the points `set`, whose influence columns are in `cols`
/// (`4 p` values per point, [`columns`]). Each point sums the set's terms
/// in its order, as `set.len()` calls of [`column_response`] would.
pub(super) fn add_set_response(
    cols: &[f64],
    p: usize,
    set: &[usize],
    q1: &[f64],
    q2: &[f64],
    u: &mut [f64],
    v: &mut [f64],
) {
    let (u, v) = (&mut u[..p], &mut v[..p]);
    if set.is_empty() {
        return;
    }
    // (every column, force and output checked once: the lanes read
    // unchecked)
    assert!(
        set.iter().all(|&j| {
            (j + 1)
                .checked_mul(4 * p)
                .is_some_and(|end| end <= cols.len())
                && j < q1.len()
                && j < q2.len()
        }),
        "a point of the set without influence columns or forces"
    );
    // the rows in whole blocks of four in AVX lanes where the CPU has it,
    // then the rest (every row without it) column by column
    #[cfg(target_arch = "x86_64")]
    let done = if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: the CPU supports AVX (checked just above); every index
        // was checked against its slice above, and the set is not empty.
        unsafe { set_response_avx(cols, p, set, q1, q2, u, v) }
    } else {
        0
    };
    #[cfg(not(target_arch = "x86_64"))]
    let done = 0;
    for &j in set {
        column_response(columns(cols, p, j), p, done..p, q1[j], q2[j], u, v);
    }
}

/// [`add_set_response`] for the rows in whole blocks of four, in AVX
/// lanes: blocks of 16 rows, then of 4, each block's sums in registers
/// over the whole set. Returns the rows done (a multiple of four); the
/// last `p % 4` are the caller's.
///
/// # Safety
///
/// The CPU supports AVX; `u`, `v` hold `p` values; `set` is not empty and
/// every `j` of it has its columns in `cols` (`4 p (j + 1) <= cols.len()`)
/// and its forces in `q1`, `q2`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn set_response_avx(
    cols: &[f64],
    p: usize,
    set: &[usize],
    q1: &[f64],
    q2: &[f64],
    u: &mut [f64],
    v: &mut [f64],
) -> usize {
    let mut i = 0;
    while i + 16 <= p {
        // SAFETY: the caller's bounds; rows i..i + 16 are below p.
        unsafe { block_avx::<4>(cols, p, i, set, q1, q2, u, v) };
        i += 16;
    }
    while i + 4 <= p {
        // SAFETY: as above, rows i..i + 4.
        unsafe { block_avx::<1>(cols, p, i, set, q1, q2, u, v) };
        i += 4;
    }
    i
}

/// Rows `i .. i + 4 L` of [`add_set_response`], their sums in `2 L`
/// registers.
///
/// # Safety
///
/// As [`set_response_avx`], and `i + 4 L <= p`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[allow(clippy::too_many_arguments)]
unsafe fn block_avx<const L: usize>(
    cols: &[f64],
    p: usize,
    i: usize,
    set: &[usize],
    q1: &[f64],
    q2: &[f64],
    u: &mut [f64],
    v: &mut [f64],
) {
    use std::arch::x86_64::*;
    // SAFETY (the whole body): rows i..i + 4L are below p, so within `u`,
    // `v` and within each point's four columns of `p` values; the caller
    // checked every j of `set` against `cols`, `q1` and `q2`.
    unsafe {
        let (up, vp) = (u.as_mut_ptr().add(i), v.as_mut_ptr().add(i));
        let mut su: [__m256d; L] = std::array::from_fn(|l| _mm256_loadu_pd(up.add(4 * l)));
        let mut sv: [__m256d; L] = std::array::from_fn(|l| _mm256_loadu_pd(vp.add(4 * l)));
        let base = cols.as_ptr().add(i);
        for &j in set {
            let c = base.add(4 * p * j);
            let (a, b) = (
                _mm256_set1_pd(*q1.get_unchecked(j)),
                _mm256_set1_pd(*q2.get_unchecked(j)),
            );
            for l in 0..L {
                let o = 4 * l;
                let du = _mm256_add_pd(
                    _mm256_mul_pd(_mm256_loadu_pd(c.add(o)), a),
                    _mm256_mul_pd(_mm256_loadu_pd(c.add(p + o)), b),
                );
                let dv = _mm256_add_pd(
                    _mm256_mul_pd(_mm256_loadu_pd(c.add(2 * p + o)), a),
                    _mm256_mul_pd(_mm256_loadu_pd(c.add(3 * p + o)), b),
                );
                su[l] = _mm256_add_pd(su[l], du);
                sv[l] = _mm256_add_pd(sv[l], dv);
            }
        }
        for l in 0..L {
            _mm256_storeu_pd(up.add(4 * l), su[l]);
            _mm256_storeu_pd(vp.add(4 * l), sv[l]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Values spread over many binades with both signs (round-off in every
    /// sum), reproducible from `seed`.
    fn values(n: usize, seed: u64) -> Vec<f64> {
        let mut s = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (0..n)
            .map(|_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let m = (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                let e = ((s >> 3) % 40) as i32 - 20;
                m * 2f64.powi(e)
            })
            .collect()
    }

    proptest! {
        /// The blocked sums equal the column-by-column ones to the bit, for
        /// any number of points (blocks of 16, of 4 and a scalar rest) and
        /// any set, repeated points and an empty set included.
        #[test]
        fn blocks_sum_as_the_columns_do(
            p in 1usize..41,
            picks in proptest::collection::vec(0usize..1000, 0..30),
            seed in any::<u64>(),
        ) {
            let set: Vec<usize> = picks.iter().map(|k| k % p).collect();
            let cols = values(4 * p * p, seed);
            let (q1, q2) = (values(p, seed ^ 1), values(p, seed ^ 2));
            let (u0, v0) = (values(p, seed ^ 3), values(p, seed ^ 4));
            let (mut u, mut v) = (u0.clone(), v0.clone());
            add_set_response(&cols, p, &set, &q1, &q2, &mut u, &mut v);
            // (where the CPU has AVX, its lanes took the whole blocks)
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx") && !set.is_empty() {
                let (mut ua, mut va) = (u0.clone(), v0.clone());
                // SAFETY: AVX is there; the lengths are those
                // `add_set_response` checked just above.
                let done =
                    unsafe { set_response_avx(&cols, p, &set, &q1, &q2, &mut ua, &mut va) };
                prop_assert_eq!(done, p - p % 4);
                for i in 0..done {
                    prop_assert_eq!(ua[i].to_bits(), u[i].to_bits());
                    prop_assert_eq!(va[i].to_bits(), v[i].to_bits());
                }
            }
            let (mut uc, mut vc) = (u0, v0);
            for &j in &set {
                column_response(columns(&cols, p, j), p, 0..p, q1[j], q2[j], &mut uc, &mut vc);
            }
            for i in 0..p {
                prop_assert_eq!(u[i].to_bits(), uc[i].to_bits(), "u at row {} of {}", i, p);
                prop_assert_eq!(v[i].to_bits(), vc[i].to_bits(), "v at row {} of {}", i, p);
            }
        }
    }

    /// A set naming a point without columns is refused, not read past.
    #[test]
    #[should_panic(expected = "without influence columns")]
    fn a_point_without_columns_is_refused() {
        let p = 8;
        let cols = vec![0.0; 4 * p * 2];
        let (q, mut u, mut v) = (vec![1.0; p], vec![0.0; p], vec![0.0; p]);
        add_set_response(&cols, p, &[2], &q, &q, &mut u, &mut v);
    }
}
