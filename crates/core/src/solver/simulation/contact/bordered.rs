//! The explicit inverse of a contact system kept up to date as points join
//! or leave it (method §4.5, "Updates"): a point is a block of two
//! equations (end value, slope) and two unknowns (`q1`, `q2`), so a point
//! joining borders the matrix with two rows and columns and a point leaving
//! removes them. With the inverse `B = M⁻¹` of the `n × n` system `M`:
//!
//! ```text
//! joining:  M' = [M c; r d],  X = B c,  Y = r B,  Z = (d - r X)⁻¹   (2 × 2)
//!           M'⁻¹ = [B + X Z Y, -X Z; -Z Y, Z]
//! leaving:  M'⁻¹ = B_kk - B_kr (B_rr)⁻¹ B_rk    (r: the two removed indices)
//! ```
//!
//! Each costs `O(n²)` against `O(n³)` for a new factorisation and inverse.
//! The matrix is general (the rows of end values and slopes make it
//! non-symmetric). Round-off grows with each update: the caller checks the
//! residual of its solves ([`BorderedInverse::backward_error`]) and
//! refactorises from scratch when it grows. For that check the system
//! itself is kept beside its inverse, in slot order, bordered and shrunk
//! with it (`O(n)` a join, `O(n²)` moves a leave), so that a residual reads
//! contiguous rows rather than gathering each entry from the tables.

use crate::base::threads::Threads;
use std::sync::atomic::{AtomicU64, Ordering};

/// Unknowns (and equations) per point.
const B: usize = 2;

/// The inverse of a system of 2 × 2 point blocks, in slot order: slot `a`
/// holds unknowns `2a`, `2a + 1` and equations `2a`, `2a + 1` of one point.
#[derive(Debug, Clone)]
pub struct BorderedInverse {
    cap: usize,
    /// The point of each slot.
    points: Vec<usize>,
    /// `M⁻¹`, `n × n` row-major with `n = 2 slots`.
    inv: Vec<f64>,
    /// The next inverse, built beside the current one and swapped in.
    next: Vec<f64>,
    /// `X = B c` (`n × 2`, column-major) and `Y = r B` (`2 × n`).
    x: Vec<f64>,
    y: Vec<f64>,
    /// The border: the new unknowns' columns `c` and equations' rows `r`.
    cb: Vec<f64>,
    rb: Vec<f64>,
    /// `M` itself in slot order, row-major with row stride `cap` (a join
    /// writes its border in place).
    mat: Vec<f64>,
    /// Updates since the inverse was last formed from a factorisation.
    pub updates: usize,
}

/// Inverse of a 2 × 2 matrix `[a b; c d]`, `None` when its determinant is
/// not finite or negligible against `scale²` (relative `1e-12`; `scale`:
/// the size of the entries the matrix was computed from, so that a
/// difference of equal blocks, zero up to round-off, counts as singular).
fn inverse2(m: [f64; 4], scale: f64) -> Option<[f64; 4]> {
    let det = m[0] * m[3] - m[1] * m[2];
    let scale = scale.max(m.iter().fold(0.0f64, |a, v| a.max(v.abs())));
    if !det.is_finite() || det.abs() <= 1e-12 * scale * scale || det == 0.0 {
        return None;
    }
    Some([m[3] / det, -m[1] / det, -m[2] / det, m[0] / det])
}

/// [`inverse2`] of a Schur complement `s`, each entry computed from terms
/// of size `scale`: singular when the complement's determinant, with rows
/// and columns scaled by `scale`, is negligible.
fn inverse2_scaled(s: [f64; 4], scale: [f64; 4]) -> Option<[f64; 4]> {
    // row scales from the diagonal terms' sizes (entries of a row share units)
    let (r0, r1) = (scale[0].max(scale[1]), scale[2].max(scale[3]));
    if !(r0 > 0.0 && r1 > 0.0) {
        return None;
    }
    let m = [s[0] / r0, s[1] / r0, s[2] / r1, s[3] / r1];
    let z = inverse2(m, 1.0)?;
    // (D s)⁻¹ = s⁻¹ D⁻¹: columns of z scaled by the row scales
    Some([z[0] / r0, z[1] / r1, z[2] / r0, z[3] / r1])
}

