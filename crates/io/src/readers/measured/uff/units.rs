//! Units: dataset 164 (the file's factors), units labels read into a
//! dimension and a factor to SI, and a record's factor to SI.

use super::scan::{field, int, number};
use super::{ParseError, Record58, Units164, dof};

/// Dataset 164 from its records.
pub(crate) fn units164(
    lines: &[&str],
    record: usize,
    first: usize,
) -> Result<Units164, ParseError> {
    let at = format!("record {record} (dataset 164, line {first}): ");
    if lines.len() < 2 {
        return Err((
            at,
            format!(
                "{} lines: expected the units code and the three factors (truncated?)",
                lines.len()
            ),
        ));
    }
    let code = int(lines[0], 0, 10, "units code", &at)?;
    let description = field(lines[0], 10, 30);
    let f: Vec<f64> = lines[1].split_whitespace().filter_map(number).collect();
    if f.len() < 3 || f[..3].iter().any(|v| !v.is_finite() || *v <= 0.0) {
        return Err((
            at,
            format!(
                "factors `{}`: expected three positive numbers (length, force, temperature)",
                lines[1].trim()
            ),
        ));
    }
    Ok(Units164 {
        record,
        code,
        description,
        length: f[0],
        force: f[1],
        temperature: f[2],
    })
}

/// Length (L), time (T) and force (F) exponents and the factor to SI.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Dim {
    l: i32,
    t: i32,
    f: i32,
    to_si: f64,
}

/// The factor to SI of a units label and its dimension, `None` when the
/// label is blank or `NONE`.
fn units_label(label: &str) -> Option<Result<Dim, String>> {
    let s: String = label
        .chars()
        .filter(|c| !c.is_whitespace() && *c != '(' && *c != ')')
        .collect::<String>()
        .replace('²', "^2")
        .replace('³', "^3")
        .replace("**", "^");
    if s.is_empty() || s.eq_ignore_ascii_case("none") || s == "-" {
        return None;
    }
    let mut d = Dim {
        l: 0,
        t: 0,
        f: 0,
        to_si: 1.0,
    };
    // `a/b*c` read left to right: `(a/b)·c`
    let mut toks = Vec::new();
    let mut sign = 1;
    let mut cur = String::new();
    for ch in s.chars() {
        if ch == '/' || ch == '*' {
            toks.push((sign, std::mem::take(&mut cur)));
            sign = if ch == '/' { -1 } else { 1 };
        } else {
            cur.push(ch);
        }
    }
    toks.push((sign, cur));
    for (k, (sign, tok)) in toks.iter().enumerate() {
        let (sign, tok) = (*sign, tok.as_str());
        let (base, exp) = match tok.split_once('^') {
            Some((b, e)) => (b, e.parse::<i32>().ok()),
            None => {
                // `s2`, `m2`: trailing digit as exponent
                let digits = tok.trim_start_matches(|c: char| !c.is_ascii_digit());
                if !digits.is_empty() && digits.len() < tok.len() {
                    (&tok[..tok.len() - digits.len()], digits.parse().ok())
                } else {
                    (tok, Some(1))
                }
            }
        };
        let Some(exp) = exp else {
            return Some(Err(format!("`{label}`: exponent of `{tok}` not read")));
        };
        let (l, t, f, factor) = match base {
            "m" => (1, 0, 0, 1.0),
            "mm" => (1, 0, 0, 1e-3),
            "cm" => (1, 0, 0, 1e-2),
            "um" | "µm" | "μm" | "micron" => (1, 0, 0, 1e-6),
            "in" | "inch" => (1, 0, 0, 0.0254),
            "ft" => (1, 0, 0, 0.3048),
            "s" | "sec" => (0, 1, 0, 1.0),
            "ms" => (0, 1, 0, 1e-3),
            "N" => (0, 0, 1, 1.0),
            "kN" => (0, 0, 1, 1e3),
            "lbf" | "lb" => (0, 0, 1, 4.448_221_615_260_5),
            "g" | "G" => (1, -2, 0, 9.806_65),
            "" | "1" if k == 0 => (0, 0, 0, 1.0), // `1/s`
            _ => {
                return Some(Err(format!(
                    "`{label}`: unit `{base}` not known (m, mm, cm, µm, in, ft, s, ms, N, kN, lbf, g)"
                )));
            }
        };
        let e = sign * exp;
        d.l += l * e;
        d.t += t * e;
        d.f += f * e;
        d.to_si *= f64::powi(factor, e);
    }
    Some(Ok(d))
}

