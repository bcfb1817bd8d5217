//! The bitmap backend of the figures. On the desktop plotters' own
//! [`BitMapBackend`]; in a browser [`GlyphBitmap`], the same backend with
//! its text drawn here: plotters' text on wasm32 is measured by the page and
//! cannot be drawn into a bitmap (its font panics there), so a figure's PNG
//! for a download would have had no text, or no figure.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};
use plotters::backend::BitMapBackend;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind,
};
use std::sync::OnceLock;

/// The backend the figures draw on.
#[cfg(not(target_arch = "wasm32"))]
pub type FigureBackend<'a> = BitMapBackend<'a>;
/// The backend the figures draw on.
#[cfg(target_arch = "wasm32")]
pub type FigureBackend<'a> = GlyphBitmap<'a>;

/// The figures' font (egui's Ubuntu Light, embedded).
fn font() -> &'static FontRef<'static> {
    static FONT: OnceLock<FontRef<'static>> = OnceLock::new();
    FONT.get_or_init(|| {
        // the embedded font is valid TrueType
        FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT)
            .expect("the embedded Ubuntu Light font reads")
    })
}

/// Width (px) of `text` at `size_px` and its line height (`size / 1.24`,
/// plotters' layout box).
pub fn text_box(text: &str, size_px: f64) -> (i32, i32) {
    let f = font().as_scaled(PxScale::from(size_px as f32));
    let mut w = 0.0f32;
    let mut prev = None;
    for c in text.chars() {
        let g = f.glyph_id(c);
        if let Some(p) = prev {
            w += f.kern(p, g);
        }
        w += f.h_advance(g);
        prev = Some(g);
    }
    (w.ceil() as i32, (size_px / 1.24).round() as i32)
}

/// [`BitMapBackend`] with text rasterised from the embedded font.
pub struct GlyphBitmap<'a> {
    inner: BitMapBackend<'a>,
}

impl<'a> GlyphBitmap<'a> {
    /// Draws into `rgb` (`w × h` pixels, 3 bytes each, rows top to bottom).
    pub fn with_buffer(rgb: &'a mut [u8], (w, h): (u32, u32)) -> Self {
        GlyphBitmap {
            inner: BitMapBackend::with_buffer(rgb, (w, h)),
        }
    }
}

type Error<'a> = DrawingErrorKind<<BitMapBackend<'a> as DrawingBackend>::ErrorType>;