impl BorderedInverse {
    /// Buffers for up to `cap_points` points.
    pub fn new(cap_points: usize) -> Self {
        let cap = B * cap_points;
        BorderedInverse {
            cap,
            points: Vec::with_capacity(cap_points),
            inv: vec![0.0; cap * cap],
            next: vec![0.0; cap * cap],
            x: vec![0.0; cap * B],
            y: vec![0.0; cap * B],
            cb: vec![0.0; cap * B],
            rb: vec![0.0; cap * B],
            mat: vec![0.0; cap * cap],
            updates: 0,
        }
    }

    /// The points in slot order.
    pub fn points(&self) -> &[usize] {
        &self.points
    }

    /// The system's size `2 × slots`.
    pub fn n(&self) -> usize {
        B * self.points.len()
    }

    /// Entry `(r, c)` of the inverse `M⁻¹` (slot order): column `c` is
    /// `M⁻¹ e_c`, read where a solve would sum it.
    #[inline]
    pub fn inverse_entry(&self, r: usize, c: usize) -> f64 {
        self.inv[r * self.n() + c]
    }

    /// Sets the inverse of the system of `points` from `inv` (`n × n`
    /// row-major, in slot order: a new factorisation's); `entry` as for
    /// [`BorderedInverse::join`] gives the system it inverts.
    pub fn set(
        &mut self,
        points: &[usize],
        inv: &[f64],
        entry: impl Fn(usize, usize, usize, usize) -> f64,
    ) {
        let n = B * points.len();
        assert!(n <= self.cap, "contact system larger than its buffers");
        self.points.clear();
        self.points.extend_from_slice(points);
        self.inv[..n * n].copy_from_slice(&inv[..n * n]);
        let cap = self.cap;
        for e in 0..n {
            for (u, m) in self.mat[e * cap..e * cap + n].iter_mut().enumerate() {
                *m = entry(points[e / B], e % B, points[u / B], u % B);
            }
        }
        self.updates = 0;
    }

    /// Empties the system.
    pub fn clear(&mut self) {
        self.points.clear();
        self.updates = 0;
    }

