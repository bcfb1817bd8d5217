//! What each numeric field of the editing panel means and which values the
//! scene accepts, for its tooltip: someone who has never seen the app learns
//! on hover what "ramp" is, in which unit it is typed and what may be typed,
//! before typing something that is refused. The words and bounds are the
//! scene format's table of fields (`scene::fields`), the bounds those
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
/// `tyre.modes[3].damping_ratio`, or `speed_kmh`): the scene format's
/// entry ([`crate::scene::fields::FIELDS`]); `None` for a name not known.
pub fn help(name: &str) -> Option<FieldHelp> {
    // the editor types the speed in km/h; its field is the speed's
    let path = if name.trim() == "speed_kmh" {
        "speed_mps"
    } else {
        name
    };
    let f = crate::scene::fields::field(path)?;
    // the unit of a field whose editor shows none beside it: a ratio, a
    // residue (its unit heads its table), a count
    let unit = match f.unit {
        "-" => "none (a ratio)",
        "" => f.shown.1,
        u if f.path.ends_with("residue[*][*]") => u,
        _ => "",
    };
    Some(FieldHelp {
        what: f.what,
        min_si: f.min_si,
        max_si: f.max_si,
        also: f.also,
        unit,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_do_not_matter() {
        assert_eq!(
            crate::scene::fields::wildcard("tyre.modes[12].residue[0][3]"),
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
