//! The force kernel: the response of the states to the active points'
//! Gauss-point forces over a step (method §3.3), `(x, v) += w1 (b · q1) +
//! w2 (b · q2)`. A scalar body, and on x86-64 with AVX three lane builds
//! picked by size: four states at a time for a few states, blocks of 16
//! states in registers for tens of them, chunks of states with the active
//! columns streamed in groups for hundreds. No FMA: every build gives the
//! same values to the bit.

use super::super::StepColumns;

/// States per block of the force kernel (the block's projections of the
/// forces stay in registers / on the stack).
const BLOCK: usize = 16;

/// `(x, v) += w1 (b · q1) + w2 (b · q2)` per state, over the active points:
/// every state (`x.len()`), whose inputs `b_s[j]` are `inp_t[j * n + s]`.
#[inline]
pub(in crate::model::convolution) fn add_gauss_forces(
    c: &StepColumns,
    inp_t: &[f64],
    active: &[usize],
    q1: &[f64],
    q2: &[f64],
    x: &mut [f64],
    v: &mut [f64],
) {
    let n = x.len();
    add_gauss_forces_at::<false>(c, 0, inp_t, n, active, q1, q2, x, v)
}

/// [`add_gauss_forces`] over the `x.len()` states from `s0` (`x`, `v` hold
/// those states only), whose inputs `b_s[j]` are `inp_t[j * stride + s]`
/// (`stride`: the stored states): each state's sums as [`add_gauss_forces`]
/// computes them.
#[inline]
pub(in crate::model::convolution) fn add_gauss_forces_range(
    c: &StepColumns,
    s0: usize,
    inp_t: &[f64],
    stride: usize,
    active: &[usize],
    q1: &[f64],
    q2: &[f64],
    x: &mut [f64],
    v: &mut [f64],
) {
    add_gauss_forces_at::<true>(c, s0, inp_t, stride, active, q1, q2, x, v)
}

/// [`add_gauss_forces_range`] from `s0` when `RANGE`, else from state 0
/// (`s0` unread: the whole-state kernel keeps no offset arithmetic).
#[inline]
fn add_gauss_forces_at<const RANGE: bool>(
    c: &StepColumns,
    s0: usize,
    inp_t: &[f64],
    stride: usize,
    active: &[usize],
    q1: &[f64],
    q2: &[f64],
    x: &mut [f64],
    v: &mut [f64],
) {
    let s0 = if RANGE { s0 } else { 0 };
    let n = x.len();
    assert!(
        v.len() >= n
            && [&c.w1x, &c.w1v, &c.w2x, &c.w2v]
                .iter()
                .all(|w| w.len() >= s0 + n)
            && active
                .iter()
                .all(|&j| j < q1.len() && j < q2.len() && j * stride + s0 + n <= inp_t.len())
    );
    #[cfg(target_arch = "x86_64")]
    {
        if n >= 4 && std::arch::is_x86_feature_detected!("avx") {
            if n < AVX_BLOCKED_FROM_STATES {
                // SAFETY: as below
                unsafe {
                    add_gauss_forces_registers_avx::<false>(
                        c, s0, inp_t, stride, active, q1, q2, x, v,
                    )
                };
                return;
            }
            if n < AVX_CHUNKED_FROM_STATES {
                // SAFETY: as below
                unsafe {
                    add_gauss_forces_registers_avx::<true>(
                        c, s0, inp_t, stride, active, q1, q2, x, v,
                    )
                };
                return;
            }
            // SAFETY: the CPU supports AVX (checked just above); the lengths
            // the kernel reads were asserted above.
            unsafe { add_gauss_forces_avx::<RANGE>(c, s0, inp_t, stride, active, q1, q2, x, v) };
            return;
        }
    }
    add_gauss_forces_scalar::<RANGE>(c, s0, inp_t, stride, active, q1, q2, x, v);
}