    /// Adds `point` as the last slot. `entry(i, r, j, c)` gives the matrix
    /// entry of equation `r` (0: end value, 1: slope) of point `i` and
    /// unknown `c` (0: `q1`, 1: `q2`) of point `j`. `false` (nothing
    /// changed) when the new pivot block is singular.
    pub fn join(
        &mut self,
        point: usize,
        entry: impl Fn(usize, usize, usize, usize) -> f64,
    ) -> bool {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                #[target_feature(enable = "avx2")]
                fn wide(
                    inv: &mut BorderedInverse,
                    point: usize,
                    entry: impl Fn(usize, usize, usize, usize) -> f64,
                ) -> bool {
                    inv.join_body(point, entry)
                }
                // SAFETY: the CPU supports AVX2 (checked just above).
                return unsafe { wide(self, point, entry) };
            }
        }
        self.join_body(point, entry)
    }

    /// [`BorderedInverse::join`]'s work, built once for the baseline CPU
    /// and once with AVX2 (the element-wise updates in four lanes, `X` in
    /// [`dot_lanes`]' lanes, the other sums in order: no FMA, the same
    /// values to the bit either way).
    #[inline(always)]
    fn join_body(
        &mut self,
        point: usize,
        entry: impl Fn(usize, usize, usize, usize) -> f64,
    ) -> bool {
        let n = self.n();
        let m = n + B;
        assert!(m <= self.cap, "contact system larger than its buffers");
        let pts = &self.points;
        // the border: columns c (new unknowns) and rows r (new equations)
        let (cb, rb) = (&mut self.cb[..B * n], &mut self.rb[..B * n]);
        for k in 0..n {
            for t in 0..B {
                cb[t * n + k] = entry(pts[k / B], k % B, point, t);
                rb[t * n + k] = entry(point, t, pts[k / B], k % B);
            }
        }
        let d = |r: usize, c: usize| entry(point, r, point, c);
        let inv = &self.inv[..n * n];
        // X = B c (column-major; each entry in the lanes of `dot_lanes`,
        // rows four at a time), Y = r B
        let (x, y) = (&mut self.x[..n * B], &mut self.y[..B * n]);
        let (c0, c1) = cb.split_at(n);
        let (x0, x1) = x.split_at_mut(n);
        rows_times_dispatch(inv, c0, x0);
        rows_times_dispatch(inv, c1, x1);
        y.fill(0.0);
        let (y0, y1) = y.split_at_mut(n);
        accumulate_rows(inv, n, rb, y0, y1);
        // Schur complement d - r X
        let mut s = [0.0; 4];
        for r in 0..B {
            for c in 0..B {
                let rx: f64 = (0..n).map(|k| rb[r * n + k] * x[c * n + k]).sum();
                s[r * B + c] = d(r, c) - rx;
            }
        }
        // (each entry of `s` against the size of the products it sums)
        let mut scale = [0.0f64; 4];
        for r in 0..B {
            for c in 0..B {
                let rx: f64 = (0..n).map(|k| (rb[r * n + k] * x[c * n + k]).abs()).sum();
                scale[r * B + c] = d(r, c).abs() + rx;
            }
        }
        let Some(z) = inverse2_scaled(s, scale) else {
            return false;
        };
        // Z Y (2 × n) into `y` in place, X Z columns computed on the fly
        let next = &mut self.next[..m * m];
        for i in 0..n {
            // row i of X Z
            let (x0, x1) = (x[i], x[n + i]);
            let xz = [x0 * z[0] + x1 * z[2], x0 * z[1] + x1 * z[3]];
            let (dst, src) = (&mut next[i * m..i * m + n], &inv[i * n..(i + 1) * n]);
            let (y0, y1) = y.split_at(n);
            for (((d, &s), &a), &b) in dst.iter_mut().zip(src).zip(y0).zip(y1) {
                *d = s + xz[0] * a + xz[1] * b;
            }
            next[i * m + n] = -xz[0];
            next[i * m + n + 1] = -xz[1];
        }
        for r in 0..B {
            let (y0, y1) = y.split_at(n);
            let row = &mut next[(n + r) * m..(n + r + 1) * m];
            for j in 0..n {
                row[j] = -(z[r * B] * y0[j] + z[r * B + 1] * y1[j]);
            }
            row[n] = z[r * B];
            row[n + 1] = z[r * B + 1];
        }
        std::mem::swap(&mut self.inv, &mut self.next);
        // the border of the system itself
        let cap = self.cap;
        for t in 0..B {
            for k in 0..n {
                self.mat[k * cap + n + t] = cb[t * n + k];
            }
            let row = &mut self.mat[(n + t) * cap..(n + t) * cap + m];
            row[..n].copy_from_slice(&rb[t * n..(t + 1) * n]);
            for c in 0..B {
                row[n + c] = d(t, c);
            }
        }
        self.points.push(point);
        self.updates += 1;
        true
    }

    /// Removes slot `k`; the slots after it move down by one. `false`
    /// (nothing changed) when its block of the inverse is singular.
    pub fn leave(&mut self, k: usize) -> bool {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                #[target_feature(enable = "avx2")]
                fn wide(inv: &mut BorderedInverse, k: usize) -> bool {
                    inv.leave_body(k)
                }
                // SAFETY: the CPU supports AVX2 (checked just above).
                return unsafe { wide(self, k) };
            }
        }
        self.leave_body(k)
    }

    /// [`BorderedInverse::leave`]'s work (built as [`Self::join_body`]).
    #[inline(always)]
    fn leave_body(&mut self, k: usize) -> bool {
        let n = self.n();
        let m = n - B;
        let inv = &self.inv[..n * n];
        let (r0, r1) = (B * k, B * k + 1);
        let block = [
            inv[r0 * n + r0],
            inv[r0 * n + r1],
            inv[r1 * n + r0],
            inv[r1 * n + r1],
        ];
        let Some(z) = inverse2(block, 0.0) else {
            return false;
        };
        let next = &mut self.next[..m * m];
        let keep = |i: usize| if i < r0 { i } else { i + B };
        for i in 0..m {
            let src = &inv[keep(i) * n..(keep(i) + 1) * n];
            // (B_kr Z) for this row
            let (a0, a1) = (src[r0], src[r1]);
            let w = [a0 * z[0] + a1 * z[2], a0 * z[1] + a1 * z[3]];
            let (c0, c1) = (&inv[r0 * n..(r0 + 1) * n], &inv[r1 * n..(r1 + 1) * n]);
            let dst = &mut next[i * m..(i + 1) * m];
            // the columns before the slot and after it (`keep`), as two
            // plain runs the compiler puts in vector lanes
            let (d0, d1) = dst.split_at_mut(r0);
            for (lo, hi, run) in [(0, r0, d0), (r0 + B, n, d1)] {
                let (s, a, b) = (&src[lo..hi], &c0[lo..hi], &c1[lo..hi]);
                for (((o, &s), &a), &b) in run.iter_mut().zip(s).zip(a).zip(b) {
                    *o = s - (w[0] * a + w[1] * b);
                }
            }
        }
        std::mem::swap(&mut self.inv, &mut self.next);
        // the system without the slot's rows and columns, moved up in place
        let cap = self.cap;
        for i in 0..m {
            let from = keep(i) * cap;
            let to = i * cap;
            if from != to {
                self.mat.copy_within(from..from + r0, to);
            }
            self.mat.copy_within(from + r0 + B..from + n, to + r0);
        }
        self.points.remove(k);
        self.updates += 1;
        true
    }

    /// `x ← M⁻¹ b` (slot order), `b` and `x` of length `n`.
    pub fn solve(&self, b: &[f64], x: &mut [f64]) {
        let n = self.n();
        rows_times_dispatch(&self.inv[..n * n], &b[..n], &mut x[..n]);
    }

    /// [`BorderedInverse::solve`] on `threads` when it pays
    /// ([`Threads::worth`]), split by rows of the inverse into contiguous
    /// ranges: each row's product is the same whatever the range, so the
    /// result is the same for any number of threads.
    pub fn solve_on(&self, b: &[f64], x: &mut [f64], threads: &Threads) {
        let n = self.n();
        if !threads.worth(n * n) {
            return self.solve(b, x);
        }
        let (inv, b) = (&self.inv[..n * n], &b[..n]);
        threads.split(n, ROW_ALIGN, [(x, 1)], |r, [x]| {
            rows_times_dispatch(&inv[r.start * n..r.end * n], b, x)
        });
    }

    /// The componentwise backward error of a solution `x` of `M x = b`,
    /// `max_e |b_e - (M x)_e| / (Σ_u |M_eu x_u| + |b_e|)` (about the
    /// unit round-off times a small factor for a backward-stable solve),
    /// from the kept system's rows.
    pub fn backward_error(&self, b: &[f64], x: &[f64]) -> f64 {
        self.rows_backward_error(b, x, 0..self.n())
    }

    /// [`BorderedInverse::backward_error`] on `threads` when it pays
    /// ([`Threads::worth`]), the equations split into contiguous ranges:
    /// each range's largest error is computed as on one thread and the
    /// largest of them taken (a maximum, exact in any order), so the
    /// result is the same for any number of threads.
    pub fn backward_error_on(&self, b: &[f64], x: &[f64], threads: &Threads) -> f64 {
        let n = self.n();
        if !threads.worth(n * n) {
            return self.backward_error(b, x);
        }
        // (a non-negative f64's bits order as the values do)
        let worst = AtomicU64::new(0);
        threads.run(&|k| {
            let r = Threads::part_range(n, threads.count(), ROW_ALIGN, k);
            let w = self.rows_backward_error(b, x, r);
            worst.fetch_max(w.to_bits(), Ordering::Relaxed);
        });
        f64::from_bits(worst.into_inner())
    }

    /// The largest componentwise backward error of the equations `rows`
    /// ([`BorderedInverse::backward_error`]; 0 for none), each row's sum and
    /// magnitude by [`sum_and_magnitude`].
    fn rows_backward_error(&self, b: &[f64], x: &[f64], rows: std::ops::Range<usize>) -> f64 {
        let (n, cap) = (self.n(), self.cap);
        let x = &x[..n];
        let mut worst = 0.0f64;
        for e in rows {
            let (s, m) = sum_and_magnitude(&self.mat[e * cap..e * cap + n], x);
            worst = worst.max(row_backward_error(b[e], s, b[e].abs() + m));
        }
        worst
    }
}

