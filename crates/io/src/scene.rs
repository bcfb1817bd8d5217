//! Scenes: what is simulated, as written in RON preset files, and their
//! validation. Every validation error names the field, the value and what was
//! expected; syntax errors give file, line and column, and so do validation
//! errors of a preset's text (where it writes the field, `locate`).

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use tirecontact_core::base::error::{FieldError, fmt_num};
use tirecontact_core::model::lsce::IdentifyOptions;
use tirecontact_core::model::ring::RingParams;
use tirecontact_core::model::road::{Road, RoadProfile};

mod edits;
mod error;
pub mod fields;
pub mod locate;
pub mod points;
pub mod share;
pub use edits::{described_with_edits, edits_since, edits_since_identified};
pub use error::SceneError;
pub use points::{PointGrid, Points, Preload};

pub use tirecontact_core::solver::problem::{Contact, ContactScheme, Point, RunShape};

/// Largest tread stiffness accepted (N/m).
pub const MAX_TREAD_STIFFNESS_N_M: f64 = 1e16;

pub use tirecontact_core::base::modal::Mode;

/// Source of the tyre's Green functions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Tyre {
    /// A modal model given mode by mode (method §2).
    Modal { modes: Vec<Mode> },
    /// The ring tyre (method §5), its radial Green functions at the contact
    /// points identified by LSCE (method §6) into a modal model. Both fields
    /// default (the reference passenger tyre, the default options).
    Ring {
        #[serde(default)]
        ring: RingParams,
        #[serde(default)]
        identification: IdentifyOptions,
    },
    /// Responses measured on a real tyre (hammer or shaker tests) or
    /// computed elsewhere (finite elements, waveguides), identified by LSCE
    /// (method §6) as the ring's are. The file (relative to the preset's
    /// folder) is UFF 58 (`.uff`, `.unv`), CSV impulse responses
    /// (`t_s, g{i}_{j}`, m/(N·s)) or CSV receptances (`freq_hz,
    /// h{i}_{j}_re, h{i}_{j}_im`, m/N): see [`crate::readers::measured`]. The data's
    /// sampling is used (`identification.sample_rate_hz` is not); its
    /// first `identification.duration_s` seconds are identified.
    Measured {
        file: PathBuf,
        #[serde(default)]
        identification: IdentifyOptions,
        /// The file's node numbers of the scene's points, in order (UFF);
        /// empty (the default): the file's points in order.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        nodes: Vec<i64>,
    },
    /// A tyre with a width (method §5.3): the belt as a tensioned
    /// orthotropic plate on an elastic foundation, its modes in closed form
    /// at the points `(x_m, y_m)` (`y_m` within `±width_m/2`). Defaults: a
    /// passenger car tyre's belt.
    Plate {
        #[serde(default)]
        plate: tirecontact_core::model::plate::PlateParams,
    },
    /// A tyre computed elsewhere (method §5.4): the normal modes of a
    /// finite-element model exported as UFF 55 or 2414 (node coordinates in
    /// 15 or 2411, units in 164), read into a modal model at the points
    /// without identification. See [`crate::readers::fe_modes`].
    FeModes {
        /// The UFF file, relative to the preset's folder.
        file: PathBuf,
        /// The file's node of each point, in order, or `Nearest`: the node
        /// nearest each point (within `nearest_within_m`).
        nodes: crate::readers::fe_modes::FeNodes,
        /// The FE axis normal to the road, pointing away from it; default Z.
        #[serde(default = "default_fe_direction")]
        direction: crate::readers::fe_modes::FeAxis,
        /// The FE axes of the points' `x_m` (along) and `y_m` (across);
        /// default `(along: X, across: Y)`.
        #[serde(default)]
        axes: crate::readers::fe_modes::FeAxes,
        /// `Ratio(ξ)`, `Modal([ξ, ...])`, `Rayleigh(alpha_per_s, beta_s)` or
        /// `FromFile`.
        damping: crate::readers::fe_modes::FeDamping,
        /// Modal masses (kg) replacing the records': one number, or one per
        /// mode kept; empty (the default): the records'.
        #[serde(
            default,
            alias = "modal_mass",
            deserialize_with = "crate::readers::fe_modes::de_masses",
            skip_serializing_if = "Vec::is_empty"
        )]
        modal_mass_kg: Vec<f64>,
        /// Modes kept, `lo <= f <= hi` (Hz); default every mode.
        #[serde(
            default = "all_fe_modes",
            skip_serializing_if = "crate::readers::fe_modes::is_all_modes"
        )]
        band_hz: (f64, f64),
        /// `Nearest`: largest distance (m) from a point to its node;
        /// default 0.001.
        #[serde(
            default = "default_nearest_within",
            skip_serializing_if = "crate::readers::fe_modes::is_default_within"
        )]
        nearest_within_m: f64,
        /// How the file scales its shapes: `Consistent` (default, 1/√ of
        /// the file's mass unit) or `LengthPerSqrtKg`.
        #[serde(
            default,
            skip_serializing_if = "crate::readers::fe_modes::FeShapeUnits::is_consistent"
        )]
        shape_units: crate::readers::fe_modes::FeShapeUnits,
    },
}