/// [`add_gauss_forces_body`] in the baseline build (a CPU without AVX, or
/// fewer than four states), out of line: inlined, its set-up made every
/// call of the dispatch above pay for it, a few-mode scene's step
/// included.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn add_gauss_forces_scalar<const RANGE: bool>(
    c: &StepColumns,
    s0: usize,
    inp_t: &[f64],
    stride: usize,
    active: &[usize],
    q1: &[f64],
    q2: &[f64],
    x: &mut [f64],
    v: &mut [f64],
) {
    add_gauss_forces_body::<RANGE>(c, s0, inp_t, stride, active, q1, q2, x, v);
}

/// Fewest states for which [`add_gauss_forces`] keeps blocks of
/// [`BLOCK`] states in registers ([`add_gauss_forces_registers_avx`]);
/// fewer take its build without blocks, whose set-up is a few
/// instructions (a single-mode scene's step spent 60 more in the chunked
/// kernel's, which these sizes took before).
#[cfg(target_arch = "x86_64")]
const AVX_BLOCKED_FROM_STATES: usize = BLOCK;

/// Fewest states for which [`add_gauss_forces`] streams the active
/// columns in chunks ([`add_gauss_forces_avx`]): below, every active
/// column of a block of states is in the cache, and the chunked kernel's
/// stores and reloads of its projections are the larger cost (the paper's
/// preset spent 102 instructions a step more in it).
#[cfg(target_arch = "x86_64")]
const AVX_CHUNKED_FROM_STATES: usize = CHUNK;

/// [`add_gauss_forces`] with AVX lanes for up to a few hundred states,
/// every sum in registers: with `BLOCKS`, blocks of [`BLOCK`] states while
/// the active columns go by in the list's order from zero; then four
/// states at a time, then one by one (without `BLOCKS` only these: a few
/// states, whose kernel's set-up is a few instructions). Same operations
/// in the same order as [`add_gauss_forces_body`] (no FMA): bit-identical.
///
/// # Safety
/// AVX; `x`, `v` and the weight columns from `s0` hold `x.len()` states,
/// `inp_t` `j * stride + s0 + x.len()` values and `q1`, `q2` more than
/// `j` values for every active `j`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[allow(clippy::too_many_arguments)]
unsafe fn add_gauss_forces_registers_avx<const BLOCKS: bool>(
    c: &StepColumns,
    s0: usize,
    inp_t: &[f64],
    stride: usize,
    active: &[usize],
    q1: &[f64],
    q2: &[f64],
    x: &mut [f64],
    v: &mut [f64],
) {
    use std::arch::x86_64::*;
    const LANES: usize = BLOCK / 4;
    let n = x.len();
    let full = if BLOCKS { n - n % BLOCK } else { 0 };
    let quads = n - n % 4;
    let (xp, vp) = (x.as_mut_ptr(), v.as_mut_ptr());
    // (raw pointers throughout: this kernel is the whole force step of a
    // small scene, where bounds checks on every column and force were a
    // fifth of its instructions; the caller asserted every length)
    let base = inp_t.as_ptr().wrapping_add(s0);
    let w = [&c.w1x, &c.w2x, &c.w1v, &c.w2v].map(|col| col.as_ptr().wrapping_add(s0));
    let (q1p, q2p) = (q1.as_ptr(), q2.as_ptr());
    // SAFETY: k + BLOCK <= full, then k + 4 <= quads, then k < n; every
    // column holds n states from s0 and every active j indexes q1, q2 (as
    // the caller guarantees)
    unsafe {
        let mut k = 0;
        while k < full {
            let mut b1 = [_mm256_setzero_pd(); LANES];
            let mut b2 = [_mm256_setzero_pd(); LANES];
            for &j in active {
                let col = base.add(j * stride + k);
                let (qa, qb) = (_mm256_set1_pd(*q1p.add(j)), _mm256_set1_pd(*q2p.add(j)));
                for l in 0..LANES {
                    let b = _mm256_loadu_pd(col.add(4 * l));
                    b1[l] = _mm256_add_pd(b1[l], _mm256_mul_pd(b, qa));
                    b2[l] = _mm256_add_pd(b2[l], _mm256_mul_pd(b, qb));
                }
            }
            for l in 0..LANES {
                add_response_quad(w, k + 4 * l, b1[l], b2[l], xp, vp);
            }
            k += BLOCK;
        }
        while k < quads {
            let (mut b1, mut b2) = (_mm256_setzero_pd(), _mm256_setzero_pd());
            for &j in active {
                let b = _mm256_loadu_pd(base.add(j * stride + k));
                b1 = _mm256_add_pd(b1, _mm256_mul_pd(b, _mm256_set1_pd(*q1p.add(j))));
                b2 = _mm256_add_pd(b2, _mm256_mul_pd(b, _mm256_set1_pd(*q2p.add(j))));
            }
            add_response_quad(w, k, b1, b2, xp, vp);
            k += 4;
        }
        for k in quads..n {
            let (mut b1, mut b2) = (0.0, 0.0);
            for &j in active {
                let b = *base.add(j * stride + k);
                b1 += b * *q1p.add(j);
                b2 += b * *q2p.add(j);
            }
            *xp.add(k) += *w[0].add(k) * b1 + *w[1].add(k) * b2;
            *vp.add(k) += *w[2].add(k) * b1 + *w[3].add(k) * b2;
        }
    }
}