/// `(Σ a_k x_k, Σ |a_k x_k|)` in eight interleaved partial sums each
/// (vector lanes): by [`sum_and_magnitude_avx`] where the CPU has AVX, the
/// same operations in the same order either way.
#[inline]
fn sum_and_magnitude(a: &[f64], x: &[f64]) -> (f64, f64) {
    assert_eq!(a.len(), x.len());
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU supports AVX (checked just above); the
            // lengths are equal (asserted above).
            return unsafe { sum_and_magnitude_avx(a, x) };
        }
    }
    sum_and_magnitude_lanes(a, x)
}

/// [`sum_and_magnitude`] in plain code: lanes `k` and `k + 4` of each
/// group of eight terms, the lanes then summed as [`dot_lanes`] sums its.
#[inline]
fn sum_and_magnitude_lanes(a: &[f64], x: &[f64]) -> (f64, f64) {
    const L: usize = 8;
    let (mut s, mut m) = ([0.0f64; L], [0.0f64; L]);
    let (ca, cx) = (a.chunks_exact(L), x.chunks_exact(L));
    let (ra, rx) = (ca.remainder(), cx.remainder());
    for (p, q) in ca.zip(cx) {
        for k in 0..L {
            let t = p[k] * q[k];
            s[k] += t;
            m[k] += t.abs();
        }
    }
    let fold = |v: [f64; L]| ((v[0] + v[4]) + (v[1] + v[5])) + ((v[2] + v[6]) + (v[3] + v[7]));
    let (mut ts, mut tm) = (0.0, 0.0);
    for (p, q) in ra.iter().zip(rx) {
        let t = p * q;
        ts += t;
        tm += t.abs();
    }
    (fold(s) + ts, fold(m) + tm)
}

