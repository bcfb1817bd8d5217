//! ASAM OpenCRG road files (method §4.8): a regular grid of heights over a
//! reference line, `u` along it and `v` across it (positive to the left),
//! written after a text header of named blocks.
//!
//! What is read, after ASAM OpenCRG 1.2: the file format as the
//! standard's reference loader (`crgLoader`) reads it, and its evaluation
//! method `crgEvaluv2z` (bilinear grid, reference line height and
//! banking):
//!
//! - `$CT`: comment text, skipped.
//! - `$ROAD_CRG`: `reference_line_start_u`, `reference_line_end_u`,
//!   `reference_line_increment` (the cross sections `u_k = u_start + k Δu`),
//!   `long_section_v_right`, `long_section_v_left`,
//!   `long_section_v_increment` (long sections by number), the constant
//!   slope `reference_line_start_s`, banking `reference_line_start_b`, the
//!   heights `reference_line_start_z`, `reference_line_end_z`; the plan-view
//!   keys (`_x`, `_y`, `_phi`, offsets, geographic `_lon`, `_lat`, `_alt`)
//!   are read and left aside: they place the road in the plane and do not
//!   change its heights along the reference line.
//! - `$KD_DEFINITION`: the data format `#:LRFI`, `#:LDFI` (formatted text,
//!   10 or 20 characters a value, each cross section starting a new
//!   80-character record), `#:KRBI`, `#:KDBI` (big-endian IEEE `f32` or
//!   `f64`, cross sections one after the other, the last 80-byte record
//!   filled with NaNs); the virtual channel `U:`; the channels `D:` in the
//!   order of the data: `long section N` (its `v` from the increment) or
//!   `long section at v = …` (explicit), `reference line slope`,
//!   `reference line banking`, and `reference line phi`, `x`, `y` (plan
//!   view, read and left aside).
//! - `$ROAD_CRG_MODS`: `scale_z_grid`, `scale_slope`, `scale_banking`,
//!   `refline_offset_z`, `grid_nan_mode`, `grid_nan_offset` are applied;
//!   `scale_length`, `scale_width` and `refpoint_z` are refused by name;
//!   the plan-view modifiers are left aside.
//! - `$ROAD_CRG_OPTS`: evaluation options; `border_smooth_ubeg` and
//!   `border_smooth_uend` (which change heights inside the grid) are
//!   refused by name; the border modes only say what lies outside the grid,
//!   where a run is refused anyway; the others do not change heights.
//! - `$ROAD_CRG_FILE` (data in other files) is refused.
//!
//! Heights are kept in single precision as the standard's evaluation keeps
//! them; a placeholder (a text field starting with `*`) or a NaN is a cell
//! without height. The height at node `(u_k, v_j)` is the standard's
//! evaluation there: `z_kj + z_ref(u_k) + b(u_k) v_j`, with `z_ref` the
//! integral of the slope channel (`z_ref(u_{k+1}) = z_ref(u_k) + s_{k+1}
//! Δu`, from `reference_line_start_z`; backwards from
//! `reference_line_end_z` blended forward when that is given) and `b` the
//! banking (channel or constant).

use std::io::{BufRead, Read};
use std::path::Path;
use tirecontact_core::model::road::SurfaceGrid;

/// Largest grid accepted (values: long sections × cross sections): 128 MB
/// of single-precision heights.
pub const MAX_CRG_VALUES: usize = 32_000_000;

/// Largest file accepted (bytes), checked before reading: a formatted
/// double-precision value takes 21 bytes with its share of a line end, and
/// the header 1 MiB.
pub const MAX_CRG_BYTES: u64 = 21 * MAX_CRG_VALUES as u64 + (1 << 20);

/// Longest header line (bytes).
const MAX_HEADER_LINE: usize = 4096;

/// Largest |height| accepted (m): a value beyond is not a road.
pub const MAX_CRG_ABS_HEIGHT_M: f64 = 1.0e5;

/// The four data formats of OpenCRG.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CrgFormat {
    /// Formatted text, 10 characters a value, 8 a record.
    Lrfi,
    /// Formatted text, 20 characters a value, 4 a record.
    Ldfi,
    /// Big-endian `f32`, records filled one after the other.
    Krbi,
    /// Big-endian `f64`, records filled one after the other.
    Kdbi,
}

