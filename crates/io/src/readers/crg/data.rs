//! The data section of an OpenCRG file: the four formats read into
//! heights, placeholders, modifiers applied.

use super::*;

/// What the data section holds in the file's order: heights cross
/// section by cross section (`nv` each, the long sections sorted by `v`),
/// the slope and banking channels, and the height offset of the modifiers.
pub(super) struct Values {
    pub(super) nv: usize,
    pub(super) z_m: Vec<f32>,
    pub(super) slope: Option<Vec<f64>>,
    pub(super) bank: Option<Vec<f64>>,
    pub(super) offset_z_m: f64,
}

/// Files the values of cross section `k` (`row`: its `nch` values); `at`
/// says where the value of a channel is.
pub(super) fn file_row(
    l: &Layout,
    k: usize,
    row: &[f64],
    out: &mut Values,
    at: &dyn Fn(usize) -> CrgPlace,
) -> Result<(), CrgFault> {
    if (k + 1) * l.sections.len() > l.max_values {
        return Err(CrgFault::new(
            at(0),
            format!("cross section {}", k + 1),
            format!("more than {} values", l.max_values),
            format!("at most {} values (cut the file along u)", l.max_values),
        ));
    }
    for &(c, _) in &l.sections {
        let z = row[c];
        if z.is_finite() && z.abs() > MAX_CRG_ABS_HEIGHT_M {
            return Err(CrgFault::new(
                at(c),
                l.value_name(k, c),
                format!("{z} m"),
                format!("|z| <= {MAX_CRG_ABS_HEIGHT_M} m (a damaged file?)"),
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
                return Err(CrgFault::new(
                    at(c),
                    l.value_name(k, c),
                    x,
                    "a finite value of at most 10 m/m",
                ));
            }
            d.push(if unused && !x.is_finite() { 0.0 } else { x });
        }
    }
    Ok(())
}

pub(super) fn empty_values(l: &Layout) -> Values {
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
pub(super) fn read_binary<R: Read>(
    r: &mut R,
    l: &Layout,
    data_bytes: u64,
    data_offset: u64,
) -> Result<Values, CrgFault> {
    let w = l.format.width() as u64;
    let nch = l.nch() as u64;
    let row_bytes = nch * w;
    if !data_bytes.is_multiple_of(w) {
        return Err(CrgFault::new(
            CrgPlace::Byte(data_offset),
            "the data's length",
            format!("{data_bytes} bytes"),
            format!(
                "a whole number of {w}-byte values ({nch} channels a cross section{}); it is not: a damaged file (a line-end conversion?)",
                l.nu.map_or(String::new(), |nu| format!(
                    ", {nu} cross sections: {} bytes padded to a whole 80-byte record",
                    (nu as u64 * row_bytes).div_ceil(80) * 80
                ))
            ),
        ));
    }
    // without the end of u, as many cross sections as the data holds
    let nu = l.nu.map_or(data_bytes / row_bytes, |n| n as u64);
    let need = nu * row_bytes;
    let padded = need.div_ceil(80) * 80;
    if data_bytes < need {
        return Err(CrgFault::new(
            CrgPlace::Byte(data_offset + data_bytes),
            "the data's end",
            format!(
                "the data ends after {} whole cross sections",
                data_bytes / row_bytes
            ),
            format!("{nu} cross sections ({need} bytes)"),
        ));
    }
    if data_bytes > padded {
        return Err(CrgFault::new(
            CrgPlace::Byte(data_offset + need),
            "bytes after the last cross section",
            data_bytes - need,
            format!(
                "at most {} bytes of padding to a whole 80-byte record",
                padded - need
            ),
        ));
    }
    let mut out = empty_values(l);
    let mut buf = vec![0u8; (nch * w) as usize];
    let mut row = vec![0.0f64; nch as usize];
    for k in 0..nu as usize {
        let base = data_offset + k as u64 * nch * w;
        r.read_exact(&mut buf)
            .map_err(|e| unreadable(CrgPlace::Byte(base), e))?;
        decode(&buf, l.format, &mut row);
        file_row(l, k, &row, &mut out, &|c| {
            CrgPlace::Byte(base + c as u64 * w)
        })?;
    }
    let mut pad = Vec::new();
    r.read_to_end(&mut pad)
        .map_err(|e| unreadable(CrgPlace::Byte(data_offset + need), e))?;
    let mut tail = vec![0.0; pad.len() / w as usize];
    decode(&pad, l.format, &mut tail);
    if let Some(i) = tail.iter().position(|x| !x.is_nan()) {
        return Err(CrgFault::new(
            CrgPlace::Byte(data_offset + need + i as u64 * w),
            "padding after the last cross section",
            tail[i],
            "NaN padding",
        ));
    }
    Ok(out)
}

/// Big-endian values of `format` in `bytes` into `out`.
#[inline]
pub(super) fn decode(bytes: &[u8], format: CrgFormat, out: &mut [f64]) {
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
pub(super) fn read_text<R: BufRead>(
    r: &mut R,
    l: &Layout,
    first_line: usize,
) -> Result<Values, CrgFault> {
    let w = l.format.width();
    let per_record = 80 / w;
    let nch = l.nch();
    let mut out = empty_values(l);
    let mut row = vec![0.0f64; nch];
    let mut line_no = first_line;
    let mut buf = Vec::with_capacity(96);
    let mut next_line = |buf: &mut Vec<u8>, line_no: &mut usize| -> Result<bool, CrgFault> {
        loop {
            buf.clear();
            let n = r
                .by_ref()
                .take(MAX_HEADER_LINE as u64 + 1)
                .read_until(b'\n', buf)
                .map_err(|e| unreadable(CrgPlace::line(*line_no), e))?;
            if n == 0 {
                return Ok(false);
            }
            if n > MAX_HEADER_LINE {
                return Err(CrgFault::new(
                    CrgPlace::line(*line_no),
                    "data record",
                    format!("longer than {MAX_HEADER_LINE} bytes"),
                    "records of 80 characters",
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
                return Err(CrgFault::new(
                    CrgPlace::line(line_no),
                    format!("cross section {}", k + 1),
                    "the data ends in it",
                    format!(
                        "{} cross sections of {nch} values",
                        l.nu.map_or("whole".to_string(), |n| n.to_string())
                    ),
                ));
            }
            let here = line_no;
            lines.push(here);
            for slot in 0..per_record.min(nch - c) {
                let place = CrgPlace::column(here, slot * w + 1);
                let field = buf.get(slot * w..(slot + 1) * w).ok_or_else(|| {
                    CrgFault::new(
                        place,
                        l.value_name(k, c),
                        "the record ends",
                        format!("{} values of {w} characters", per_record.min(nch - c)),
                    )
                })?;
                row[c] = parse_field(field).ok_or_else(|| {
                    let text: String = field.iter().map(|&b| b as char).collect();
                    CrgFault::new(
                        place,
                        l.value_name(k, c),
                        format!("`{text}`"),
                        format!("a number of {w} characters or a placeholder starting with `*`"),
                    )
                })?;
                c += 1;
            }
            line_no += 1;
        }
        let at = |ch: usize| {
            let rec = ch / per_record;
            CrgPlace::column(
                lines.get(rec).copied().unwrap_or(0),
                (ch % per_record) * w + 1,
            )
        };
        file_row(l, k, &row, &mut out, &at)?;
    }
    if next_line(&mut buf, &mut line_no)? {
        return Err(CrgFault::new(
            CrgPlace::line(line_no),
            "data record",
            format!(
                "a record after the {} cross sections from reference_line_start_u to reference_line_end_u",
                l.nu.unwrap_or(0)
            ),
            "the end of the file",
        ));
    }
    Ok(out)
}

/// The number a header value starts with (the standard's readers take
/// the longest leading number: `2.000000000+e00` is 2).
pub(super) fn leading_number(text: &str) -> Option<f64> {
    let end = text
        .find(|c: char| !(c.is_ascii_digit() || matches!(c, '+' | '-' | '.' | 'e' | 'E')))
        .unwrap_or(text.len());
    (1..=end).rev().find_map(|n| text[..n].parse::<f64>().ok())
}

/// One formatted value: a number (Fortran `D` exponents allowed), or NaN
/// for a placeholder starting with `*` (`**unused**` included); `None`
/// for anything else.
pub(super) fn parse_field(field: &[u8]) -> Option<f64> {
    let text: String = field.iter().map(|&b| b as char).collect();
    let t = text.trim();
    if t.starts_with('*') {
        return Some(f64::NAN);
    }
    let s = t.replace(['d', 'D'], "e");
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() || x.is_nan() => Some(x),
        _ => None,
    }
}

/// A read that failed at `place`.
pub(super) fn unreadable(place: CrgPlace, e: std::io::Error) -> CrgFault {
    CrgFault::new(
        place,
        "the file",
        format!("cannot read: {e}"),
        "a readable file",
    )
}

/// Applies the `$ROAD_CRG_MODS` that change heights; refuses those that
/// would change the grid's geometry or a height reference not applied.
pub(super) fn apply_mods(h: &Header, v: &mut Values) -> Result<(), CrgFault> {
    let mut nan_mode = None;
    let mut nan_offset = 0.0;
    for (key, value, line) in &h.mods {
        let (key, value, line) = (key.as_str(), *value, *line);
        let modifier = |expected: &str| {
            CrgFault::new(
                CrgPlace::line(line),
                format!("modifier {key}"),
                value,
                expected,
            )
        };
        if !value.is_finite() {
            return Err(modifier("a finite number"));
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
                    return Err(modifier(
                        "a slope channel or no such modifier (the slope is constant)",
                    ));
                }
            }
            "scale_banking" => {
                if let Some(b) = v.bank.as_mut() {
                    b.iter_mut().for_each(|x| *x *= value);
                } else if value != 1.0 {
                    return Err(modifier(
                        "a banking channel or no such modifier (the banking is constant)",
                    ));
                }
            }
            "refline_offset_z" => v.offset_z_m += value,
            "grid_nan_mode" => nan_mode = Some((value, line)),
            "grid_nan_offset" => nan_offset = value,
            "scale_length" | "scale_width" | "refpoint_z" => {
                return Err(modifier(
                    "a file without it (it changes the grid or its height reference; not applied here)",
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
                return Err(CrgFault::new(
                    CrgPlace::line(line),
                    "modifier grid_nan_mode",
                    mode,
                    "0 (keep), 1 (set to the offset) or 2 (keep the last value)",
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
pub(super) fn keep_last(v: &mut Values, offset: f64) {
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
