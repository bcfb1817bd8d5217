//! The per-step kernels over the states (structure of arrays). Each runs the
//! same scalar code, compiled twice on x86-64: for the baseline target and,
//! picked at run time when the CPU has it, for AVX2 (4-wide lanes). AVX2
//! without FMA keeps every operation and its order: both builds give
//! bit-identical results.

use super::{StepColumns, dot2};

mod gauss;
#[cfg(test)]
use gauss::add_gauss_forces_body;
pub(super) use gauss::{add_gauss_forces, add_gauss_forces_range};

/// `(ox, ov) = Φ (x, v)` per state, every state (`x.len()`).
#[inline]
pub(super) fn predict(c: &StepColumns, x: &[f64], v: &[f64], ox: &mut [f64], ov: &mut [f64]) {
    predict_at::<false>(c, 0, x, v, ox, ov)
}

/// [`predict`] over the `x.len()` states from `s0` (`x`, `v`, `ox`, `ov`
/// hold those states only): each state as [`predict`] computes it.
#[inline]
pub(super) fn predict_range(
    c: &StepColumns,
    s0: usize,
    x: &[f64],
    v: &[f64],
    ox: &mut [f64],
    ov: &mut [f64],
) {
    predict_at::<true>(c, s0, x, v, ox, ov)
}

/// [`predict_body`] in 4-wide AVX lanes where the CPU has AVX. (Inlined
/// into its caller: a few-mode scene's step calls it for one or two lanes,
/// where a call's set-up would cost as much as the lanes.)
#[inline(always)]
fn predict_at<const RANGE: bool>(
    c: &StepColumns,
    s0: usize,
    x: &[f64],
    v: &[f64],
    ox: &mut [f64],
    ov: &mut [f64],
) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU supports AVX (checked just above).
            unsafe { predict_avx(c, if RANGE { s0 } else { 0 }, x, v, ox, ov) };
            return;
        }
    }
    predict_scalar::<RANGE>(c, s0, x, v, ox, ov)
}

/// [`predict_body`] in the baseline build (a CPU without AVX, and the
/// states past [`predict_avx`]'s whole lanes).
#[inline(never)]
fn predict_scalar<const RANGE: bool>(
    c: &StepColumns,
    s0: usize,
    x: &[f64],
    v: &[f64],
    ox: &mut [f64],
    ov: &mut [f64],
) {
    predict_body::<RANGE>(c, s0, x, v, ox, ov)
}

/// [`predict_body`] from state `s0` of the step's columns: whole lanes of
/// four states in AVX registers, one lane a pass (a few-mode scene's
/// stored states are one or two lanes), then any states past them one by
/// one. Each state alone with the same operations (no FMA): bit-identical.
///
/// # Safety
/// The CPU supports AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn predict_avx(
    c: &StepColumns,
    s0: usize,
    x: &[f64],
    v: &[f64],
    ox: &mut [f64],
    ov: &mut [f64],
) {
    use std::arch::x86_64::*;
    let n = x.len();
    let cols = [&c.pxx, &c.pxv, &c.pvx, &c.pvv];
    // (one check of every length: the lanes read through pointers)
    assert!(
        s0.checked_add(n)
            .is_some_and(|end| cols.iter().all(|col| col.len() >= end))
            && v.len() >= n
            && ox.len() >= n
            && ov.len() >= n,
        "a step's columns or states shorter than the states predicted"
    );
    let lanes = n - n % 4;
    let [a, b, cc, d] = cols.map(|col| col.as_ptr().wrapping_add(s0));
    let (xp, vp, oxp, ovp) = (x.as_ptr(), v.as_ptr(), ox.as_mut_ptr(), ov.as_mut_ptr());
    let mut s = 0;
    // SAFETY (the loads and stores): s + 3 < lanes <= n, and every column
    // holds n values from s0, every state slice n (asserted above).
    unsafe {
        while s < lanes {
            let (xs, vs) = (_mm256_loadu_pd(xp.add(s)), _mm256_loadu_pd(vp.add(s)));
            let at = |col: *const f64| _mm256_loadu_pd(col.add(s));
            let pos = _mm256_add_pd(_mm256_mul_pd(at(a), xs), _mm256_mul_pd(at(b), vs));
            let vel = _mm256_add_pd(_mm256_mul_pd(at(cc), xs), _mm256_mul_pd(at(d), vs));
            _mm256_storeu_pd(oxp.add(s), pos);
            _mm256_storeu_pd(ovp.add(s), vel);
            s += 4;
        }
    }
    // (the states past the whole lanes, one by one: none where the states
    // are stored in whole lanes, as the solver's are)
    if lanes < n {
        predict_scalar::<true>(
            c,
            s0 + lanes,
            &x[lanes..],
            &v[lanes..n],
            &mut ox[lanes..n],
            &mut ov[lanes..n],
        );
    }
}

