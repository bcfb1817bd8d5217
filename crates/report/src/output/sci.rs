//! Numbers of the run CSV in scientific notation with ten significant
//! digits: the text of Rust's `format!("{x:.9e}")`, byte for byte, several
//! times faster.
//!
//! `{:.9e}` rounds the exact binary value `x = m 2^q` to ten digits; the
//! standard library finds them with an exact algorithm that often falls
//! back to big-number arithmetic, and writing a patch's CSV took longer
//! than its steps. Here the ten digits are the rounded integer part of
//! `N = |x| 10^(9 - e)`, `e` the decimal exponent of `x`, computed as the
//! 53-bit `m` times a 128-bit `10^(9 - e)` from a table (`POW10`), built
//! by repeated multiplication and division by 10 from `10^0`, each entry
//! truncated: its relative error is below `320 2^-127`, so `N` (below
//! `2^37`) is known to a few units of `2^-80`. Wherever that leaves the
//! rounding in doubt, the fraction of `N` within a few of those units of
//! one half (an exact tie, or a value too close to one to tell), the
//! standard library writes the number, as it does zeros of negative sign,
//! subnormal numbers, infinities and NaN.

/// Appends `x` as `format!("{x:.9e}")` would write it.
#[inline]
pub fn push_e9(text: &mut Vec<u8>, x: f64) {
    if x == 0.0 && x.is_sign_positive() {
        text.extend_from_slice(b"0.000000000e0");
        return;
    }
    if !x.is_normal() {
        return fallback(text, x);
    }
    let Some((digits, exp10)) = ten_digits(x) else {
        return fallback(text, x);
    };
    // `-d.ddddddddde-ddd`: at most 17 bytes
    let mut o = [0u8; 24];
    let mut n = 0;
    if x < 0.0 {
        o[0] = b'-';
        n = 1;
    }
    let mut r = digits;
    for k in (0..10).rev() {
        // digit k of ten at o[n], o[n + 2 ..]
        let at = if k == 0 { n } else { n + 1 + k };
        o[at] = b'0' + (r % 10) as u8;
        r /= 10;
    }
    o[n + 1] = b'.';
    o[n + 11] = b'e';
    n += 12;
    if exp10 < 0 {
        o[n] = b'-';
        n += 1;
    }
    let e = exp10.unsigned_abs();
    if e >= 100 {
        o[n] = b'0' + (e / 100) as u8;
        n += 1;
    }
    if e >= 10 {
        o[n] = b'0' + (e / 10 % 10) as u8;
        n += 1;
    }
    o[n] = b'0' + (e % 10) as u8;
    text.extend_from_slice(&o[..n + 1]);
}

#[cold]
fn fallback(text: &mut Vec<u8>, x: f64) {
    text.extend_from_slice(format!("{x:.9e}").as_bytes());
}

/// Smallest and largest powers of ten in [`POW10`]: `9 - e` for the
/// decimal exponents `e` of normal numbers, one either side.
const S_MIN: i32 = -300;
const S_MAX: i32 = 320;

/// `10^s ≈ M 2^b` for `s` in `S_MIN..=S_MAX`: `(M, b)` with `M` in
/// `[2^127, 2^128)`, each entry truncated from its neighbour towards
/// `10^0` (exact up to `10^38`).
static POW10: [(u128, i32); (S_MAX - S_MIN + 1) as usize] = pow10_table();

const fn pow10_table() -> [(u128, i32); (S_MAX - S_MIN + 1) as usize] {
    let mut t = [(0u128, 0i32); (S_MAX - S_MIN + 1) as usize];
    let zero = (-S_MIN) as usize;
    t[zero] = (1u128 << 127, -127);
    // up: times 10, renormalised (10 M < 2^132)
    let mut k = zero + 1;
    while k < t.len() {
        let (m, b) = t[k - 1];
        let (hi, lo) = (m >> 64, m & u64::MAX as u128);
        let lo10 = lo * 10;
        let hi10 = hi * 10 + (lo10 >> 64);
        // 10 M = hi10 2^64 + (lo10 mod 2^64), hi10 < 2^68
        let shift = 128 - hi10.leading_zeros() as i32 - 64; // 3 or 4
        let low = lo10 & u64::MAX as u128;
        let m10 = (hi10 << (64 - shift)) | (low >> shift);
        t[k] = (m10, b + shift);
        k += 1;
    }
    // down: divided by 10, renormalised (M / 10 in [2^123.7, 2^124.7))
    let mut k = zero;
    while k > 0 {
        let (m, b) = t[k];
        let (q, r) = (m / 10, m % 10);
        let shift = if q >> 124 != 0 { 3 } else { 4 };
        t[k - 1] = ((q << shift) | ((r << shift) / 10), b - shift);
        k -= 1;
    }
    t
}

