//! Roads that vary across the tread: a height grid `z(x, y)` read from a
//! CSV file (`Road::Surface`) or generated as a random texture
//! (`Road::Texture`, see [`texture`](super::texture)), method §4.8.
//!
//! A point `(x_i, y_i)` at time `t` bears on `R(x_i + V t, y_i)`, the
//! convention of the profile roads. Points do not move across the tread, so
//! each point sees the blend of two grid rows,
//!
//! ```text
//! z_i(s) = (1 - w_i) Z_j(x_i + s) + w_i Z_{j+1}(x_i + s),   y_i = y_j + w_i Δy,
//! ```
//!
//! and each row `Z_j(x)` is a cubic Hermite curve through its nodes with
//! slopes `dZ/dx` at the nodes (exact slopes for a texture, centred
//! differences for a file: Catmull-Rom). `z_i` and `dz_i/dx` are continuous
//! along the rolling direction: the grid's lines are not contact events.

use super::OutOfRange;

/// Relative tolerance on a grid's spacing: a coordinate is on the grid when
/// it is within `1e-9 Δ` of a node.
pub const GRID_TOLERANCE: f64 = 1e-9;

/// Largest surface grid (nodes): a file's rows take 32 bytes each while it
/// is read (x, y, z and the line number), 256 MB at the cap; the grid
/// keeps 16 bytes per node (heights and slopes).
pub const MAX_SURFACE_NODES: usize = 8_000_000;

/// Largest surface file (bytes), checked before reading: 64 bytes per node
/// of [`MAX_SURFACE_NODES`] (a row of three full-precision numbers is
/// about 65 bytes; most files write fewer digits).
pub const MAX_SURFACE_BYTES: u64 = 80 * MAX_SURFACE_NODES as u64;

/// A regular height grid, row-major across: node `(i, j)` at
/// `x = x0 + i Δx`, `y = y0 + j Δy` holds `z[j nx + i]` and its slope
/// along `x`, `dzdx[j nx + i]`.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceGrid {
    pub x0_m: f64,
    pub dx_m: f64,
    pub nx: usize,
    pub y0_m: f64,
    pub dy_m: f64,
    pub ny: usize,
    /// Repeats along `x` with period `nx Δx` (its last column is not the
    /// first repeated).
    pub looped: bool,
    /// Repeats across `y` with period `ny Δy` (a generated texture); a
    /// file's grid covers `[y0, y0 + (ny - 1) Δy]` only.
    pub periodic_y: bool,
    pub z_m: Vec<f64>,
    pub dzdx: Vec<f64>,
    /// The rows' positions across (m), strictly increasing, where they are
    /// not evenly spaced (an OpenCRG file's long sections at explicit `v`);
    /// empty for an even grid. `y0_m` is then the first and `dy_m` the mean
    /// spacing.
    pub rows_y_m: Vec<f64>,
    /// The height (m) taken off the file's heights to refer them to the
    /// road's mean plane (an OpenCRG file); 0 otherwise.
    pub datum_m: f64,
    /// The file's own coordinates (m) of `(x, y) = (0, 0)`: an OpenCRG
    /// file's `(u, v)` there; `(0, 0)` otherwise.
    pub file_origin_m: (f64, f64),
}

/// Where a point sits across the grid: rows `j0`, `j1` and the weight `w`
/// of `j1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RowBlend {
    pub j0: usize,
    pub j1: usize,
    pub w: f64,
}

