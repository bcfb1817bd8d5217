//! The figures' font, adjusted for plotters' text drawing.
//!
//! plotters 0.3.7 (its `ab_glyph` backend) draws each glyph's ink from the
//! pen position, dropping the glyph's left side bearing: a narrow glyph
//! with a wide bearing (a tabular `1`) is drawn at the left of its cell and
//! the gap after it doubles ("1 0" for "10", "alph a" for "alpha"). It
//! places the ink relative to the outline's bounding box, so a glyph whose
//! outline reaches x = 0 is drawn where it belongs. [`with_origin_points`]
//! gives every simple glyph of a TrueType font one more contour: a single
//! point at x = 0, on its lowest y (no ink, no change of height), so that
//! its bounding box starts at the origin. Advances, kerning and every other
//! table are kept; hinting instructions are dropped (ab_glyph does not
//! hint).

/// Reads a big-endian u16 at `at`.
fn u16_at(d: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_be_bytes(d.get(at..at + 2)?.try_into().ok()?))
}

fn u32_at(d: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_be_bytes(d.get(at..at + 4)?.try_into().ok()?))
}

fn i16_at(d: &[u8], at: usize) -> Option<i16> {
    u16_at(d, at).map(|v| v as i16)
}

/// A simple glyph with one more contour, a single on-curve point at
/// `(0, y_min)`, and no instructions; `None` if it is not a well-formed
/// simple glyph or already reaches x = 0.
fn add_origin_point(g: &[u8]) -> Option<Vec<u8>> {
    let contours = i16_at(g, 0)?;
    let (x_min, y_min) = (i16_at(g, 2)?, i16_at(g, 4)?);
    if contours <= 0 || x_min <= 0 {
        return None;
    }
    let n = contours as usize;
    let ends_at = 10;
    let points = usize::from(u16_at(g, ends_at + 2 * (n - 1))?) + 1;
    let ins_len = usize::from(u16_at(g, ends_at + 2 * n)?);
    let flags_at = ends_at + 2 * n + 2 + ins_len;
    // the flags, expanded, and where they end
    let mut flags = Vec::with_capacity(points);
    let mut at = flags_at;
    while flags.len() < points {
        let f = *g.get(at)?;
        at += 1;
        let repeat = if f & 0x08 != 0 {
            at += 1;
            usize::from(*g.get(at - 1)?)
        } else {
            0
        };
        for _ in 0..=repeat {
            flags.push(f);
        }
    }
    flags.truncate(points);
    let flags_end = at;
    // coordinate deltas: the last point's absolute x and y, where x and y end
    let read = |at: &mut usize, short: u8, same: u8| -> Option<i32> {
        let mut sum = 0i32;
        for &f in &flags {
            if f & short != 0 {
                let v = i32::from(*g.get(*at)?);
                *at += 1;
                sum += if f & same != 0 { v } else { -v };
            } else if f & same == 0 {
                sum += i32::from(i16_at(g, *at)?);
                *at += 2;
            }
        }
        Some(sum)
    };
    let mut at = flags_end;
    let last_x = read(&mut at, 0x02, 0x10)?;
    let x_end = at;
    let last_y = read(&mut at, 0x04, 0x20)?;
    let y_end = at;
    let dx = i16::try_from(-last_x).ok()?;
    let dy = i16::try_from(i32::from(y_min) - last_y).ok()?;
    let mut out = Vec::with_capacity(y_end + 16);
    out.extend_from_slice(&(contours + 1).to_be_bytes());
    out.extend_from_slice(&0i16.to_be_bytes());
    out.extend_from_slice(&g[4..10]);
    out.extend_from_slice(&g[ends_at..ends_at + 2 * n]);
    out.extend_from_slice(&u16::try_from(points).ok()?.to_be_bytes());
    out.extend_from_slice(&0u16.to_be_bytes());
    out.extend_from_slice(&g[flags_at..flags_end]);
    out.push(0x01); // on curve, x and y as 16-bit deltas
    out.extend_from_slice(&g[flags_end..x_end]);
    out.extend_from_slice(&dx.to_be_bytes());
    out.extend_from_slice(&g[x_end..y_end]);
    out.extend_from_slice(&dy.to_be_bytes());
    Some(out)
}

/// The TrueType font `ttf` with a point at x = 0 in every simple glyph that
/// starts right of it (see the module's note), its `loca` table in the long
/// format; `None` if the font is not one this can read (then use it as is).
pub fn with_origin_points(ttf: &[u8]) -> Option<Vec<u8>> {
    let num_tables = usize::from(u16_at(ttf, 4)?);
    let mut tables: Vec<([u8; 4], Vec<u8>)> = Vec::with_capacity(num_tables);
    for i in 0..num_tables {
        let rec = 12 + 16 * i;
        let tag: [u8; 4] = ttf.get(rec..rec + 4)?.try_into().ok()?;
        let off = u32_at(ttf, rec + 8)? as usize;
        let len = u32_at(ttf, rec + 12)? as usize;
        tables.push((tag, ttf.get(off..off.checked_add(len)?)?.to_vec()));
    }
    let find = |tag: &[u8; 4]| tables.iter().position(|t| &t.0 == tag);
    let (head, loca, glyf, maxp) = (
        find(b"head")?,
        find(b"loca")?,
        find(b"glyf")?,
        find(b"maxp")?,
    );
    let long = i16_at(&tables[head].1, 50)? == 1;
    let glyphs = usize::from(u16_at(&tables[maxp].1, 4)?);
    let offset = |k: usize| -> Option<usize> {
        if long {
            u32_at(&tables[loca].1, 4 * k).map(|v| v as usize)
        } else {
            u16_at(&tables[loca].1, 2 * k).map(|v| 2 * usize::from(v))
        }
    };
    let mut new_glyf = Vec::with_capacity(tables[glyf].1.len() + 16 * glyphs);
    let mut new_loca = Vec::with_capacity(4 * (glyphs + 1));
    for k in 0..glyphs {
        let (a, b) = (offset(k)?, offset(k + 1)?);
        let g = tables[glyf].1.get(a..b)?;
        new_loca.extend_from_slice(&u32::try_from(new_glyf.len()).ok()?.to_be_bytes());
        match add_origin_point(g) {
            Some(p) => new_glyf.extend_from_slice(&p),
            None => new_glyf.extend_from_slice(g),
        }
        while new_glyf.len() % 4 != 0 {
            new_glyf.push(0);
        }
    }
    new_loca.extend_from_slice(&u32::try_from(new_glyf.len()).ok()?.to_be_bytes());
    tables[glyf].1 = new_glyf;
    tables[loca].1 = new_loca;
    tables[head]
        .1
        .get_mut(50..52)?
        .copy_from_slice(&1i16.to_be_bytes());
    // the same directory, the tables one after the other, 4-byte aligned
    // (checksums are not recomputed: the font is only read by ttf-parser)
    let mut out = ttf.get(..12 + 16 * num_tables)?.to_vec();
    for (i, (_, data)) in tables.iter().enumerate() {
        let rec = 12 + 16 * i;
        let off = u32::try_from(out.len()).ok()?;
        let len = u32::try_from(data.len()).ok()?;
        out[rec + 8..rec + 12].copy_from_slice(&off.to_be_bytes());
        out[rec + 12..rec + 16].copy_from_slice(&len.to_be_bytes());
        out.extend_from_slice(data);
        while out.len() % 4 != 0 {
            out.push(0);
        }
    }
    Some(out)
}