fn default_fe_direction() -> crate::readers::fe_modes::FeAxis {
    crate::readers::fe_modes::FeAxis::Z
}

fn all_fe_modes() -> (f64, f64) {
    crate::readers::fe_modes::ALL_MODES_HZ
}

fn default_nearest_within() -> f64 {
    crate::readers::fe_modes::DEFAULT_NEAREST_WITHIN_M
}

impl Tyre {
    /// An FE tyre's fields, its file resolved against `base_dir`.
    pub fn fe_spec(
        &self,
        base_dir: Option<&Path>,
    ) -> Option<crate::readers::fe_modes::FeModesSpec> {
        let Tyre::FeModes {
            file,
            nodes,
            direction,
            axes,
            damping,
            modal_mass_kg,
            band_hz,
            nearest_within_m,
            shape_units,
        } = self
        else {
            return None;
        };
        Some(crate::readers::fe_modes::FeModesSpec {
            file: crate::readers::fe_modes::resolve(base_dir, file),
            nodes: nodes.clone(),
            direction: *direction,
            axes: *axes,
            damping: damping.clone(),
            modal_mass_kg: modal_mass_kg.clone(),
            band_hz: *band_hz,
            nearest_within_m: *nearest_within_m,
            shape_units: *shape_units,
        })
    }
}

/// A complete scene: tyre, contact points, road, speed and time stepping.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Display name.
    pub name: String,
    /// Free text shown with the scene (optional).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// The tyre model. Changing it restarts the run.
    pub tyre: Tyre,
    /// Contact points: a list of `Point(...)`, or `Grid(...)` (see
    /// [`PointGrid`]). Changing them restarts the run.
    pub points: Points,
    /// Road profile. Applied live.
    pub road: Road,
    /// Rolling speed `V` (m/s), >= 0. Applied live.
    pub speed_mps: f64,
    /// Ramp time `T_ramp` (s) of preload and road, >= 0; default 0.
    #[serde(default)]
    pub ramp_s: f64,
    /// Time step (s), > 0. Changing it restarts the run.
    pub dt_s: f64,
    /// Duration of a run (s), >= dt_s.
    pub duration_s: f64,
    /// Contact scheme; default `Located`.
    #[serde(default)]
    pub contact_scheme: ContactScheme,
    /// Contact law; default `Rigid` (the paper's kinematic contact).
    #[serde(default, skip_serializing_if = "Contact::is_rigid")]
    pub contact: Contact,
    /// Folder the scene was loaded from (for relative road files). Not saved.
    #[serde(skip)]
    pub base_dir: Option<PathBuf>,
}

/// Largest number of steps a run may have (bounds memory and time).
pub const MAX_STEPS: f64 = 1e10;

/// Largest scene file read (bytes): 64 MiB, far above any preset (mode
/// shapes take 20 bytes per point and mode).
pub const MAX_SCENE_BYTES: u64 = 64 << 20;

/// Largest number of contact points: the contact solver keeps about 16 P²
/// numbers (operators and their factorisations), 0.5 GB at 2000 points.
pub const MAX_POINTS: usize = 2000;

/// Largest number of sampled response values (pairs of points times
/// samples) a ring tyre's identification may need: 5e7 values, 400 MB; the
/// paper preset needs 1.5e4, 300 points at its 1000 samples 4.5e7.
pub const MAX_RING_RESPONSE_VALUES: f64 = 5e7;

fn ron_options() -> ron::Options {
    ron::Options::default()
}

impl Scene {
    /// Parses RON text; `file` names the source in messages.
    pub fn from_ron_str(text: &str, file: &str) -> Result<Scene, SceneError> {
        ron_options().from_str::<Scene>(text).map_err(|e| {
            let (line, col) = skip_blanks(text, e.span.start.line, e.span.start.col);
            SceneError::Syntax {
                file: file.to_string(),
                line,
                col,
                message: format!(
                    "{}{}{}",
                    e.code,
                    syntax_hint(&e.code),
                    source_excerpt(text, line, col)
                ),
            }
        })
    }

    /// Parses and validates RON text.
    pub fn parse(text: &str, file: &str) -> Result<Scene, SceneError> {
        let scene = Self::from_ron_str(text, file)?;
        scene.validate().map_err(|errors| SceneError::Invalid {
            file: file.to_string(),
            at: locate::locate_all(text, errors.iter().map(|e| e.field.as_str())),
            errors,
        })?;
        Ok(scene)
    }