/// The ten significant digits of `|x|` (normal), rounded half away from
/// zero, as an integer in `[10^9, 10^10)`, and the decimal exponent of the
/// first; `None` where the rounding is in doubt (within `8 2^-80` of a
/// tie).
#[inline]
fn ten_digits(x: f64) -> Option<(u64, i32)> {
    let bits = x.to_bits();
    let m = (bits & ((1u64 << 52) - 1)) | (1u64 << 52);
    let q = ((bits >> 52) & 0x7ff) as i32 - 1075;
    // |x| in [2^(q + 52), 2^(q + 53)): e is this floor of (q + 52) log10 2,
    // or one more (78913 / 2^18 is log10 2 to well within the range's needs)
    let e_low = ((q + 52) * 78_913) >> 18;
    let ((n, above_half), mut e) = match scaled(m, q, 9 - e_low)? {
        (n, _) if n >= 10_000_000_000 => (scaled(m, q, 8 - e_low)?, e_low + 1),
        r => (r, e_low),
    };
    let mut digits = n + above_half as u64;
    if digits == 10_000_000_000 {
        digits = 1_000_000_000;
        e += 1;
    }
    (1_000_000_000..10_000_000_000)
        .contains(&digits)
        .then_some((digits, e))
}

/// `|x| 10^s` for `|x| = m 2^q`: its integer part and whether its
/// fraction is above one half; `None` when the fraction is
/// too close to one half to tell, or `s` is outside the table.
#[inline]
fn scaled(m: u64, q: i32, s: i32) -> Option<(u64, bool)> {
    let idx = s.checked_sub(S_MIN)?;
    let &(p, b) = POW10.get(usize::try_from(idx).ok()?)?;
    let (m, hi, lo) = (m as u128, p >> 64, p & u64::MAX as u128);
    // m p = t 2^64 + (low 64 bits, dropped): t < 2^118
    let t = m * hi + ((m * lo) >> 64);
    // |x| 10^s = t 2^(q + b + 64)
    let sh = -(q + b + 64);
    if !(40..=127).contains(&sh) {
        return None;
    }
    let int = t >> sh;
    let frac = t & ((1u128 << sh) - 1);
    let half = 1u128 << (sh - 1);
    // t is within 2 units of the exact product's (table and dropped bits)
    if frac.abs_diff(half) <= 8 {
        return None;
    }
    Some((u64::try_from(int).ok()?, frac > half))
}

#[cfg(test)]
mod tests {
    use super::push_e9;
    use rand_chacha::ChaCha8Rng;
    use rand_chacha::rand_core::{RngCore, SeedableRng};

    fn ours(x: f64) -> String {
        let mut s = Vec::new();
        push_e9(&mut s, x);
        String::from_utf8(s).unwrap()
    }

    fn check(x: f64) {
        assert_eq!(ours(x), format!("{x:.9e}"), "bits {:#018x}", x.to_bits());
    }

    /// Random bit patterns over the whole range, every exponent.
    #[test]
    fn equals_the_standard_library_on_random_bits() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..400_000 {
            check(f64::from_bits(rng.next_u64()));
        }
    }

    /// Values a run writes: displacements, velocities, forces, gaps and
    /// times of every size, short decimals and their neighbours.
    #[test]
    fn equals_the_standard_library_on_run_values() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let mut next = || rng.next_u64();
        for _ in 0..200_000 {
            let m = (next() >> 11) as f64 / (1u64 << 53) as f64;
            let e = (next() % 40) as i32 - 25;
            let x = (m - 0.5) * 10f64.powi(e);
            check(x);
            // a time on the step grid, and its neighbours
            let t = (next() % 10_000_000) as f64 * 1e-5;
            for y in [t, t.next_up(), t.next_down()] {
                check(y);
            }
        }
    }

    /// Ties, carries, powers of ten, the edges of the range and the values
    /// the fast path hands over.
    #[test]
    fn equals_the_standard_library_on_hard_values() {
        let mut xs = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            f64::MIN_POSITIVE.next_up(),
            5e-324,
            -5e-324,
            2.2250738585072e-309,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            9.9999999995,
            9.99999999949,
            9.9999999994999,
            9.99999999951,
            1.00000000005,
            1.00000000015,
            1.23456789050,
            1.23456789049999,
            0.5,
            0.125,
            1e-5,
            2e-5,
            123456.0,
            1e16,
            1.2345678905e16,
            1e22,
            1e23,
        ];
        for k in -320..=308 {
            let p = format!("1e{k}").parse::<f64>().unwrap();
            xs.extend([
                p,
                p.next_up(),
                p.next_down(),
                9.9999999995 * p,
                1.00000000005 * p,
            ]);
        }
        // eleven-digit decimals ending in 5 (ties of the shortest form) and
        // their neighbours
        for k in 0..2_000u64 {
            let x = format!(
                "{}.{:09}5e{}",
                1 + k % 9,
                k * 7919 % 1_000_000_000,
                k as i64 % 60 - 30
            )
            .parse::<f64>()
            .unwrap();
            xs.extend([x, x.next_up(), x.next_down(), -x]);
        }
        for x in xs {
            if x.is_nan() {
                assert_eq!(ours(x), "NaN");
            } else {
                check(x);
            }
        }
    }
}