/// [`sum_and_magnitude_lanes`] with AVX registers (no FMA: bit-identical).
///
/// # Safety
/// The CPU supports AVX; `a.len() == x.len()`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn sum_and_magnitude_avx(a: &[f64], x: &[f64]) -> (f64, f64) {
    use std::arch::x86_64::*;
    let n = a.len();
    let full = n - n % 8;
    let (ap, xp) = (a.as_ptr(), x.as_ptr());
    let sign = _mm256_set1_pd(-0.0);
    let (mut s0, mut s1) = (_mm256_setzero_pd(), _mm256_setzero_pd());
    let (mut m0, mut m1) = (_mm256_setzero_pd(), _mm256_setzero_pd());
    let mut c = 0;
    // SAFETY (all loads): c + 8 <= full <= n for both slices.
    unsafe {
        while c < full {
            let t0 = _mm256_mul_pd(_mm256_loadu_pd(ap.add(c)), _mm256_loadu_pd(xp.add(c)));
            let t1 = _mm256_mul_pd(
                _mm256_loadu_pd(ap.add(c + 4)),
                _mm256_loadu_pd(xp.add(c + 4)),
            );
            s0 = _mm256_add_pd(s0, t0);
            s1 = _mm256_add_pd(s1, t1);
            m0 = _mm256_add_pd(m0, _mm256_andnot_pd(sign, t0));
            m1 = _mm256_add_pd(m1, _mm256_andnot_pd(sign, t1));
            c += 8;
        }
    }
    let fold = |lo: __m256d, hi: __m256d| {
        let (mut l, mut h) = ([0.0f64; 4], [0.0f64; 4]);
        // SAFETY: `l`, `h` hold four f64.
        unsafe {
            _mm256_storeu_pd(l.as_mut_ptr(), lo);
            _mm256_storeu_pd(h.as_mut_ptr(), hi);
        }
        ((l[0] + h[0]) + (l[1] + h[1])) + ((l[2] + h[2]) + (l[3] + h[3]))
    };
    let (mut ts, mut tm) = (0.0, 0.0);
    for (p, q) in a[full..].iter().zip(&x[full..]) {
        let t = p * q;
        ts += t;
        tm += t.abs();
    }
    (fold(s0, s1) + ts, fold(m0, m1) + tm)
}