/// `col = Σ_{m ≥ 1} lam[m] W_m`, `W_m` the column `ci` of node `m` in
/// `weights` (`(m * 4 + ci) * ns`, `ns` long; node 0's columns are zero):
/// the interpolated Gauss weights of a short step (method §4.6), node by
/// node in order, through an AVX2 build where the CPU has it (no FMA: the
/// same operations, bit-identical).
#[inline]
pub(super) fn combine_columns(lam: &[f64], weights: &[f64], ci: usize, ns: usize, col: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            #[target_feature(enable = "avx2")]
            fn wide(lam: &[f64], weights: &[f64], ci: usize, ns: usize, col: &mut [f64]) {
                combine_body(lam, weights, ci, ns, col)
            }
            // SAFETY: the CPU supports AVX2 (checked just above).
            return unsafe { wide(lam, weights, ci, ns, col) };
        }
    }
    combine_body(lam, weights, ci, ns, col)
}

#[inline(always)]
fn combine_body(lam: &[f64], weights: &[f64], ci: usize, ns: usize, col: &mut [f64]) {
    let col = &mut col[..ns];
    let node = |m: usize| &weights[(m * 4 + ci) * ns..(m * 4 + ci + 1) * ns];
    let (l1, w) = (lam[1], node(1));
    for (x, y) in col.iter_mut().zip(w) {
        *x = l1 * y;
    }
    for (m, &l) in lam.iter().enumerate().skip(2) {
        for (x, y) in col.iter_mut().zip(node(m)) {
            *x += l * y;
        }
    }
}

/// `u += Σ_m lam[m] (G_x1 q1 + G_x2 q2)`, `v` likewise with the velocity
/// columns: one point's response by the nodes' influence columns `cols`
/// (node `m`'s four columns of `p` values from `4 m p`, in the order
/// `x1, x2, v1, v2`), node by node in order, through an AVX2 build where
/// the CPU has it (no FMA: bit-identical).
#[inline]
pub(super) fn add_node_columns(
    lam: &[f64],
    cols: &[f64],
    p: usize,
    q1: f64,
    q2: f64,
    u: &mut [f64],
    v: &mut [f64],
) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            #[target_feature(enable = "avx2")]
            fn wide(
                lam: &[f64],
                cols: &[f64],
                p: usize,
                q1: f64,
                q2: f64,
                u: &mut [f64],
                v: &mut [f64],
            ) {
                node_columns_body(lam, cols, p, q1, q2, u, v)
            }
            // SAFETY: the CPU supports AVX2 (checked just above).
            return unsafe { wide(lam, cols, p, q1, q2, u, v) };
        }
    }
    node_columns_body(lam, cols, p, q1, q2, u, v)
}

#[inline(always)]
fn node_columns_body(
    lam: &[f64],
    cols: &[f64],
    p: usize,
    q1: f64,
    q2: f64,
    u: &mut [f64],
    v: &mut [f64],
) {
    let (u, v) = (&mut u[..p], &mut v[..p]);
    for (m, &l) in lam.iter().enumerate() {
        let c = &cols[m * 4 * p..(m + 1) * 4 * p];
        let (a1, a2) = (l * q1, l * q2);
        let (gx1, rest) = c.split_at(p);
        let (gx2, rest) = rest.split_at(p);
        let (gv1, gv2) = rest.split_at(p);
        for i in 0..p {
            u[i] += gx1[i] * a1 + gx2[i] * a2;
            v[i] += gv1[i] * a1 + gv2[i] * a2;
        }
    }
}