    /// Reads, parses and validates a scene file; relative road files are
    /// resolved against its folder.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let io = |source: std::io::Error| SceneError::Io {
            path: path.to_path_buf(),
            source: source.into(),
        };
        // a regular file only (a named pipe would block, a device never
        // end), and a bounded read: a runaway file is refused
        let file = crate::fsio::read::open_regular(path).map_err(|e| {
            io(std::io::Error::new(
                e.kind(),
                format!(
                    "{e}: expected {} scene preset file (RON), e.g. presets/paper.ron",
                    if e.kind() == std::io::ErrorKind::NotFound {
                        "an existing"
                    } else {
                        "a"
                    }
                ),
            ))
        })?;
        let too_big = || {
            io(std::io::Error::other(format!(
                "more than {MAX_SCENE_BYTES} bytes: expected a scene file of at most {} MiB",
                MAX_SCENE_BYTES >> 20
            )))
        };
        // a regular file's size is known: one too big is refused unread
        if file.metadata().map_err(io)?.len() > MAX_SCENE_BYTES {
            return Err(too_big());
        }
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(
            &mut std::io::Read::take(file, MAX_SCENE_BYTES + 1),
            &mut bytes,
        )
        .map_err(io)?;
        if bytes.len() as u64 > MAX_SCENE_BYTES {
            // (grown while read)
            return Err(too_big());
        }
        let file = path.display().to_string();
        let text = String::from_utf8(bytes).map_err(|e| not_utf8(&file, e))?;
        let mut scene = Self::parse(&text, &file)?;
        scene.base_dir = path.parent().map(Path::to_path_buf);
        Ok(scene)
    }

    /// The scene as pretty RON text.
    pub fn to_ron_string(&self) -> String {
        let cfg = ron::ser::PrettyConfig::new()
            .struct_names(true)
            .depth_limit(4)
            .indentor("    ".to_string());
        // Serialising plain data structures cannot fail.
        ron_options()
            .to_string_pretty(self, cfg)
            .unwrap_or_else(|e| format!("// serialisation failed: {e}"))
    }

    /// Saves atomically: writes a temporary file in the same folder, flushes
    /// it to disk, then renames it over `path`. A failed write leaves the old
    /// file intact.
    pub fn save(&self, path: &Path) -> Result<(), SceneError> {
        crate::fsio::write_atomic(path, self.to_ron_string().as_bytes()).map_err(|source| {
            SceneError::Io {
                path: path.to_path_buf(),
                source: source.into(),
            }
        })
    }

    /// Number of contact points `P`.
    pub fn num_points(&self) -> usize {
        self.points.len()
    }

    /// Number of steps of a full run.
    /// Whether the tyre's modes are identified from responses (a ring or
    /// measured tyre) rather than given or computed exactly.
    pub fn modes_identified(&self) -> bool {
        matches!(self.tyre, Tyre::Ring { .. } | Tyre::Measured { .. })
    }

    /// Steps of the whole run ([`RunShape::num_steps`]).
    pub fn num_steps(&self) -> u64 {
        RunShape::num_steps(self)
    }

    /// Points whose `y` lies outside a surface file's grid (the grid does
    /// not say what the road is there), each named.
    pub fn surface_errors(
        &self,
        road: &tirecontact_core::model::road::RoadProfile,
    ) -> Vec<FieldError> {
        let Some((lo, hi)) = road.surface().and_then(|g| g.y_range_m()) else {
            return Vec::new();
        };
        self.points
            .iter()
            .enumerate()
            .filter(|(_, pt)| road.surface().is_some_and(|g| g.rows_at(pt.y_m).is_none()))
            .map(|(i, pt)| FieldError {
                field: format!("points[{i}].y_m"),
                value: fmt_num(pt.y_m),
                expected: format!(
                    "a position across the tread within the road surface's grid, {} m to {} m",
                    fmt_num(lo),
                    fmt_num(hi)
                ),
            })
            .collect()
    }

    /// `T_ramp = 0` is allowed only where no point starts below the road
    /// (`z(x_i) - h_i <= 0` for all `i`, method §4).
    pub fn ramp_error(
        &self,
        road: &tirecontact_core::model::road::RoadProfile,
    ) -> Option<FieldError> {
        if self.ramp_s != 0.0 {
            return None;
        }
        self.points.iter().enumerate().find_map(|(i, pt)| {
            let z = road.sample_at(pt.x_m, pt.y_m).map(|s| s.0).unwrap_or(0.0);
            (z - pt.h_m > 0.0).then(|| FieldError {
                field: "ramp_s".into(),
                value: "0".into(),
                expected: format!(
                    "a ramp time > 0 s: point {i} starts {:.3e} m below the road (docs/method.md §4)",
                    z - pt.h_m
                ),
            })
        })
    }

    /// Checks every value; returns all problems found.
    pub fn validate(&self) -> Result<(), Vec<FieldError>> {
        let mut v = Validator::default();
        if let Some((field, value, expected)) = self.points.grid().and_then(|g| g.check()) {
            v.push(&field, value, &expected);
            return v.finish();
        }
        let p = self.points.len();
        if p == 0 {
            v.push("points", "[]", "at least one contact point");
        }
        if p > MAX_POINTS {
            v.push(
                "points",
                format!("{p} points"),
                &format!(
                    "at most {MAX_POINTS} contact points (the contact solver keeps ~16 P² numbers)"
                ),
            );
            // the per-point checks below are quadratic: stop here
            return v.finish();
        }
        validate_points(&mut v, &self.points);
        validate_points_across(&mut v, &self.tyre, &self.contact, &self.points);
        validate_tyre(&mut v, &self.tyre, p);
        validate_plate_points(&mut v, &self.tyre, &self.contact, &self.points);
        validate_road(&mut v, &self.road);
        if let Contact::Compliant { stiffness_n_m } = &self.contact {
            validate_tread(&mut v, stiffness_n_m, p);
        }
        self.validate_speed_and_ramp(&mut v);
        self.validate_time_step(&mut v);
        v.finish()
    }

    /// The speed, the ramp time, and a ramp time of 0 where a point starts
    /// below the road (`ramp_error`; a measured road's when its file is read).
    fn validate_speed_and_ramp(&self, v: &mut Validator) {
        if v.nonneg("speed_mps", self.speed_mps, "a finite speed >= 0 m/s")
            && self.speed_mps > 1000.0
        {
            v.push("speed_mps", self.speed_mps, "a speed <= 1000 m/s");
        }
        v.nonneg("ramp_s", self.ramp_s, "a ramp time >= 0 s");
        // (a road read from a file or generated on a grid is checked when it
        // is loaded: `PreparedModel`)
        if !matches!(
            self.road,
            Road::Measured { .. } | Road::Surface { .. } | Road::Texture { .. }
        ) && let Ok(prof) = load_road(&self.road, None)
            && let Some(e) = self.ramp_error(&prof)
        {
            v.errors.push(e);
        }
    }

    /// The time step and the duration, each alone and against each other
    /// (at least one step, at most [`MAX_STEPS`]).
    fn validate_time_step(&self, v: &mut Validator) {
        // one message per field: an infinite dt_s is "not > 0 and finite", not
        // also "too large"
        if v.positive("dt_s", self.dt_s, "a finite time step > 0 s") && self.dt_s > 0.1 {
            v.push("dt_s", self.dt_s, "a time step <= 0.1 s");
        }
        let duration_ok = v.positive("duration_s", self.duration_s, "a finite duration > 0 s");
        if duration_ok && self.dt_s.is_finite() && self.dt_s > 0.0 && self.dt_s <= 0.1 {
            if self.dt_s > self.duration_s {
                v.push(
                    "dt_s",
                    self.dt_s,
                    &format!("a time step <= duration_s = {} s", fmt_num(self.duration_s)),
                );
            } else if self.duration_s / self.dt_s > MAX_STEPS {
                v.push(
                    "duration_s",
                    self.duration_s,
                    &format!(
                        "at most {MAX_STEPS:e} steps of dt_s = {} s ({:.3e} requested)",
                        fmt_num(self.dt_s),
                        self.duration_s / self.dt_s
                    ),
                );
            }
        }
    }
}