/// One equation's componentwise backward error: its residual `|b_e - s|`
/// against `mag = Σ_u |M_eu x_u| + |b_e|` (0 without a residual, infinite
/// for a residual over nothing).
#[inline]
pub(crate) fn row_backward_error(b_e: f64, s: f64, mag: f64) -> f64 {
    let r = (b_e - s).abs();
    if r > 0.0 {
        if mag > 0.0 { r / mag } else { f64::INFINITY }
    } else {
        0.0
    }
}

/// Rows of the inverse per range of a threaded [`BorderedInverse::solve_on`]
/// (a cache line of the solution).
const ROW_ALIGN: usize = 8;

/// `x_i = a_i · b` for the rows `a_i` of `a` (`x.len()` rows of `b.len()`),
/// each in [`dot_lanes`]' order: by [`rows_times_avx`] where the CPU has
/// AVX (four rows at a time), else [`rows_times`]. The same operations
/// either way: bit-identical.
#[inline]
fn rows_times_dispatch(a: &[f64], b: &[f64], x: &mut [f64]) {
    assert!(a.len() >= x.len() * b.len());
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU supports AVX (checked just above); `a` holds
            // `x.len()` rows of `b.len()` (asserted above).
            unsafe { rows_times_avx(a, b, x) };
            return;
        }
    }
    rows_times(a, b, x)
}

/// `x_i = a_i · b` row by row, each by [`dot_lanes`].
#[inline]
fn rows_times(a: &[f64], b: &[f64], x: &mut [f64]) {
    for (xi, row) in x.iter_mut().zip(a.chunks_exact(b.len().max(1))) {
        *xi = dot_lanes(row, b);
    }
}