/// States per chunk of [`add_gauss_forces_avx`]: the chunk's force
/// projections (two arrays of this many values) stay in the L1 cache while
/// every active column streams through.
#[cfg(target_arch = "x86_64")]
const CHUNK: usize = 256;

/// [`add_gauss_forces`] with AVX lanes. The states go in chunks of
/// [`CHUNK`]; within a chunk the active columns stream four at a time
/// (contiguous runs the prefetcher follows, where one block of states
/// across every column jumps from column to column), each added to the
/// chunk's projections in the active list's order. Same operations in the
/// same order as [`add_gauss_forces_body`] (no FMA): bit-identical.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn add_gauss_forces_avx<const RANGE: bool>(
    c: &StepColumns,
    s0: usize,
    inp_t: &[f64],
    stride: usize,
    active: &[usize],
    q1: &[f64],
    q2: &[f64],
    x: &mut [f64],
    v: &mut [f64],
) {
    use std::arch::x86_64::*;
    let n = x.len();
    let (xp, vp) = (x.as_mut_ptr(), v.as_mut_ptr());
    // (the range's states: pointers from `s0`; `c0` counts from there)
    let s0 = if RANGE { s0 } else { 0 };
    let inp_t = &inp_t[s0..];
    let (w1x, w1v, w2x, w2v) = (&c.w1x[s0..], &c.w1v[s0..], &c.w2x[s0..], &c.w2v[s0..]);
    let (w1x, w1v, w2x, w2v) = (w1x.as_ptr(), w1v.as_ptr(), w2x.as_ptr(), w2v.as_ptr());
    // (the chunk's first `len` values: written by its first column group,
    // which starts its sums from zero, before any is read)
    let mut b1 = [std::mem::MaybeUninit::<f64>::uninit(); CHUNK];
    let mut b2 = [std::mem::MaybeUninit::<f64>::uninit(); CHUNK];
    let (p1, p2) = (b1.as_mut_ptr().cast::<f64>(), b2.as_mut_ptr().cast::<f64>());
    let groups = active.len() - active.len() % 4;
    let mut c0 = 0;
    // SAFETY (all loads and stores): within a chunk, k + 4 <= quads <= len
    // <= CHUNK and c0 + len <= n; p1, p2 hold CHUNK values, the first len
    // written (by the first column group, or zeroed without active
    // columns) before any is read; x, v and the weight columns hold s0 + n
    // entries, inp_t j stride + s0 + n for every active j (asserted by the
    // caller).
    unsafe {
        while c0 < n {
            let len = CHUNK.min(n - c0);
            let quads = len - len % 4;
            if active.is_empty() {
                std::ptr::write_bytes(p1, 0, len);
                std::ptr::write_bytes(p2, 0, len);
            }
            // the active columns eight, then four at a time, then one at a
            // time; each state's sums take the columns in the list's order,
            // from zero
            let mut g = 0;
            while g + 8 <= groups {
                let (js, first) = (&active[g..g + 8], g == 0);
                gauss_columns_avx::<8>(js, inp_t, stride, c0, q1, q2, p1, p2, len, first);
                g += 8;
            }
            while g < groups {
                let (js, first) = (&active[g..g + 4], g == 0);
                gauss_columns_avx::<4>(js, inp_t, stride, c0, q1, q2, p1, p2, len, first);
                g += 4;
            }
            for (k, j) in active[groups..].chunks(1).enumerate() {
                let first = groups + k == 0;
                gauss_columns_avx::<1>(j, inp_t, stride, c0, q1, q2, p1, p2, len, first);
            }
            // the chunk's responses into the states
            let mut k = 0;
            while k < quads {
                let o = c0 + k;
                let (bb1, bb2) = (_mm256_loadu_pd(p1.add(k)), _mm256_loadu_pd(p2.add(k)));
                add_response_quad([w1x, w2x, w1v, w2v], o, bb1, bb2, xp, vp);
                k += 4;
            }
            for k in quads..len {
                let o = c0 + k;
                let (bb1, bb2) = (*p1.add(k), *p2.add(k));
                *xp.add(o) += *w1x.add(o) * bb1 + *w2x.add(o) * bb2;
                *vp.add(o) += *w1v.add(o) * bb1 + *w2v.add(o) * bb2;
            }
            c0 += len;
        }
    }
}