/// RON reports some errors (a value of the wrong type) where it starts
/// reading, before the blanks that precede the offending token: move the
/// position (1-based line and column, in characters) forward over blanks to
/// that token. Unchanged when only blanks follow.
fn skip_blanks(text: &str, line: usize, col: usize) -> (usize, usize) {
    let (mut l, mut c) = (1, 1);
    let mut chars = text.chars().peekable();
    while (l, c) < (line, col) {
        match chars.next() {
            Some('\n') => (l, c) = (l + 1, 1),
            Some(_) => c += 1,
            None => return (line, col),
        }
    }
    while let Some(&ch) = chars.peek() {
        if !ch.is_whitespace() {
            return (l, c);
        }
        if ch == '\n' {
            (l, c) = (l + 1, 1);
        } else {
            c += 1;
        }
        chars.next();
    }
    (line, col)
}

/// A file that is not UTF-8 text: a syntax error at the first invalid byte
/// (1-based line and column, in characters, as RON counts them).
fn not_utf8(file: &str, e: std::string::FromUtf8Error) -> SceneError {
    let at = e.utf8_error().valid_up_to();
    let bytes = e.as_bytes();
    let before = String::from_utf8_lossy(&bytes[..at]);
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    let text = String::from_utf8_lossy(bytes);
    SceneError::Syntax {
        file: file.to_string(),
        line,
        col,
        message: format!(
            "byte 0x{:02X} is not UTF-8: expected a UTF-8 text file (re-save the preset as UTF-8){}",
            // a FromUtf8Error always has an invalid byte at valid_up_to
            bytes[at],
            source_excerpt(&text, line, col)
        ),
    }
}

/// What to do about a RON error whose fix is not where it points: a missing
/// comma is reported at the next value, usually on the next line.
fn syntax_hint(code: &ron::Error) -> &'static str {
    match code {
        ron::Error::ExpectedComma => {
            ": a `,` is missing after the previous value (often at the end of the line above)"
        }
        _ => "",
    }
}