impl CrgFormat {
    fn width(self) -> usize {
        match self {
            CrgFormat::Lrfi => 10,
            CrgFormat::Ldfi => 20,
            CrgFormat::Krbi => 4,
            CrgFormat::Kdbi => 8,
        }
    }
    fn binary(self) -> bool {
        matches!(self, CrgFormat::Krbi | CrgFormat::Kdbi)
    }
}

/// A road read from an OpenCRG file.
#[derive(Debug, Clone, PartialEq)]
pub struct CrgRoad {
    pub format: CrgFormat,
    /// First cross section `u_0` (m).
    pub u_first_m: f64,
    /// Spacing of the cross sections `Δu` (m), > 0.
    pub u_inc_m: f64,
    /// Number of cross sections.
    pub nu: usize,
    /// The long sections' positions `v_j` (m), strictly increasing (right
    /// to left).
    pub v_m: Vec<f64>,
    /// Grid heights, single precision, long section by long section:
    /// `z[j nu + k]` at `(u_k, v_j)`; NaN where the file has none.
    pub z_m: Vec<f32>,
    /// Height of the reference line at each cross section (m).
    pub ref_z_m: Vec<f64>,
    /// Banking at each cross section (m/m), positive raising the left.
    pub bank: Vec<f64>,
}

impl CrgRoad {
    /// Position `u_k` (m) of cross section `k`.
    pub fn u_at(&self, k: usize) -> f64 {
        self.u_first_m + k as f64 * self.u_inc_m
    }

    /// The last cross section's `u` (m).
    pub fn u_last_m(&self) -> f64 {
        self.u_at(self.nu - 1)
    }

    /// The height (m) at node `(u_k, v_j)` as the standard evaluates it:
    /// the grid's height plus the reference line's height plus banking
    /// times `v` (NaN where the grid has no height).
    #[inline]
    pub fn node_height_m(&self, k: usize, j: usize) -> f64 {
        self.z_m[j * self.nu + k] as f64 + self.ref_z_m[k] + self.bank[k] * self.v_m[j]
    }

    /// The standard's evaluation `z(u, v)` inside the grid (`None` outside
    /// or on a cell without height): the grid's heights bilinear in `u` and
    /// `v`, the reference line's height and the banking linear in `u`, the
    /// banking times `v`.
    pub fn evaluate_m(&self, u_m: f64, v_m: f64) -> Option<f64> {
        let fu = (u_m - self.u_first_m) / self.u_inc_m;
        let last_u = (self.nu - 1) as f64;
        let (v0, v1) = (self.v_m[0], self.v_m[self.v_m.len() - 1]);
        if !(fu >= 0.0 && fu <= last_u && v_m >= v0 && v_m <= v1) {
            return None;
        }
        let k = (fu as usize).min(self.nu - 2);
        let a = fu - k as f64;
        let j = (self.v_m.partition_point(|&v| v <= v_m).max(1) - 1).min(self.v_m.len() - 2);
        let b = (v_m - self.v_m[j]) / (self.v_m[j + 1] - self.v_m[j]);
        let z = |kk: usize, jj: usize| self.z_m[jj * self.nu + kk] as f64;
        let grid = (1.0 - a) * ((1.0 - b) * z(k, j) + b * z(k, j + 1))
            + a * ((1.0 - b) * z(k + 1, j) + b * z(k + 1, j + 1));
        let lin = |c: &[f64]| c[k] + a * (c[k + 1] - c[k]);
        let h = grid + lin(&self.ref_z_m) + lin(&self.bank) * v_m;
        h.is_finite().then_some(h)
    }

    /// The mean (m) of the finite node heights: the road's mean plane.
    pub fn mean_height_m(&self) -> f64 {
        let (mut sum, mut n) = (0.0, 0usize);
        for j in 0..self.v_m.len() {
            for k in 0..self.nu {
                let h = self.node_height_m(k, j);
                if h.is_finite() {
                    sum += h;
                    n += 1;
                }
            }
        }
        if n == 0 { 0.0 } else { sum / n as f64 }
    }

