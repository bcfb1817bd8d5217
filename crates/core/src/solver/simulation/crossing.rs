//! Where a free point lands inside a step (method §4.4, "Impact location"):
//! the first crossing of the road by the cubic Hermite interpolant of its
//! gap, from the gap and its rate at the step's two ends; a cheap bound
//! rejects most points, Newton steps kept in the root's bracket locate it.

/// First `y ∈ (0, 1]` where the cubic Hermite interpolant with values `g0`,
/// `g1` and scaled slopes `d0`, `d1` (slope × interval) goes below `-tol`;
/// returns the zero crossing before it. With
/// `require_rise`, only a crossing after the cubic rose above `+tol` counts.
#[inline]
pub fn first_crossing(
    g0: f64,
    d0: f64,
    g1: f64,
    d1: f64,
    tol: f64,
    require_rise: bool,
) -> Option<f64> {
    // A start slightly below the road (round-off, or the O(θ⁴) gap of a point
    // just thrown off) counts as on the road: falling, it lands at once;
    // rising, it lands where it comes back.
    // (`g0.max(0.0)` as a plain comparison: a NaN becomes 0 as with `max`)
    let g0 = if g0 > 0.0 { g0 } else { 0.0 };
    if clear_of_road(g0, d0, g1, d1, tol) {
        return None;
    }
    crossing_of_cubic::<true>(g0, d0, g1, d1, tol, require_rise)
}

/// Whether [`first_crossing`] finds a crossing, without locating it (the
/// steady trial only asks whether any free point lands).
#[inline]
pub fn crosses(g0: f64, d0: f64, g1: f64, d1: f64, tol: f64, require_rise: bool) -> bool {
    let g0 = if g0 > 0.0 { g0 } else { 0.0 };
    !clear_of_road(g0, d0, g1, d1, tol)
        && crossing_of_cubic::<false>(g0, d0, g1, d1, tol, require_rise).is_some()
}

/// The cheap rejection (inlined: most free points of most steps): all of
/// the cubic is above `-tol`. On `[0, 1]` the Hermite basis has
/// `H00 + H01 = 1` (both >= 0), `0 <= H10 <= 4/27` and `-4/27 <= H11 <= 0`,
/// so the cubic is at least `min(g0, g1) - 4/27 (max(0, -d0) + max(0, d1))`;
/// past `g1 >= -tol` neither value is a NaN, so the plain minimum is
/// `f64::min`. `g0 >= 0`.
#[inline(always)]
fn clear_of_road(g0: f64, d0: f64, g1: f64, d1: f64, tol: f64) -> bool {
    if g1 >= -tol {
        let low = if g0 < g1 { g0 } else { g1 };
        let dip = (if d0 < 0.0 { -d0 } else { 0.0 }) + (if d1 > 0.0 { d1 } else { 0.0 });
        low - (4.0 / 27.0) * dip >= -tol
    } else {
        false
    }
}

/// [`first_crossing`] past its cheap rejection, `g0 >= 0`; with `LOCATE`
/// false, any `Some` once the crossing is known to exist.
fn crossing_of_cubic<const LOCATE: bool>(
    g0: f64,
    d0: f64,
    g1: f64,
    d1: f64,
    tol: f64,
    require_rise: bool,
) -> Option<f64> {
    let c = [
        g0,
        d0,
        -3.0 * g0 - 2.0 * d0 + 3.0 * g1 - d1,
        2.0 * g0 + d0 - 2.0 * g1 + d1,
    ];
    let p = |y: f64| ((c[3] * y + c[2]) * y + c[1]) * y + c[0];
    // breakpoints: critical points of the cubic in (0, 1), then 1
    let (qa, qb, qc) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let mut bp = [1.0f64; 3];
    let mut nb = 0;
    if qa.abs() > 1e-300 {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let sq = disc.sqrt();
            let qq = -0.5 * (qb + qb.signum() * sq);
            for y in [qq / qa, if qq != 0.0 { qc / qq } else { f64::NAN }] {
                if y > 0.0 && y < 1.0 {
                    bp[nb] = y;
                    nb += 1;
                }
            }
        }
    } else if qb.abs() > 1e-300 {
        let y = -qc / qb;
        if y > 0.0 && y < 1.0 {
            bp[nb] = y;
            nb += 1;
        }
    }
    bp[nb] = 1.0;
    let bps = &mut bp[..nb + 1];
    bps.sort_by(f64::total_cmp);
    let mut ya = 0.0;
    let mut risen = !require_rise || g0 > tol;
    for &yb in bps.iter() {
        let pb = p(yb);
        if risen && pb < -tol {
            if !LOCATE {
                return Some(ya);
            }
            let pa = p(ya);
            if pa < 0.0 {
                return Some(ya);
            }
            return Some(monotone_root(&c, ya, pa, yb, pb));
        }
        risen |= pb > tol;
        ya = yb;
    }
    None
}

/// The root of the cubic `c` (coefficients from the constant up) on
/// `[lo, hi]`, where it decreases from `p_lo >= 0` to `p_hi < 0`: Newton's
/// steps while they stay inside the bracket (which every value narrows),
/// a bisection where one would leave it; done when a step moves `y` by
/// less than 2 ε (`y` is a fraction of the interval) or the bracket holds
/// no float between its ends.
fn monotone_root(c: &[f64; 4], mut lo: f64, p_lo: f64, mut hi: f64, p_hi: f64) -> f64 {
    let p = |y: f64| ((c[3] * y + c[2]) * y + c[1]) * y + c[0];
    let dp = |y: f64| (3.0 * c[3] * y + 2.0 * c[2]) * y + c[1];
    // start from the secant's root: on a near-linear piece it is the answer
    let mut y = lo + (hi - lo) * (p_lo / (p_lo - p_hi));
    if !(y > lo && y < hi) {
        y = 0.5 * (lo + hi);
    }
    for _ in 0..100 {
        let v = p(y);
        if v == 0.0 {
            return y;
        }
        if v > 0.0 {
            lo = y;
        } else {
            hi = y;
        }
        let newton = y - v / dp(y);
        if newton > lo && newton < hi {
            if (newton - y).abs() <= 2.0 * f64::EPSILON {
                return newton;
            }
            y = newton;
        } else {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            y = mid;
        }
    }
    0.5 * (lo + hi)
}