/// The source line `line` (1-based) with a caret under column `col` (1-based,
/// in characters, as RON counts them), so that a syntax or type error shows the
/// field and the value it is about. Empty when the line does not exist.
fn source_excerpt(text: &str, line: usize, col: usize) -> String {
    let Some(src) = text.lines().nth(line.wrapping_sub(1)) else {
        return String::new();
    };
    // long lines (minified files, fuzzed bytes) are cut around the column
    let chars: Vec<char> = src.chars().collect();
    let c = col.saturating_sub(1).min(chars.len());
    let from = c.saturating_sub(60);
    let to = (c + 60).min(chars.len());
    let shown: String = chars[from..to].iter().collect();
    let caret = " ".repeat(c - from);
    format!(
        "\n  {line:>4} | {}{shown}\n       | {}{caret}^",
        if from > 0 { "..." } else { "" },
        if from > 0 { "   " } else { "" }
    )
}

/// The contact points: finite positions, heights of a tyre deflection, no
/// two at one place `(x, y)`.
fn validate_points(v: &mut Validator, points: &[Point]) {
    for (i, pt) in points.iter().enumerate() {
        v.finite(
            &format!("points[{i}].x_m"),
            pt.x_m,
            "a finite position in m",
        );
        v.finite(
            &format!("points[{i}].y_m"),
            pt.y_m,
            "a finite position across the tread in m (0 on its centreline)",
        );
        if v.finite(&format!("points[{i}].h_m"), pt.h_m, "a finite height in m")
            && pt.h_m.abs() > 1.0
        {
            v.push(
                &format!("points[{i}].h_m"),
                pt.h_m,
                "|h| <= 1 m (a tyre deflection, in metres)",
            );
        }
        if let Some(j) = points[..i]
            .iter()
            .position(|q| q.x_m == pt.x_m && q.y_m == pt.y_m)
        {
            v.push(
                &format!("points[{i}].x_m"),
                pt.x_m,
                &format!(
                    "a place different from points[{j}]'s: both are at x_m = {} m, y_m = {} m (coincident points make the contact system singular)",
                    fmt_num(pt.x_m),
                    fmt_num(pt.y_m)
                ),
            );
        }
    }
}

/// Points at one `x` and different `y` on a ring tyre with rigid contact:
/// the ring's response does not depend on `y`, so their rows (and columns)
/// of the contact system are identical: it is singular, and nothing shares
/// their force out between them. Compliant contact adds the tread springs,
/// one per point, and solves it. A modal tyre's residues
/// may depend on `y`, and are the user's to give; a measured tyre's rows
/// are its file's responses, one per point.
fn validate_points_across(v: &mut Validator, tyre: &Tyre, contact: &Contact, points: &[Point]) {
    if !(contact.is_rigid() && matches!(tyre, Tyre::Ring { .. })) {
        return;
    }
    for (i, pt) in points.iter().enumerate() {
        if let Some(j) = points[..i]
            .iter()
            .position(|q| q.x_m == pt.x_m && q.y_m != pt.y_m)
        {
            v.push(
                &format!("points[{i}].x_m"),
                pt.x_m,
                &format!(
                    "a position different from points[{j}].x_m: points[{j}] and points[{i}] share x_m = {} m at different y_m ({} m and {} m), but a Ring tyre's response does not depend on y, so with rigid contact their rows of the contact system are identical (singular); use contact: Compliant(...) or a Modal tyre whose residues depend on y",
                    fmt_num(pt.x_m),
                    fmt_num(points[j].y_m),
                    fmt_num(pt.y_m)
                ),
            );
        }
    }
}

/// The tyre of a scene of `p` points.
fn validate_tyre(v: &mut Validator, tyre: &Tyre, p: usize) {
    match tyre {
        Tyre::Modal { modes } => {
            if modes.is_empty() {
                v.push("tyre.modes", "[]", "at least one mode");
            }
            for (k, m) in modes.iter().enumerate() {
                validate_mode(v, &format!("tyre.modes[{k}]"), m, p);
            }
        }
        Tyre::Ring {
            ring,
            identification,
        } => validate_ring_tyre(v, ring, identification, p),
        Tyre::Measured {
            file,
            identification,
            nodes,
        } => validate_measured_tyre(v, file, identification, nodes, p),
        Tyre::Plate { plate } => v.errors.extend(plate.validate("tyre.plate")),
        Tyre::FeModes { .. } => validate_fe_tyre(v, tyre, p),
    }
}