/// The dimension of a specific data type (records 9, 10).
fn data_dim(specific: i64) -> Option<(i32, i32, i32, &'static str)> {
    match specific {
        8 => Some((1, 0, 0, "displacement")),
        11 => Some((1, -1, 0, "velocity")),
        12 => Some((1, -2, 0, "acceleration")),
        9 | 13 => Some((0, 0, 1, "force")),
        _ => None,
    }
}

impl Record58 {
    /// Where messages place it.
    pub fn at(&self) -> String {
        format!(
            "record {} (dataset 58{}, line {}), {} / {}: ",
            self.record,
            if self.binary { "b" } else { "" },
            self.line,
            dof(self.response_node, self.response_direction),
            dof(self.reference_node, self.reference_direction)
        )
    }

    /// The response of the numerator: 8 displacement, 11 velocity, 12
    /// acceleration, from its specific data type (record 9) or — a general
    /// type (0 unknown, 1 general) — from its units label's dimension
    /// (`m/s^2`, or the whole ratio `(1/N)*(m/s²)`); `None` when neither
    /// says.
    pub fn response_kind(&self) -> Option<i64> {
        if matches!(self.numerator, 8 | 11 | 12) {
            return Some(self.numerator);
        }
        if !matches!(self.numerator, 0 | 1) {
            return None;
        }
        let Some(Ok(d)) = units_label(&self.numerator_units) else {
            return None;
        };
        match (d.l, d.t, d.f) {
            (1, 0, 0 | -1) => Some(8),
            (1, -1, 0 | -1) => Some(11),
            (1, -2, 0 | -1) => Some(12),
            _ => None,
        }
    }

    /// The factor that makes its values SI (numerator over denominator)
    /// and how it was found: the units labels when set, else dataset 164
    /// (`units`), else 1.
    pub fn si_factor(&self, units: Option<&Units164>) -> Result<(f64, String), ParseError> {
        let mut factor = 1.0;
        let mut how = Vec::new();
        for (specific, label, what) in [
            (
                self.response_kind().unwrap_or(self.numerator),
                &self.numerator_units,
                "numerator",
            ),
            (self.denominator, &self.denominator_units, "denominator"),
        ] {
            let zero_force = what == "denominator" && specific == 0;
            let Some((l, t, f, name)) =
                data_dim(specific).or(zero_force.then_some((0, 0, 1, "force")))
            else {
                continue;
            };
            let sign = if what == "numerator" { 1 } else { -1 };
            let to_si = match units_label(label) {
                Some(Ok(d)) if what == "numerator" && (d.l, d.t, d.f) == (l, t, f - 1) => {
                    // the whole ratio in the numerator's label
                    how.push(format!("{what} `{label}` (over force)"));
                    factor *= d.to_si;
                    break;
                }
                Some(Ok(d)) => {
                    if (d.l, d.t, d.f) != (l, t, f) {
                        return Err((
                            self.at(),
                            format!(
                                "{what} units `{label}` for {name} (specific data type {specific}): expected units of {name}"
                            ),
                        ));
                    }
                    how.push(format!("{what} `{label}`"));
                    d.to_si
                }
                Some(Err(m)) => {
                    return Err((
                        self.at(),
                        format!("{what} units {m}: expected a units label that can be read"),
                    ));
                }
                None => match units {
                    Some(u) => {
                        how.push(format!("{what} by dataset 164 ({})", u.description));
                        if f == 1 {
                            1.0 / u.force
                        } else {
                            1.0 / u.length
                        }
                    }
                    None => 1.0,
                },
            };
            factor *= if sign > 0 { to_si } else { 1.0 / to_si };
        }
        let how = if how.is_empty() {
            "no units labels nor dataset 164: taken as SI".to_string()
        } else {
            how.join(", ")
        };
        Ok((factor, how))
    }
}
