//! Road files (method §4.1): a measured profile `x_m, z_m` and a surface
//! grid `x_m, y_m, z_m`, both CSV, read with bounded sizes and errors that
//! name the file, the line and the column (`crate::scene::load_road`
//! makes any road of a scene into the profile the solver samples).

use std::path::{Path, PathBuf};
use tirecontact_core::model::road::SurfaceGrid;
use tirecontact_core::model::road::surface::{
    GRID_TOLERANCE, MAX_SURFACE_BYTES, MAX_SURFACE_NODES,
};

/// A road file that cannot be used: which file, and why (naming the line
/// and column where one is at fault).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{path}: {message}")]
pub struct RoadFileError {
    pub path: PathBuf,
    pub message: String,
}

/// The regular file at `path` and its length (bytes), refused when it is
/// not a regular file (`what` it should be) or longer than `max_bytes`
/// (`limit` says why).
pub(super) fn open_capped(
    path: &Path,
    what: &str,
    max_bytes: u64,
    limit: &str,
) -> Result<(std::fs::File, u64), RoadFileError> {
    let err = |message: String| RoadFileError {
        path: path.to_path_buf(),
        message,
    };
    let file = crate::fsio::read::open_regular(path).map_err(|e| {
        err(if e.kind() == std::io::ErrorKind::InvalidInput {
            format!("{e}: expected {what}")
        } else {
            format!("cannot open: {e}")
        })
    })?;
    let len = file
        .metadata()
        .map_err(|e| err(format!("cannot read: {e}")))?
        .len();
    if len > max_bytes {
        return Err(err(format!(
            "{len} bytes: expected at most {max_bytes} bytes ({limit})"
        )));
    }
    Ok((file, len))
}

/// Opens a road file for reading as CSV: a regular file (a named pipe
/// would block, a device never end) of at most `max_bytes` (checked before
/// reading, `limit` saying what that holds), read through a cap one byte
/// past it and lines of at most [`MAX_LINE_BYTES`]; `rows` names the rows
/// expected.
fn open_road_csv(
    path: &Path,
    rows: &str,
    max_bytes: u64,
    limit: &str,
) -> Result<csv::Reader<crate::fsio::read::LineCap<std::io::Take<std::fs::File>>>, RoadFileError> {
    let (file, _) = open_capped(
        path,
        &format!("a CSV file of {rows} rows"),
        max_bytes,
        limit,
    )?;
    Ok(csv::ReaderBuilder::new()
        .has_headers(false)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .flexible(true)
        // a file growing while read is cut one byte past the limit, and a
        // line longer than any row (a file without line ends) is refused
        // before it is buffered
        .from_reader(crate::fsio::read::LineCap::new(
            std::io::Read::take(file, max_bytes.saturating_add(1)),
            MAX_LINE_BYTES,
        )))
}

/// Largest measured profile accepted (rows): 20 million rows are 320 MB of
/// `f64` in memory.
pub const MAX_PROFILE_ROWS: usize = 20_000_000;

/// Largest measured profile file accepted (bytes), checked before reading:
/// 64 bytes per row of [`MAX_PROFILE_ROWS`] (a row of two full-precision
/// numbers is about 45 bytes), so a huge or runaway file is refused at once
/// instead of being read.
pub const MAX_PROFILE_BYTES: u64 = 64 * MAX_PROFILE_ROWS as u64;

/// Longest line of a road profile file (bytes): a row is two numbers, a
/// comment a sentence.
pub const MAX_LINE_BYTES: usize = 4096;

/// Reads a `x_m, z_m` CSV: optional header, strictly increasing finite `x`,
/// at most [`MAX_PROFILE_ROWS`] rows and [`MAX_PROFILE_BYTES`] bytes.
pub fn read_profile_csv(path: &Path) -> Result<(Vec<f64>, Vec<f64>), RoadFileError> {
    read_profile_csv_limited(path, MAX_PROFILE_ROWS, MAX_PROFILE_BYTES)
}

/// [`read_profile_csv`] with explicit limits (rows, bytes), so that the limit
/// logic can be tested on small files.
pub fn read_profile_csv_limited(
    path: &Path,
    max_rows: usize,
    max_bytes: u64,
) -> Result<(Vec<f64>, Vec<f64>), RoadFileError> {
    let err = |message: String| RoadFileError {
        path: path.to_path_buf(),
        message,
    };
    let mut rdr = open_road_csv(
        path,
        "`x_m, z_m`",
        max_bytes,
        &format!("{max_rows} rows; resample the profile"),
    )?;
    let (mut xs, mut zs) = (Vec::new(), Vec::new());
    let mut rec = csv::StringRecord::new();
    for row in 0usize.. {
        let more = rdr.read_record(&mut rec);
        if rdr.position().byte() > max_bytes {
            return Err(err(format!(
                "more than {max_bytes} bytes: expected at most {max_bytes} bytes ({max_rows} rows; resample the profile)"
            )));
        }
        if !more.map_err(|e| match e.kind() {
            csv::ErrorKind::Io(io) if io.kind() == std::io::ErrorKind::InvalidData => err(format!(
                "{io}: expected `x_m, z_m` rows of at most {MAX_LINE_BYTES} bytes"
            )),
            _ => err(format!("record {}: {e}", row + 1)),
        })? {
            break;
        }
        // the file's own line number (comment lines are skipped by the reader)
        let line = rec.position().map_or(row as u64 + 1, |p| p.line());
        if rec.len() < 2 {
            return Err(err(format!(
                "line {line}: expected two columns `x_m, z_m`, found {}",
                rec.len()
            )));
        }
        let (sx, sz) = (&rec[0], &rec[1]);
        let (x, z) = match (sx.parse::<f64>(), sz.parse::<f64>()) {
            (Ok(x), Ok(z)) => (x, z),
            _ if row == 0 => continue, // header
            _ => {
                return Err(err(format!(
                    "line {line}: expected two numbers `x_m, z_m`, found `{sx}, {sz}`"
                )));
            }
        };
        if !x.is_finite() || !z.is_finite() {
            return Err(err(format!(
                "line {line}: x = {x}, z = {z}: expected finite numbers"
            )));
        }
        if let Some(&last) = xs.last()
            && x <= last
        {
            return Err(err(format!(
                "line {line}: x = {x} m after x = {last} m: expected strictly increasing x"
            )));
        }
        if xs.len() >= max_rows {
            return Err(err(format!(
                "line {line}: more than {max_rows} rows: expected at most {max_rows} rows (resample the profile)"
            )));
        }
        xs.push(x);
        zs.push(z);
    }
    if xs.len() < 2 {
        return Err(err(format!(
            "{} data row(s): expected at least two `x_m, z_m` rows",
            xs.len()
        )));
    }
    Ok((xs, zs))
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
pub fn read_surface_csv(path: &Path, looped: bool) -> Result<SurfaceGrid, RoadFileError> {
    read_surface_csv_limited(path, looped, MAX_SURFACE_NODES, MAX_SURFACE_BYTES)
}

/// [`read_surface_csv`] with explicit limits (nodes, bytes), so that the
/// limits can be tested on small files.
pub fn read_surface_csv_limited(
    path: &Path,
    looped: bool,
    max_nodes: usize,
    max_bytes: u64,
) -> Result<SurfaceGrid, RoadFileError> {
    let err = |message: String| RoadFileError {
        path: path.to_path_buf(),
        message,
    };
    let mut rdr = open_road_csv(
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
}
