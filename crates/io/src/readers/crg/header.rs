//! The header of an OpenCRG file: its blocks, keys and channels, and the
//! layout of the data they define.

use super::*;

/// One channel of the data, in the order of `D:` lines.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Channel {
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
pub(super) struct Header {
    pub(super) keys: std::collections::HashMap<String, (f64, usize)>,
    pub(super) mods: Vec<(String, f64, usize)>,
    pub(super) format: Option<(CrgFormat, usize)>,
    pub(super) channels: Vec<(Channel, usize)>,
}

#[derive(Clone, Copy, PartialEq)]
pub(super) enum Block {
    None,
    Comment,
    Road,
    Def,
    Opts,
    Mods,
}

/// Reads one line (without its end) of at most [`MAX_HEADER_LINE`]
/// bytes; `None` at the end of the file.
pub(super) fn header_line<R: BufRead>(
    r: &mut R,
    line: usize,
) -> Result<Option<(String, usize)>, CrgFault> {
    let mut buf = Vec::new();
    let n = r
        .by_ref()
        .take(MAX_HEADER_LINE as u64 + 1)
        .read_until(b'\n', &mut buf)
        .map_err(|e| unreadable(CrgPlace::line(line), e))?;
    if n == 0 {
        return Ok(None);
    }
    if buf.last() != Some(&b'\n') && n > MAX_HEADER_LINE {
        return Err(CrgFault::new(
            CrgPlace::line(line),
            "header line",
            format!("longer than {MAX_HEADER_LINE} bytes"),
            "header lines of an OpenCRG file",
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
pub(super) fn read_header<R: BufRead>(r: &mut R) -> Result<(Header, usize, u64), CrgFault> {
    let mut h = Header::default();
    let mut block = Block::None;
    let mut offset = 0u64;
    for line in 1usize.. {
        let Some((text, n)) = header_line(r, line)? else {
            return Err(CrgFault::new(
                CrgPlace::line(line - 1),
                "the file",
                format!("ends at line {}", line - 1),
                "the data after a `$$$$` line",
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
                    return Err(CrgFault::new(
                        CrgPlace::line(line),
                        "block `$ROAD_CRG_FILE` (data in other files)",
                        "",
                        "one self-contained OpenCRG file",
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
                        return Err(CrgFault::new(
                            CrgPlace::line(line),
                            "a line of block $ROAD_CRG",
                            format!("`{body}`"),
                            "`key = value` in block $ROAD_CRG",
                        ));
                    }
                    continue;
                };
                let key = key.trim().to_ascii_lowercase();
                let value_text = value.trim();
                let value = leading_number(value_text).ok_or_else(|| {
                    CrgFault::new(
                        CrgPlace::line(line),
                        key.as_str(),
                        format!("`{value_text}`"),
                        "a number",
                    )
                })?;
                match block {
                    Block::Road => {
                        if !value.is_finite() {
                            return Err(CrgFault::new(
                                CrgPlace::line(line),
                                key,
                                value_text,
                                "a finite number",
                            ));
                        }
                        h.keys.insert(key, (value, line));
                    }
                    Block::Opts => {
                        if key == "border_smooth_ubeg" || key == "border_smooth_uend" {
                            return Err(CrgFault::new(
                                CrgPlace::line(line),
                                format!("option {key}"),
                                format!(
                                    "{value_text} (heights faded towards the reference line at the ends)"
                                ),
                                "a file without it (not applied here)",
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
                            return Err(CrgFault::new(
                                CrgPlace::line(line),
                                "data format",
                                format!("`#:{name}`"),
                                "#:LRFI, #:LDFI, #:KRBI or #:KDBI",
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
pub(super) fn channel(d: &str, line: usize) -> Result<Channel, CrgFault> {
    let (name, unit) = d.split_once(',').unwrap_or((d, ""));
    let name = name.trim().to_ascii_lowercase();
    let unit = unit
        .split(',')
        .next()
        .unwrap_or("")
        .trim()
        .to_ascii_lowercase();
    let at = CrgPlace::line(line);
    let want_unit = |want: &str| {
        if unit == want {
            Ok(())
        } else {
            Err(CrgFault::new(
                at,
                format!("the unit of channel `{name}`"),
                format!("`{unit}`"),
                format!("the unit `{want}`"),
            ))
        }
    };
    if let Some(rest) = name.strip_prefix("long section") {
        want_unit("m")?;
        let rest = rest.trim();
        if let Some(at_v) = rest.strip_prefix("at v") {
            let v_text = at_v.trim().trim_start_matches('=').trim();
            let position = |expected: &str| {
                CrgFault::new(
                    at,
                    "the v of a long section",
                    format!("`{v_text}`"),
                    expected,
                )
            };
            let v: f64 = v_text.parse().map_err(|_| position("a position in m"))?;
            if !v.is_finite() {
                return Err(position("a finite position"));
            }
            return Ok(Channel::Section {
                v_m: Some(v),
                number: 0.0,
            });
        }
        let number: f64 = rest.parse().map_err(|_| {
            CrgFault::new(
                at,
                "channel",
                format!("`long section {rest}`"),
                "`long section N` or `long section at v = …`",
            )
        })?;
        return Ok(Channel::Section { v_m: None, number });
    }
    if let Some(what) = name.strip_prefix("reference line") {
        return match what.trim() {
            "slope" => want_unit("m/m").map(|_| Channel::Slope),
            "banking" => want_unit("m/m").map(|_| Channel::Bank),
            "phi" | "x" | "y" => Ok(Channel::Aside),
            other => Err(CrgFault::new(
                at,
                "channel",
                format!("`reference line {other}`"),
                "slope, banking, phi, x or y (cross sections evenly spaced by reference_line_increment)",
            )),
        };
    }
    Err(CrgFault::new(
        at,
        "channel",
        format!("`{name}`"),
        "`long section …` or `reference line …`",
    ))
}

/// The data's shape, from the header.
pub(super) struct Layout {
    pub(super) format: CrgFormat,
    /// Number of cross sections, when the header gives the end of `u`
    /// (else as many as the data holds).
    pub(super) nu: Option<usize>,
    pub(super) u_first_m: f64,
    pub(super) u_inc_m: f64,
    pub(super) channels: Vec<Channel>,
    /// Index of each long section's channel, sorted by `v`, and its `v`.
    pub(super) sections: Vec<(usize, f64)>,
    pub(super) slope: Option<usize>,
    pub(super) bank: Option<usize>,
    pub(super) max_values: usize,
    pub(super) start_s: f64,
    pub(super) start_b: f64,
    pub(super) start_z: f64,
    pub(super) end_z: Option<f64>,
}

impl Layout {
    pub(super) fn of(h: &Header, max_values: usize) -> Result<Self, CrgFault> {
        let key = |k: &str| h.keys.get(k).copied();
        let need = |k: &str| {
            key(k)
                .map(|(v, _)| v)
                .ok_or_else(|| CrgFault::new(CrgPlace::Header, k, "", "a value in block $ROAD_CRG"))
        };
        let (format, _) = h.format.ok_or_else(|| {
            CrgFault::new(
                CrgPlace::Header,
                "data format (block $KD_DEFINITION)",
                "",
                "#:LRFI, #:LDFI, #:KRBI or #:KDBI",
            )
        })?;
        let u0 = key("reference_line_start_u").map_or(0.0, |k| k.0);
        let du = need("reference_line_increment")?;
        let line_of = |k: &str| key(k).map_or(CrgPlace::Header, |(_, l)| CrgPlace::line(l));
        if du.is_nan() || du <= 0.0 {
            return Err(CrgFault::new(
                line_of("reference_line_increment"),
                "reference_line_increment",
                du,
                "an increment > 0 m",
            ));
        }
        let nu = match key("reference_line_end_u") {
            Some((u1, line)) => {
                let steps = (u1 - u0) / du;
                let n = steps.round();
                if n.is_nan() || n < 1.0 || (steps - n).abs() > 1e-6 * n.max(1.0) || n > 1e12 {
                    return Err(CrgFault::new(
                        CrgPlace::line(line),
                        "reference_line_end_u",
                        u1,
                        format!(
                            "reference_line_start_u = {u0} plus a whole number (>= 1) of increments {du} m"
                        ),
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
                        return Err(CrgFault::new(
                            CrgPlace::line(line),
                            "channel",
                            format!("long section {number}"),
                            format!("long section {by_number} (numbered in order from 1)"),
                        ));
                    }
                    sections.push((k, f64::NAN));
                }
                Channel::Slope if slope.is_none() => slope = Some(k),
                Channel::Bank if bank.is_none() => bank = Some(k),
                Channel::Slope | Channel::Bank => {
                    return Err(CrgFault::new(
                        CrgPlace::line(line),
                        "channel",
                        "a second reference line slope or banking channel",
                        "at most one of each",
                    ));
                }
                Channel::Aside => {}
            }
        }
        if by_v > 0 && by_number > 0 {
            return Err(CrgFault::new(
                CrgPlace::Header,
                "long sections",
                "both numbered and at explicit v",
                "one way for all",
            ));
        }
        if sections.len() < 2 {
            return Err(CrgFault::new(
                CrgPlace::Header,
                "long sections",
                sections.len(),
                "at least two `D:long section …` channels",
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
                return Err(CrgFault::new(
                    line_of("long_section_v_increment"),
                    "long_section_v_increment",
                    dv,
                    "an increment > 0 m",
                ));
            }
            if let Some((left, l)) = key("long_section_v_left") {
                let last = right + (sections.len() - 1) as f64 * dv;
                if (last - left).abs() > 1e-6 * dv.max(1.0) + 1e-9 {
                    return Err(CrgFault::new(
                        CrgPlace::line(l),
                        "long_section_v_left",
                        left,
                        format!(
                            "long_section_v_right + ({} - 1) × {dv} = {last} ({} numbered long sections)",
                            sections.len(),
                            sections.len()
                        ),
                    ));
                }
            }
            for (j, s) in sections.iter_mut().enumerate() {
                s.1 = right + j as f64 * dv;
            }
        } else {
            sections.sort_by(|a, b| a.1.total_cmp(&b.1));
            if let Some(w) = sections.windows(2).find(|w| w[1].1 - w[0].1 < 1e-6) {
                let line = h.channels[w[1].0].1;
                return Err(CrgFault::new(
                    CrgPlace::line(line),
                    "long section",
                    format!("at v = {} m beside one at v = {} m", w[1].1, w[0].1),
                    "positions at least 1e-6 m apart",
                ));
            }
        }
        if let Some(nu) = nu {
            let values = (nu as u128) * (sections.len() as u128);
            if values > max_values as u128 {
                return Err(CrgFault::new(
                    CrgPlace::Header,
                    "the grid's size",
                    format!(
                        "{nu} cross sections × {} long sections = {values} values",
                        sections.len()
                    ),
                    format!("at most {max_values} (cut the file along u)"),
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

    pub(super) fn nch(&self) -> usize {
        self.channels.len()
    }

    /// The name of the value of channel `c` in cross section `k`: the
    /// cross section and the channel as the file defines it.
    pub(super) fn value_name(&self, k: usize, c: usize) -> String {
        let channel = match self.channels.get(c) {
            Some(Channel::Section { v_m: Some(v), .. }) => format!("long section at v = {v} m"),
            Some(Channel::Section { v_m: None, number }) => format!("long section {number}"),
            Some(Channel::Slope) => "reference line slope".into(),
            Some(Channel::Bank) => "reference line banking".into(),
            Some(Channel::Aside) | None => format!("channel {}", c + 1),
        };
        format!("cross section {}, {channel}", k + 1)
    }

    /// The heights and reference channels from the values (cross section
    /// by cross section, `nch` each).
    pub(super) fn road(&self, v: Values) -> Result<CrgRoad, CrgFault> {
        let nv = self.sections.len();
        let nu = v.z_m.len() / nv;
        if nu < 2 {
            return Err(CrgFault::new(
                CrgPlace::Grid,
                "cross sections",
                nu,
                "at least two",
            ));
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
            return Err(CrgFault::new(
                CrgPlace::Grid,
                format!(
                    "reference line height at cross section {} (u = {} m)",
                    k + 1,
                    self.u_first_m + k as f64 * self.u_inc_m
                ),
                ref_z[k],
                "a finite height (finite slopes)",
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