/// The fields of an FE tyre (method §5.4) for `p` points; the file itself
/// is read when the model is prepared.
fn validate_fe_tyre(v: &mut Validator, tyre: &Tyre, p: usize) {
    use crate::readers::fe_modes::{FeDamping, FeNodes};
    let Some(spec) = tyre.fe_spec(None) else {
        return;
    };
    if spec.file.as_os_str().is_empty() {
        v.push(
            "tyre.file",
            "\"\"",
            "the path of a UFF file of normal modes (datasets 55 or 2414)",
        );
    }
    if let FeNodes::List(nodes) = &spec.nodes {
        validate_node_list(v, nodes, p, ", or Nearest");
    }
    let (along, across, normal) = (spec.axes.along, spec.axes.across, spec.direction);
    if along == across {
        v.push(
            "tyre.axes.across",
            across.name(),
            &format!("an FE axis other than along ({})", along.name()),
        );
    }
    if normal == along || normal == across {
        v.push(
            "tyre.direction",
            normal.name(),
            &format!(
                "the FE axis normal to the road, other than the axes along ({}) and across ({})",
                along.name(),
                across.name()
            ),
        );
    }
    let ratio = |v: &mut Validator, field: &str, x: f64| {
        if !(x.is_finite() && (0.0..=MAX_FE_DAMPING).contains(&x)) {
            v.push(field, x, "a damping ratio from 0 to 10");
        }
    };
    match &spec.damping {
        FeDamping::Ratio(x) => ratio(v, "tyre.damping.0", *x),
        FeDamping::Modal(list) => {
            if list.is_empty() {
                v.push("tyre.damping.0", "[]", "one damping ratio per mode kept");
            }
            for (k, x) in list.iter().enumerate() {
                ratio(v, &format!("tyre.damping.0[{k}]"), *x);
            }
        }
        FeDamping::Rayleigh {
            alpha_per_s,
            beta_s,
        } => {
            if !(alpha_per_s.is_finite() && *alpha_per_s >= 0.0) {
                v.push("tyre.damping.alpha_per_s", *alpha_per_s, "α >= 0 (1/s)");
            }
            if !(beta_s.is_finite() && *beta_s >= 0.0) {
                v.push("tyre.damping.beta_s", *beta_s, "β >= 0 (s)");
            }
        }
        FeDamping::FromFile => {}
    }
    for (k, m) in spec.modal_mass_kg.iter().enumerate() {
        if !(m.is_finite() && *m > 0.0) {
            v.push(
                &format!("tyre.modal_mass_kg[{k}]"),
                *m,
                "a modal mass > 0 kg",
            );
        }
    }
    let (lo, hi) = spec.band_hz;
    if lo.is_nan() || hi.is_nan() || lo < 0.0 || hi <= lo {
        v.push(
            "tyre.band_hz",
            format!("({lo}, {hi})"),
            "a band (lo, hi) in Hz with 0 <= lo < hi",
        );
    }
    if !(spec.nearest_within_m.is_finite() && spec.nearest_within_m > 0.0) {
        v.push(
            "tyre.nearest_within_m",
            spec.nearest_within_m,
            "a distance > 0 m",
        );
    }
}

/// Largest damping ratio an FE tyre may state.
const MAX_FE_DAMPING: f64 = 10.0;

/// The points of a plate tyre lie inside the belt (its edges do not move),
/// and rigid contact needs at least as many modes as points (the contact
/// system is the sum of one rank-one term per mode).
fn validate_plate_points(v: &mut Validator, tyre: &Tyre, contact: &Contact, points: &[Point]) {
    let Tyre::Plate { plate } = tyre else {
        return;
    };
    if !plate.validate("tyre.plate").is_empty() {
        return;
    }
    let half = 0.5 * plate.width_m;
    for (i, pt) in points.iter().enumerate() {
        if pt.y_m.is_finite() && pt.y_m.abs() >= half {
            v.push(
                &format!("points[{i}].y_m"),
                pt.y_m,
                &format!(
                    "a position inside the belt, |y_m| < width_m / 2 = {} m (its edges do not move)",
                    fmt_num(half)
                ),
            );
        }
    }
    if contact.is_rigid() {
        let k = plate.plate_modes().len();
        if points.len() > k {
            v.push(
                "contact",
                "Rigid",
                &format!(
                    "Compliant(stiffness_n_m: [...]) tread springs: rigid contact of {} points on a plate tyre of {k} modes is singular (at most as many points as modes); or raise tyre.plate.max_freq_hz",
                    points.len()
                ),
            );
        }
    }
}

/// A ring tyre of `p` points: the ring, the identification options, and the
/// size of the sampled responses that identification needs.
fn validate_ring_tyre(
    v: &mut Validator,
    ring: &RingParams,
    identification: &IdentifyOptions,
    p: usize,
) {
    v.errors.extend(ring.validate("tyre.ring"));
    let id_errors = identification.validate("tyre.identification");
    if id_errors.is_empty() {
        // identification samples the responses of every pair of points
        let n = identification.num_samples();
        let values = (p * (p + 1) / 2) as f64 * n as f64;
        if values > MAX_RING_RESPONSE_VALUES {
            let most = (0..=p)
                .rev()
                .find(|&q| (q * (q + 1) / 2) as f64 * n as f64 <= MAX_RING_RESPONSE_VALUES)
                .unwrap_or(0);
            v.push(
                "points",
                format!("{p} points"),
                &format!(
                    "at most {most} points with tyre: Ring at {n} samples per response (identification samples P(P+1)/2 responses: {values:.3e} values, at most {MAX_RING_RESPONSE_VALUES:e}, {} MB); use fewer points or a shorter tyre.identification.duration_s",
                    MAX_RING_RESPONSE_VALUES as u64 * 8 / 1_000_000
                ),
            );
        }
    }
    v.errors.extend(id_errors);
}

