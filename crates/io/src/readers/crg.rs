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

use super::road::RoadFileError;
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

/// One channel of the data, in the order of `D:` lines.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Channel {
    /// A long section and its `v` (explicit) or number (1-based).
    Section {
        v_m: Option<f64>,
        number: f64,
    },
    Slope,
    Bank,
    /// Plan-view channels (phi, x, y): read and left aside.
    Aside,
}

#[derive(Debug, Default)]
struct Header {
    keys: std::collections::HashMap<String, (f64, usize)>,
    mods: Vec<(String, f64, usize)>,
    format: Option<(CrgFormat, usize)>,
    channels: Vec<(Channel, usize)>,
}

#[derive(Clone, Copy, PartialEq)]
enum Block {
    None,
    Comment,
    Road,
    Def,
    Opts,
    Mods,
}

/// Reads an OpenCRG file (see the module's documentation).
pub fn read_crg(path: &Path) -> Result<CrgRoad, RoadFileError> {
    read_crg_limited(path, MAX_CRG_VALUES)
}

/// [`read_crg`] with an explicit cap on the grid's values, so that the
/// limit can be tested on small files.
pub fn read_crg_limited(path: &Path, max_values: usize) -> Result<CrgRoad, RoadFileError> {
    let err = |message: String| RoadFileError {
        path: path.to_path_buf(),
        message,
    };
    let file = crate::fsio::read::open_regular(path).map_err(|e| {
        err(if e.kind() == std::io::ErrorKind::InvalidInput {
            format!("{e}: expected an OpenCRG file")
        } else {
            format!("cannot open: {e}")
        })
    })?;
    let len = file
        .metadata()
        .map_err(|e| err(format!("cannot read: {e}")))?
        .len();
    if len > MAX_CRG_BYTES {
        return Err(err(format!(
            "{len} bytes: expected at most {MAX_CRG_BYTES} bytes ({MAX_CRG_VALUES} values)"
        )));
    }
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

/// Reads one line (without its end) of at most [`MAX_HEADER_LINE`]
/// bytes; `None` at the end of the file.
fn header_line<R: BufRead>(r: &mut R, line: usize) -> Result<Option<(String, usize)>, String> {
    let mut buf = Vec::new();
    let n = r
        .by_ref()
        .take(MAX_HEADER_LINE as u64 + 1)
        .read_until(b'\n', &mut buf)
        .map_err(|e| format!("line {line}: cannot read: {e}"))?;
    if n == 0 {
        return Ok(None);
    }
    if buf.last() != Some(&b'\n') && n > MAX_HEADER_LINE {
        return Err(format!(
            "line {line}: longer than {MAX_HEADER_LINE} bytes: expected header lines of an OpenCRG file"
        ));
    }
    while matches!(buf.last(), Some(b'\n' | b'\r')) {
        buf.pop();
    }
    // ISO-8859-1: every byte is a character
    Ok(Some((buf.iter().map(|&b| b as char).collect(), n)))
}

/// The header up to the `$$$$` line: its blocks, the line number of the
/// data's first line and the byte offset of the data.
fn read_header<R: BufRead>(r: &mut R) -> Result<(Header, usize, u64), String> {
    let mut h = Header::default();
    let mut block = Block::None;
    let mut offset = 0u64;
    for line in 1usize.. {
        let Some((text, n)) = header_line(r, line)? else {
            return Err(format!(
                "ends at line {}: expected the data after a `$$$$` line",
                line - 1
            ));
        };
        offset += n as u64;
        if text.starts_with("$$$$") {
            return Ok((h, line + 1, offset));
        }
        if let Some(tag) = text.strip_prefix('$') {
            let name = tag
                .split(|c: char| c.is_whitespace() || c == '!')
                .next()
                .unwrap_or("")
                .to_ascii_uppercase();
            block = match name.as_str() {
                "CT" => Block::Comment,
                "ROAD_CRG" => Block::Road,
                "KD_DEFINITION" => Block::Def,
                "ROAD_CRG_OPTS" => Block::Opts,
                "ROAD_CRG_MODS" => Block::Mods,
                "ROAD_CRG_FILE" => {
                    return Err(format!(
                        "line {line}: block `$ROAD_CRG_FILE` (data in other files): expected one self-contained OpenCRG file"
                    ));
                }
                _ => Block::None,
            };
            continue;
        }
        if block == Block::Comment || text.trim_start().starts_with('*') || text.trim().is_empty() {
            continue;
        }
        // an in-line comment starts with `!`
        let body = text.split('!').next().unwrap_or("").trim();
        if body.is_empty() {
            continue;
        }
        match block {
            Block::Road | Block::Mods | Block::Opts => {
                let Some((key, value)) = body.split_once('=') else {
                    if block == Block::Road {
                        return Err(format!(
                            "line {line}: `{body}`: expected `key = value` in block $ROAD_CRG"
                        ));
                    }
                    continue;
                };
                let key = key.trim().to_ascii_lowercase();
                let value_text = value.trim();
                let value = leading_number(value_text).ok_or_else(|| {
                    format!("line {line}: {key} = `{value_text}`: expected a number")
                })?;
                match block {
                    Block::Road => {
                        if !value.is_finite() {
                            return Err(format!(
                                "line {line}: {key} = {value_text}: expected a finite number"
                            ));
                        }
                        h.keys.insert(key, (value, line));
                    }
                    Block::Opts => {
                        if key == "border_smooth_ubeg" || key == "border_smooth_uend" {
                            return Err(format!(
                                "line {line}: option {key} = {value_text} (heights faded towards the reference line at the ends): expected a file without it (not applied here)"
                            ));
                        }
                    }
                    _ => h.mods.push((key, value, line)),
                }
            }
            Block::Def => {
                if let Some(f) = body.strip_prefix("#:") {
                    let name = f.trim().get(..4).unwrap_or(f.trim()).to_ascii_uppercase();
                    let format = match name.as_str() {
                        "LRFI" => CrgFormat::Lrfi,
                        "LDFI" => CrgFormat::Ldfi,
                        "KRBI" => CrgFormat::Krbi,
                        "KDBI" => CrgFormat::Kdbi,
                        _ => {
                            return Err(format!(
                                "line {line}: data format `#:{name}`: expected #:LRFI, #:LDFI, #:KRBI or #:KDBI"
                            ));
                        }
                    };
                    h.format = Some((format, line));
                } else if let Some(d) = body.strip_prefix("D:") {
                    h.channels.push((channel(d.trim(), line)?, line));
                }
                // `U:` is a virtual channel: no data
            }
            Block::None | Block::Comment => {}
        }
    }
    unreachable!("the loop returns")
}

/// A `D:` channel definition (without `D:`): `name,unit`.
fn channel(d: &str, line: usize) -> Result<Channel, String> {
    let (name, unit) = d.split_once(',').unwrap_or((d, ""));
    let name = name.trim().to_ascii_lowercase();
    let unit = unit
        .split(',')
        .next()
        .unwrap_or("")
        .trim()
        .to_ascii_lowercase();
    let want_unit = |want: &str| {
        if unit == want {
            Ok(())
        } else {
            Err(format!(
                "line {line}: channel `{name}` in `{unit}`: expected the unit `{want}`"
            ))
        }
    };
    if let Some(rest) = name.strip_prefix("long section") {
        want_unit("m")?;
        let rest = rest.trim();
        if let Some(at) = rest.strip_prefix("at v") {
            let v_text = at.trim().trim_start_matches('=').trim();
            let v: f64 = v_text.parse().map_err(|_| {
                format!("line {line}: `long section at v = {v_text}`: expected a position in m")
            })?;
            if !v.is_finite() {
                return Err(format!(
                    "line {line}: long section at v = {v_text}: expected a finite position"
                ));
            }
            return Ok(Channel::Section {
                v_m: Some(v),
                number: 0.0,
            });
        }
        let number: f64 = rest.parse().map_err(|_| {
            format!("line {line}: `long section {rest}`: expected `long section N` or `long section at v = …`")
        })?;
        return Ok(Channel::Section { v_m: None, number });
    }
    if let Some(what) = name.strip_prefix("reference line") {
        return match what.trim() {
            "slope" => want_unit("m/m").map(|_| Channel::Slope),
            "banking" => want_unit("m/m").map(|_| Channel::Bank),
            "phi" | "x" | "y" => Ok(Channel::Aside),
            other => Err(format!(
                "line {line}: channel `reference line {other}`: expected slope, banking, phi, x or y (cross sections evenly spaced by reference_line_increment)"
            )),
        };
    }
    Err(format!(
        "line {line}: channel `{name}`: expected `long section …` or `reference line …`"
    ))
}

/// The data's shape, from the header.
struct Layout {
    format: CrgFormat,
    /// Number of cross sections, when the header gives the end of `u`
    /// (else as many as the data holds).
    nu: Option<usize>,
    u_first_m: f64,
    u_inc_m: f64,
    channels: Vec<Channel>,
    /// Index of each long section's channel, sorted by `v`, and its `v`.
    sections: Vec<(usize, f64)>,
    slope: Option<usize>,
    bank: Option<usize>,
    max_values: usize,
    start_s: f64,
    start_b: f64,
    start_z: f64,
    end_z: Option<f64>,
}

impl Layout {
    fn of(h: &Header, max_values: usize) -> Result<Self, String> {
        let key = |k: &str| h.keys.get(k).copied();
        let need = |k: &str| {
            key(k)
                .map(|(v, _)| v)
                .ok_or_else(|| format!("block $ROAD_CRG has no {k}: expected it"))
        };
        let (format, _) = h.format.ok_or_else(|| {
            "block $KD_DEFINITION has no data format: expected #:LRFI, #:LDFI, #:KRBI or #:KDBI"
                .to_string()
        })?;
        let u0 = key("reference_line_start_u").map_or(0.0, |k| k.0);
        let du = need("reference_line_increment")?;
        let line_of = |k: &str| key(k).map_or(0, |(_, l)| l);
        if du.is_nan() || du <= 0.0 {
            return Err(format!(
                "line {}: reference_line_increment = {du}: expected an increment > 0 m",
                line_of("reference_line_increment")
            ));
        }
        let nu = match key("reference_line_end_u") {
            Some((u1, line)) => {
                let steps = (u1 - u0) / du;
                let n = steps.round();
                if n.is_nan() || n < 1.0 || (steps - n).abs() > 1e-6 * n.max(1.0) || n > 1e12 {
                    return Err(format!(
                        "line {line}: reference_line_end_u = {u1}: expected reference_line_start_u = {u0} plus a whole number (>= 1) of increments {du} m"
                    ));
                }
                Some(n as usize + 1)
            }
            None => None,
        };
        let channels: Vec<Channel> = h.channels.iter().map(|c| c.0).collect();
        let mut sections: Vec<(usize, f64)> = Vec::new();
        let (mut by_v, mut by_number) = (0usize, 0usize);
        let (mut slope, mut bank) = (None, None);
        for (k, &(c, line)) in h.channels.iter().enumerate() {
            match c {
                Channel::Section { v_m: Some(v), .. } => {
                    by_v += 1;
                    sections.push((k, v));
                }
                Channel::Section { v_m: None, number } => {
                    by_number += 1;
                    if number != by_number as f64 {
                        return Err(format!(
                            "line {line}: long section {number}: expected long section {by_number} (numbered in order from 1)"
                        ));
                    }
                    sections.push((k, f64::NAN));
                }
                Channel::Slope if slope.is_none() => slope = Some(k),
                Channel::Bank if bank.is_none() => bank = Some(k),
                Channel::Slope | Channel::Bank => {
                    return Err(format!(
                        "line {line}: a second reference line slope or banking channel: expected at most one of each"
                    ));
                }
                Channel::Aside => {}
            }
        }
        if by_v > 0 && by_number > 0 {
            return Err(
                "long sections both numbered and at explicit v: expected one way for all".into(),
            );
        }
        if sections.len() < 2 {
            return Err(format!(
                "{} long section(s): expected at least two `D:long section …` channels",
                sections.len()
            ));
        }
        if by_number > 0 {
            let gaps = (sections.len() - 1) as f64;
            let dv = match key("long_section_v_increment") {
                Some((dv, _)) => dv,
                None => {
                    let left = need("long_section_v_left")?;
                    (left - need("long_section_v_right")?) / gaps
                }
            };
            // without the right edge: from the left edge, else centred
            let right = match (key("long_section_v_right"), key("long_section_v_left")) {
                (Some((r, _)), _) => r,
                (None, Some((l, _))) => l - gaps * dv,
                (None, None) => -0.5 * gaps * dv,
            };
            if dv.is_nan() || dv <= 0.0 {
                return Err(format!(
                    "line {}: long_section_v_increment = {dv}: expected an increment > 0 m",
                    line_of("long_section_v_increment")
                ));
            }
            if let Some((left, l)) = key("long_section_v_left") {
                let last = right + (sections.len() - 1) as f64 * dv;
                if (last - left).abs() > 1e-6 * dv.max(1.0) + 1e-9 {
                    return Err(format!(
                        "line {l}: long_section_v_left = {left}: expected long_section_v_right + ({} - 1) × {dv} = {last} ({} numbered long sections)",
                        sections.len(),
                        sections.len()
                    ));
                }
            }
            for (j, s) in sections.iter_mut().enumerate() {
                s.1 = right + j as f64 * dv;
            }
        } else {
            sections.sort_by(|a, b| a.1.total_cmp(&b.1));
            if let Some(w) = sections.windows(2).find(|w| w[1].1 - w[0].1 < 1e-6) {
                return Err(format!(
                    "long sections at v = {} m and v = {} m: expected positions at least 1e-6 m apart",
                    w[0].1, w[1].1
                ));
            }
        }
        if let Some(nu) = nu {
            let values = (nu as u128) * (sections.len() as u128);
            if values > max_values as u128 {
                return Err(format!(
                    "{nu} cross sections × {} long sections = {values} values: expected at most {max_values} (cut the file along u)",
                    sections.len()
                ));
            }
        }
        Ok(Layout {
            format,
            nu,
            u_first_m: u0,
            u_inc_m: du,
            channels,
            sections,
            slope,
            bank,
            max_values,
            start_s: key("reference_line_start_s").map_or(0.0, |k| k.0),
            start_b: key("reference_line_start_b").map_or(0.0, |k| k.0),
            start_z: key("reference_line_start_z").map_or(0.0, |k| k.0),
            end_z: key("reference_line_end_z").map(|k| k.0),
        })
    }

    fn nch(&self) -> usize {
        self.channels.len()
    }

    /// The heights and reference channels from the values (cross section
    /// by cross section, `nch` each).
    fn road(&self, v: Values) -> Result<CrgRoad, String> {
        let nv = self.sections.len();
        let nu = v.z_m.len() / nv;
        if nu < 2 {
            return Err(format!("{nu} cross section(s): expected at least two"));
        }
        let Values {
            z_m: by_u,
            slope,
            bank,
            offset_z_m,
            ..
        } = v;
        // section-major from the file's cross-section-major order
        let mut z_m = vec![0.0f32; nu * nv];
        for (k, row) in by_u.chunks_exact(nv).enumerate() {
            for (j, z) in row.iter().enumerate() {
                z_m[j * nu + k] = *z;
            }
        }
        // the reference line's height: the slope integrated along u
        let mut ref_z = vec![self.start_z; nu];
        let slope_at = |k: usize| slope.as_ref().map_or(self.start_s, |s| s[k]);
        if slope.is_some() || self.start_s != 0.0 {
            if let Some(end_z) = self.end_z {
                // backwards from the end, then forwards blended towards it
                ref_z[nu - 1] = end_z;
                for k in (1..nu).rev() {
                    ref_z[k - 1] = ref_z[k] - slope_at(k) * self.u_inc_m;
                }
                ref_z[0] = self.start_z;
                for k in 0..nu.saturating_sub(2) {
                    let f = k as f64 / (nu - 1) as f64;
                    ref_z[k + 1] =
                        (1.0 - f) * (ref_z[k] + slope_at(k + 1) * self.u_inc_m) + f * ref_z[k + 1];
                }
            } else {
                for k in 0..nu - 1 {
                    ref_z[k + 1] = ref_z[k] + slope_at(k + 1) * self.u_inc_m;
                }
            }
        }
        for z in &mut ref_z {
            *z += offset_z_m;
        }
        if let Some(k) = ref_z.iter().position(|z| !z.is_finite()) {
            return Err(format!(
                "reference line height at cross section {} (u = {} m) is not finite: expected finite slopes",
                k + 1,
                self.u_first_m + k as f64 * self.u_inc_m
            ));
        }
        let bank = bank.unwrap_or_else(|| vec![self.start_b; nu]);
        Ok(CrgRoad {
            format: self.format,
            u_first_m: self.u_first_m,
            u_inc_m: self.u_inc_m,
            nu,
            v_m: self.sections.iter().map(|s| s.1).collect(),
            z_m,
            ref_z_m: ref_z,
            bank,
        })
    }
}

/// What the data section holds in the file's order: heights cross
/// section by cross section (`nv` each, the long sections sorted by `v`),
/// the slope and banking channels, and the height offset of the modifiers.
struct Values {
    nv: usize,
    z_m: Vec<f32>,
    slope: Option<Vec<f64>>,
    bank: Option<Vec<f64>>,
    offset_z_m: f64,
}

/// Files the values of cross section `k` (`row`: its `nch` values); `at`
/// says where a refused value is.
fn file_row(
    l: &Layout,
    k: usize,
    row: &[f64],
    out: &mut Values,
    at: &dyn Fn(usize) -> String,
) -> Result<(), String> {
    if (k + 1) * l.sections.len() > l.max_values {
        return Err(format!(
            "{}: more than {} values: expected at most {} (cut the file along u)",
            at(0),
            l.max_values,
            l.max_values
        ));
    }
    for &(c, _) in &l.sections {
        let z = row[c];
        if z.is_finite() && z.abs() > MAX_CRG_ABS_HEIGHT_M {
            return Err(format!(
                "{}: height {z} m: expected |z| <= {MAX_CRG_ABS_HEIGHT_M} m (a damaged file?)",
                at(c)
            ));
        }
        out.z_m.push(z as f32);
    }
    for (ch, dst) in [(l.slope, &mut out.slope), (l.bank, &mut out.bank)] {
        if let (Some(c), Some(d)) = (ch, dst.as_mut()) {
            let x = row[c];
            // the slope of the first cross section is not used (no
            // interval before it): a placeholder is allowed there
            let unused = k == 0 && Some(c) == l.slope;
            if !(unused || x.is_finite() && x.abs() <= 10.0) {
                return Err(format!(
                    "{}: reference line {} {x}: expected a finite value of at most 10 m/m",
                    at(c),
                    if Some(c) == l.slope {
                        "slope"
                    } else {
                        "banking"
                    }
                ));
            }
            d.push(if unused && !x.is_finite() { 0.0 } else { x });
        }
    }
    Ok(())
}

fn empty_values(l: &Layout) -> Values {
    let nu = l.nu.unwrap_or(0);
    Values {
        nv: l.sections.len(),
        z_m: Vec::with_capacity(nu * l.sections.len()),
        slope: l.slope.map(|_| Vec::with_capacity(nu)),
        bank: l.bank.map(|_| Vec::with_capacity(nu)),
        offset_z_m: 0.0,
    }
}

/// The binary data: `nch` big-endian values a cross section, one after
/// the other; after the last, only NaN padding up to a whole 80-byte
/// record.
fn read_binary<R: Read>(
    r: &mut R,
    l: &Layout,
    data_bytes: u64,
    data_offset: u64,
) -> Result<Values, String> {
    let w = l.format.width() as u64;
    let nch = l.nch() as u64;
    let row_bytes = nch * w;
    if !data_bytes.is_multiple_of(w) {
        return Err(format!(
            "byte {data_offset}: the data is {data_bytes} bytes, not a whole number of {w}-byte values ({nch} channels a cross section{}): a damaged file (a line-end conversion?)",
            l.nu.map_or(String::new(), |nu| format!(
                ", {nu} cross sections: {} bytes padded to a whole 80-byte record",
                (nu as u64 * row_bytes).div_ceil(80) * 80
            ))
        ));
    }
    // without the end of u, as many cross sections as the data holds
    let nu = l.nu.map_or(data_bytes / row_bytes, |n| n as u64);
    let need = nu * row_bytes;
    let padded = need.div_ceil(80) * 80;
    if data_bytes < need {
        return Err(format!(
            "byte {}: the data ends after {} whole cross sections: expected {nu} ({need} bytes)",
            data_offset + data_bytes,
            data_bytes / row_bytes
        ));
    }
    if data_bytes > padded {
        return Err(format!(
            "byte {}: {} bytes after the last cross section: expected at most {} bytes of padding to a whole 80-byte record",
            data_offset + need,
            data_bytes - need,
            padded - need
        ));
    }
    let mut out = empty_values(l);
    let mut buf = vec![0u8; (nch * w) as usize];
    let mut row = vec![0.0f64; nch as usize];
    for k in 0..nu as usize {
        r.read_exact(&mut buf).map_err(|e| {
            format!(
                "byte {}: cannot read: {e}",
                data_offset + k as u64 * nch * w
            )
        })?;
        decode(&buf, l.format, &mut row);
        let base = data_offset + k as u64 * nch * w;
        file_row(l, k, &row, &mut out, &|c| {
            format!("byte {}", base + c as u64 * w)
        })?;
    }
    let mut pad = Vec::new();
    r.read_to_end(&mut pad)
        .map_err(|e| format!("byte {}: cannot read: {e}", data_offset + need))?;
    let mut tail = vec![0.0; pad.len() / w as usize];
    decode(&pad, l.format, &mut tail);
    if let Some(i) = tail.iter().position(|x| !x.is_nan()) {
        return Err(format!(
            "byte {}: a value {} after the last cross section: expected NaN padding",
            data_offset + need + i as u64 * w,
            tail[i]
        ));
    }
    Ok(out)
}

/// Big-endian values of `format` in `bytes` into `out`.
#[inline]
fn decode(bytes: &[u8], format: CrgFormat, out: &mut [f64]) {
    match format {
        CrgFormat::Kdbi => {
            for (o, c) in out.iter_mut().zip(bytes.chunks_exact(8)) {
                *o = f64::from_be_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]);
            }
        }
        _ => {
            for (o, c) in out.iter_mut().zip(bytes.chunks_exact(4)) {
                *o = f32::from_be_bytes([c[0], c[1], c[2], c[3]]) as f64;
            }
        }
    }
}