impl SurfaceGrid {
    /// Builds a grid from its heights, computing the slopes along `x` by
    /// centred differences (one-sided at the ends of a grid that is not
    /// looped).
    pub fn from_heights(
        (x0_m, dx_m, nx): (f64, f64, usize),
        (y0_m, dy_m, ny): (f64, f64, usize),
        looped: bool,
        z_m: Vec<f64>,
    ) -> Self {
        let mut dzdx = vec![0.0; z_m.len()];
        for j in 0..ny {
            let row = &z_m[j * nx..(j + 1) * nx];
            let d = &mut dzdx[j * nx..(j + 1) * nx];
            for i in 0..nx {
                d[i] = if nx < 2 {
                    0.0
                } else if looped {
                    (row[(i + 1) % nx] - row[(i + nx - 1) % nx]) / (2.0 * dx_m)
                } else if i == 0 {
                    (row[1] - row[0]) / dx_m
                } else if i == nx - 1 {
                    (row[i] - row[i - 1]) / dx_m
                } else {
                    (row[i + 1] - row[i - 1]) / (2.0 * dx_m)
                };
            }
        }
        SurfaceGrid {
            x0_m,
            dx_m,
            nx,
            y0_m,
            dy_m,
            ny,
            looped,
            periodic_y: false,
            z_m,
            dzdx,
            rows_y_m: Vec::new(),
            datum_m: 0.0,
            file_origin_m: (0.0, 0.0),
        }
    }

    /// The range of `y` (m) the grid covers; `None` when it repeats across.
    pub fn y_range_m(&self) -> Option<(f64, f64)> {
        (!self.periodic_y).then(|| match self.rows_y_m.last() {
            Some(&last) => (self.y0_m, last),
            None => (self.y0_m, self.y0_m + (self.ny - 1) as f64 * self.dy_m),
        })
    }

    /// The range of `x` (m) covered by one period (looped) or by the grid.
    pub fn x_range_m(&self) -> (f64, f64) {
        let n = if self.looped { self.nx } else { self.nx - 1 };
        (self.x0_m, self.x0_m + n as f64 * self.dx_m)
    }

    /// Largest |z| (m).
    pub fn scale_m(&self) -> f64 {
        self.z_m.iter().fold(0.0, |m, z| m.max(z.abs()))
    }

    /// The rows a point at `y` (m) blends; `None` outside a file's grid.
    pub fn rows_at(&self, y_m: f64) -> Option<RowBlend> {
        if !self.rows_y_m.is_empty() {
            return self.uneven_rows_at(y_m);
        }
        let u = (y_m - self.y0_m) / self.dy_m;
        if self.periodic_y {
            let u = u.rem_euclid(self.ny as f64);
            // (`u >= 0`: truncation is the floor, without a libm call)
            let j0 = (u as usize).min(self.ny - 1);
            return Some(RowBlend {
                j0,
                j1: (j0 + 1) % self.ny,
                w: (u - j0 as f64).clamp(0.0, 1.0),
            });
        }
        let last = (self.ny - 1) as f64;
        // on the edges within the grid's tolerance
        if !(u >= -GRID_TOLERANCE && u <= last + GRID_TOLERANCE) {
            return None;
        }
        let u = u.clamp(0.0, last);
        // (`u >= 0` after the clamp: truncation is the floor)
        let j0 = (u as usize).min(self.ny.saturating_sub(2));
        Some(RowBlend {
            j0,
            j1: (j0 + 1).min(self.ny - 1),
            w: (u - j0 as f64).clamp(0.0, 1.0),
        })
    }

    /// [`SurfaceGrid::rows_at`] on rows at the positions `rows_y_m`:
    /// linear between the two rows around `y`.
    fn uneven_rows_at(&self, y_m: f64) -> Option<RowBlend> {
        let y = &self.rows_y_m;
        let (lo, hi) = (y[0], y[y.len() - 1]);
        let tol = GRID_TOLERANCE * self.dy_m;
        if !(y_m >= lo - tol && y_m <= hi + tol) {
            return None;
        }
        if y.len() == 1 {
            return Some(RowBlend {
                j0: 0,
                j1: 0,
                w: 0.0,
            });
        }
        let yy = y_m.clamp(lo, hi);
        // rows j0 < j1 with y[j0] <= yy <= y[j1]
        let j0 = (y.partition_point(|&r| r <= yy).max(1) - 1).min(y.len() - 2);
        let w = ((yy - y[j0]) / (y[j0 + 1] - y[j0])).clamp(0.0, 1.0);
        Some(RowBlend { j0, j1: j0 + 1, w })
    }

