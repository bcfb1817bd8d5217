//! The numeric fields of the scene format, in one table: each path (a
//! `[*]` stands for any index) with the label the editor gives it, its SI
//! unit, the unit it is shown in, what it means and the values the scene
//! accepts. Sweeps and studies name their parameters and axes from it, the
//! edit list of a description names its changes from it, the visualiser's
//! tooltips read it, and [`numeric_fields`] reaches the values it lists.
//!
//! A new numeric field of the scene is one entry of [`FIELDS`] and one
//! line of [`numeric_fields`] (the tests below fail when either is missing).

use super::{MAX_POINTS, MAX_TREAD_STIFFNESS_N_M};

mod walk;
pub use walk::{GRID_PATHS, grid_fields, numeric_fields, set_grid_field};

/// One numeric field of the scene format.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Field {
    /// Its path, `[*]` for every index: `tyre.modes[*].freq_hz`.
    pub path: &'static str,
    /// The editor's name of it: `speed V`; for an indexed field the name
    /// after its holder (`frequency` of `mode 2`, see [`label`]), with
    /// `{1}` and `{2}` for the path's further indices (`shape at point
    /// {1}`). Empty: the path is its name.
    pub label: &'static str,
    /// The holder named before the label of an indexed field (`mode`,
    /// `point`); empty for a field of the scene itself.
    pub holder: &'static str,
    /// Its SI unit (`m/s`, `-` for a ratio); empty for a count or a
    /// number without unit.
    pub unit: &'static str,
    /// The factor and the unit it is shown in by the editor (`1e3`, `mm`
    /// for a road amplitude in m).
    pub shown: (f64, &'static str),
    /// What the value is, in words.
    pub what: &'static str,
    /// The lowest accepted value (SI) and whether it is itself accepted.
    pub min_si: Option<(f64, bool)>,
    /// The highest accepted value (SI), accepted itself.
    pub max_si: Option<f64>,
    /// Conditions on other fields, if any (empty if none).
    pub also: &'static str,
}

impl Field {
    const fn new(path: &'static str, unit: &'static str, what: &'static str) -> Self {
        Field {
            path,
            label: "",
            holder: "",
            unit,
            shown: (1.0, unit),
            what,
            min_si: None,
            max_si: None,
            also: "",
        }
    }
    const fn label(mut self, label: &'static str) -> Self {
        self.label = label;
        self
    }
    const fn of(mut self, holder: &'static str, label: &'static str) -> Self {
        self.holder = holder;
        self.label = label;
        self
    }
    const fn shown(mut self, scale: f64, unit: &'static str) -> Self {
        self.shown = (scale, unit);
        self
    }
    const fn min(mut self, lo: f64, inclusive: bool) -> Self {
        self.min_si = Some((lo, inclusive));
        self
    }
    const fn max(mut self, hi: f64) -> Self {
        self.max_si = Some(hi);
        self
    }
    const fn also(mut self, also: &'static str) -> Self {
        self.also = also;
        self
    }
}

const SPEED: &str = "rolling speed of the tyre over the road (0: the road stands still)";
const ALONG_ACROSS: &str = "along × across at most the points' limit";

