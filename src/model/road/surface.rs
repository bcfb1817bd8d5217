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

use super::{MAX_LINE_BYTES, OutOfRange};
use crate::base::error::SceneError;
use std::path::Path;

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
        }
    }

    /// The range of `y` (m) the grid covers; `None` when it repeats across.
    pub fn y_range_m(&self) -> Option<(f64, f64)> {
        (!self.periodic_y).then(|| (self.y0_m, self.y0_m + (self.ny - 1) as f64 * self.dy_m))
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
        let u = (y_m - self.y0_m) / self.dy_m;
        if self.periodic_y {
            let u = u.rem_euclid(self.ny as f64);
            let j0 = (u.floor() as usize).min(self.ny - 1);
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
        let j0 = (u.floor() as usize).min(self.ny.saturating_sub(2));
        Some(RowBlend {
            j0,
            j1: (j0 + 1).min(self.ny - 1),
            w: (u - j0 as f64).clamp(0.0, 1.0),
        })
    }

    /// Height (m) and slope along `x` (-) of row `j` at `x` (m).
    #[inline]
    fn sample_row(&self, j: usize, x_m: f64) -> Result<(f64, f64), OutOfRange> {
        let (z, d) = (
            &self.z_m[j * self.nx..(j + 1) * self.nx],
            &self.dzdx[j * self.nx..(j + 1) * self.nx],
        );
        let u = (x_m - self.x0_m) / self.dx_m;
        let (m, m1, s) = if self.looped {
            let u = rem_euclid_exact(u, self.nx as f64);
            // (`u >= 0`: the truncation is the floor, without a libm call)
            let m = (u as usize).min(self.nx - 1);
            (m, (m + 1) % self.nx, (u - m as f64).clamp(0.0, 1.0))
        } else {
            let last = (self.nx - 1) as f64;
            if !(u >= -GRID_TOLERANCE && u <= last + GRID_TOLERANCE) {
                let (min_m, max_m) = self.x_range_m();
                return Err(OutOfRange { x_m, min_m, max_m });
            }
            let u = u.clamp(0.0, last);
            let m = (u.floor() as usize).min(self.nx - 2);
            (m, m + 1, (u - m as f64).clamp(0.0, 1.0))
        };
        Ok(hermite(z[m], z[m1], d[m], d[m1], self.dx_m, s))
    }

    /// Height (m) and slope along `x` (-) where a point blending `rows`
    /// is at `x` (m).
    #[inline]
    pub fn sample_blend(&self, rows: RowBlend, x_m: f64) -> Result<(f64, f64), OutOfRange> {
        let (z0, d0) = self.sample_row(rows.j0, x_m)?;
        if rows.w == 0.0 {
            return Ok((z0, d0));
        }
        let (z1, d1) = self.sample_row(rows.j1, x_m)?;
        Ok((
            (1.0 - rows.w) * z0 + rows.w * z1,
            (1.0 - rows.w) * d0 + rows.w * d1,
        ))
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
            for seg in row.chunks_exact(per) {
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
        // (`u / n >= 0` below 2^52: the truncation is the floor)
        let k = (u / n) as u64 as f64;
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

/// Cubic Hermite interpolation over one interval of length `h` at
/// fraction `s`: height and slope.
#[inline]
fn hermite(z0: f64, z1: f64, d0: f64, d1: f64, h: f64, s: f64) -> (f64, f64) {
    let (d0, d1) = (d0 * h, d1 * h);
    let (s2, s3) = (s * s, s * s * s);
    let zv = (2.0 * s3 - 3.0 * s2 + 1.0) * z0
        + (s3 - 2.0 * s2 + s) * d0
        + (-2.0 * s3 + 3.0 * s2) * z1
        + (s3 - s2) * d1;
    let dv = ((6.0 * s2 - 6.0 * s) * (z0 - z1)
        + (3.0 * s2 - 4.0 * s + 1.0) * d0
        + (3.0 * s2 - 2.0 * s) * d1)
        / h;
    (zv, dv)
}

/// One row of a surface file as read.
struct Node {
    x: f64,
    y: f64,
    z: f64,
    line: u64,
}

/// Reads a surface file: the header `x_m,y_m,z_m` (spaces around commas and
/// `#` comment lines allowed), then one row per node of a regular grid, rows
/// in any order. See [`read_surface_csv_limited`].
pub fn read_surface_csv(path: &Path, looped: bool) -> Result<SurfaceGrid, SceneError> {
    read_surface_csv_limited(path, looped, MAX_SURFACE_NODES, MAX_SURFACE_BYTES)
}

/// [`read_surface_csv`] with explicit limits (nodes, bytes), so that the
/// limits can be tested on small files.
pub fn read_surface_csv_limited(
    path: &Path,
    looped: bool,
    max_nodes: usize,
    max_bytes: u64,
) -> Result<SurfaceGrid, SceneError> {
    let err = |message: String| SceneError::RoadFile {
        path: path.to_path_buf(),
        message,
    };
    let mut rdr = super::open_road_csv(
        path,
        "`x_m,y_m,z_m`",
        max_bytes,
        &format!("a grid of at most {max_nodes} nodes; resample the surface"),
    )?;
    let mut nodes: Vec<Node> = Vec::new();
    let mut rec = csv::ByteRecord::new();
    let mut header = false;
    loop {
        let more = rdr.read_byte_record(&mut rec).map_err(|e| match e.kind() {
            csv::ErrorKind::Io(io) if io.kind() == std::io::ErrorKind::InvalidData => err(format!(
                "{io}: expected `x_m,y_m,z_m` rows of at most {MAX_LINE_BYTES} bytes"
            )),
            _ => err(format!("{e}")),
        })?;
        if rdr.position().byte() > max_bytes {
            return Err(err(format!(
                "more than {max_bytes} bytes: expected a grid of at most {max_nodes} nodes"
            )));
        }
        if !more {
            break;
        }
        let line = rec.position().map_or(0, |p| p.line());
        let field = |k: usize| std::str::from_utf8(rec.get(k).unwrap_or(b"")).unwrap_or("\u{fffd}");
        if !header {
            let names: Vec<&str> = (0..rec.len()).map(field).collect();
            if names != ["x_m", "y_m", "z_m"] {
                return Err(err(format!(
                    "line {line}: header `{}`: expected the header `x_m,y_m,z_m`",
                    names.join(",")
                )));
            }
            header = true;
            continue;
        }
        if rec.len() != 3 {
            return Err(err(format!(
                "line {line}: {} column(s): expected three columns `x_m,y_m,z_m`",
                rec.len()
            )));
        }
        let mut v = [0.0; 3];
        for (k, name) in ["x_m", "y_m", "z_m"].iter().enumerate() {
            let s = field(k);
            v[k] = s.parse::<f64>().map_err(|_| {
                err(format!(
                    "line {line}, column {}: {name} = `{s}`: expected a number",
                    k + 1
                ))
            })?;
            if !v[k].is_finite() {
                return Err(err(format!(
                    "line {line}, column {}: {name} = {s}: expected a finite number",
                    k + 1
                )));
            }
        }
        if nodes.len() >= max_nodes {
            return Err(err(format!(
                "line {line}: more than {max_nodes} nodes: expected a grid of at most {max_nodes} nodes (resample the surface)"
            )));
        }
        nodes.push(Node {
            x: v[0],
            y: v[1],
            z: v[2],
            line,
        });
    }
    if !header {
        return Err(err(
            "empty file: expected the header `x_m,y_m,z_m` and one row per node".into(),
        ));
    }
    grid_of_nodes(&nodes, looped).map_err(err)
}

/// The axis of a set of coordinates: `(first, spacing, count)`, or why not
/// regular (naming a line).
fn axis(
    nodes: &[Node],
    name: &str,
    get: impl Fn(&Node) -> f64,
) -> Result<(f64, f64, usize), String> {
    let mut v: Vec<(f64, u64)> = nodes.iter().map(|n| (get(n), n.line)).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (lo, hi) = (v[0].0, v[v.len() - 1].0);
    let tol = GRID_TOLERANCE * (hi - lo).abs().max(f64::MIN_POSITIVE);
    // distinct values (within the tolerance), with the line of their first row
    let mut distinct: Vec<(f64, u64)> = Vec::new();
    for &(c, line) in &v {
        match distinct.last_mut() {
            Some(last) if c - last.0 <= tol => last.1 = last.1.min(line),
            _ => distinct.push((c, line)),
        }
    }
    let n = distinct.len();
    if n < 2 {
        return Err(format!(
            "one {name} value ({lo} m): expected a grid of at least 2 × 2 nodes"
        ));
    }
    let step = (hi - lo) / (n - 1) as f64;
    for w in distinct.windows(2) {
        let gap = w[1].0 - w[0].0;
        if (gap - step).abs() > GRID_TOLERANCE * step {
            return Err(format!(
                "line {}: {name} = {} m follows {name} = {} m: a spacing of {gap:e} m where the grid's is {step:e} m (expected a regular grid, spacings equal within {GRID_TOLERANCE:e} relative)",
                w[1].1, w[1].0, w[0].0
            ));
        }
    }
    Ok((lo, step, n))
}

/// Places every node on the grid its coordinates define; refuses duplicates
/// and missing nodes.
fn grid_of_nodes(nodes: &[Node], looped: bool) -> Result<SurfaceGrid, String> {
    if nodes.len() < 4 {
        return Err(format!(
            "{} data row(s): expected a grid of at least 2 × 2 nodes",
            nodes.len()
        ));
    }
    let (x0, dx, nx) = axis(nodes, "x_m", |n| n.x)?;
    let (y0, dy, ny) = axis(nodes, "y_m", |n| n.y)?;
    let mut z = vec![f64::NAN; nx * ny];
    let mut seen: Vec<u64> = vec![0; nx * ny];
    for n in nodes {
        let i = ((n.x - x0) / dx).round() as usize;
        let j = ((n.y - y0) / dy).round() as usize;
        let k = j * nx + i;
        if seen[k] != 0 {
            return Err(format!(
                "line {}: node x_m = {} m, y_m = {} m given again (first at line {}): expected one row per node",
                n.line, n.x, n.y, seen[k]
            ));
        }
        seen[k] = n.line;
        z[k] = n.z;
    }
    if let Some(k) = seen.iter().position(|&l| l == 0) {
        let (i, j) = (k % nx, k / nx);
        return Err(format!(
            "{} rows for a grid of {nx} × {ny} = {} nodes: node x_m = {} m, y_m = {} m is missing (expected every node of the grid)",
            nodes.len(),
            nx * ny,
            x0 + i as f64 * dx,
            y0 + j as f64 * dy
        ));
    }
    if !looped && nx < 2 {
        return Err("one column along x: expected at least two".into());
    }
    Ok(SurfaceGrid::from_heights(
        (x0, dx, nx),
        (y0, dy, ny),
        looped,
        z,
    ))
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
    use std::io::Write;

    fn write(text: &str) -> tempfile::NamedTempFile {
        let mut f = tempfile::NamedTempFile::new().unwrap();
        f.write_all(text.as_bytes()).unwrap();
        f
    }

    /// A plane `z = a x + b y + c` is reproduced exactly between the nodes
    /// (Hermite with exact slopes, linear across), with rows shuffled.
    #[test]
    fn a_plane_is_interpolated_exactly_from_shuffled_rows() {
        let (a, b, c) = (0.01, -0.02, 0.003);
        let mut rows = Vec::new();
        for j in 0..4 {
            for i in 0..7 {
                let (x, y) = (0.1 + i as f64 * 0.005, -0.01 + j as f64 * 0.0075);
                rows.push(format!("{x} , {y},{}", a * x + b * y + c));
            }
        }
        rows.reverse();
        rows.swap(3, 17);
        let text = format!("# a plane\nx_m, y_m ,z_m\n{}\n", rows.join("\n"));
        let f = write(&text);
        let g = read_surface_csv(f.path(), false).unwrap();
        assert_eq!((g.nx, g.ny), (7, 4));
        for (x, y) in [(0.1, -0.01), (0.1123, 0.0), (0.13, 0.0125), (0.117, 0.004)] {
            let (z, dz) = g.sample(x, y).unwrap();
            assert!((z - (a * x + b * y + c)).abs() < 1e-15, "z at ({x}, {y})");
            assert!((dz - a).abs() < 1e-12, "slope at ({x}, {y}): {dz}");
        }
        assert!(g.sample(0.2, 0.0).is_err());
        assert!(g.rows_at(0.02).is_none() && g.rows_at(-0.0101).is_none());
    }

    #[test]
    fn bad_files_are_refused_naming_the_line() {
        let cases = [
            ("x,y,z\n0,0,0\n", "line 1: header `x,y,z`"),
            (
                "x_m,y_m,z_m\n0,0,0\n1,0,0\n0,1,0\n1,1,zz\n",
                "line 5, column 3: z_m = `zz`",
            ),
            (
                "x_m,y_m,z_m\n0,0,0\n1,0,0\n0,1,0\n1,1,0\n1,1,2\n",
                "line 6: node x_m = 1 m, y_m = 1 m given again (first at line 5)",
            ),
            ("x_m,y_m,z_m\n0,0,0\n1,0,0\n0,1,0\n", "3 data row(s)"),
            (
                "x_m,y_m,z_m\n0,0,0\n1,0,0\n3,0,0\n0,1,0\n1,1,0\n3,1,0\n",
                "line 3: x_m = 1 m follows x_m = 0 m: a spacing of 1e0 m where the grid's is 1.5e0 m",
            ),
            (
                "x_m,y_m,z_m\n0,0,0\n1,0,0\n2,0,0\n0,1,0\n1,1,0\n",
                "node x_m = 2 m, y_m = 1 m is missing",
            ),
            ("x_m,y_m,z_m\n0,0,0\n1,0\n", "line 3: 2 column(s)"),
            (
                "x_m,y_m,z_m\n0,0,inf\n",
                "line 2, column 3: z_m = inf: expected a finite number",
            ),
        ];
        for (text, want) in cases {
            let f = write(text);
            let e = read_surface_csv(f.path(), false).unwrap_err().to_string();
            assert!(e.contains(want), "{text:?}: {e}");
        }
        // the node cap
        let f = write("x_m,y_m,z_m\n0,0,0\n1,0,0\n0,1,0\n1,1,0\n");
        let e = read_surface_csv_limited(f.path(), false, 3, 1 << 20)
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 5: more than 3 nodes"), "{e}");
        let e = read_surface_csv_limited(f.path(), false, 100, 10)
            .unwrap_err()
            .to_string();
        assert!(e.contains("expected at most 10 bytes"), "{e}");
    }

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
}