/// The formatted data: each cross section starts a new record (line) of 80
/// characters, its values `width` characters each, `80 / width` a record.
fn read_text<R: BufRead>(r: &mut R, l: &Layout, first_line: usize) -> Result<Values, String> {
    let w = l.format.width();
    let per_record = 80 / w;
    let nch = l.nch();
    let mut out = empty_values(l);
    let mut row = vec![0.0f64; nch];
    let mut line_no = first_line;
    let mut buf = Vec::with_capacity(96);
    let mut next_line = |buf: &mut Vec<u8>, line_no: &mut usize| -> Result<bool, String> {
        loop {
            buf.clear();
            let n = r
                .by_ref()
                .take(MAX_HEADER_LINE as u64 + 1)
                .read_until(b'\n', buf)
                .map_err(|e| format!("line {line_no}: cannot read: {e}"))?;
            if n == 0 {
                return Ok(false);
            }
            if n > MAX_HEADER_LINE {
                return Err(format!(
                    "line {line_no}: longer than {MAX_HEADER_LINE} bytes: expected records of 80 characters"
                ));
            }
            while matches!(buf.last(), Some(b'\n' | b'\r')) {
                buf.pop();
            }
            if buf.iter().all(|b| *b == b' ') {
                // a blank line holds no record
                *line_no += 1;
                continue;
            }
            return Ok(true);
        }
    };
    for k in 0.. {
        if l.nu == Some(k) {
            break;
        }
        let mut c = 0;
        let mut lines = Vec::new();
        while c < nch {
            if !next_line(&mut buf, &mut line_no)? {
                if c == 0 && l.nu.is_none() {
                    return Ok(out);
                }
                return Err(format!(
                    "line {line_no}: the data ends in cross section {}: expected {} cross sections of {nch} values",
                    k + 1,
                    l.nu.map_or("whole".to_string(), |n| n.to_string())
                ));
            }
            let here = line_no;
            lines.push(here);
            for slot in 0..per_record.min(nch - c) {
                let field = buf.get(slot * w..(slot + 1) * w).ok_or_else(|| {
                    format!(
                        "line {here}, column {}: the record ends: expected {} values of {w} characters",
                        slot * w + 1,
                        per_record.min(nch - c)
                    )
                })?;
                row[c] = parse_field(field).map_err(|f| {
                    format!(
                        "line {here}, column {}: `{f}`: expected a number of {w} characters or a placeholder starting with `*`",
                        slot * w + 1
                    )
                })?;
                c += 1;
            }
            line_no += 1;
        }
        let at = |ch: usize| {
            let rec = ch / per_record;
            format!(
                "line {}, column {}",
                lines.get(rec).copied().unwrap_or(0),
                (ch % per_record) * w + 1
            )
        };
        file_row(l, k, &row, &mut out, &at)?;
    }
    if next_line(&mut buf, &mut line_no)? {
        return Err(format!(
            "line {line_no}: a record after the {} cross sections from reference_line_start_u to reference_line_end_u: expected the end of the file",
            l.nu.unwrap_or(0)
        ));
    }
    Ok(out)
}