impl<'a> DrawingBackend for GlyphBitmap<'a> {
    type ErrorType = <BitMapBackend<'a> as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.inner.get_size()
    }
    fn ensure_prepared(&mut self) -> Result<(), Error<'a>> {
        self.inner.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), Error<'a>> {
        self.inner.present()
    }
    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> Result<(), Error<'a>> {
        self.inner.draw_pixel(point, color)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), Error<'a>> {
        self.inner.draw_line(from, to, style)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), Error<'a>> {
        self.inner.draw_rect(upper_left, bottom_right, style, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), Error<'a>> {
        self.inner.draw_path(path, style)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), Error<'a>> {
        self.inner.draw_circle(center, radius, style, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), Error<'a>> {
        self.inner.fill_polygon(vert, style)
    }
    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Result<(), Error<'a>> {
        self.inner.blit_bitmap(pos, size, src)
    }

    fn estimate_text_size<TStyle: BackendTextStyle>(
        &self,
        text: &str,
        style: &TStyle,
    ) -> Result<(u32, u32), Error<'a>> {
        let (w, h) = text_box(text, style.size());
        Ok((w.max(0) as u32, h.max(0) as u32))
    }

    /// The text's glyphs, anchored and rotated as plotters' default does,
    /// each pixel's coverage blended into the bitmap.
    fn draw_text<TStyle: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &TStyle,
        pos: BackendCoord,
    ) -> Result<(), Error<'a>> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let size = style.size();
        let (width, height) = text_box(text, size);
        let dx = match style.anchor().h_pos {
            HPos::Left => 0,
            HPos::Right => -width,
            HPos::Center => -width / 2,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0,
            VPos::Center => -height / 2,
            VPos::Bottom => -height,
        };
        let trans = style.transform();
        let (w, h) = self.get_size();
        let f = font().as_scaled(PxScale::from(size as f32));
        // the baseline where the box's height ends less the descent
        // (plotters' box is `size / 1.24` high)
        let baseline = f64::from(height) + f64::from(f.descent()) * 0.6;
        let mut pen = 0.0f32;
        let mut prev = None;
        for c in text.chars() {
            let id = f.glyph_id(c);
            if let Some(p) = prev {
                pen += f.kern(p, id);
            }
            prev = Some(id);
            let glyph = id.with_scale_and_position(f.scale(), point(pen, baseline as f32));
            pen += f.h_advance(id);
            let Some(outline) = font().outline_glyph(glyph) else {
                continue;
            };
            let b = outline.px_bounds();
            let mut pixels = Vec::new();
            outline.draw(|x, y, cover| pixels.push((x, y, cover)));
            for (x, y, cover) in pixels {
                if cover <= 0.0 {
                    continue;
                }
                let (gx, gy) = (b.min.x as i32 + x as i32, b.min.y as i32 + y as i32);
                let (tx, ty) = trans.transform(gx + dx, gy + dy);
                let (px, py) = (pos.0 + tx, pos.1 + ty);
                if px >= 0 && px < w as i32 && py >= 0 && py < h as i32 {
                    self.inner.draw_pixel(
                        (px, py),
                        BackendColor {
                            alpha: color.alpha * f64::from(cover.min(1.0)),
                            rgb: color.rgb,
                        },
                    )?;
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::prelude::*;

    /// The ink of `text` drawn at `(x, y)` with `anchor` and `transform`
    /// on a white 200 × 200 bitmap: its bounding box (x0, y0, x1, y1).
    fn ink(text: &str, pos: (i32, i32), style: TextStyle<'_>) -> Option<(i32, i32, i32, i32)> {
        let (w, h) = (200u32, 200u32);
        let mut rgb = vec![255u8; (w * h * 3) as usize];
        {
            let root = GlyphBitmap::with_buffer(&mut rgb, (w, h)).into_drawing_area();
            root.draw(&Text::new(text.to_string(), pos, style)).unwrap();
            root.present().unwrap();
        }
        let mut bb: Option<(i32, i32, i32, i32)> = None;
        for y in 0..h as i32 {
            for x in 0..w as i32 {
                let i = ((y as u32 * w + x as u32) * 3) as usize;
                if rgb[i] < 128 {
                    bb = Some(bb.map_or((x, y, x, y), |(a, b, c, d)| {
                        (a.min(x), b.min(y), c.max(x), d.max(y))
                    }));
                }
            }
        }
        bb
    }

    #[test]
    fn text_is_drawn_where_anchored_and_turned_when_rotated() {
        let style = ("sans-serif", 20).into_font().color(&BLACK);
        let (x0, y0, x1, y1) = ink("100", (50, 50), style.clone()).expect("ink");
        let (w, h) = text_box("100", 20.0);
        // left-top anchored: the ink within the text's box from (50, 50)
        assert!(
            (50..=53).contains(&x0) && x1 <= 50 + w && x1 > 50 + w / 2,
            "{x0}..{x1} of {w}"
        );
        assert!(
            y0 >= 50 && y1 <= 50 + h + 2 && y1 - y0 >= 10,
            "{y0}..{y1} of {h}"
        );
        // centred: the box's middle at x = 100
        let c = style.pos(plotters_backend::text_anchor::Pos::new(
            HPos::Center,
            VPos::Center,
        ));
        let (cx0, cy0, cx1, cy1) = ink("100", (100, 100), c).expect("ink");
        assert!(((cx0 + cx1) / 2 - 100).abs() <= 2, "{cx0}..{cx1}");
        assert!(((cy0 + cy1) / 2 - 100).abs() <= 3, "{cy0}..{cy1}");
        // rotated a quarter turn (a y axis title): taller than wide
        let r = ("sans-serif", 20)
            .into_font()
            .transform(FontTransform::Rotate270)
            .color(&BLACK);
        let (rx0, ry0, rx1, ry1) = ink("height (mm)", (100, 150), r).expect("ink");
        assert!(ry1 - ry0 > 3 * (rx1 - rx0), "{rx0}..{rx1} x {ry0}..{ry1}");
    }
}