    /// The first node without height (its `(x, y)`, m) that a point
    /// blending `rows` reads while it moves from `x_from_m` to `x_to_m`
    /// (the nodes of every interval it crosses, in the rows of weight > 0);
    /// `None` if there is none. For a grid that is not looped.
    pub fn gap_on_path(&self, rows: RowBlend, x_from_m: f64, x_to_m: f64) -> Option<(f64, f64)> {
        let last = self.nx.saturating_sub(1);
        let index = |x: f64| ((x - self.x0_m) / self.dx_m).clamp(0.0, last as f64);
        let (a, b) = (index(x_from_m.min(x_to_m)), index(x_from_m.max(x_to_m)));
        let (m0, m1) = (a.floor() as usize, (b.ceil() as usize).min(last));
        let mut used = Vec::with_capacity(2);
        if rows.w < 1.0 {
            used.push(rows.j0);
        }
        if rows.w > 0.0 {
            used.push(rows.j1);
        }
        for m in m0..=m1 {
            for &j in &used {
                if !self.z_m[j * self.nx + m].is_finite() {
                    let y = self
                        .rows_y_m
                        .get(j)
                        .copied()
                        .unwrap_or(self.y0_m + j as f64 * self.dy_m);
                    return Some((self.x0_m + m as f64 * self.dx_m, y));
                }
            }
        }
        None
    }

    /// The cell of `x` (m) along the rows: its first and last columns and
    /// the fraction `s` across it (the same for every row).
    #[inline(always)]
    pub(crate) fn cell(&self, x_m: f64) -> Result<(usize, usize, f64), OutOfRange> {
        let u = (x_m - self.x0_m) / self.dx_m;
        // (cells are counted in i64, whose conversions from and to f64 are
        // single instructions: `u` is below the grid's size)
        if self.looped {
            let u = rem_euclid_exact(u, self.nx as f64);
            // (`u >= 0`: the truncation is the floor, without a libm call)
            let k = (u as i64).min(self.nx as i64 - 1);
            let m = k as usize;
            // (the wrap without an integer division)
            let m1 = if m + 1 == self.nx { 0 } else { m + 1 };
            Ok((m, m1, (u - k as f64).clamp(0.0, 1.0)))
        } else {
            let last = (self.nx - 1) as f64;
            if !(u >= -GRID_TOLERANCE && u <= last + GRID_TOLERANCE) {
                let (min_m, max_m) = self.x_range_m();
                return Err(OutOfRange { x_m, min_m, max_m });
            }
            // (`u >= 0`, not a NaN past the range check: the truncation is
            // the floor, without a libm call)
            let u = u.clamp(0.0, last);
            let k = (u as i64).min(self.nx as i64 - 2);
            let m = k as usize;
            Ok((m, m + 1, (u - k as f64).clamp(0.0, 1.0)))
        }
    }

    /// The cubic of row `j` over the cell `(m, m1)` in powers of the
    /// fraction `s` ([`hermite_cubic`]).
    #[inline(always)]
    fn row_cubic(&self, j: usize, m: usize, m1: usize) -> [f64; 4] {
        let (z, d) = (
            &self.z_m[j * self.nx..(j + 1) * self.nx],
            &self.dzdx[j * self.nx..(j + 1) * self.nx],
        );
        hermite_cubic(z[m], z[m1], d[m] * self.dx_m, d[m1] * self.dx_m)
    }

    /// The height of a point blending `rows` over the cell `(m, m1)` as a
    /// cubic in the fraction `s` across it: the blend of the two rows'
    /// cubics (a row of weight 0 is not read: it may hold no height there).
    /// [`SurfaceGrid::cubic_at`] evaluates it.
    #[inline]
    pub fn blend_cubic(&self, rows: RowBlend, m: usize, m1: usize) -> [f64; 4] {
        if rows.w == 1.0 {
            return self.row_cubic(rows.j1, m, m1);
        }
        let a = self.row_cubic(rows.j0, m, m1);
        if rows.w == 0.0 {
            return a;
        }
        let b = self.row_cubic(rows.j1, m, m1);
        let w = rows.w;
        std::array::from_fn(|k| (1.0 - w) * a[k] + w * b[k])
    }