/// A measured tyre of `p` points: a file named, one distinct node per point
/// when nodes are given, and the identification options.
fn validate_measured_tyre(
    v: &mut Validator,
    file: &Path,
    identification: &IdentifyOptions,
    nodes: &[i64],
    p: usize,
) {
    if file.as_os_str().is_empty() {
        v.push(
            "tyre.file",
            "\"\"",
            "the path of a UFF 58 or CSV file of the tyre's responses",
        );
    }
    if !nodes.is_empty() {
        validate_node_list(v, nodes, p, "");
    }
    // the band against the data's Nyquist frequency, and the
    // samples, are checked when the file is read
    v.errors
        .extend(identification.validate_for_data("tyre.identification"));
}

/// The tread stiffnesses of compliant contact with `p` points: one for all
/// or one per point, each in (0, [`MAX_TREAD_STIFFNESS_N_M`]].
/// `tyre.nodes` as a list: one node per point (`or_else`: the other form
/// the field takes, said after the count), none listed twice.
fn validate_node_list(v: &mut Validator, nodes: &[i64], p: usize, or_else: &str) {
    if nodes.len() != p {
        v.push(
            "tyre.nodes",
            format!("{} nodes", nodes.len()),
            &format!("one node number per point ({p}){or_else}"),
        );
    }
    for (k, a) in nodes.iter().enumerate() {
        if nodes[..k].contains(a) {
            v.push(
                &format!("tyre.nodes[{k}]"),
                a.to_string(),
                "a node not listed before",
            );
        }
    }
}

fn validate_tread(v: &mut Validator, stiffness_n_m: &[f64], p: usize) {
    if stiffness_n_m.len() != 1 && stiffness_n_m.len() != p {
        v.push(
            "contact.stiffness_n_m",
            format!("{} values", stiffness_n_m.len()),
            &format!("one stiffness for all points or {p} (one per point)"),
        );
    }
    for (i, &k) in stiffness_n_m.iter().enumerate() {
        if !(k.is_finite() && k > 0.0 && k <= MAX_TREAD_STIFFNESS_N_M) {
            v.push(
                &format!("contact.stiffness_n_m[{i}]"),
                k,
                &format!("a tread stiffness > 0 and <= {MAX_TREAD_STIFFNESS_N_M:e} N/m"),
            );
        }
    }
}

fn validate_mode(v: &mut Validator, at: &str, m: &Mode, p: usize) {
    if v.positive(
        &format!("{at}.freq_hz"),
        m.freq_hz,
        "a finite frequency > 0 Hz",
    ) && m.freq_hz > 1e6
    {
        v.push(&format!("{at}.freq_hz"), m.freq_hz, "a frequency <= 1e6 Hz");
    }
    if v.nonneg(
        &format!("{at}.damping_ratio"),
        m.damping_ratio,
        "a finite damping ratio >= 0 (0 undamped, 1 critical, > 1 overdamped)",
    ) && m.damping_ratio > 1e4
    {
        v.push(
            &format!("{at}.damping_ratio"),
            m.damping_ratio,
            "a damping ratio <= 1e4",
        );
    }
    match (m.residue.is_empty(), m.shape.is_empty()) {
        (true, true) => v.push(
            &format!("{at}.residue"),
            "(missing)",
            &format!("a {p}x{p} residue matrix or a shape of {p} values"),
        ),
        (false, false) => v.push(
            &format!("{at}.shape"),
            format!("{:?}", m.shape),
            "either `residue` or `shape`, not both",
        ),
        (false, true) => {
            if m.residue.len() != p || m.residue.iter().any(|r| r.len() != p) {
                let shape: Vec<usize> = m.residue.iter().map(Vec::len).collect();
                v.push(
                    &format!("{at}.residue"),
                    format!("{} rows of lengths {shape:?}", m.residue.len()),
                    &format!("a {p}x{p} matrix (one row and column per contact point)"),
                );
            }
            for (i, row) in m.residue.iter().enumerate() {
                for (j, a) in row.iter().enumerate() {
                    v.finite(
                        &format!("{at}.residue[{i}][{j}]"),
                        *a,
                        "a finite residue in 1/kg",
                    );
                }
            }
        }
        (true, false) => {
            if m.shape.len() != p {
                v.push(
                    &format!("{at}.shape"),
                    format!("{} values", m.shape.len()),
                    &format!("{p} values (one per contact point)"),
                );
            }
            for (i, a) in m.shape.iter().enumerate() {
                v.finite(
                    &format!("{at}.shape[{i}]"),
                    *a,
                    "a finite value in 1/sqrt(kg)",
                );
            }
        }
    }
}