/// One point's responses to unit Gauss values by the nodes' influence
/// columns `cols` (as [`add_node_columns`]): `ux1 = Σ_m lam[m] G_x1`,
/// `uv1` with `G_v1`, `ux2`, `uv2` with the `q2` columns, summed from zero
/// node by node in order. One pass over the columns gives what
/// [`add_node_columns`] gives into zeroed outputs with `(q1, q2) = (1, 0)`
/// and then `(0, 1)`, bit for bit: the term multiplied by zero adds a
/// signed zero to a sum that starts at `+0` and so is never `-0`.
#[inline]
pub(super) fn unit_node_columns(lam: &[f64], cols: &[f64], p: usize, out: [&mut [f64]; 4]) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            #[target_feature(enable = "avx2")]
            fn wide(lam: &[f64], cols: &[f64], p: usize, out: [&mut [f64]; 4]) {
                unit_columns_body(lam, cols, p, out)
            }
            // SAFETY: the CPU supports AVX2 (checked just above).
            return unsafe { wide(lam, cols, p, out) };
        }
    }
    unit_columns_body(lam, cols, p, out)
}

#[inline(always)]
fn unit_columns_body(lam: &[f64], cols: &[f64], p: usize, out: [&mut [f64]; 4]) {
    let [ux1, uv1, ux2, uv2] = out;
    let (ux1, uv1, ux2, uv2) = (&mut ux1[..p], &mut uv1[..p], &mut ux2[..p], &mut uv2[..p]);
    for o in [&mut *ux1, &mut *uv1, &mut *ux2, &mut *uv2] {
        o.fill(0.0);
    }
    for (m, &l) in lam.iter().enumerate() {
        let c = &cols[m * 4 * p..(m + 1) * 4 * p];
        let (gx1, rest) = c.split_at(p);
        let (gx2, rest) = rest.split_at(p);
        let (gv1, gv2) = rest.split_at(p);
        for i in 0..p {
            ux1[i] += gx1[i] * l;
            uv1[i] += gv1[i] * l;
            ux2[i] += gx2[i] * l;
            uv2[i] += gv2[i] * l;
        }
    }
}

/// `(u_i, v_i) = (a_i · x, a_i · v)` for the points `i` in `rows` only
/// (rows of `out`, `ns` wide), each sum in [`dot2`]'s order, as
/// [`project`] gives them.
#[inline]
pub(super) fn project_rows(
    out: &[f64],
    ns: usize,
    rows: &[usize],
    x: &[f64],
    v: &[f64],
    u: &mut [f64],
    w: &mut [f64],
) {
    gathered_rows(out, ns, rows, x, v, |k, ru, rv| {
        let i = rows[k];
        (u[i], w[i]) = (ru, rv);
    });
}

/// [`project_rows`] with the values of `rows[k]` into `u[k]`, `w[k]`
/// (packed in the list's order; the same sums).
#[inline]
pub(super) fn project_rows_packed(
    out: &[f64],
    ns: usize,
    rows: &[usize],
    x: &[f64],
    v: &[f64],
    u: &mut [f64],
    w: &mut [f64],
) {
    gathered_rows(out, ns, rows, x, v, |k, ru, rv| (u[k], w[k]) = (ru, rv));
}

/// The sums `(a_i · x, a_i · v)` of the rows `rows` of `out` (`ns` wide),
/// each handed to `put(k, u, v)` with its place `k` in the list: through
/// [`project_gathered_avx`] where the CPU has AVX (rows six at a time, as
/// [`project`] takes consecutive ones), else [`dot2`] row by row. The same
/// operations in the same order either way: bit-identical.
#[inline]
fn gathered_rows(
    out: &[f64],
    ns: usize,
    rows: &[usize],
    x: &[f64],
    v: &[f64],
    mut put: impl FnMut(usize, f64, f64),
) {
    let (x, v) = (&x[..ns], &v[..ns]);
    assert!(rows.iter().all(|&i| (i + 1) * ns <= out.len()));
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU supports AVX (checked just above); every row
            // of `rows` lies inside `out` (asserted above), `x` and `v`
            // hold `ns` values.
            unsafe { project_gathered_avx(out, ns, rows, x, v, &mut put) };
            return;
        }
    }
    for (k, &i) in rows.iter().enumerate() {
        let (ru, rv) = dot2(&out[i * ns..(i + 1) * ns], x, v);
        put(k, ru, rv);
    }
}