/// [`rows_times`] with AVX lanes, four rows at a time: the eight partial
/// sums of [`dot_lanes`] are two registers per row, so each load of `b`
/// serves four rows and the eight accumulations are independent chains.
/// Same operations in the same order as [`dot_lanes`] (no FMA):
/// bit-identical.
///
/// # Safety
/// The CPU supports AVX; `a.len() >= x.len() * b.len()`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn rows_times_avx(a: &[f64], b: &[f64], x: &mut [f64]) {
    use std::arch::x86_64::*;
    const R: usize = 4;
    let n = b.len();
    let m = n - n % 8;
    let sum = |lo: __m256d, hi: __m256d, row: &[f64]| {
        let (mut l, mut h) = ([0.0f64; 4], [0.0f64; 4]);
        // SAFETY: `l`, `h` hold four f64.
        unsafe {
            _mm256_storeu_pd(l.as_mut_ptr(), lo);
            _mm256_storeu_pd(h.as_mut_ptr(), hi);
        }
        let mut tail = 0.0;
        for (p, q) in row[m..n].iter().zip(&b[m..n]) {
            tail += p * q;
        }
        ((l[0] + h[0]) + (l[1] + h[1])) + ((l[2] + h[2]) + (l[3] + h[3])) + tail
    };
    let full = x.len() - x.len() % R;
    let bp = b.as_ptr();
    let mut i = 0;
    while i < full {
        let mut lo = [_mm256_setzero_pd(); R];
        let mut hi = [_mm256_setzero_pd(); R];
        // SAFETY (all loads): c + 8 <= m <= n; rows i..i + R of `a` exist
        // (the caller's contract).
        unsafe {
            let base: [*const f64; R] = std::array::from_fn(|r| a.as_ptr().add((i + r) * n));
            let mut c = 0;
            while c < m {
                let (b0, b1) = (_mm256_loadu_pd(bp.add(c)), _mm256_loadu_pd(bp.add(c + 4)));
                for r in 0..R {
                    let a0 = _mm256_loadu_pd(base[r].add(c));
                    let a1 = _mm256_loadu_pd(base[r].add(c + 4));
                    lo[r] = _mm256_add_pd(lo[r], _mm256_mul_pd(a0, b0));
                    hi[r] = _mm256_add_pd(hi[r], _mm256_mul_pd(a1, b1));
                }
                c += 8;
            }
        }
        for r in 0..R {
            x[i + r] = sum(lo[r], hi[r], &a[(i + r) * n..(i + r + 1) * n]);
        }
        i += R;
    }
    for k in full..x.len() {
        x[k] = dot_lanes(&a[k * n..(k + 1) * n], b);
    }
}

/// `Y = r B` of a join: `y0[j] += r0[k] B[k][j]`, `y1[j] += r1[k] B[k][j]`
/// over the rows `k` of the `n × n` row-major `inv` (`rb`: `r0` then `r1`,
/// `n` each), each entry summed over `k` in row order. Four rows per pass
/// over `y0`, `y1`, so that each entry is loaded and stored once per four
/// rows; the same additions in the same order as one row per pass.
#[inline(always)]
fn accumulate_rows(inv: &[f64], n: usize, rb: &[f64], y0: &mut [f64], y1: &mut [f64]) {
    const R: usize = 4;
    let (r0, r1) = rb.split_at(n);
    let (y0, y1) = (&mut y0[..n], &mut y1[..n]);
    let rows = &inv[..n * n];
    let full = n - n % R;
    let mut k = 0;
    while k < full {
        let a = [r0[k], r0[k + 1], r0[k + 2], r0[k + 3]];
        let b = [r1[k], r1[k + 1], r1[k + 2], r1[k + 3]];
        let (v0, rest) = rows[k * n..(k + R) * n].split_at(n);
        let (v1, rest) = rest.split_at(n);
        let (v2, v3) = rest.split_at(n);
        let it = y0.iter_mut().zip(y1.iter_mut());
        for (((((p, q), &e0), &e1), &e2), &e3) in it.zip(v0).zip(v1).zip(v2).zip(v3) {
            *p = (((*p + a[0] * e0) + a[1] * e1) + a[2] * e2) + a[3] * e3;
            *q = (((*q + b[0] * e0) + b[1] * e1) + b[2] * e2) + b[3] * e3;
        }
        k += R;
    }
    for k in full..n {
        let (a, b) = (r0[k], r1[k]);
        for ((p, q), v) in y0
            .iter_mut()
            .zip(y1.iter_mut())
            .zip(&rows[k * n..(k + 1) * n])
        {
            *p += a * v;
            *q += b * v;
        }
    }
}

/// `Σ a_k b_k` in eight interleaved partial sums (vector lanes; another
/// order of the sum than left to right, to round-off).
#[inline(always)]
pub fn dot_lanes(a: &[f64], b: &[f64]) -> f64 {
    const L: usize = 8;
    let mut acc = [0.0f64; L];
    let (ca, cb) = (a.chunks_exact(L), b.chunks_exact(L));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..L {
            acc[k] += x[k] * y[k];
        }
    }
    let mut tail = 0.0;
    for (x, y) in ra.iter().zip(rb) {
        tail += x * y;
    }
    ((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7])) + tail
}

#[cfg(test)]
mod tests;