    /// The road as a surface grid for a tyre starting at `u_start_m`, its
    /// points' `y` at `v = v_offset_m + y`: node `(u_k, v_j)` at `x = u_k -
    /// u_start`, `y = v_j - v_offset`, its height the standard's less the
    /// mean height ([`CrgRoad::mean_height_m`], kept as `datum_m`). Slopes
    /// along `x` by centred differences (one-sided beside a cell without
    /// height and at the ends); a NaN node stays NaN (checked against the
    /// points' paths before a run).
    pub fn surface(&self, u_start_m: f64, v_offset_m: f64) -> SurfaceGrid {
        let (nu, nv) = (self.nu, self.v_m.len());
        let datum = self.mean_height_m();
        let mut z = vec![0.0; nu * nv];
        for j in 0..nv {
            for k in 0..nu {
                z[j * nu + k] = self.node_height_m(k, j) - datum;
            }
        }
        let h = self.u_inc_m;
        let mut dzdx = vec![0.0; nu * nv];
        for j in 0..nv {
            let row = &z[j * nu..(j + 1) * nu];
            for k in 0..nu {
                let here = row[k];
                let before = (k > 0).then(|| row[k - 1]).filter(|x| x.is_finite());
                let after = row.get(k + 1).copied().filter(|x| x.is_finite());
                dzdx[j * nu + k] = if !here.is_finite() {
                    0.0
                } else {
                    match (before, after) {
                        (Some(b), Some(a)) => (a - b) / (2.0 * h),
                        (None, Some(a)) => (a - here) / h,
                        (Some(b), None) => (here - b) / h,
                        (None, None) => 0.0,
                    }
                };
            }
        }
        let rows_y_m: Vec<f64> = self.v_m.iter().map(|v| v - v_offset_m).collect();
        let width = rows_y_m[nv - 1] - rows_y_m[0];
        SurfaceGrid {
            x0_m: self.u_first_m - u_start_m,
            dx_m: h,
            nx: nu,
            y0_m: rows_y_m[0],
            dy_m: width / (nv - 1) as f64,
            ny: nv,
            looped: false,
            periodic_y: false,
            z_m: z,
            dzdx,
            rows_y_m,
            datum_m: datum,
            file_origin_m: (u_start_m, v_offset_m),
        }
    }
}

mod data;
mod error;
mod header;
use data::*;
pub use error::{CrgError, CrgFault, CrgPlace};
use header::*;

/// Reads an OpenCRG file (see the module's documentation).
pub fn read_crg(path: &Path) -> Result<CrgRoad, CrgError> {
    read_crg_limited(path, MAX_CRG_VALUES)
}