/// [`gathered_rows`] with AVX lanes: the rows of `rows` six at a time by
/// [`project_rows_avx`].
///
/// # Safety
/// The CPU supports AVX; every row of `rows` lies inside `out`; `x` and
/// `v` hold `ns` values.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn project_gathered_avx(
    out: &[f64],
    ns: usize,
    rows: &[usize],
    x: &[f64],
    v: &[f64],
    put: &mut impl FnMut(usize, f64, f64),
) {
    let mut k = 0;
    while k < rows.len() {
        let take = (rows.len() - k).min(6);
        let (mut us, mut vs) = ([0.0; 6], [0.0; 6]);
        let idx: [usize; 6] = std::array::from_fn(|r| rows[k + r.min(take - 1)] * ns);
        // SAFETY: the caller's contract: each row lies inside `out`.
        unsafe {
            match take {
                6 => project_rows_avx::<6>(out, idx, x, v, &mut us, &mut vs),
                5 => project_rows_avx::<5>(out, idx, x, v, &mut us, &mut vs),
                4 => project_rows_avx::<4>(out, idx, x, v, &mut us, &mut vs),
                3 => project_rows_avx::<3>(out, idx, x, v, &mut us, &mut vs),
                2 => project_rows_avx::<2>(out, idx, x, v, &mut us, &mut vs),
                _ => project_rows_avx::<1>(out, idx, x, v, &mut us, &mut vs),
            }
        }
        for r in 0..take {
            put(k + r, us[r], vs[r]);
        }
        k += take;
    }
}

/// `(u_i, v_i) = (a_i · x, a_i · v)` for every point `i` (rows of `out`),
/// each sum in [`dot2`]'s order.
#[inline(always)]
pub(super) fn project(out: &[f64], p: usize, x: &[f64], v: &[f64], u: &mut [f64], w: &mut [f64]) {
    let ns = x.len();
    assert!(out.len() >= p * ns && v.len() >= ns && u.len() >= p && w.len() >= p);
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU supports AVX (checked just above); the slice
            // lengths the kernel reads were asserted above.
            unsafe { project_avx(out, p, x, v, u, w) };
            return;
        }
    }
    project_body(out, p, x, v, u, w);
}

/// [`project`] with AVX lanes: the four accumulators of [`dot2`] are the four
/// lanes of one register; rows are taken up to six at a time (twelve
/// independent accumulations in registers: five rows, as in the paper's
/// five points, in one pass). Same operations in the same order as
/// [`dot2`] (no FMA): bit-identical.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn project_avx(out: &[f64], p: usize, x: &[f64], v: &[f64], u: &mut [f64], w: &mut [f64]) {
    let mut i = 0;
    while i < p {
        let rows = (p - i).min(6);
        // SAFETY: the caller asserted the lengths; rows i..i + rows exist.
        unsafe {
            match rows {
                6 => project_block_avx::<6>(out, i, x, v, u, w),
                5 => project_block_avx::<5>(out, i, x, v, u, w),
                4 => project_block_avx::<4>(out, i, x, v, u, w),
                3 => project_block_avx::<3>(out, i, x, v, u, w),
                2 => project_block_avx::<2>(out, i, x, v, u, w),
                _ => project_block_avx::<1>(out, i, x, v, u, w),
            }
        }
        i += rows;
    }
}

/// Rows `i .. i + R` of [`project_avx`]: [`project_rows_avx`] on
/// consecutive rows, their sums into `u[i + r]`, `w[i + r]`.
///
/// # Safety
/// The CPU supports AVX; `out` holds rows `..i + R` (`x.len()` wide);
/// `v` holds `x.len()` values; `u` and `w` hold `i + R`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn project_block_avx<const R: usize>(
    out: &[f64],
    i: usize,
    x: &[f64],
    v: &[f64],
    u: &mut [f64],
    w: &mut [f64],
) {
    use std::arch::x86_64::*;
    let ns = x.len();
    let m = ns - ns % 4;
    let lanes = |r: __m256d| {
        let mut a = [0.0f64; 4];
        // SAFETY: `a` holds four f64.
        unsafe { _mm256_storeu_pd(a.as_mut_ptr(), r) };
        (a[0] + a[1]) + (a[2] + a[3])
    };
    let (xp, vp) = (x.as_ptr(), v.as_ptr());
    let mut su = [_mm256_setzero_pd(); R];
    let mut sv = [_mm256_setzero_pd(); R];
    // SAFETY (all loads): c + 3 < m <= ns, rows of `out` have ns entries
    // (the caller's contract), i + r < i + R.
    unsafe {
        let base = out.as_ptr().add(i * ns);
        let mut c = 0;
        while c < m {
            let (xc, vc) = (_mm256_loadu_pd(xp.add(c)), _mm256_loadu_pd(vp.add(c)));
            for r in 0..R {
                let a = _mm256_loadu_pd(base.add(r * ns + c));
                su[r] = _mm256_add_pd(su[r], _mm256_mul_pd(a, xc));
                sv[r] = _mm256_add_pd(sv[r], _mm256_mul_pd(a, vc));
            }
            c += 4;
        }
    }
    for r in 0..R {
        let row = &out[(i + r) * ns..(i + r + 1) * ns];
        let (mut ru, mut rv) = (lanes(su[r]), lanes(sv[r]));
        for c in m..ns {
            ru += row[c] * x[c];
            rv += row[c] * v[c];
        }
        (u[i + r], w[i + r]) = (ru, rv);
    }
}