    /// Height (m) and slope along `x` (-) of the cell cubic `c` at the
    /// fraction `s`.
    #[inline(always)]
    pub fn cubic_at(&self, c: &[f64; 4], s: f64) -> (f64, f64) {
        let z = ((c[3] * s + c[2]) * s + c[1]) * s + c[0];
        let dz = ((3.0 * c[3] * s + 2.0 * c[2]) * s + c[1]) / self.dx_m;
        (z, dz)
    }

    /// Height (m) and slope along `x` (-) where a point blending `rows`
    /// is at `x` (m): the blended cubic of the cell of `x` at its fraction.
    #[inline]
    pub fn sample_blend(&self, rows: RowBlend, x_m: f64) -> Result<(f64, f64), OutOfRange> {
        let (m, m1, s) = self.cell(x_m)?;
        Ok(self.cubic_at(&self.blend_cubic(rows, m, m1), s))
    }

    /// Height (m) and slope (-) at `(x, y)`; `y` outside a file's grid is
    /// clamped to its nearest edge (points are checked against it first).
    pub fn sample(&self, x_m: f64, y_m: f64) -> Result<(f64, f64), OutOfRange> {
        let y = match self.y_range_m() {
            Some((lo, hi)) => y_m.clamp(lo, hi),
            None => y_m,
        };
        // a finite y in range always has rows
        let rows = self.rows_at(y).unwrap_or(RowBlend {
            j0: 0,
            j1: 0,
            w: 0.0,
        });
        self.sample_blend(rows, x_m)
    }

    /// The mean profile depth (m) of the grid's rows along `x`, ISO
    /// 13473-1: each row is cut into 100 mm baselines; on each, the
    /// least-squares line is removed and the mean segment depth is the mean
    /// of the peaks of its two 50 mm halves; MPD is the mean over all
    /// baselines of all rows. `None` when a row is shorter than 100 mm.
    pub fn mpd_m(&self) -> Option<f64> {
        let per = (MPD_BASELINE_M / self.dx_m).round() as usize;
        if per < 4 || self.nx < per {
            return None;
        }
        let (mut sum, mut count) = (0.0, 0usize);
        for j in 0..self.ny {
            let row = &self.z_m[j * self.nx..(j + 1) * self.nx];
            // (a baseline over cells without height is left out)
            for seg in row
                .chunks_exact(per)
                .filter(|s| s.iter().all(|z| z.is_finite()))
            {
                sum += segment_depth(seg);
                count += 1;
            }
        }
        (count > 0).then(|| sum / count as f64)
    }
}

/// `u.rem_euclid(n)` for a whole number `n >= 1`, without the software
/// `fmod` where `0 <= u < 2^52`: `u - k n` with `k = ⌊u / n⌋` (corrected
/// by one where the quotient rounded across a whole number) is exact there
/// (a multiple of `ulp(u)`, no larger than `u`), as `fmod` is: the same
/// value, bit for bit.
#[inline]
fn rem_euclid_exact(u: f64, n: f64) -> f64 {
    if (0.0..n).contains(&u) {
        return u;
    }
    if (0.0..4_503_599_627_370_496.0).contains(&u) {
        // (`u / n >= 0` below 2^52: the truncation is the floor, and a
        // signed conversion is one instruction where an unsigned one is
        // several)
        let k = (u / n) as i64 as f64;
        let r = u - k * n;
        if r < 0.0 {
            return u - (k - 1.0) * n;
        }
        if r >= n {
            return u - (k + 1.0) * n;
        }
        return r;
    }
    u.rem_euclid(n)
}

/// Baseline of the mean profile depth (m), ISO 13473-1.
pub const MPD_BASELINE_M: f64 = 0.1;