/// States `o..o + 4`: `x += w1x b1 + w2x b2`, `v += w1v b1 + w2v b2`, the
/// weights `w` in the order `w1x, w2x, w1v, w2v`.
///
/// # Safety
/// AVX; the four weight columns, `xp` and `vp` hold `o + 4` values.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn add_response_quad(
    w: [*const f64; 4],
    o: usize,
    b1: std::arch::x86_64::__m256d,
    b2: std::arch::x86_64::__m256d,
    xp: *mut f64,
    vp: *mut f64,
) {
    use std::arch::x86_64::*;
    // SAFETY: as the caller guarantees
    unsafe {
        let dx = _mm256_add_pd(
            _mm256_mul_pd(_mm256_loadu_pd(w[0].add(o)), b1),
            _mm256_mul_pd(_mm256_loadu_pd(w[1].add(o)), b2),
        );
        let dv = _mm256_add_pd(
            _mm256_mul_pd(_mm256_loadu_pd(w[2].add(o)), b1),
            _mm256_mul_pd(_mm256_loadu_pd(w[3].add(o)), b2),
        );
        _mm256_storeu_pd(xp.add(o), _mm256_add_pd(_mm256_loadu_pd(xp.add(o)), dx));
        _mm256_storeu_pd(vp.add(o), _mm256_add_pd(_mm256_loadu_pd(vp.add(o)), dv));
    }
}