/// Every numeric field of the scene format, in the order
/// [`numeric_fields`] lists them (the grid's fields after the points').
pub const FIELDS: &[Field] = &[
    Field::new("speed_mps", "m/s", SPEED)
        .label("speed V")
        .min(0.0, true)
        .max(1000.0),
    Field::new(
        "ramp_s",
        "s",
        "time over which the road and the preload are eased in from zero, so that the run \
         starts at rest without a shock",
    )
    .label("ramp")
    .min(0.0, true)
    .also("0 only if no point starts below the road"),
    Field::new(
        "dt_s",
        "s",
        "solver time step: smaller is more accurate (impacts are located inside the step) \
         and slower",
    )
    .label("time step dt")
    .shown(1e6, "µs")
    .min(0.0, false)
    .max(0.1)
    .also("at most the duration"),
    Field::new("duration_s", "s", "simulated time of one run, from t = 0")
        .label("duration")
        .min(0.0, false)
        .also("at most 1e10 time steps"),
    Field::new(
        "points[*].x_m",
        "m",
        "position of this contact point along the contact line (0: under the wheel centre)",
    )
    .of("point", "position x")
    .shown(1e3, "mm")
    .also("each point at a place (x, y) of its own"),
    Field::new(
        "points[*].y_m",
        "m",
        "position of this contact point across the tread (0: on its centreline); the road \
         is the same profile at every y, a modal tyre's residues may differ with it",
    )
    .of("point", "position y")
    .shown(1e3, "mm")
    .also(
        "each point at a place (x, y) of its own; a ring tyre's response does not depend \
         on y, so with rigid contact its points need an x each",
    ),
    Field::new(
        "points[*].h_m",
        "m",
        "height of the undeformed tyre at this point above the road's mean line; below 0 \
         the tyre is pressed into the road (preload)",
    )
    .of("point", "height h")
    .shown(1e3, "mm")
    .min(-1.0, true)
    .max(1.0),
    Field::new(
        "road.amplitude_m",
        "m",
        "height of the sine road's crests above its mean line (half the crest-to-trough height)",
    )
    .label("road amplitude a")
    .shown(1e3, "mm")
    .min(0.0, true)
    .max(1.0),
    Field::new(
        "road.wavelength_m",
        "m",
        "length of one road period: crest to crest; the excitation frequency is V / λ",
    )
    .label("road wavelength λ")
    .min(0.0, false),
    Field::new(
        "road.components[*].amplitude_m",
        "m",
        "amplitude of this harmonic of the road (its crest height)",
    )
    .of("harmonic", "amplitude")
    .shown(1e3, "mm"),
    Field::new(
        "road.components[*].wavelength_m",
        "m",
        "wavelength of this harmonic of the road",
    )
    .of("harmonic", "wavelength")
    .min(0.0, false),
    Field::new(
        "road.components[*].phase_rad",
        "rad",
        "phase of this harmonic of the road at x = 0",
    )
    .of("harmonic", "phase"),
    Field::new(
        "road.length_m",
        "m",
        "length of the random road or texture along x, after which it repeats (its loop)",
    )
    .label("road loop length L")
    .min(0.0, false)
    .also("with at most a set number of grid points: length × highest n is capped"),
    Field::new(
        "road.width_m",
        "m",
        "width of the texture across the road, after which it repeats",
    )
    .label("texture period across")
    .min(0.0, false),
    Field::new(
        "road.u_start_m",
        "m",
        "position u along the OpenCRG file's reference line under x = 0 at the start \
         (default: the file's first cross section)",
    )
    .label("OpenCRG start u")
    .also("the run stays within the file's u range"),
    Field::new(
        "road.v_offset_m",
        "m",
        "position v across the OpenCRG file (positive to the left of the reference line) \
         under y = 0",
    )
    .label("OpenCRG offset v")
    .also("every point within the file's v range"),
    Field::new(
        "road.min_wavenumber_cpm",
        "cycles/m",
        "lowest spatial frequency of the random road or texture: 1 / its longest wavelength",
    )
    .label("lowest wavenumber n")
    .min(0.0, false),
    Field::new(
        "road.max_wavenumber_cpm",
        "cycles/m",
        "highest spatial frequency of the random road or texture: 1 / its shortest wavelength",
    )
    .label("highest wavenumber n")
    .min(0.0, false)
    .also("at least the lowest n"),
    Field::new(
        "contact.stiffness_n_m[*]",
        "N/m",
        "tread stiffness: the spring between the contact point and the road (compliant \
         contact)",
    )
    .of("point", "tread stiffness of")
    .min(0.0, false)
    .max(MAX_TREAD_STIFFNESS_N_M),
    Field::new(
        "tyre.modes[*].freq_hz",
        "Hz",
        "natural frequency of this mode of the tyre",
    )
    .of("mode", "frequency")
    .min(0.0, false)
    .max(1e6),
    Field::new(
        "tyre.modes[*].damping_ratio",
        "-",
        "damping ratio ξ of this mode: 0 undamped, about 0.05 for a tyre, 1 critical, \
         more than 1 overdamped",
    )
    .of("mode", "damping ratio")
    .min(0.0, true)
    .max(1e4),
    Field::new(
        "tyre.modes[*].shape[*]",
        "1/√kg",
        "this mode's shape at this contact point (mass-normalised): the residue between \
         points i and j is shape[i] × shape[j]",
    )
    .of("mode", "shape at point {1}"),
    Field::new(
        "tyre.modes[*].residue[*][*]",
        "1/kg",
        "residue A[i][j] of this mode: how much a force at point j moves point i through it",
    )
    .of("mode", "residue at point {1} of a force at point {2}"),
    Field::new("tyre.ring.radius_m", "m", "radius of the ring's belt").label("ring radius"),
    Field::new("tyre.ring.belt_width_m", "m", "width of the ring's belt").label("belt width"),
    Field::new(
        "tyre.ring.mass_per_length_kg_m",
        "kg/m",
        "mass of the belt per length of its circumference",
    )
    .label("ring mass per length"),
    Field::new(
        "tyre.ring.inflation_pa",
        "Pa",
        "inflation pressure of the tyre",
    )
    .label("inflation")
    .shown(1e-5, "bar"),
    Field::new(
        "tyre.ring.radial_stiffness_n_m2",
        "N/m²",
        "stiffness of the sidewalls against a radial displacement of the belt, per length",
    )
    .label("ring radial stiffness"),
    Field::new(
        "tyre.ring.tangential_stiffness_n_m2",
        "N/m²",
        "stiffness of the sidewalls against a tangential displacement of the belt, per length",
    )
    .label("ring tangential stiffness"),
    Field::new(
        "tyre.ring.bending_stiffness_n_m2",
        "N·m²",
        "bending stiffness EI of the belt",
    )
    .label("ring bending stiffness EI"),
    Field::new(
        "tyre.ring.extensional_stiffness_n",
        "N",
        "extensional stiffness EA of the belt",
    )
    .label("ring extensional stiffness EA"),
    Field::new(
        "tyre.ring.damping_ratio",
        "-",
        "damping ratio of every mode of the ring",
    )
    .label("ring damping ratio"),
    Field::new(
        "tyre.identification.band_hz.0",
        "Hz",
        "lowest frequency of the band in which the modes are identified",
    )
    .label("identification band from"),
    Field::new(
        "tyre.identification.band_hz.1",
        "Hz",
        "highest frequency of the band in which the modes are identified",
    )
    .label("identification band to"),
    Field::new(
        "tyre.identification.sample_rate_hz",
        "Hz",
        "sample rate of the ring's simulated impulse responses",
    )
    .label("identification sample rate"),
    Field::new(
        "tyre.identification.duration_s",
        "s",
        "length of the impulse responses the modes are identified from",
    )
    .label("identification duration"),
    Field::new(
        "tyre.damping.0",
        "-",
        "damping ratio of every mode of the FE model",
    )
    .label("FE damping ratio"),
    Field::new(
        "tyre.damping.0[*]",
        "-",
        "damping ratio of this mode of the FE model",
    )
    .of("FE mode", "damping ratio"),
    Field::new(
        "tyre.damping.alpha_per_s",
        "1/s",
        "Rayleigh damping's mass factor α: ξ = α / (2ω) + β ω / 2",
    )
    .label("Rayleigh α"),
    Field::new(
        "tyre.damping.beta_s",
        "s",
        "Rayleigh damping's stiffness factor β: ξ = α / (2ω) + β ω / 2",
    )
    .label("Rayleigh β"),
    Field::new(
        "tyre.nearest_within_m",
        "m",
        "largest distance from a contact point to the FE node that stands for it",
    )
    .label("nearest node within")
    .shown(1e3, "mm"),
    Field::new("tyre.plate.width_m", "m", "width W of the plate").label("plate width W"),
    Field::new(
        "tyre.plate.circumference_m",
        "m",
        "circumference L of the plate: the period of its modes along the rolling direction",
    )
    .label("plate circumference L"),
    Field::new(
        "tyre.plate.mass_per_area_kg_m2",
        "kg/m²",
        "mass of the plate per area",
    )
    .label("plate mass per area"),
    Field::new(
        "tyre.plate.bending_along_nm",
        "N·m",
        "bending stiffness Bx of the plate along the rolling direction",
    )
    .label("plate bending along Bx"),
    Field::new(
        "tyre.plate.bending_across_nm",
        "N·m",
        "bending stiffness By of the plate across the tread",
    )
    .label("plate bending across By"),
    Field::new(
        "tyre.plate.tension_along_n_m",
        "N/m",
        "tension Tx of the plate along the rolling direction (the inflation's)",
    )
    .label("plate tension along Tx"),
    Field::new(
        "tyre.plate.tension_across_n_m",
        "N/m",
        "tension Ty of the plate across the tread",
    )
    .label("plate tension across Ty"),
    Field::new(
        "tyre.plate.foundation_n_m3",
        "N/m³",
        "stiffness s of the elastic foundation under the plate (the sidewalls), per area",
    )
    .label("plate foundation s"),
    Field::new(
        "tyre.plate.damping_ratio",
        "-",
        "damping ratio of every mode of the plate",
    )
    .label("plate damping ratio"),
    Field::new(
        "tyre.plate.max_freq_hz",
        "Hz",
        "the plate's modes are kept up to this frequency",
    )
    .label("plate modes up to"),
    Field::new(
        "points.along",
        "",
        "points of the contact patch along the rolling direction, in each row (a whole number)",
    )
    .label("points along")
    .shown(1.0, "points")
    .min(1.0, true)
    .max(MAX_POINTS as f64)
    .also(ALONG_ACROSS),
    Field::new(
        "points.across",
        "",
        "rows of the contact patch across the tread (a whole number)",
    )
    .label("rows across")
    .shown(1.0, "rows")
    .min(1.0, true)
    .max(MAX_POINTS as f64)
    .also(ALONG_ACROSS),
    Field::new(
        "points.spacing_m.0",
        "m",
        "distance between neighbouring points along the rolling direction",
    )
    .label("spacing along Δx")
    .shown(1e3, "mm")
    .min(0.0, false),
    Field::new(
        "points.spacing_m.1",
        "m",
        "distance between neighbouring rows across the tread",
    )
    .label("spacing across Δy")
    .shown(1e3, "mm")
    .min(0.0, false),
    Field::new(
        "points.preload.depth_m",
        "m",
        "how deep the undeformed tyre is pressed into the mean road plane (at the \
         footprint's centre for a parabolic one)",
    )
    .label("press depth")
    .shown(1e3, "mm")
    .min(0.0, true)
    .max(1.0),
    Field::new(
        "points.preload.length_m",
        "m",
        "length of the parabolic footprint along the rolling direction; points beyond it \
         start above the road",
    )
    .label("footprint length")
    .shown(1e3, "mm")
    .min(0.0, false),
];