/// Mean segment depth of one baseline of equally spaced heights (ISO
/// 13473-1): the least-squares line removed, the mean of the two halves'
/// peaks.
pub fn segment_depth(seg: &[f64]) -> f64 {
    let n = seg.len() as f64;
    let xm = (n - 1.0) / 2.0;
    let zm = seg.iter().sum::<f64>() / n;
    let (mut sxz, mut sxx) = (0.0, 0.0);
    for (i, z) in seg.iter().enumerate() {
        let dx = i as f64 - xm;
        sxz += dx * (z - zm);
        sxx += dx * dx;
    }
    let slope = if sxx > 0.0 { sxz / sxx } else { 0.0 };
    let detrended = |i: usize| seg[i] - zm - slope * (i as f64 - xm);
    let half = seg.len() / 2;
    let peak = |r: std::ops::Range<usize>| r.map(detrended).fold(f64::NEG_INFINITY, f64::max);
    0.5 * (peak(0..half) + peak(half..seg.len()))
}

/// The cubic Hermite interpolant through `z0` at `s = 0` and `z1` at
/// `s = 1` with slopes `d0`, `d1` per unit of `s` (a node's `dz/dx` times
/// the spacing), in powers of `s`: `z(s) = c0 + c1 s + c2 s² + c3 s³`.
#[inline(always)]
fn hermite_cubic(z0: f64, z1: f64, d0: f64, d1: f64) -> [f64; 4] {
    [
        z0,
        d0,
        3.0 * (z1 - z0) - 2.0 * d0 - d1,
        2.0 * (z0 - z1) + d0 + d1,
    ]
}

