//! What each numeric field of the editing panel means and which values the
//! scene accepts, for its tooltip: someone who has never seen the app learns
//! on hover what "ramp" is, in which unit it is typed and what may be typed,
//! before typing something that is refused. The bounds are the ones
//! `Scene::validate` checks (tests/gui/field_help.rs holds them to it).

/// The meaning of a field and the values it accepts (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FieldHelp {
    /// What the value is, in words.
    pub what: &'static str,
    /// The lowest accepted value (SI) and whether it is itself accepted.
    pub min_si: Option<(f64, bool)>,
    /// The highest accepted value (SI), accepted itself.
    pub max_si: Option<f64>,
    /// Conditions on other fields, if any (empty if none).
    pub also: &'static str,
    /// The unit of a field shown without one (a ratio, a residue whose
    /// unit heads its table); empty when the field shows its unit.
    pub unit: &'static str,
}

impl FieldHelp {
    const fn new(what: &'static str) -> Self {
        FieldHelp {
            what,
            min_si: None,
            max_si: None,
            also: "",
            unit: "",
        }
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
    const fn unit(mut self, unit: &'static str) -> Self {
        self.unit = unit;
        self
    }

    /// The accepted values in a field's display unit (`scale` × SI), e.g.
    /// "0 to 1000 mm", "> 0 m", "any finite number".
    pub fn range_text(&self, scale: f64, unit: &str) -> String {
        // a ratio's "unit" (`none (a ratio)`) is not written after numbers
        let u = if unit.is_empty() || unit.starts_with("none") {
            String::new()
        } else {
            format!(" {unit}")
        };
        let f = |x: f64| crate::gui::widgets::number::format_number(x * scale);
        let mut s = match (self.min_si, self.max_si) {
            (Some((lo, true)), Some(hi)) => format!("{} to {}{u}", f(lo), f(hi)),
            (Some((lo, false)), Some(hi)) => format!("> {} up to {}{u}", f(lo), f(hi)),
            (Some((lo, true)), None) => format!(">= {}{u}", f(lo)),
            (Some((lo, false)), None) => format!("> {}{u}", f(lo)),
            (None, Some(hi)) => format!("<= {}{u}", f(hi)),
            (None, None) => format!("any finite number{u}"),
        };
        if !self.also.is_empty() {
            s.push_str("; ");
            s.push_str(self.also);
        }
        s
    }

    /// The whole tooltip of field `name` shown in `unit` at `scale` × SI;
    /// `apply` says how an edit reaches the run.
    pub fn tooltip(&self, name: &str, scale: f64, unit: &str, apply: &str) -> String {
        let shown_unit = if unit.is_empty() { self.unit } else { unit };
        let range = self.range_text(scale, shown_unit);
        format!(
            "{}\nunit: {shown_unit} · accepts: {range}\n{apply} (preset field `{name}`)",
            self.what
        )
    }
}

/// The help of the numeric field named `name` (a scene path such as
/// `tyre.modes[3].damping_ratio`, or `speed_kmh`); `None` for a name not
/// known here.
pub fn help(name: &str) -> Option<FieldHelp> {
    let speed = "rolling speed of the tyre over the road (0: the road stands still)";
    Some(match crate::studies::sweep::wildcard(name).as_str() {
        "road.amplitude_m" => FieldHelp::new(
            "height of the sine road's crests above its mean line (half the crest-to-trough height)",
        )
        .min(0.0, true)
        .max(1.0),
        "road.wavelength_m" => FieldHelp::new(
            "length of one road period: crest to crest; the excitation frequency is V / λ",
        )
        .min(0.0, false),
        "speed_kmh" | "speed_mps" => FieldHelp::new(speed).min(0.0, true).max(1000.0),
        "ramp_s" => FieldHelp::new(
            "time over which the road and the preload are eased in from zero, so that the run \
             starts at rest without a shock",
        )
        .min(0.0, true)
        .also("0 only if no point starts below the road"),
        "dt_s" => FieldHelp::new(
            "solver time step: smaller is more accurate (impacts are located inside the step) \
             and slower",
        )
        .min(0.0, false)
        .max(0.1)
        .also("at most the duration"),
        "duration_s" => FieldHelp::new("simulated time of one run, from t = 0")
            .min(0.0, false)
            .also("at most 1e10 time steps"),
        "tyre.modes[*].freq_hz" => FieldHelp::new("natural frequency of this mode of the tyre")
            .min(0.0, false)
            .max(1e6),
        "tyre.modes[*].damping_ratio" => FieldHelp::new(
            "damping ratio ξ of this mode: 0 undamped, about 0.05 for a tyre, 1 critical, \
             more than 1 overdamped",
        )
        .min(0.0, true)
        .max(1e4)
        .unit("none (a ratio)"),
        "tyre.modes[*].shape[*]" => FieldHelp::new(
            "this mode's shape at this contact point (mass-normalised): the residue between \
             points i and j is shape[i] × shape[j]",
        ),
        "tyre.modes[*].residue[*][*]" => FieldHelp::new(
            "residue A[i][j] of this mode: how much a force at point j moves point i through it",
        )
        .unit("1/kg"),
        "points[*].x_m" => FieldHelp::new(
            "position of this contact point along the contact line (0: under the wheel centre)",
        )
        .also("each point at a place (x, y) of its own"),
        "points[*].y_m" => FieldHelp::new(
            "position of this contact point across the tread (0: on its centreline); the road \
             is the same profile at every y, a modal tyre's residues may differ with it",
        )
        .also(
            "each point at a place (x, y) of its own; a ring tyre's response does not depend \
             on y, so with rigid contact its points need an x each",
        ),
        "points[*].h_m" => FieldHelp::new(
            "height of the undeformed tyre at this point above the road's mean line; below 0 \
             the tyre is pressed into the road (preload)",
        )
        .min(-1.0, true)
        .max(1.0),
        "road.components[*].amplitude_m" => {
            FieldHelp::new("amplitude of this harmonic of the road (its crest height)")
        }
        "road.components[*].wavelength_m" => {
            FieldHelp::new("wavelength of this harmonic of the road").min(0.0, false)
        }
        "road.components[*].phase_rad" => {
            FieldHelp::new("phase of this harmonic of the road at x = 0")
        }
        "contact.stiffness_n_m[*]" => FieldHelp::new(
            "tread stiffness: the spring between the contact point and the road (compliant \
             contact)",
        )
        .min(0.0, false)
        .max(crate::scene::MAX_TREAD_STIFFNESS_N_M),
        "road.length_m" => {
            FieldHelp::new("length of the random road or texture along x, after which it repeats (its loop)")
                .min(0.0, false)
                .also("with at most a set number of grid points: length × highest n is capped")
        }
        "road.min_wavenumber_cpm" => FieldHelp::new(
            "lowest spatial frequency of the random road or texture: 1 / its longest wavelength",
        )
        .min(0.0, false),
        "road.max_wavenumber_cpm" => FieldHelp::new(
            "highest spatial frequency of the random road or texture: 1 / its shortest wavelength",
        )
        .min(0.0, false)
        .also("at least the lowest n"),
        "road.width_m" => FieldHelp::new(
            "width of the texture across the road, after which it repeats",
        )
        .min(0.0, false),
        "points.along" => FieldHelp::new(
            "points of the contact patch along the rolling direction, in each row (a whole number)",
        )
        .min(1.0, true)
        .max(crate::scene::MAX_POINTS as f64)
        .also("along × across at most the points' limit")
        .unit("points"),
        "points.across" => FieldHelp::new("rows of the contact patch across the tread (a whole number)")
            .min(1.0, true)
            .max(crate::scene::MAX_POINTS as f64)
            .also("along × across at most the points' limit")
            .unit("rows"),
        "points.spacing_m.0" => {
            FieldHelp::new("distance between neighbouring points along the rolling direction")
                .min(0.0, false)
        }
        "points.spacing_m.1" => {
            FieldHelp::new("distance between neighbouring rows across the tread").min(0.0, false)
        }
        "points.preload.depth_m" => FieldHelp::new(
            "how deep the undeformed tyre is pressed into the mean road plane (at the \
             footprint's centre for a parabolic one)",
        )
        .min(0.0, true)
        .max(1.0),
        "points.preload.length_m" => FieldHelp::new(
            "length of the parabolic footprint along the rolling direction; points beyond it \
             start above the road",
        )
        .min(0.0, false),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_do_not_matter() {
        assert_eq!(
            crate::studies::sweep::wildcard("tyre.modes[12].residue[0][3]"),
            "tyre.modes[*].residue[*][*]"
        );
        assert_eq!(help("tyre.modes[7].freq_hz"), help("tyre.modes[0].freq_hz"));
        assert!(help("no.such_field").is_none());
    }

    #[test]
    fn ranges_read_in_the_display_unit() {
        let a = help("road.amplitude_m").unwrap();
        assert_eq!(a.range_text(1e3, "mm"), "0 to 1000 mm");
        let dt = help("dt_s").unwrap();
        assert_eq!(
            dt.range_text(1e6, "µs"),
            "> 0 up to 100000 µs; at most the duration"
        );
        let v = help("speed_kmh").unwrap();
        assert_eq!(v.range_text(3.6, "km/h"), "0 to 3600 km/h");
        let x = help("tyre.modes[0].shape[1]").unwrap();
        assert_eq!(x.range_text(1.0, "1/√kg"), "any finite number 1/√kg");
        // a ratio has no unit after its range (it read "0 to 10000 none (a ratio)")
        let z = help("tyre.modes[0].damping_ratio").unwrap();
        assert_eq!(z.range_text(1.0, z.unit), "0 to 10000");
        assert!(
            z.tooltip("tyre.modes[0].damping_ratio", 1.0, "", "restarts the run")
                .contains("unit: none (a ratio) · accepts: 0 to 10000\n")
        );
    }
}