/// `G` active columns `js` of [`add_gauss_forces_avx`] added to a chunk's
/// projections `p1`, `p2` (`len` states from `c0`): each state's sums take
/// the columns in order, the projections loaded and stored once per `G`
/// columns. The `first` group of a chunk starts the sums from zero instead
/// of loading the projections (the same sums as on zeroed projections).
///
/// # Safety
/// AVX; `p1`, `p2` hold `len` values, written unless `first`; every
/// column `j` of `js` holds `j * stride + c0 + len` values of `inp_t`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[allow(clippy::too_many_arguments)]
unsafe fn gauss_columns_avx<const G: usize>(
    js: &[usize],
    inp_t: &[f64],
    stride: usize,
    c0: usize,
    q1: &[f64],
    q2: &[f64],
    p1: *mut f64,
    p2: *mut f64,
    len: usize,
    first: bool,
) {
    use std::arch::x86_64::*;
    let quads = len - len % 4;
    let js: [usize; G] = std::array::from_fn(|r| js[r]);
    // SAFETY: as the caller guarantees
    unsafe {
        let col: [*const f64; G] = std::array::from_fn(|r| inp_t.as_ptr().add(js[r] * stride + c0));
        let qa: [__m256d; G] = std::array::from_fn(|r| _mm256_set1_pd(q1[js[r]]));
        let qb: [__m256d; G] = std::array::from_fn(|r| _mm256_set1_pd(q2[js[r]]));
        let mut k = 0;
        while k < quads {
            let (mut a1, mut a2) = if first {
                (_mm256_setzero_pd(), _mm256_setzero_pd())
            } else {
                (_mm256_loadu_pd(p1.add(k)), _mm256_loadu_pd(p2.add(k)))
            };
            for r in 0..G {
                let b = _mm256_loadu_pd(col[r].add(k));
                a1 = _mm256_add_pd(a1, _mm256_mul_pd(b, qa[r]));
                a2 = _mm256_add_pd(a2, _mm256_mul_pd(b, qb[r]));
            }
            _mm256_storeu_pd(p1.add(k), a1);
            _mm256_storeu_pd(p2.add(k), a2);
            k += 4;
        }
        for k in quads..len {
            let (mut a1, mut a2) = if first {
                (0.0, 0.0)
            } else {
                (*p1.add(k), *p2.add(k))
            };
            for r in 0..G {
                let b = *col[r].add(k);
                a1 += b * q1[js[r]];
                a2 += b * q2[js[r]];
            }
            (*p1.add(k), *p2.add(k)) = (a1, a2);
        }
    }
}

#[inline(always)]
pub(super) fn add_gauss_forces_body<const RANGE: bool>(
    c: &StepColumns,
    s0: usize,
    inp_t: &[f64],
    stride: usize,
    active: &[usize],
    q1: &[f64],
    q2: &[f64],
    x: &mut [f64],
    v: &mut [f64],
) {
    let s0 = if RANGE { s0 } else { 0 };
    let n = x.len();
    let v = &mut v[..n];
    let r = s0..s0 + n;
    let (w1x, w1v) = (&c.w1x[r.clone()], &c.w1v[r.clone()]);
    let (w2x, w2v) = (&c.w2x[r.clone()], &c.w2v[r]);
    let inp_t = &inp_t[s0..];
    let mut c0 = 0;
    while c0 < n {
        let len = BLOCK.min(n - c0);
        let (mut b1, mut b2) = ([0.0f64; BLOCK], [0.0f64; BLOCK]);
        if len == BLOCK {
            for &j in active {
                let col = &inp_t[j * stride + c0..j * stride + c0 + BLOCK];
                let (qa, qb) = (q1[j], q2[j]);
                for k in 0..BLOCK {
                    b1[k] += col[k] * qa;
                    b2[k] += col[k] * qb;
                }
            }
        } else {
            for &j in active {
                let col = &inp_t[j * stride + c0..j * stride + c0 + len];
                let (qa, qb) = (q1[j], q2[j]);
                for k in 0..len {
                    b1[k] += col[k] * qa;
                    b2[k] += col[k] * qb;
                }
            }
        }
        let (x, v) = (&mut x[c0..c0 + len], &mut v[c0..c0 + len]);
        let (w1x, w1v) = (&w1x[c0..c0 + len], &w1v[c0..c0 + len]);
        let (w2x, w2v) = (&w2x[c0..c0 + len], &w2v[c0..c0 + len]);
        for k in 0..len {
            x[k] += w1x[k] * b1[k] + w2x[k] * b2[k];
            v[k] += w1v[k] * b1[k] + w2v[k] * b2[k];
        }
        c0 += len;
    }
}