#[cfg(test)]
mod tests {
    /// The wrap of a looped grid equals `rem_euclid` bit for bit: near
    /// every multiple of the period, at large distances, for odd periods
    /// and below zero.
    #[test]
    fn the_exact_wrap_equals_rem_euclid_bit_for_bit() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for n in [1.0, 2.0, 3.0, 7.0, 500.0, 1001.0, 65_537.0] {
            for _ in 0..20_000 {
                let k = (next() % 100_000) as f64;
                let ulps = (next() % 9) as i64 - 4;
                let base: f64 = k * n;
                // a few ulps either side of a multiple of the period
                let u = f64::from_bits((base.to_bits() as i64 + ulps).max(0) as u64);
                let w = (next() % 1_000_000) as f64 / 1_000.0 * n;
                let neg = -((next() % 1_000_000) as f64) / 997.0;
                for x in [u, w, neg, base + 0.5, 4.5e15, 1e300] {
                    assert_eq!(
                        super::rem_euclid_exact(x, n).to_bits(),
                        x.rem_euclid(n).to_bits(),
                        "u = {x:e}, n = {n}"
                    );
                }
            }
        }
    }

    use super::*;

    /// A looped grid's period is `nx Δx`: the surface `sin(2π x / L)`
    /// sampled on `nx` columns repeats seamlessly across the wrap.
    #[test]
    fn a_looped_grid_repeats_with_period_nx_dx() {
        let (nx, ny, dx) = (64, 2, 0.01);
        let len = nx as f64 * dx;
        let z: Vec<f64> = (0..ny)
            .flat_map(|_| {
                (0..nx).map(move |i| 1e-3 * (std::f64::consts::TAU * i as f64 * dx / len).sin())
            })
            .collect();
        let g = SurfaceGrid::from_heights((0.0, dx, nx), (0.0, 0.01, ny), true, z);
        for x in [-0.3, 0.005, 0.637, 0.6395, 1.0] {
            let want = 1e-3 * (std::f64::consts::TAU * x / len).sin();
            let (zz, _) = g.sample(x, 0.005).unwrap();
            assert!((zz - want).abs() < 2e-7, "x = {x}: {zz} vs {want}");
            // one period on
            let (z2, _) = g.sample(x + len, 0.005).unwrap();
            assert!((z2 - zz).abs() < 1e-15);
        }
    }

    /// ISO 13473-1 on closed forms: on each 100 mm baseline, a cosine
    /// symmetric about the baseline's centre (so that it adds nothing to the
    /// least-squares line) with its peaks on nodes of both halves has a
    /// segment depth of its amplitude less its mean; a tilt is removed.
    #[test]
    fn mean_profile_depth_of_cosines_and_tilts() {
        let per = 201; // nodes per 100 mm baseline, centre node 100
        let dx = MPD_BASELINE_M / per as f64;
        let (nx, amp) = (3 * per, 7e-4);
        let cosine = |m: usize| (std::f64::consts::TAU * (m as f64 - 100.0) / 40.0).cos();
        let mean = (0..per).map(cosine).sum::<f64>() / per as f64;
        for tilt in [0.0, 0.02, -0.3] {
            let z: Vec<f64> = (0..2)
                .flat_map(|_| (0..nx).map(move |i| amp * cosine(i % per) + tilt * i as f64 * dx))
                .collect();
            let g = SurfaceGrid::from_heights((0.0, dx, nx), (0.0, 0.01, 2), false, z);
            let mpd = g.mpd_m().unwrap();
            let want = amp * (1.0 - mean);
            assert!(
                (mpd - want).abs() < 1e-12 * amp.max(tilt.abs()),
                "tilt {tilt}: MPD {mpd} vs {want}"
            );
        }
        // shorter than a baseline: no MPD
        let g = SurfaceGrid::from_heights((0.0, dx, 100), (0.0, 0.01, 2), false, vec![0.0; 200]);
        assert!(g.mpd_m().is_none());
    }

    /// The cell cubic in powers of `s` is the cubic Hermite interpolant:
    /// it equals the textbook basis form (`h00 z0 + h10 d0 + h01 z1 + h11
    /// d1` and its derivative) to round-off over random cells, and passes
    /// through the nodes' heights and slopes at both ends.
    #[test]
    fn the_cell_cubic_is_the_hermite_interpolant() {
        use rand_chacha::ChaCha8Rng;
        use rand_chacha::rand_core::{RngCore, SeedableRng};
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let mut next = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        let h = 0.002;
        let g = SurfaceGrid::from_heights((0.0, h, 2), (0.0, 0.01, 1), false, vec![0.0; 2]);
        for _ in 0..10_000 {
            let scale = 10f64.powi((next() * 12.0) as i32);
            let (z0, z1) = (next() * scale, next() * scale);
            let (dz0, dz1) = (next() * scale / h, next() * scale / h);
            let c = hermite_cubic(z0, z1, dz0 * h, dz1 * h);
            for s in [0.0, 1e-9, 0.25, 0.5, 0.7, 1.0 - 1e-12, 1.0, next() + 0.5] {
                let (zz, dd) = g.cubic_at(&c, s);
                let (s2, s3) = (s * s, s * s * s);
                let want = (2.0 * s3 - 3.0 * s2 + 1.0) * z0
                    + (s3 - 2.0 * s2 + s) * dz0 * h
                    + (-2.0 * s3 + 3.0 * s2) * z1
                    + (s3 - s2) * dz1 * h;
                let dwant = (6.0 * s2 - 6.0 * s) * (z0 - z1) / h
                    + (3.0 * s2 - 4.0 * s + 1.0) * dz0
                    + (3.0 * s2 - 2.0 * s) * dz1;
                let size = z0.abs() + z1.abs() + (dz0.abs() + dz1.abs()) * h;
                assert!(
                    (zz - want).abs() <= 1e-14 * size,
                    "z at s = {s}: {zz} vs {want}"
                );
                assert!(
                    (dd - dwant).abs() <= 1e-13 * size / h,
                    "dz at s = {s}: {dd} vs {dwant}"
                );
            }
            // the nodes
            assert_eq!(g.cubic_at(&c, 0.0), (z0, dz0 * h / h));
            let (ze, de) = g.cubic_at(&c, 1.0);
            assert!(
                (ze - z1).abs()
                    <= 4.0 * f64::EPSILON * (z0.abs() + z1.abs() + (dz0.abs() + dz1.abs()) * h)
            );
            assert!(
                (de - dz1).abs() <= 1e-14 * (z0.abs() + z1.abs() + (dz0.abs() + dz1.abs()) * h) / h
            );
        }
    }
}