/// `points[3].h_m` -> `points[*].h_m` (every index, nested ones too).
pub fn wildcard(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    let mut in_index = false;
    for c in path.chars() {
        match c {
            '[' => {
                in_index = true;
                out.push_str("[*");
            }
            ']' => {
                in_index = false;
                out.push(']');
            }
            _ if in_index => {}
            _ => out.push(c),
        }
    }
    out
}

/// The entry of the field at `path` (any index, or `[*]`); `None` for a
/// path the scene format has no number at.
pub fn field(path: &str) -> Option<&'static Field> {
    let w = wildcard(path.trim());
    FIELDS.iter().find(|f| f.path == w)
}

/// The field at `path` as the editor names it: `speed V` for `speed_mps`,
/// `mode 2 damping ratio` for `tyre.modes[2].damping_ratio`, `every
/// point's height h` for `points[*].h_m`, `tread stiffness of point 1`;
/// the path itself for a field without a name.
pub fn label(path: &str) -> String {
    let path = path.trim();
    let Some(f) = field(path).filter(|f| !f.label.is_empty()) else {
        return path.to_string();
    };
    if f.holder.is_empty() {
        return f.label.to_string();
    }
    // the first index of the path names the holder, the further ones
    // fill the label's `{1}`, `{2}` (`i`, `j` for every index)
    let indices = indices(path);
    let index = indices.first().copied().unwrap_or("*");
    let mut text = f.label.to_string();
    for (k, letter) in [(1, "i"), (2, "j")] {
        let i = indices.get(k).copied().unwrap_or("*");
        text = text.replace(&format!("{{{k}}}"), if i == "*" { letter } else { i });
    }
    // a label that ends in "of" takes its holder after it
    if let Some(head) = text.strip_suffix(" of") {
        return if index == "*" {
            format!("{head} of every {}", f.holder)
        } else {
            format!("{head} of {} {index}", f.holder)
        };
    }
    if index == "*" {
        format!("every {}'s {text}", f.holder)
    } else {
        format!("{} {index} {text}", f.holder)
    }
}

/// The indices of `path` in order: `["2", "0", "1"]` for
/// `tyre.modes[2].residue[0][1]`.
fn indices(path: &str) -> Vec<&str> {
    path.split('[')
        .skip(1)
        .filter_map(|rest| rest.split_once(']').map(|(i, _)| i.trim()))
        .collect()
}

/// The SI unit of the field at `path`; `None` for an unknown path or a
/// field without unit (a count).
pub fn unit(path: &str) -> Option<&'static str> {
    field(path).map(|f| f.unit).filter(|u| !u.is_empty())
}

/// An axis title of the field at `path`: its [`label()`] and its [`unit()`],
/// `speed V (m/s)`, `mode 0 frequency (Hz)`; no unit when it has none.
pub fn axis_label(path: &str) -> String {
    match unit(path) {
        Some(u) => format!("{} ({u})", label(path)),
        None => label(path),
    }
}

#[cfg(test)]
#[path = "fields/tests.rs"]
mod tests;