fn validate_road(v: &mut Validator, road: &Road) {
    match road {
        Road::Sine {
            amplitude_m,
            wavelength_m,
        } => {
            if v.nonneg("road.amplitude_m", *amplitude_m, "an amplitude >= 0 m")
                && *amplitude_m > 1.0
            {
                v.push("road.amplitude_m", *amplitude_m, "an amplitude <= 1 m");
            }
            v.positive("road.wavelength_m", *wavelength_m, "a wavelength > 0 m");
        }
        Road::Harmonics { components } => {
            if components.is_empty() {
                v.push("road.components", "[]", "at least one harmonic");
            }
            for (k, c) in components.iter().enumerate() {
                v.finite(
                    &format!("road.components[{k}].amplitude_m"),
                    c.amplitude_m,
                    "a finite amplitude in m",
                );
                v.positive(
                    &format!("road.components[{k}].wavelength_m"),
                    c.wavelength_m,
                    "a wavelength > 0 m",
                );
                v.finite(
                    &format!("road.components[{k}].phase_rad"),
                    c.phase_rad,
                    "a finite phase in rad",
                );
            }
        }
        Road::Measured { file, .. } => {
            if file.as_os_str().is_empty() {
                v.push("road.file", "\"\"", "the path of a CSV of `x_m, z_m` rows");
            }
        }
        Road::Random { .. } => v.errors.extend(road.random_errors("road")),
        Road::Surface { file, .. } => {
            if file.as_os_str().is_empty() {
                v.push(
                    "road.file",
                    "\"\"",
                    "the path of a CSV of `x_m,y_m,z_m` rows (a height grid)",
                );
            }
        }
        Road::Texture { .. } => v.errors.extend(road.texture_errors("road")),
    }
}

/// A value as shown in a [`FieldError`]: numbers through [`fmt_num`].
trait ValueText {
    fn text(&self) -> String;
}

impl ValueText for f64 {
    fn text(&self) -> String {
        fmt_num(*self)
    }
}

impl ValueText for &str {
    fn text(&self) -> String {
        self.to_string()
    }
}

impl ValueText for String {
    fn text(&self) -> String {
        self.clone()
    }
}

#[derive(Default)]
struct Validator {
    errors: Vec<FieldError>,
}

impl Validator {
    fn push(&mut self, field: &str, value: impl ValueText, expected: &str) {
        self.errors.push(FieldError {
            field: field.to_string(),
            value: value.text(),
            expected: expected.to_string(),
        });
    }
    fn finite(&mut self, field: &str, x: f64, expected: &str) -> bool {
        if !x.is_finite() {
            self.push(field, x, expected);
            return false;
        }
        true
    }
    fn nonneg(&mut self, field: &str, x: f64, expected: &str) -> bool {
        if !(x.is_finite() && x >= 0.0) {
            self.push(field, x, expected);
            return false;
        }
        true
    }
    fn positive(&mut self, field: &str, x: f64, expected: &str) -> bool {
        if !(x.is_finite() && x > 0.0) {
            self.push(field, x, expected);
            return false;
        }
        true
    }
    fn finish(self) -> Result<(), Vec<FieldError>> {
        if self.errors.is_empty() {
            Ok(())
        } else {
            Err(self.errors)
        }
    }
}

impl RunShape for Scene {
    fn points(&self) -> &[Point] {
        &self.points
    }
    fn dt_s(&self) -> f64 {
        self.dt_s
    }
    fn duration_s(&self) -> f64 {
        self.duration_s
    }
    fn ramp_s(&self) -> f64 {
        self.ramp_s
    }
    fn grid_spacing_m(&self) -> Option<(f64, f64)> {
        self.points.grid().map(|g| g.spacing_m)
    }
}

/// The profile of `road`, ready to be sampled: a measured or surface file
/// read relative to `base_dir`, a generated road made after its fields are
/// checked (refused as invalid values of `road`).
pub fn load_road(road: &Road, base_dir: Option<&Path>) -> Result<RoadProfile, SceneError> {
    let path = |file: &Path| match base_dir {
        Some(d) if file.is_relative() => d.join(file),
        _ => file.to_path_buf(),
    };
    match road {
        Road::Measured { file, looped } => {
            let (x_m, z_m) = crate::readers::road::read_profile_csv(&path(file))?;
            Ok(RoadProfile::Measured {
                x_m,
                z_m,
                looped: *looped,
            })
        }
        Road::Surface { file, looped } => Ok(RoadProfile::Surface(std::sync::Arc::new(
            crate::readers::road::read_surface_csv(&path(file), *looped)?,
        ))),
        _ => match RoadProfile::generated(road) {
            Some(Ok(profile)) => Ok(profile),
            Some(Err(errors)) => Err(SceneError::Invalid {
                file: "road".into(),
                errors,
                at: Vec::new(),
            }),
            None => unreachable!("every road without a file is generated"),
        },
    }
}