/// The number a header value starts with (the standard's readers take
/// the longest leading number: `2.000000000+e00` is 2).
fn leading_number(text: &str) -> Option<f64> {
    let end = text
        .find(|c: char| !(c.is_ascii_digit() || matches!(c, '+' | '-' | '.' | 'e' | 'E')))
        .unwrap_or(text.len());
    (1..=end).rev().find_map(|n| text[..n].parse::<f64>().ok())
}

/// One formatted value: a number (Fortran `D` exponents allowed), or NaN
/// for a placeholder starting with `*` (`**unused**` included).
fn parse_field(field: &[u8]) -> Result<f64, String> {
    let text: String = field.iter().map(|&b| b as char).collect();
    let t = text.trim();
    if t.starts_with('*') {
        return Ok(f64::NAN);
    }
    let s = t.replace(['d', 'D'], "e");
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(x) if x.is_nan() => Ok(x),
        _ => Err(text),
    }
}

/// Applies the `$ROAD_CRG_MODS` that change heights; refuses those that
/// would change the grid's geometry or a height reference not applied.
fn apply_mods(h: &Header, v: &mut Values) -> Result<(), String> {
    let mut nan_mode = None;
    let mut nan_offset = 0.0;
    for (key, value, line) in &h.mods {
        let (key, value, line) = (key.as_str(), *value, *line);
        if !value.is_finite() {
            return Err(format!(
                "line {line}: modifier {key} = {value}: expected a finite number"
            ));
        }
        match key {
            "scale_z_grid" => {
                for z in &mut v.z_m {
                    *z *= value as f32;
                }
            }
            "scale_slope" => {
                if let Some(s) = v.slope.as_mut() {
                    s.iter_mut().for_each(|x| *x *= value);
                } else if value != 1.0 {
                    return Err(format!(
                        "line {line}: modifier scale_slope = {value} on a constant slope: expected a slope channel or no such modifier"
                    ));
                }
            }
            "scale_banking" => {
                if let Some(b) = v.bank.as_mut() {
                    b.iter_mut().for_each(|x| *x *= value);
                } else if value != 1.0 {
                    return Err(format!(
                        "line {line}: modifier scale_banking = {value} on a constant banking: expected a banking channel or no such modifier"
                    ));
                }
            }
            "refline_offset_z" => v.offset_z_m += value,
            "grid_nan_mode" => nan_mode = Some((value, line)),
            "grid_nan_offset" => nan_offset = value,
            "scale_length" | "scale_width" | "refpoint_z" => {
                return Err(format!(
                    "line {line}: modifier {key} = {value}: expected a file without it (it changes the grid or its height reference; not applied here)"
                ));
            }
            // plan view and curvature: no height changes along the line
            _ => {}
        }
    }
    if let Some((mode, line)) = nan_mode {
        match mode as i64 {
            0 if mode == 0.0 => {}
            1 if mode == 1.0 => {
                for z in &mut v.z_m {
                    if z.is_nan() {
                        *z = nan_offset as f32;
                    }
                }
            }
            2 if mode == 2.0 => keep_last(v, nan_offset),
            _ => {
                return Err(format!(
                    "line {line}: modifier grid_nan_mode = {mode}: expected 0 (keep), 1 (set to the offset) or 2 (keep the last value)"
                ));
            }
        }
    }
    Ok(())
}