/// [`read_crg`] with an explicit cap on the grid's values, so that the
/// limit can be tested on small files.
pub fn read_crg_limited(path: &Path, max_values: usize) -> Result<CrgRoad, CrgError> {
    let err = |fault: CrgFault| CrgError::Fault {
        path: path.to_path_buf(),
        fault,
    };
    let limit = format!("{MAX_CRG_VALUES} values");
    let (file, len) = super::road::open_capped(path, "an OpenCRG file", MAX_CRG_BYTES, &limit)?;
    let mut r = std::io::BufReader::with_capacity(1 << 16, file.take(len));
    let (header, data_line, data_offset) = read_header(&mut r).map_err(err)?;
    let layout = Layout::of(&header, max_values).map_err(err)?;
    let mut values = if layout.format.binary() {
        read_binary(&mut r, &layout, len - data_offset, data_offset)
    } else {
        read_text(&mut r, &layout, data_line)
    }
    .map_err(err)?;
    apply_mods(&header, &mut values).map_err(err)?;
    layout.road(values).map_err(err)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn data(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/crg")
            .join(name)
    }

    fn belgian() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../presets/roads/belgian_block.crg")
    }

    fn tmp(name: &str, bytes: &[u8]) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("tirecontact-crg-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    }

    /// The straight handmade file: 23 cross sections 1 m apart, seven
    /// long sections numbered from v = -1.5 m by 0.5 m; `*missing*` cells
    /// hold no height.
    #[test]
    fn the_straight_handmade_file() {
        let r = read_crg(&data("handmade_straight.crg")).unwrap();
        assert_eq!(r.format, CrgFormat::Lrfi);
        assert_eq!((r.nu, r.u_first_m, r.u_inc_m), (23, 0.0, 1.0));
        assert_eq!(r.v_m, [-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5]);
        // cross section 2 (u = 1 m), on the reference line
        assert_eq!(r.node_height_m(1, 3), 0.0111111f32 as f64);
        // cross section 8: `*missing*` at both edges
        assert!(r.node_height_m(7, 0).is_nan() && r.node_height_m(7, 6).is_nan());
        assert_eq!(r.node_height_m(7, 1), 0.0111111f32 as f64);
        assert!(r.ref_z_m.iter().all(|z| *z == 0.0) && r.bank.iter().all(|b| *b == 0.0));
        // the minimalist file (no u range, v centred) is the same road
        let m = read_crg(&data("handmade_straight_minimalist.crg")).unwrap();
        assert_eq!((m.nu, m.u_first_m, &m.v_m), (r.nu, r.u_first_m, &r.v_m));
        assert_eq!(format!("{:?}", m.z_m), format!("{:?}", r.z_m));
        // and so is the double-precision one, rounded to single precision
        let d = read_crg(&data("handmade_straight_double.crg")).unwrap();
        assert_eq!(d.format, CrgFormat::Ldfi);
        assert_eq!((d.nu, &d.v_m), (r.nu, &r.v_m));
        for (a, b) in d.z_m.iter().zip(&r.z_m) {
            assert!(
                a.is_nan() && b.is_nan() || (a - b).abs() <= 1e-7,
                "{a} vs {b}"
            );
        }
    }

    /// The slope channel integrates into the reference line's height
    /// (`z_ref(u_{k+1}) = z_ref(u_k) + s_{k+1} Δu`), the banking adds
    /// `b(u) v`; long sections at explicit, uneven `v`.
    #[test]
    fn slope_and_banking_channels() {
        let s = read_crg(&data("handmade_sloped.crg")).unwrap();
        assert_eq!(s.v_m, [-1.5, -1.25, -1.0, 0.0, 1.0, 1.25, 1.5]);
        // slopes 0 (unused), 0, 0.011, 0.022, …: heights 0, 0, 0.011, 0.033
        let want = [0.0, 0.0, 0.011, 0.033, 0.066];
        for (k, w) in want.iter().enumerate() {
            assert!((s.ref_z_m[k] - w).abs() < 1e-12, "{k}: {}", s.ref_z_m[k]);
        }
        // at a node: the grid's height plus the reference line's
        assert_eq!(
            s.evaluate_m(2.0, 0.0).unwrap(),
            0.0111111f32 as f64 + s.ref_z_m[2]
        );
        let b = read_crg(&data("handmade_banked.crg")).unwrap();
        assert!(b.ref_z_m.iter().all(|z| *z == 0.0));
        // banking 0.011 at u = 2 m: 1.5 m to the left is 0.0165 m higher
        assert!((b.bank[2] - 0.011).abs() < 1e-12);
        let left = b.evaluate_m(2.0, 1.5).unwrap();
        assert!((left - (0.0 + 0.011 * 1.5)).abs() < 1e-9, "{left}");
        // all three channels (heading left aside)
        let c = read_crg(&data("handmade_curved_banked_sloped.crg")).unwrap();
        assert!(c.ref_z_m.iter().any(|z| *z != 0.0) && c.bank.iter().any(|b| *b != 0.0));
    }

    /// The grid's nodes of the surface a run samples are the standard's
    /// evaluation there, less the mean height; between nodes across, the
    /// height is linear.
    #[test]
    fn surface_nodes_equal_the_standards_evaluation() {
        for name in [
            "handmade_curved_banked_sloped.crg",
            "handmade_straight.crg",
            "handmade_banked.crg",
        ] {
            let r = read_crg(&data(name)).unwrap();
            let (u0, v0) = (r.u_first_m + 2.0, 0.25);
            let g = r.surface(u0, v0);
            assert_eq!((g.nx, g.ny), (r.nu, r.v_m.len()));
            for j in 0..g.ny {
                for k in 0..g.nx {
                    let (u, v) = (r.u_at(k), r.v_m[j]);
                    let Some(want) = r.evaluate_m(u, v) else {
                        continue;
                    };
                    assert_eq!(want, r.node_height_m(k, j), "{name} ({k}, {j})");
                    assert_eq!(g.z_m[j * g.nx + k], want - g.datum_m, "{name} ({k}, {j})");
                    // sampled where the scene puts it: x = u - u0, y = v - v0
                    if let Ok((z, _)) = g.sample(u - u0, v - v0) {
                        assert!((z - (want - g.datum_m)).abs() < 1e-12, "{name} ({k}, {j})");
                    }
                }
            }
            // half way across two long sections at a cross section
            let (k, j) = (5, 3);
            let mid = 0.5 * (r.v_m[j] + r.v_m[j + 1]);
            if let (Some(a), Ok((z, _))) = (
                r.evaluate_m(r.u_at(k), mid),
                g.sample(r.u_at(k) - u0, mid - v0),
            ) {
                assert!((z - (a - g.datum_m)).abs() < 1e-12, "{name}");
            }
        }
    }

    /// `grid_nan_mode = 2` (keep the last value) fills the cells without
    /// height; evaluation options that do not change heights are read.
    #[test]
    fn modifiers_and_options() {
        let p = read_crg(&data("handmade_platform.crg")).unwrap();
        assert!(p.z_m.iter().all(|z| z.is_finite()));
        assert!(read_crg(&data("handmade_sloped_opts.crg")).is_ok());
        let text = std::fs::read_to_string(data("handmade_straight.crg")).unwrap();
        for (block, name, value) in [
            ("$ROAD_CRG_MODS\nscale_length = 2\n", "scale_length", "2"),
            ("$ROAD_CRG_MODS\nrefpoint_z = 1\n", "refpoint_z", "1"),
            (
                "$ROAD_CRG_OPTS\nborder_smooth_ubeg = 1\n",
                "border_smooth_ubeg",
                "1 (heights faded",
            ),
        ] {
            let p = tmp(&format!("{name}.crg"), format!("{block}{text}").as_bytes());
            let e = read_crg(&p).unwrap_err();
            let f = e.fault().unwrap();
            assert_eq!(f.place, CrgPlace::line(2), "{e}");
            assert!(f.field.ends_with(name) && f.value.starts_with(value), "{e}");
            assert!(f.expected.contains("a file without it"), "{e}");
            assert!(e.to_string().contains("line 2: "), "{e}");
        }
        let p = tmp(
            "scaled.crg",
            format!("$ROAD_CRG_MODS\nscale_z_grid = 2\nrefline_offset_z = 0.5\n{text}").as_bytes(),
        );
        let s = read_crg(&p).unwrap();
        assert_eq!(s.node_height_m(1, 3), 2.0 * 0.0111111f32 as f64 + 0.5);
    }

    /// A damaged text record is refused naming its line and column; a
    /// missing record naming where the data ends.
    #[test]
    fn damaged_text_is_refused_by_line_and_column() {
        let text = std::fs::read_to_string(data("handmade_straight.crg")).unwrap();
        let bad = text.replacen(
            " 0.0111111 0.0000000 0.0000000-0.0111111",
            " 0.0111111 0.00x0000 0.0000000-0.0111111",
            1,
        );
        let line = bad.lines().position(|l| l.contains("0.00x")).unwrap() + 1;
        let column = bad.lines().nth(line - 1).unwrap().find(" 0.00x").unwrap() + 1;
        let e = read_crg(&tmp("bad_field.crg", bad.as_bytes())).unwrap_err();
        let f = e.fault().unwrap();
        assert_eq!(f.place, CrgPlace::column(line, column), "{e}");
        // the fourteenth cross section (u = 13 m), its fifth channel
        assert_eq!(f.field, "cross section 14, long section 5", "{e}");
        assert_eq!(f.value, "` 0.00x0000`", "{e}");
        assert!(f.expected.starts_with("a number of 10 characters"), "{e}");
        assert!(
            e.to_string()
                .contains(&format!("bad_field.crg: line {line}, column {column}: ")),
            "{e}"
        );
        let short: String = text
            .lines()
            .take(text.lines().count() - 3)
            .map(|l| format!("{l}\n"))
            .collect();
        let e = read_crg(&tmp("short.crg", short.as_bytes())).unwrap_err();
        let f = e.fault().unwrap();
        assert_eq!(
            (f.field.as_str(), f.value.as_str()),
            ("cross section 21", "the data ends in it"),
            "{e}"
        );
        assert_eq!(f.place, CrgPlace::line(short.lines().count() + 1), "{e}");
        assert!(matches!(&e, CrgError::Fault { path, .. } if path.ends_with("short.crg")));
        let huge = text.replacen("0.0111111", "9.9999e20", 1);
        let line = huge.lines().position(|l| l.contains("9.9999e20")).unwrap() + 1;
        let e = read_crg(&tmp("huge.crg", huge.as_bytes())).unwrap_err();
        let f = e.fault().unwrap();
        assert!(
            matches!(f.place, CrgPlace::Line { line: l, column: Some(_) } if l == line),
            "{e}"
        );
        assert!(
            f.value.starts_with("999990000000000000000") && f.value.ends_with(" m"),
            "{e}"
        );
        assert!(f.expected.starts_with("|z| <="), "{e}");
    }

    /// The Belgian block (KRBI): 1001 cross sections 1 cm apart from u =
    /// 730 m, 341 long sections 1 cm apart across 3.4 m, heights about
    /// 2.1 m; the same road written as KDBI reads the same; the size cap
    /// is named.
    #[test]
    fn the_belgian_block_in_both_binary_formats() {
        let t = std::time::Instant::now();
        let r = read_crg(&belgian()).unwrap();
        eprintln!("belgian block read in {:?}", t.elapsed());
        assert_eq!(r.format, CrgFormat::Krbi);
        assert_eq!(
            (r.nu, r.v_m.len(), r.u_first_m, r.u_inc_m),
            (1001, 341, 730.0, 0.01)
        );
        assert!((r.v_m[0] + 1.7).abs() < 1e-12 && (r.v_m[340] - 1.7).abs() < 1e-12);
        let finite: Vec<f32> = r.z_m.iter().copied().filter(|z| z.is_finite()).collect();
        let (lo, hi) = finite
            .iter()
            .fold((f32::MAX, f32::MIN), |(a, b), z| (a.min(*z), b.max(*z)));
        assert!(lo > 2.0 && hi < 2.2, "{lo} .. {hi}");
        assert!(
            (r.mean_height_m() - 2.1135).abs() < 1e-3,
            "{}",
            r.mean_height_m()
        );
        // KDBI: the same values in f64, the last record padded with NaN
        let bytes = std::fs::read(belgian()).unwrap();
        let at = bytes.windows(5).position(|w| w == b"\n$$$$").unwrap() + 1;
        let end = at + bytes[at..].iter().position(|b| *b == b'\n').unwrap() + 1;
        let f = bytes.windows(6).position(|w| w == b"#:KRBI").unwrap();
        let mut out = bytes[..end].to_vec();
        out[f + 3] = b'D';
        let n = 1001 * 342;
        for c in bytes[end..end + 4 * n].chunks_exact(4) {
            let x = f32::from_be_bytes([c[0], c[1], c[2], c[3]]) as f64;
            out.extend_from_slice(&x.to_be_bytes());
        }
        while !(out.len() - end).is_multiple_of(80) {
            out.extend_from_slice(&f64::NAN.to_be_bytes());
        }
        let d = read_crg(&tmp("belgian_kdbi.crg", &out)).unwrap();
        assert_eq!(d.format, CrgFormat::Kdbi);
        assert_eq!(format!("{:?}", d.z_m), format!("{:?}", r.z_m));
        let e = read_crg_limited(&belgian(), 100_000).unwrap_err();
        let f = e.fault().unwrap();
        assert_eq!(f.place, CrgPlace::Header);
        assert!(
            e.to_string()
                .contains("341 long sections = 341341 values: expected at most 100000"),
            "{e}"
        );
    }

    /// A binary file whose data is not a whole number of values (a
    /// line-end conversion adds a byte before every line feed) is refused
    /// with that reason and the byte where the data starts; one cut short
    /// naming where it ends; trailing values that are not padding naming
    /// their byte.
    #[test]
    fn damaged_binary_files_are_refused() {
        let bytes = std::fs::read(belgian()).unwrap();
        let at = bytes.windows(5).position(|w| w == b"\n$$$$").unwrap() + 1;
        let end = at + bytes[at..].iter().position(|b| *b == b'\n').unwrap() + 1;
        let mut crlf = Vec::new();
        for &b in &bytes {
            if b == b'\n' {
                crlf.push(b'\r');
            }
            crlf.push(b);
        }
        let e = read_crg(&tmp("crlf.crg", &crlf)).unwrap_err();
        let f = e.fault().unwrap();
        // the header's line ends gained a byte each: the data starts later
        let header_lines = bytes[..end].iter().filter(|b| **b == b'\n').count();
        assert_eq!(f.place, CrgPlace::Byte((end + header_lines) as u64), "{e}");
        assert_eq!(f.field, "the data's length", "{e}");
        let data_len = crlf.len() - end - header_lines;
        assert_eq!(f.value, format!("{data_len} bytes"), "{e}");
        assert!(
            f.expected.contains("a whole number of 4-byte values"),
            "{e}"
        );
        let cut = end + 4 * 342 * 500;
        let e = read_crg(&tmp("cut.crg", &bytes[..cut])).unwrap_err();
        let f = e.fault().unwrap();
        assert_eq!(f.place, CrgPlace::Byte(cut as u64), "{e}");
        assert_eq!(
            f.value, "the data ends after 500 whole cross sections",
            "{e}"
        );
        let mut extra = bytes.clone();
        let pad = extra.len() - 8;
        extra[pad..pad + 4].copy_from_slice(&1.0f32.to_be_bytes());
        let e = read_crg(&tmp("extra.crg", &extra)).unwrap_err();
        let f = e.fault().unwrap();
        assert_eq!(f.place, CrgPlace::Byte(pad as u64), "{e}");
        assert_eq!(
            (f.field.as_str(), f.value.as_str()),
            ("padding after the last cross section", "1"),
            "{e}"
        );
        // a height beyond any road, named by its byte, cross section and
        // long section
        let mut absurd = bytes.clone();
        let at = end + 4 * (342 * 7 + 3);
        absurd[at..at + 4].copy_from_slice(&3.0e6f32.to_be_bytes());
        let e = read_crg(&tmp("absurd.crg", &absurd)).unwrap_err();
        let f = e.fault().unwrap();
        assert_eq!(f.place, CrgPlace::Byte(at as u64), "{e}");
        assert_eq!(f.field, "cross section 8, long section 3", "{e}");
        assert_eq!(f.value, "3000000 m", "{e}");
    }

    /// 25 million values (KRBI, 100 MB): read within a few seconds (run
    /// with `--ignored`; it writes the file to the temporary folder).
    #[test]
    #[ignore]
    fn twenty_five_million_values_read_in_seconds() {
        let (nu, nv) = (25_000usize, 1000usize);
        let mut out = format!(
            "$ROAD_CRG\nreference_line_start_u = 0\nreference_line_end_u = {}\nreference_line_increment = 0.01\nlong_section_v_right = -0.5\nlong_section_v_increment = {}\n$KD_DEFINITION\n#:KRBI\n",
            (nu - 1) as f64 * 0.01,
            1.0 / (nv - 1) as f64
        );
        for j in 0..nv {
            out.push_str(&format!("D:long section {},m\n", j + 1));
        }
        out.push_str("$$$$\n");
        let mut bytes = out.into_bytes();
        for k in 0..nu * nv {
            bytes.extend_from_slice(&((k % 977) as f32 * 1e-5).to_be_bytes());
        }
        let p = tmp("large.crg", &bytes);
        let t = std::time::Instant::now();
        let r = read_crg(&p).unwrap();
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let t = std::time::Instant::now();
        let g = r.surface(0.0, 0.0);
        let surface_ms = t.elapsed().as_secs_f64() * 1e3;
        eprintln!(
            "{} values, {:.0} MB: read in {ms:.0} ms, surface built in {surface_ms:.0} ms ({} nodes)",
            nu * nv,
            bytes.len() as f64 / 1e6,
            g.z_m.len()
        );
        std::fs::remove_file(&p).unwrap();
        assert!(ms < 10_000.0);
    }
}