/// The `R` rows of `out` starting at `start[r]` (`x.len()` wide each) of
/// [`project_gathered_avx`], their sums into `u[r]`,
/// `w[r]`.
///
/// # Safety
/// The CPU supports AVX; `start[r] + x.len() <= out.len()` for `r < R`;
/// `v` holds `x.len()` values; `u` and `w` hold `R`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn project_rows_avx<const R: usize>(
    out: &[f64],
    start: [usize; 6],
    x: &[f64],
    v: &[f64],
    u: &mut [f64],
    w: &mut [f64],
) {
    use std::arch::x86_64::*;
    let ns = x.len();
    let m = ns - ns % 4;
    let lanes = |r: __m256d| {
        let mut a = [0.0f64; 4];
        // SAFETY: `a` holds four f64.
        unsafe { _mm256_storeu_pd(a.as_mut_ptr(), r) };
        (a[0] + a[1]) + (a[2] + a[3])
    };
    let (xp, vp) = (x.as_ptr(), v.as_ptr());
    let mut su = [_mm256_setzero_pd(); R];
    let mut sv = [_mm256_setzero_pd(); R];
    // SAFETY (all loads): c + 3 < m <= ns, each row has ns entries from
    // its start inside `out` (the caller's contract).
    unsafe {
        let base: [*const f64; R] = std::array::from_fn(|r| out.as_ptr().add(start[r]));
        let mut c = 0;
        while c < m {
            let (xc, vc) = (_mm256_loadu_pd(xp.add(c)), _mm256_loadu_pd(vp.add(c)));
            for r in 0..R {
                let a = _mm256_loadu_pd(base[r].add(c));
                su[r] = _mm256_add_pd(su[r], _mm256_mul_pd(a, xc));
                sv[r] = _mm256_add_pd(sv[r], _mm256_mul_pd(a, vc));
            }
            c += 4;
        }
    }
    for r in 0..R {
        let row = &out[start[r]..start[r] + ns];
        let (mut ru, mut rv) = (lanes(su[r]), lanes(sv[r]));
        for c in m..ns {
            ru += row[c] * x[c];
            rv += row[c] * v[c];
        }
        (u[r], w[r]) = (ru, rv);
    }
}

#[inline(always)]
fn predict_body<const RANGE: bool>(
    c: &StepColumns,
    s0: usize,
    x: &[f64],
    v: &[f64],
    ox: &mut [f64],
    ov: &mut [f64],
) {
    let s0 = if RANGE { s0 } else { 0 };
    let n = x.len();
    let (v, ox, ov) = (&v[..n], &mut ox[..n], &mut ov[..n]);
    let r = s0..s0 + n;
    let (a, b) = (&c.pxx[r.clone()], &c.pxv[r.clone()]);
    let (cc, d) = (&c.pvx[r.clone()], &c.pvv[r]);
    for s in 0..n {
        ox[s] = a[s] * x[s] + b[s] * v[s];
        ov[s] = cc[s] * x[s] + d[s] * v[s];
    }
}

fn project_body(out: &[f64], p: usize, x: &[f64], v: &[f64], u: &mut [f64], w: &mut [f64]) {
    let ns = x.len();
    for i in 0..p {
        (u[i], w[i]) = dot2(&out[i * ns..(i + 1) * ns], x, v);
    }
}

#[cfg(test)]
mod tests;