/// `grid_nan_mode = 2`: in each cross section, a NaN takes the value of
/// its neighbour to the right (scanning leftwards), then the NaNs left at
/// the right edge the value of their neighbour to the left, the offset
/// added to the first value so filled in each scan.
fn keep_last(v: &mut Values, offset: f64) {
    let nv = v.nv;
    for z in v.z_m.chunks_exact_mut(nv) {
        let mut applied = false;
        for j in 1..nv {
            if z[j].is_nan() {
                z[j] = z[j - 1];
                if !applied && !z[j].is_nan() {
                    z[j] += offset as f32;
                    applied = true;
                }
            }
        }
        let mut applied = false;
        for j in (1..nv).rev() {
            if z[j - 1].is_nan() && !z[j].is_nan() {
                z[j - 1] = z[j];
                if !applied {
                    z[j - 1] += offset as f32;
                    applied = true;
                }
            }
        }
    }
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
        for (block, name) in [
            ("$ROAD_CRG_MODS\nscale_length = 2\n", "scale_length"),
            ("$ROAD_CRG_MODS\nrefpoint_z = 1\n", "refpoint_z"),
            (
                "$ROAD_CRG_OPTS\nborder_smooth_ubeg = 1\n",
                "border_smooth_ubeg",
            ),
        ] {
            let p = tmp(&format!("{name}.crg"), format!("{block}{text}").as_bytes());
            let e = read_crg(&p).unwrap_err();
            assert!(
                e.message.contains(name) && e.message.starts_with("line 2"),
                "{e}"
            );
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
        assert!(
            e.message
                .starts_with(&format!("line {line}, column {column}:")),
            "{e}"
        );
        let short: String = text
            .lines()
            .take(text.lines().count() - 3)
            .map(|l| format!("{l}\n"))
            .collect();
        let e = read_crg(&tmp("short.crg", short.as_bytes())).unwrap_err();
        assert!(
            e.message.contains("the data ends in cross section 21"),
            "{e}"
        );
        assert!(e.path.ends_with("short.crg"));
        let huge = text.replacen("0.0111111", "9.9999e20", 1);
        let e = read_crg(&tmp("huge.crg", huge.as_bytes())).unwrap_err();
        assert!(e.message.contains("expected |z| <="), "{e}");
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
        assert!(
            e.message
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
        assert!(
            e.message.contains("not a whole number of 4-byte values"),
            "{e}"
        );
        assert!(e.message.starts_with("byte "), "{e}");
        let e = read_crg(&tmp("cut.crg", &bytes[..end + 4 * 342 * 500])).unwrap_err();
        assert!(
            e.message
                .contains("the data ends after 500 whole cross sections"),
            "{e}"
        );
        let mut extra = bytes.clone();
        let pad = extra.len() - 8;
        extra[pad..pad + 4].copy_from_slice(&1.0f32.to_be_bytes());
        let e = read_crg(&tmp("extra.crg", &extra)).unwrap_err();
        assert!(
            e.message.contains(&format!("byte {pad}")) && e.message.contains("padding"),
            "{e}"
        );
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
